// A pinhole with any K and OpenCV's radial-tangential distortion (cv::projectPoints, D = k1, k2,
// p1, p2, k3): x' = x (1 + k1 r^2 + k2 r^4 + k3 r^6) + 2 p1 x y + p2 (r^2 + 2 x^2), y' likewise,
// pixel = K (x', y', 1), of the normalised point (x, y) = (X / Z, Y / Z). Four coefficients (as
// Kalibr's radtan gives them) mean k3 = 0.
#include <Eigen/Dense>

#include "camera/lenses/lens_math.h"

namespace flowscape::lens {
namespace {

std::vector<double> distortion(const nlohmann::json& p) {
  const bool four = p.contains("D") && p.at("D").is_array() && p.at("D").size() == 4;
  std::vector<double> d = numbers(p, "D", four ? 4 : 5, std::vector<double>(5, 0));
  d.resize(5, 0);
  return d;
}

class Pinhole : public SizedLens {
 public:
  explicit Pinhole(const nlohmann::json& p) : SizedLens(p), k_(intrinsics(p)), d_(distortion(p)) {
    // where the radial part stops growing, up to 84 degrees off the axis (r = 10)
    max_r_ = increasing_until([this](double r) { return r * radial(r * r); }, 10);
    require(max_r_ > 0.05, "lens distortion folds back right next to the axis");
  }
  std::string model() const override { return "pinhole"; }
  nlohmann::json parameters() const override {
    return {{"width", width_}, {"height", height_}, {"K", k_.matrix()}, {"D", d_}};
  }

  std::optional<Vec2> project(const Vec3& d) const override {
    if (!(d.z() > 0)) return std::nullopt;
    const Vec2 n(d.x() / d.z(), d.y() / d.z());
    if (n.squaredNorm() > max_r_ * max_r_) return std::nullopt;
    const Vec2 m = distorted(n);
    return Vec2(k_.fx * m.x() + k_.cx, k_.fy * m.y() + k_.cy);
  }

  // Undistorts by Newton's method on the 2-D map, from the distorted point itself.
  std::optional<Vec3> ray(Vec2 pixel) const override {
    const Vec2 target((pixel.x() - k_.cx) / k_.fx, (pixel.y() - k_.cy) / k_.fy);
    Vec2 n = target;
    for (int i = 0; i < 50; ++i) {
      const Vec2 step = jacobian(n).inverse() * (distorted(n) - target);
      n -= step;
      if (!n.allFinite() || n.squaredNorm() > max_r_ * max_r_) return std::nullopt;
      if (step.norm() < 1e-15) break;
    }
    if ((distorted(n) - target).norm() > 1e-12) return std::nullopt;
    return Vec3(n.x(), n.y(), 1).normalized();
  }

 private:
  double radial(double r2) const { return 1 + r2 * (d_[0] + r2 * (d_[1] + r2 * d_[4])); }
  Vec2 distorted(const Vec2& n) const {
    const double x = n.x(), y = n.y(), r2 = x * x + y * y, k = radial(r2);
    return {x * k + 2 * d_[2] * x * y + d_[3] * (r2 + 2 * x * x),
            y * k + d_[2] * (r2 + 2 * y * y) + 2 * d_[3] * x * y};
  }
  Eigen::Matrix2d jacobian(const Vec2& n) const {
    const double x = n.x(), y = n.y(), r2 = x * x + y * y, k = radial(r2);
    const double dk = d_[0] + r2 * (2 * d_[1] + r2 * 3 * d_[4]);  // dk / d(r^2)
    Eigen::Matrix2d j;
    j << k + 2 * x * x * dk + 2 * d_[2] * y + 6 * d_[3] * x,
        2 * x * y * dk + 2 * d_[2] * x + 2 * d_[3] * y,
        2 * x * y * dk + 2 * d_[2] * x + 2 * d_[3] * y,
        k + 2 * y * y * dk + 6 * d_[2] * y + 2 * d_[3] * x;
    return j;
  }

  Intrinsics k_;
  std::vector<double> d_;
  double max_r_ = 0;
};

}  // namespace

std::shared_ptr<const Lens> make_pinhole(const nlohmann::json& p) {
  return std::make_shared<Pinhole>(p);
}

}  // namespace flowscape::lens
