#pragma once
// Panoramic geometry, written once: ERP pixel <-> direction, cube face pixel <-> direction,
// the paper's forward ERP (Eq. 1), C2E (Eq. 13-14) and 360-degree flow (Eq. 3).
//
// Rig frame: x forward, y left, z up (right-handed, the world convention of design.md).
// ERP (W = 2H): longitude phi in (-pi, pi] grows to the right (phi = 0 looks forward, at x = W/2),
// latitude theta in (-pi/2, pi/2) grows downwards. Continuous pixel coordinates put the centre of
// pixel (i, j) at (i + 0.5, j + 0.5), for ERP and for cube faces alike.
// Cube faces are 90-degree pinholes of N x N pixels (focal N/2, principal point N/2, N/2).
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string_view>

#include "flowscape/core/image.h"
#include "flowscape/core/types.h"

namespace flowscape {

// ---- ERP -------------------------------------------------------------------------------------

struct Angles {
  double phi;    // longitude, (-pi, pi], right-positive
  double theta;  // latitude, (-pi/2, pi/2), down-positive
};

template <class T, std::size_t kTerms>
constexpr T polynomial(T x, const T (&coefficients)[kTerms]) {  // Horner
  T sum = coefficients[kTerms - 1];
  for (int k = int(kTerms) - 2; k >= 0; --k) sum = coefficients[k] + x * sum;
  return sum;
}

// atan2 without branches, so that loops over it vectorise (the stitcher calls it per pixel):
// octant reduction, atan(z) = pi/4 + atan((z - 1) / (z + 1)) above tan(pi/8), then
// atan(z) = z P(z^2) with P a Chebyshev interpolant of atan(z)/z on [0, tan^2(pi/8)].
template <class T, std::size_t kTerms>
inline T reduced_atan2(T y, T x, const T (&p)[kTerms]) {
  const T tan_pi8 = T(0.41421356237309503), pi = T(kPi);
  const T ax = x < 0 ? -x : x, ay = y < 0 ? -y : y;
  const T small = ax < ay ? ax : ay, large = ax < ay ? ay : ax;
  const bool shifted = small > tan_pi8 * large;
  const T numerator = shifted ? small - large : small;
  const T denominator = shifted ? small + large : (large > 0 ? large : T(1));
  const T z = numerator / denominator, z2 = z * z;
  T angle = z * polynomial(z2, p) + (shifted ? pi / 4 : T(0));
  angle = ay > ax ? pi / 2 - angle : angle;
  angle = x < 0 ? pi - angle : angle;
  return y < 0 ? -angle : angle;
}

// To within 1e-10 rad (P of degree 6, error below 1e-11).
inline double fast_atan2(double y, double x) {
  static constexpr double kP[7] = {0.9999999999783997,   -0.333333320976096,  0.19999883856481723,
                                   -0.14281588769911768, 0.11040489189652566, -0.0845619267239619,
                                   0.04707347702726853};
  return reduced_atan2(y, x, kP);
}

// To float precision, relative to the angle (P of degree 4, relative error below 2e-8).
inline float fast_atan2(float y, float x) {
  static constexpr float kP[5] = {0.9999999812646111f, -0.3333278577192415f, 0.199740824154833f,
                                  -0.13848490211930034f, 0.07976291805297275f};
  return reduced_atan2(y, x, kP);
}

struct SinCos {
  double sin, cos;
};

// sin and cos without libm calls (the renderer needs them per sample), to within 4e-16 for
// |x| <= 2 pi (the error of the reduction grows with |x|: 1e-14 at 40 pi):
// x = k pi/2 + r with |r| <= pi/4, Taylor polynomials in r, then the quadrant k mod 4.
inline SinCos sin_cos(double x) {
  static constexpr double kSin[8] = {1,
                                     -1.0 / 6,
                                     1.0 / 120,
                                     -1.0 / 5040,
                                     1.0 / 362880,
                                     -1.0 / 39916800,
                                     1.0 / 6227020800,
                                     -1.0 / 1307674368000};
  static constexpr double kCos[9] = {1,
                                     -0.5,
                                     1.0 / 24,
                                     -1.0 / 720,
                                     1.0 / 40320,
                                     -1.0 / 3628800,
                                     1.0 / 479001600,
                                     -1.0 / 87178291200,
                                     1.0 / 20922789888000};
  constexpr double kRound = 0x1.8p52;  // adding and subtracting it rounds to the nearest integer
  constexpr double kHalfPiHi = 1.5707963267948966, kHalfPiLo = 6.123233995736766e-17;
  const double k = (x * (2 / kPi) + kRound) - kRound;
  const double r = (x - k * kHalfPiHi) - k * kHalfPiLo, r2 = r * r;
  const double s = r * polynomial(r2, kSin), c = polynomial(r2, kCos);
  switch (static_cast<long long>(k) & 3) {
    case 0:
      return {s, c};
    case 1:
      return {c, -s};
    case 2:
      return {-s, -c};
    default:
      return {-c, s};
  }
}

// Paper Eq. 1: x = L (phi - phi0) cos(theta1), y = L (theta - theta0).
inline Vec2 paper_forward_erp(double phi, double theta, double L, double phi0, double theta0,
                              double theta1) {
  return {L * (phi - phi0) * std::cos(theta1), L * (theta - theta0)};
}

// Eq. 1 with L = W / (2 pi), phi0 = -pi, theta0 = -pi/2, theta1 = 0 (requires W = 2H).
inline Vec2 erp_from_angles(Angles a, int erp_width) {
  return paper_forward_erp(a.phi, a.theta, erp_width / (2 * kPi), -kPi, -kPi / 2, 0.0);
}
Angles angles_from_erp(Vec2 p, int erp_width);

Vec3 direction_from_angles(Angles a);  // unit vector
inline Vec3 direction_from_sin_cos(SinCos phi, SinCos theta) {
  return {theta.cos * phi.cos, -theta.cos * phi.sin, -theta.sin};
}
// d need not be unit length
inline Angles angles_from_direction(const Vec3& d) {
  return {fast_atan2(-d.y(), d.x()), fast_atan2(-d.z(), std::sqrt(d.x() * d.x() + d.y() * d.y()))};
}
inline Vec2 erp_from_direction(const Vec3& d, int erp_width) {
  return erp_from_angles(angles_from_direction(d), erp_width);
}
Vec3 direction_from_erp(Vec2 p, int erp_width);  // unit vector

// ---- cube ------------------------------------------------------------------------------------

enum class Face : int { Front, Right, Back, Left, Up, Down };
inline constexpr std::array<Face, 6> kFaces{Face::Front, Face::Right, Face::Back,
                                            Face::Left,  Face::Up,    Face::Down};
std::string_view face_name(Face face);  // "front", "right", ...
std::optional<Face> face_from_name(std::string_view name);

// A cubemap is one image of N x 6N pixels: the six faces stacked top to bottom in kFaces order, so
// pixel indices address any face directly.
template <class T>
ImageView<T> face_view(ImageView<T> cube, Face face) {
  return {cube.width, cube.width, cube.channels, cube.pixel(0, int(face) * cube.width)};
}

// Orthonormal basis of a face camera. Up and down are pitched like a car camera at +-90 deg:
// the lower edge of "up" and the upper edge of "down" both touch the front face.
struct FaceBasis {
  Vec3 forward, right, down;
};
inline const std::array<FaceBasis, 6> kFaceBases{{
    {{1, 0, 0}, {0, -1, 0}, {0, 0, -1}},   // front
    {{0, -1, 0}, {-1, 0, 0}, {0, 0, -1}},  // right
    {{-1, 0, 0}, {0, 1, 0}, {0, 0, -1}},   // back
    {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},    // left
    {{0, 0, 1}, {0, -1, 0}, {1, 0, 0}},    // up
    {{0, 0, -1}, {0, -1, 0}, {-1, 0, 0}},  // down
}};
inline const FaceBasis& face_basis(Face face) { return kFaceBases[int(face)]; }
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
inline double wrap_360(double u, int erp_width) {
  const double W = erp_width;
  return u > W / 2 ? u - W : u <= -W / 2 ? u + W : u;
}

// The horizontal ERP flow in the chosen form, from its 360-degree form at column source_x:
// classic flow adds or removes W where the target crosses the seam.
inline double erp_flow_u(double u360, double source_x, int erp_width, FlowMode mode) {
  if (mode == FlowMode::Wrap360) return u360;
  const double target = source_x + u360;
  return target >= erp_width ? u360 - erp_width : target < 0 ? u360 + erp_width : u360;
}

// Middlebury's marker for unknown flow (any component above 1e9 means unknown).
inline constexpr float kUnknownFlow = 1e10f;
inline bool is_known_flow(float u, float v) {
  return std::abs(u) < 1e9f && std::abs(v) < 1e9f;  // false for NaN too
}

}  // namespace flowscape
