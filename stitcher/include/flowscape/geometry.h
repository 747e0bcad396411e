#pragma once
// Panoramic geometry, written once: ERP pixel <-> direction, cube face pixel <-> direction,
// the paper's forward ERP (Eq. 1), C2E (Eq. 13-14) and 360-degree flow (Eq. 3).
//
// Rig frame: x forward, y left, z up (right-handed, the world convention of design.md).
// ERP (W = 2H): longitude phi in (-pi, pi] grows to the right (phi = 0 looks forward, at x = W/2),
// latitude theta in (-pi/2, pi/2) grows downwards. Continuous pixel coordinates put the centre of
// pixel (i, j) at (i + 0.5, j + 0.5), for ERP and for cube faces alike.
// Cube faces are 90-degree pinholes of N x N pixels (focal N/2, principal point N/2, N/2).
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string_view>

namespace flowscape {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

inline constexpr double kPi = 3.14159265358979323846;

// ---- ERP -------------------------------------------------------------------------------------

struct Angles {
  double phi;    // longitude, (-pi, pi], right-positive
  double theta;  // latitude, (-pi/2, pi/2), down-positive
};

// Paper Eq. 1: x = L (phi - phi0) cos(theta1), y = L (theta - theta0).
Vec2 paper_forward_erp(double phi, double theta, double L, double phi0, double theta0,
                       double theta1);

// Eq. 1 with L = W / (2 pi), phi0 = -pi, theta0 = -pi/2, theta1 = 0 (requires W = 2H).
Vec2 erp_from_angles(Angles a, int erp_width);
Angles angles_from_erp(Vec2 p, int erp_width);

Vec3 direction_from_angles(Angles a);          // unit vector
Angles angles_from_direction(const Vec3& d);   // d need not be unit length
Vec2 erp_from_direction(const Vec3& d, int erp_width);
Vec3 direction_from_erp(Vec2 p, int erp_width);  // unit vector

// ---- cube ------------------------------------------------------------------------------------

enum class Face : int { Front, Right, Back, Left, Up, Down };
inline constexpr std::array<Face, 6> kFaces{Face::Front, Face::Right, Face::Back,
                                            Face::Left,  Face::Up,    Face::Down};
std::string_view face_name(Face face);  // "front", "right", ...
std::optional<Face> face_from_name(std::string_view name);

// Orthonormal basis of a face camera. Up and down are pitched like a car camera at +-90 deg:
// the lower edge of "up" and the upper edge of "down" both touch the front face.
struct FaceBasis {
  Vec3 forward, right, down;
};
const FaceBasis& face_basis(Face face);
// Columns right, down, forward: maps face-camera coordinates (x right, y down, z forward) to rig.
Mat3 face_rotation(Face face);

struct CubePoint {
  Face face;
  Vec2 pixel;  // continuous, in [0, N)
};

// The face whose 90-degree frustum holds d (ties go to the earlier face in kFaces).
CubePoint cube_from_direction(const Vec3& d, int face_size);
// Ray through a face-plane point: forward + a right + b down, with a, b in [-1, 1] on the face;
// not normalised. Points outside [0, N) give rays through the extended plane.
Vec3 ray_from_cube(Face face, Vec2 pixel, int face_size);
// Projection of d onto the (extended) plane of one face; nullopt when d is not in front of it.
std::optional<Vec2> face_plane_from_direction(Face face, const Vec3& d, int face_size);

// Paper Eq. 13 (m = 0..3 for front, right, back, left) and Eq. 14 (up, down), in pixels relative to
// the face centre (x right, y down). `elevation` is up-positive (= -theta). The paper's down view
// (n = 1) is our down face turned by 180 degrees; the function returns the paper's value.
Vec2 paper_c2e(Face face, double phi, double elevation, int face_size);

// ---- flow ------------------------------------------------------------------------------------

enum class FlowMode { Wrap360, Classic };

// Paper Eq. 3: the horizontal component the short way round, in (-W/2, W/2].
double wrap_360(double u, int erp_width);

// Middlebury's marker for unknown flow (any component above 1e9 means unknown).
inline constexpr float kUnknownFlow = 1e10f;
inline bool is_known_flow(float u, float v) {
  return u == u && v == v && u > -1e9f && u < 1e9f && v > -1e9f && v < 1e9f;
}

}  // namespace flowscape
