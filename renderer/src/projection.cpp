#include "flowscape/projection.h"

#include <cmath>

namespace flowscape {

Projection Projection::cube_face(Face face, int face_size) {
  return {Kind::Pinhole, face_size, face_size, face_rotation(face), face_size / 2.0};
}

Projection Projection::pinhole(int width, int height, double fov_x_degrees) {
  return {Kind::Pinhole, width, height, face_rotation(Face::Front),
          width / 2.0 / std::tan(fov_x_degrees * kPi / 360)};
}

Projection Projection::equirectangular(int height) {
  return {Kind::Equirectangular, 2 * height, height, Mat3::Identity(), 0};
}

Vec3 Projection::ray(Vec2 pixel) const {
  if (kind == Kind::Equirectangular) return direction_from_erp(pixel, width);
  return rotation * Vec3((pixel.x() - width / 2.0) / focal, (pixel.y() - height / 2.0) / focal, 1);
}

std::optional<Vec2> Projection::project(const Vec3& direction) const {
  if (kind == Kind::Equirectangular) return erp_from_direction(direction, width);
  const Vec3 camera = rotation.transpose() * direction;
  if (!(camera.z() > 0)) return std::nullopt;
  return Vec2(width / 2.0 + focal * camera.x() / camera.z(),
              height / 2.0 + focal * camera.y() / camera.z());
}

}  // namespace flowscape
