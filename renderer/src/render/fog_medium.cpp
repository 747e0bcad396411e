#include "render/fog_medium.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace flowscape {

FogMedium::FogMedium(const Fog& fog, const Vec3& sun_direction, const Rgb& sun_irradiance,
                     const Rgb& sky_mean)
    : fog_(fog),
      sun_direction_(sun_direction),
      sun_irradiance_(sun_irradiance),
      sky_mean_(sky_mean) {}

double FogMedium::extinction(double z) const {
  return fog_.density * std::exp(std::min(50.0, -(z - fog_.base) / fog_.height));
}

// sigma(s) = a exp(-b s) along the ray, with a the extinction at o and b = d_z / H, so the
// optical depth is a (1 - exp(-b s)) / b.
double FogMedium::optical_depth(const Vec3& o, const Vec3& d, double t) const {
  const double a = extinction(o.z()), b = d.z() / fog_.height;
  if (std::abs(b) < 1e-12) return a * t;
  if (std::isinf(t)) return b > 0 ? a / b : std::numeric_limits<double>::infinity();
  return a * -std::expm1(-b * t) / b;
}

// With u = optical depth from o, the extinction at a point is sigma = a - b u and T = exp(-u);
// the sun reaches the point through the optical depth sigma H / s_z (s = the sun direction), so
//   sun: albedo E / (4 pi) * integral_0^U exp(-u) exp(-(a - b u) H / s_z) du
//      = albedo E / (4 pi) exp(-a H / s_z) (1 - exp(-c U)) / c,  c = 1 - d_z / s_z,
//   sky: albedo L_mean * integral_0^U exp(-u) du = albedo L_mean (1 - exp(-U)).
Rgb FogMedium::inscattered(const Vec3& o, const Vec3& d, double depth) const {
  const double scattered = std::isinf(depth) ? 1 : -std::expm1(-depth);
  Rgb light = sky_mean_ * scattered;
  const double sun_z = sun_direction_.z();
  if (sun_z > 1e-6) {
    // an infinite depth needs a level or falling ray, so c >= 1 there
    const double c = 1 - d.z() / sun_z, a = extinction(o.z());
    const double integral = std::isinf(depth)            ? 1 / c
                            : std::abs(c) * depth < 1e-9 ? depth
                                                         : -std::expm1(-c * depth) / c;
    light += sun_irradiance_ * (std::exp(-a * fog_.height / sun_z) * integral / (4 * kPi));
  }
  return light.cwiseProduct(fog_.albedo.cast<double>());
}

}  // namespace flowscape
