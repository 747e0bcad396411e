#pragma once
// Internal: what the lens models share: reading their parameters, solving a monotonic function
// for its argument, and the radial model r = g(theta) the fisheyes are made of.
#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "flowscape/core/types.h"
#include "flowscape/renderer/lens.h"

namespace flowscape::lens {

inline constexpr double kDegree = kPi / 180;

// A finite number parameter; `fallback` when absent (nullopt: required).
double number(const nlohmann::json& p, const char* key, std::optional<double> fallback = {});
// A list of `count` finite numbers (K rows, distortion coefficients).
std::vector<double> numbers(const nlohmann::json& p, const char* key, std::size_t count,
                            std::optional<std::vector<double>> fallback = {});
// The image size (width, height >= 2) a lens's parameters give.
int dimension(const nlohmann::json& p, const char* key);
void require(bool ok, const std::string& what);  // std::invalid_argument naming the parameter

// A 3x3 "K" as OpenCV writes it (the centre of the top-left pixel at (0, 0)), held here with the
// principal point in continuous coordinates (pixel centres at +0.5).
struct Intrinsics {
  double fx, fy, cx, cy;
  nlohmann::json matrix() const {  // back to OpenCV's form
    return {{fx, 0, cx - 0.5}, {0, fy, cy - 0.5}, {0, 0, 1}};
  }
};
Intrinsics intrinsics(const nlohmann::json& p);  // from "K": rows of 3, no skew

// The x in [lo, hi] with f(x) = y, for f increasing there, `slope` its derivative: Newton steps,
// bisection where a step would leave the bracket (Numerical Recipes' rtsafe), to 1e-15.
double solve_increasing(const std::function<double(double)>& f,
                        const std::function<double(double)>& slope, double y, double lo, double hi);
// The largest x in (0, limit] up to which f keeps increasing (sampled finely), for where a
// polynomial model folds back.
double increasing_until(const std::function<double(double)>& f, double limit);

// A lens of the image size its parameters give ("width", "height").
class SizedLens : public Lens {
 public:
  int width() const override { return width_; }
  int height() const override { return height_; }

 protected:
  SizedLens() = default;
  explicit SizedLens(const nlohmann::json& p)
      : width_(dimension(p, "width")), height_(dimension(p, "height")) {}
  int width_ = 0, height_ = 0;
};

// A radially symmetric lens: a direction at angle theta from the optical axis and azimuth phi
// lands at c + g(theta) (fx cos phi, fy sin phi); g increasing on [0, max_angle].
class RadialLens : public SizedLens {
 public:
  std::optional<Vec3> ray(Vec2 pixel) const override;
  std::optional<Vec2> project(const Vec3& direction) const override;

 protected:
  virtual double radius(double theta) const = 0;        // g
  virtual double radius_slope(double theta) const = 0;  // dg / dtheta
  // Call once the subclass's coefficients are set: checks that g increases up to max_angle.
  void finish(int width, int height, double fx, double fy, double cx, double cy, double max_angle);
  double fx_ = 1, fy_ = 1, cx_ = 0, cy_ = 0, max_angle_ = 0;  // cx, cy: continuous coordinates
};

}  // namespace flowscape::lens
