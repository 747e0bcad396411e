// The panoramic annular lens in Scaramuzza's omnidirectional model (OCamCalib, Scaramuzza et al.
// 2006): an image point m, relative to the centre and through the affine [c d; e 1], looks along
// (m_x, m_y, f(rho)), rho = |m|, f(rho) = a0 + a1 rho + a2 rho^2 + a3 rho^3 + a4 rho^4. The lens
// looks along its z (mounted up), sees every azimuth and the band of angles from the axis
// [min_angle, max_angle]: the annulus; the pixels inside and outside it see nothing.
#include <Eigen/Dense>

#include "camera/lenses/lens_math.h"

namespace flowscape::lens {
namespace {

class PanoramicAnnular : public SizedLens {
 public:
  explicit PanoramicAnnular(const nlohmann::json& p)
      : SizedLens(p),
        centre_(numbers(p, "centre", 2)),
        affine_(numbers(p, "affine", 3, std::vector<double>{1, 0, 0})),
        a_(numbers(p, "polynomial", 5)),
        min_angle_(number(p, "min_angle_degrees") * kDegree),
        max_angle_(number(p, "max_angle_degrees") * kDegree) {
    require(min_angle_ >= 0 && min_angle_ < max_angle_ && max_angle_ < kPi,
            "lens min_angle_degrees < max_angle_degrees must lie in [0, 180)");
    require(affine_[0] != affine_[1] * affine_[2], "lens parameter \"affine\" is singular");
    const double reach = 4.0 * std::max(width_, height_);
    const double end = increasing_until([this](double r) { return angle(r); }, reach);
    require(angle(end) >= max_angle_,
            "the lens polynomial does not reach max_angle_degrees with a growing angle");
    rho_min_ = solve(min_angle_, 0, end), rho_max_ = solve(max_angle_, 0, end);
  }
  std::string model() const override { return "panoramic_annular"; }
  nlohmann::json parameters() const override {
    return {{"width", width_},
            {"height", height_},
            {"centre", centre_},
            {"affine", affine_},
            {"polynomial", a_},
            {"min_angle_degrees", min_angle_ / kDegree},
            {"max_angle_degrees", max_angle_ / kDegree}};
  }

  std::optional<Vec3> ray(Vec2 pixel) const override {
    // the centre in OpenCV's pixel convention, as OCamCalib writes it
    const Vec2 offset(pixel.x() - 0.5 - centre_[0], pixel.y() - 0.5 - centre_[1]);
    const Vec2 m = affine().inverse() * offset;
    const double rho = m.norm(), theta = angle(rho);
    if (theta < min_angle_ || theta > max_angle_) return std::nullopt;
    return Vec3(m.x(), m.y(), f(rho)).normalized();
  }

  std::optional<Vec2> project(const Vec3& d) const override {
    const double r = std::hypot(d.x(), d.y()), theta = std::atan2(r, d.z());
    if (!(r > 0) || theta < min_angle_ || theta > max_angle_) return std::nullopt;
    const double rho = solve(theta, rho_min_, rho_max_);
    const Vec2 offset = affine() * (rho / r * Vec2(d.x(), d.y()));
    return Vec2(offset.x() + 0.5 + centre_[0], offset.y() + 0.5 + centre_[1]);
  }

 private:
  double f(double rho) const {
    return a_[0] + rho * (a_[1] + rho * (a_[2] + rho * (a_[3] + rho * a_[4])));
  }
  double f_slope(double rho) const {
    return a_[1] + rho * (2 * a_[2] + rho * (3 * a_[3] + rho * 4 * a_[4]));
  }
  double angle(double rho) const { return std::atan2(rho, f(rho)); }  // from the axis
  double angle_slope(double rho) const {
    return (f(rho) - rho * f_slope(rho)) / (rho * rho + f(rho) * f(rho));
  }
  double solve(double theta, double lo, double hi) const {
    return solve_increasing([this](double r) { return angle(r); },
                            [this](double r) { return angle_slope(r); }, theta, lo, hi);
  }
  Eigen::Matrix2d affine() const {
    Eigen::Matrix2d a;
    a << affine_[0], affine_[1], affine_[2], 1;
    return a;
  }

  std::vector<double> centre_, affine_, a_;
  double min_angle_, max_angle_, rho_min_ = 0, rho_max_ = 0;
};

}  // namespace

std::shared_ptr<const Lens> make_panoramic_annular(const nlohmann::json& p) {
  return std::make_shared<PanoramicAnnular>(p);
}

// A polynomial whose angle grows evenly from the band's upper edge at 0.16 of the size to its
// lower edge at 0.47 (a fit of rho / tan(theta) by least squares; the mask is at the exact angles).
std::shared_ptr<const Lens> panoramic_annular(int size, double band_degrees) {
  require(band_degrees > 0 && band_degrees < 180, "a PAL's band must be in (0, 180) degrees");
  const double low = (90 - band_degrees / 2) * kDegree, high = (90 + band_degrees / 2) * kDegree;
  const double inner = 0.16 * size, outer = 0.47 * size;
  constexpr int kSamples = 64;
  Eigen::MatrixXd powers(kSamples, 4);
  Eigen::VectorXd target(kSamples);
  for (int i = 0; i < kSamples; ++i) {
    const double rho = inner + (outer - inner) * i / (kSamples - 1);
    const double theta = low + (high - low) * i / (kSamples - 1);
    const double x = rho / size;  // fit in units of the size: well conditioned
    powers.row(i) << 1, x * x, x * x * x, x * x * x * x;
    target[i] = rho / std::tan(theta) / size;
  }
  const Eigen::Vector4d c = powers.colPivHouseholderQr().solve(target);
  const double s = size;
  const nlohmann::json p = {
      {"width", size},
      {"height", size},
      {"centre", {s / 2 - 0.5, s / 2 - 0.5}},
      {"affine", {1, 0, 0}},
      {"polynomial", {c[0] * s, 0, c[1] / s, c[2] / (s * s), c[3] / (s * s * s)}},
      {"min_angle_degrees", low / kDegree},
      {"max_angle_degrees", high / kDegree}};
  return make_panoramic_annular(p);
}

}  // namespace flowscape::lens
