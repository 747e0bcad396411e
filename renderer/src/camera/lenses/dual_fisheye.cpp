// Two equidistant fisheyes back to back in one image, as consumer 360 cameras record: the left
// half the front lens (looking along +z), the right half the rear one (along -z, its x mirrored),
// each an image circle of the half's height. A direction belongs to the lens whose axis is nearer;
// the ring of each circle beyond 90 degrees sees what the other lens owns.
#include "camera/lenses/lens_math.h"

namespace flowscape::lens {
namespace {

class DualFisheye : public SizedLens {
 public:
  explicit DualFisheye(const nlohmann::json& p) : SizedLens(p) {
    require(width_ == 2 * height_, "a dual fisheye image is twice as wide as high");
    max_angle_ = number(p, "max_angle_degrees") * kDegree;
    require(max_angle_ >= kPi / 2 && max_angle_ < kPi,
            "a dual fisheye's max_angle_degrees must be in [90, 180)");
    f_ = number(p, "f", height_ / 2.0 / max_angle_);
    require(f_ > 0, "lens parameter \"f\" must be positive");
  }
  std::string model() const override { return "dual_fisheye"; }
  nlohmann::json parameters() const override {
    return {{"width", width_},
            {"height", height_},
            {"f", f_},
            {"max_angle_degrees", max_angle_ / kDegree}};
  }

  std::optional<Vec3> ray(Vec2 pixel) const override {
    const bool rear = pixel.x() >= height_;
    const Vec2 m = (pixel - centre(rear)) / f_;
    const double theta = m.norm();
    if (theta > max_angle_) return std::nullopt;
    const double s = theta > 0 ? std::sin(theta) / theta : 1;
    const Vec3 own(s * m.x(), s * m.y(), std::cos(theta));  // in the lens's own frame
    return rear ? Vec3(-own.x(), own.y(), -own.z()) : own;
  }

  std::optional<Vec2> project(const Vec3& d) const override {
    if (!(d.squaredNorm() > 0)) return std::nullopt;
    const bool rear = d.z() < 0;
    const Vec3 own = rear ? Vec3(-d.x(), d.y(), -d.z()) : d;
    const double r = std::hypot(own.x(), own.y()), theta = std::atan2(r, own.z());
    if (r == 0) return centre(rear);
    return centre(rear) + f_ * theta / r * Vec2(own.x(), own.y());
  }

 private:
  Vec2 centre(bool rear) const { return {(rear ? 1.5 : 0.5) * height_, 0.5 * height_}; }
  double max_angle_ = 0, f_ = 0;
};

}  // namespace

std::shared_ptr<const Lens> make_dual_fisheye(const nlohmann::json& p) {
  return std::make_shared<DualFisheye>(p);
}

}  // namespace flowscape::lens
