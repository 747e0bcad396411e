#include "lights.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sampling.h"

namespace flowscape {
Lights::Lights(const Environment& e)
    : environment(e),
      sun_frame(frame_around(e.sun_direction)),
      sun_cos_radius(std::cos(e.sun_angular_radius)),
      sun_irradiance(e.sun_irradiance.cast<double>()),
      sun_disc_radiance(sun_irradiance * e.sun_disc_visibility / (2 * kPi * (1 - sun_cos_radius))),
      // the sky dome's radiance averaged over the sphere: above the horizon (1 - t) horizon +
      // t zenith with t = sqrt(z), whose mean over z in [0, 1] is 2/3; below it the ground's
      sky_mean(((e.sky_horizon / 3 + 2 * e.sky_zenith / 3 + e.ground) / 2).cast<double>()) {}

Rgb Lights::sky_radiance(const Vec3& d) const {
  if (d.z() < 0) return environment.ground.cast<double>();
  const double t = std::sqrt(d.z());
  return ((1 - t) * environment.sky_horizon + t * environment.sky_zenith).cast<double>();
}

Rgb Lights::sun_radiance(const Vec3& d) const {
  return d.dot(environment.sun_direction) < sun_cos_radius ? Rgb::Zero() : sun_disc_radiance;
}

Vec3 Lights::sun_sample(Vec2 u) const {
  const double cos_t = 1 - u.x() * (1 - sun_cos_radius), sin_t = std::sqrt(1 - cos_t * cos_t);
  const SinCos phi = sin_cos(2 * kPi * u.y());
  return sun_frame * Vec3(sin_t * phi.cos, sin_t * phi.sin, cos_t);
}

double Lights::fog_extinction(double z) const {
  const Fog& fog = environment.fog;
  return fog.density * std::exp(std::min(50.0, -(z - fog.base) / fog.height));
}

// sigma(s) = a exp(-b s) along the ray, with a the extinction at o and b = d_z / H, so the
// optical depth is a (1 - exp(-b s)) / b.
double Lights::optical_depth(const Vec3& o, const Vec3& d, double t) const {
  const double a = fog_extinction(o.z()), b = d.z() / environment.fog.height;
  if (std::abs(b) < 1e-12) return a * t;
  if (std::isinf(t)) return b > 0 ? a / b : std::numeric_limits<double>::infinity();
  return a * -std::expm1(-b * t) / b;
}

// With u = optical depth from o, the extinction at a point is sigma = a - b u and T = exp(-u);
// the sun reaches the point through the optical depth sigma H / s_z (s = the sun direction), so
//   sun: albedo E / (4 pi) * integral_0^U exp(-u) exp(-(a - b u) H / s_z) du
//      = albedo E / (4 pi) exp(-a H / s_z) (1 - exp(-c U)) / c,  c = 1 - d_z / s_z,
//   sky: albedo L_mean * integral_0^U exp(-u) du = albedo L_mean (1 - exp(-U)).
Rgb Lights::inscattered(const Vec3& o, const Vec3& d, double t) const {
  const Fog& fog = environment.fog;
  const double depth = optical_depth(o, d, t);
  const double scattered = std::isinf(depth) ? 1 : -std::expm1(-depth);
  Rgb light = sky_mean * scattered;
  const double sun_z = environment.sun_direction.z();
  if (sun_z > 1e-6) {
    // an infinite depth needs a level or falling ray, so c >= 1 there
    const double c = 1 - d.z() / sun_z, a = fog_extinction(o.z());
    const double integral = std::isinf(depth)            ? 1 / c
                            : std::abs(c) * depth < 1e-9 ? depth
                                                         : -std::expm1(-c * depth) / c;
    light += sun_irradiance * (std::exp(-a * fog.height / sun_z) * integral / (4 * kPi));
  }
  return light.cwiseProduct(fog.albedo.cast<double>());
}

}  // namespace flowscape
