// Kannala-Brandt fisheye (OpenCV's cv::fisheye): theta_d = theta (1 + k1 theta^2 + k2 theta^4 +
// k3 theta^6 + k4 theta^8), pixel = K (theta_d / r) (x, y); the equidistant fisheye is the same
// with k = 0 (theta_d = theta).
#include "camera/lenses/lens_math.h"

namespace flowscape::lens {
namespace {

class KannalaBrandt : public RadialLens {
 public:
  KannalaBrandt(const nlohmann::json& p, bool equidistant) : equidistant_(equidistant) {
    const Intrinsics K = intrinsics(p);
    k_ = equidistant ? std::vector<double>(4, 0) : numbers(p, "D", 4);
    finish(dimension(p, "width"), dimension(p, "height"), K.fx, K.fy, K.cx, K.cy,
           number(p, "max_angle_degrees") * kDegree);
  }
  std::string model() const override { return equidistant_ ? "equidistant" : "kannala_brandt"; }
  nlohmann::json parameters() const override {
    nlohmann::json p = {{"width", width_},
                        {"height", height_},
                        {"K", Intrinsics{fx_, fy_, cx_, cy_}.matrix()},
                        {"max_angle_degrees", max_angle_ / kDegree}};
    if (!equidistant_) p["D"] = k_;
    return p;
  }

 protected:
  double radius(double t) const override {
    const double t2 = t * t;
    return t * (1 + t2 * (k_[0] + t2 * (k_[1] + t2 * (k_[2] + t2 * k_[3]))));
  }
  double radius_slope(double t) const override {
    const double t2 = t * t;
    return 1 + t2 * (3 * k_[0] + t2 * (5 * k_[1] + t2 * (7 * k_[2] + t2 * 9 * k_[3])));
  }

 private:
  bool equidistant_;
  std::vector<double> k_;
};

}  // namespace

std::shared_ptr<const Lens> make_kannala_brandt(const nlohmann::json& p, bool equidistant) {
  return std::make_shared<KannalaBrandt>(p, equidistant);
}

}  // namespace flowscape::lens
