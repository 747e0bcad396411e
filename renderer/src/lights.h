#pragma once
// Internal: the sun, the sky and the height fog of an Environment, with what every sample needs
// computed once per frame. The fog is integrated in closed form along every ray segment
// (transmittance and single scattering), so it adds no noise.
#include <Eigen/Core>

#include "flowscape/scenes/scene.h"

namespace flowscape {

using Rgb = Eigen::Vector3d;

struct Lights {
  explicit Lights(const Environment& environment);

  Rgb sky_radiance(const Vec3& d) const;
  // Radiance of the sun disc seen along d (irradiance spread over the disc's solid angle).
  Rgb sun_radiance(const Vec3& d) const;
  // A direction towards the sun disc, uniform over its solid angle.
  Vec3 sun_sample(Vec2 u) const;

  bool foggy() const { return environment.fog.density > 0; }
  // Optical depth of the fog along o + s d for s in [0, t] (t may be infinite).
  double optical_depth(const Vec3& o, const Vec3& d, double t) const;
  // Light the fog scatters towards o along the segment o + s d, s in [0, t] (single scattering of
  // the sun and of the sky's mean radiance; the sun's light is not shadowed inside the fog).
  Rgb inscattered(const Vec3& o, const Vec3& d, double t) const;

  const Environment& environment;
  Mat3 sun_frame;
  double sun_cos_radius;
  Rgb sun_irradiance, sun_disc_radiance, sky_mean;

 private:
  double fog_extinction(double z) const;
};

}  // namespace flowscape
