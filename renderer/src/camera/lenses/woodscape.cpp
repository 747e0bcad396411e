// The WoodScape fisheye (Yogamani et al. 2019): rho = k1 theta + k2 theta^2 + k3 theta^3 +
// k4 theta^4 pixels from the principal point (image centre + offset), the vertical scaled by the
// aspect ratio.
#include "camera/lenses/lens_math.h"

namespace flowscape::lens {
namespace {

class WoodScape : public RadialLens {
 public:
  explicit WoodScape(const nlohmann::json& p) : k_(numbers(p, "k", 4)) {
    const int W = dimension(p, "width"), H = dimension(p, "height");
    cx_offset_ = number(p, "cx_offset", 0), cy_offset_ = number(p, "cy_offset", 0);
    const double aspect = number(p, "aspect_ratio", 1);
    finish(W, H, 1, aspect, W / 2.0 + cx_offset_, H / 2.0 + cy_offset_,
           number(p, "max_angle_degrees") * kDegree);
  }
  std::string model() const override { return "woodscape"; }
  nlohmann::json parameters() const override {
    return {{"width", width_},
            {"height", height_},
            {"k", k_},
            {"cx_offset", cx_offset_},
            {"cy_offset", cy_offset_},
            {"aspect_ratio", fy_},
            {"max_angle_degrees", max_angle_ / kDegree}};
  }

 protected:
  double radius(double t) const override {
    return t * (k_[0] + t * (k_[1] + t * (k_[2] + t * k_[3])));
  }
  double radius_slope(double t) const override {
    return k_[0] + t * (2 * k_[1] + t * (3 * k_[2] + t * 4 * k_[3]));
  }

 private:
  std::vector<double> k_;
  double cx_offset_ = 0, cy_offset_ = 0;
};

}  // namespace

std::shared_ptr<const Lens> make_woodscape(const nlohmann::json& p) {
  return std::make_shared<WoodScape>(p);
}

}  // namespace flowscape::lens
