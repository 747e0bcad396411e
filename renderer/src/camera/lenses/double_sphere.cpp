// The double sphere model (Usenko, Demmel, Cremers 2018, Eq. 40-51): a point goes to the unit
// sphere, is shifted by xi along z onto a second sphere and projected by a pinhole displaced by
// alpha / (1 - alpha).
#include <algorithm>

#include "camera/lenses/lens_math.h"

namespace flowscape::lens {
namespace {

class DoubleSphere : public SizedLens {
 public:
  explicit DoubleSphere(const nlohmann::json& p)
      : SizedLens(p), k_(intrinsics(p)), xi_(number(p, "xi")), alpha_(number(p, "alpha")) {
    require(alpha_ >= 0 && alpha_ <= 1, "lens parameter \"alpha\" must be in [0, 1]");
    require(xi_ > -1 && xi_ < 1, "lens parameter \"xi\" must be in (-1, 1)");
    const double w1 = alpha_ <= 0.5 ? alpha_ / (1 - alpha_) : (1 - alpha_) / alpha_;
    w2_ = (w1 + xi_) / std::sqrt(2 * w1 * xi_ + xi_ * xi_ + 1);
    const double reach = std::acos(std::clamp(-w2_, -1.0, 1.0));  // Eq. 45: z > -w2 |p|
    max_angle_ = number(p, "max_angle_degrees", reach / kDegree) * kDegree;
    require(max_angle_ > 0 && max_angle_ <= reach + 1e-12,
            "lens max_angle_degrees is beyond what the double sphere model reaches");
  }
  std::string model() const override { return "double_sphere"; }
  nlohmann::json parameters() const override {
    return {{"width", width_}, {"height", height_}, {"K", k_.matrix()},
            {"xi", xi_},       {"alpha", alpha_},   {"max_angle_degrees", max_angle_ / kDegree}};
  }

  std::optional<Vec2> project(const Vec3& d) const override {
    const double d1 = d.norm();
    if (!(d1 > 0) || std::acos(std::clamp(d.z() / d1, -1.0, 1.0)) > max_angle_) return std::nullopt;
    const double shifted = xi_ * d1 + d.z();
    const double d2 = std::sqrt(d.x() * d.x() + d.y() * d.y() + shifted * shifted);
    const double denominator = alpha_ * d2 + (1 - alpha_) * shifted;
    return Vec2(k_.fx * d.x() / denominator + k_.cx, k_.fy * d.y() / denominator + k_.cy);
  }

  std::optional<Vec3> ray(Vec2 pixel) const override {
    const double mx = (pixel.x() - k_.cx) / k_.fx, my = (pixel.y() - k_.cy) / k_.fy;
    const double r2 = mx * mx + my * my;
    if (alpha_ > 0.5 && r2 > 1 / (2 * alpha_ - 1)) return std::nullopt;
    const double mz =
        (1 - alpha_ * alpha_ * r2) / (alpha_ * std::sqrt(1 - (2 * alpha_ - 1) * r2) + 1 - alpha_);
    const double k = (mz * xi_ + std::sqrt(mz * mz + (1 - xi_ * xi_) * r2)) / (mz * mz + r2);
    const Vec3 ray = Vec3(k * mx, k * my, k * mz - xi_).normalized();
    if (std::acos(std::clamp(ray.z(), -1.0, 1.0)) > max_angle_) return std::nullopt;
    return ray;
  }

 private:
  Intrinsics k_;
  double xi_, alpha_, w2_ = 0, max_angle_ = 0;
};

}  // namespace

std::shared_ptr<const Lens> make_double_sphere(const nlohmann::json& p) {
  return std::make_shared<DoubleSphere>(p);
}

}  // namespace flowscape::lens
