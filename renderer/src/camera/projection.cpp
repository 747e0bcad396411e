#include "flowscape/renderer/projection.h"

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

Projection Projection::of_lens(std::shared_ptr<const Lens> lens, const Mat3& camera_to_rig) {
  const int W = lens->width(), H = lens->height();
  return {Kind::Lens, W, H, camera_to_rig, 0, std::move(lens)};
}

bool Projection::rectilinear() const {
  return kind == Kind::Pinhole || (kind == Kind::Lens && lens->model() == "pinhole");
}

std::string Projection::model() const {
  if (kind == Kind::Lens) return lens->model();
  return kind == Kind::Equirectangular ? "equirectangular" : "pinhole";
}

nlohmann::json Projection::parameters() const {
  if (kind == Kind::Lens) return lens->parameters();
  if (kind == Kind::Equirectangular) return {{"height", height}};
  return {{"width", width},
          {"height", height},
          {"K", {{focal, 0, width / 2.0 - 0.5}, {0, focal, height / 2.0 - 0.5}, {0, 0, 1}}}};
}

bool Projection::covers(Vec2 pixel) const {
  return kind != Kind::Lens || lens->ray(pixel).has_value();
}

Mat3 Projection::camera_to_rig() const {
  return kind == Kind::Equirectangular ? face_rotation(Face::Front) : rotation;
}

Vec3 Projection::ray(Vec2 pixel) const {
  if (kind == Kind::Equirectangular) return direction_from_erp(pixel, width);
  if (kind == Kind::Lens) {
    const std::optional<Vec3> ray = lens->ray(pixel);
    return ray ? Vec3(rotation * *ray) : Vec3::Zero();
  }
  return rotation * Vec3((pixel.x() - width / 2.0) / focal, (pixel.y() - height / 2.0) / focal, 1);
}

std::optional<Vec2> Projection::project(const Vec3& direction) const {
  if (kind == Kind::Equirectangular) return erp_from_direction(direction, width);
  if (kind == Kind::Lens) return lens->project(rotation.transpose() * direction);
  const Vec3 camera = rotation.transpose() * direction;
  if (!(camera.z() > 0)) return std::nullopt;
  return Vec2(width / 2.0 + focal * camera.x() / camera.z(),
              height / 2.0 + focal * camera.y() / camera.z());
}

namespace {

// The angle between the rays through pixel +- half a pixel along `axis`; twice one side's where
// the other leaves the image; 0 where neither sees.
double lens_span(const Lens& lens, Vec2 pixel, Vec2 axis) {
  const std::optional<Vec3> centre = lens.ray(pixel), a = lens.ray(pixel - axis / 2),
                            b = lens.ray(pixel + axis / 2);
  const auto angle = [](const Vec3& u, const Vec3& v) {
    return std::atan2(u.cross(v).norm(), u.dot(v));
  };
  if (a && b) return angle(*a, *b);
  if (centre && (a || b)) return 2 * angle(*centre, a ? *a : *b);
  return 0;
}

}  // namespace

double Projection::pixel_spread(Vec2 pixel) const {
  if (kind == Kind::Equirectangular) return 2 * kPi / width;
  if (kind == Kind::Lens)
    return std::sqrt(lens_span(*lens, pixel, Vec2::UnitX()) *
                     lens_span(*lens, pixel, Vec2::UnitY()));
  const Vec2 offset = (pixel - Vec2(width / 2.0, height / 2.0)) / focal;
  const double cos_axis = 1 / std::sqrt(1 + offset.squaredNorm());
  return std::pow(cos_axis, 1.5) / focal;
}

namespace {

// |d| <= pi / 64 (half a pixel of an ERP at least 64 wide): the series' remainders are below 1e-17.
SinCos small_angle_sin_cos(double d) {
  static constexpr double kSin[5] = {1, -1.0 / 6, 1.0 / 120, -1.0 / 5040, 1.0 / 362880};
  static constexpr double kCos[5] = {1, -0.5, 1.0 / 24, -1.0 / 720, 1.0 / 40320};
  const double d2 = d * d;
  return {d * polynomial(d2, kSin), polynomial(d2, kCos)};
}

SinCos angle_sum(SinCos a, SinCos b) {
  return {a.sin * b.cos + a.cos * b.sin, a.cos * b.cos - a.sin * b.sin};
}

}  // namespace

PixelRays::PixelRays(const Projection& projection, int x, int y)
    : projection_(projection),
      corner_(x, y),
      incremental_(projection.kind == Projection::Kind::Equirectangular && projection.width >= 64) {
  if (!incremental_) return;
  const Angles centre = angles_from_erp(corner_ + Vec2(0.5, 0.5), projection.width);
  phi_ = sin_cos(centre.phi), theta_ = sin_cos(centre.theta);
}

Vec3 PixelRays::operator()(Vec2 offset) const {
  if (!incremental_) return projection_.ray(corner_ + offset);
  const double radians_per_pixel = 2 * kPi / projection_.width;
  const Vec2 d = (offset - Vec2(0.5, 0.5)) * radians_per_pixel;
  return direction_from_sin_cos(angle_sum(phi_, small_angle_sin_cos(d.x())),
                                angle_sum(theta_, small_angle_sin_cos(d.y())));
}

}  // namespace flowscape
