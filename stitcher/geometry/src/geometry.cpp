#include "flowscape/geometry/geometry.h"

#include <cmath>

namespace flowscape {

Angles angles_from_erp(Vec2 p, int erp_width) {
  const double L = erp_width / (2 * kPi);
  return {p.x() / L - kPi, p.y() / L - kPi / 2};
}

Vec3 direction_from_angles(Angles a) {
  return direction_from_sin_cos(sin_cos(a.phi), sin_cos(a.theta));
}

Vec3 direction_from_erp(Vec2 p, int erp_width) {
  return direction_from_angles(angles_from_erp(p, erp_width));
}

namespace {

constexpr std::array<std::string_view, 6> kFaceNames{"front", "right", "back",
                                                     "left",  "up",    "down"};

}  // namespace

std::string_view face_name(Face face) { return kFaceNames[int(face)]; }

std::optional<Face> face_from_name(std::string_view name) {
  for (Face face : kFaces)
    if (face_name(face) == name) return face;
  return std::nullopt;
}

Mat3 face_rotation(Face face) {
  const FaceBasis& b = face_basis(face);
  Mat3 m;
  m << b.right, b.down, b.forward;
  return m;
}

CubePoint cube_from_direction(const Vec3& d, int face_size) {
  Face best = Face::Front;
  double best_forward = -1e300;
  for (Face face : kFaces) {
    const double forward = d.dot(face_basis(face).forward);
    if (forward > best_forward) best = face, best_forward = forward;
  }
  return {best, *face_plane_from_direction(best, d, face_size)};
}

Vec3 ray_from_cube(Face face, Vec2 pixel, int face_size) {
  const FaceBasis& b = face_basis(face);
  const double a = 2 * pixel.x() / face_size - 1, c = 2 * pixel.y() / face_size - 1;
  return b.forward + a * b.right + c * b.down;
}

std::optional<Vec2> face_plane_from_direction(Face face, const Vec3& d, int face_size) {
  const FaceBasis& b = face_basis(face);
  const double forward = d.dot(b.forward);
  if (!(forward > 0)) return std::nullopt;
  const double half = 0.5 * face_size;
  return Vec2{half * (1 + d.dot(b.right) / forward), half * (1 + d.dot(b.down) / forward)};
}

Vec2 paper_c2e(Face face, double phi, double elevation, int face_size) {
  const double half = 0.5 * face_size;
  if (face == Face::Up || face == Face::Down) {
    const int n = face == Face::Up ? 0 : 1;
    const double r = std::tan(kPi / 2 - elevation);
    return {half * r * std::sin(phi), half * r * std::cos(phi + n * kPi)};
  }
  const double local = phi - int(face) * kPi / 2;
  return {half * std::tan(local), -half * std::tan(elevation) / std::cos(local)};
}

}  // namespace flowscape
