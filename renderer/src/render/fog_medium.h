#pragma once
// Internal: the fog as the path tracer's participating medium: an exponential height fog
// (scene.h's Fog) with closed-form optical depth, lit by single scattering of the sun and of the
// sky's mean radiance (the sun's light is not shadowed inside the fog).
#include <cmath>

#include "flowscape/scenes/scene.h"

namespace flowscape {

using Rgb = Eigen::Vector3d;

class FogMedium {
 public:
  FogMedium(const Fog& fog, const Vec3& sun_direction, const Rgb& sun_irradiance,
            const Rgb& sky_mean);

  bool present() const { return fog_.density > 0; }
  // Optical depth along o + s d for s in [0, t] (t may be infinite).
  double optical_depth(const Vec3& o, const Vec3& d, double t) const;
  // The share of light it lets through over that segment (1 without fog).
  double transmittance(const Vec3& o, const Vec3& d, double t) const {
    return present() ? std::exp(-optical_depth(o, d, t)) : 1;
  }
  // Light it scatters towards o along that segment, whose optical depth is `depth`.
  Rgb inscattered(const Vec3& o, const Vec3& d, double depth) const;

 private:
  double extinction(double z) const;
  Fog fog_;
  Vec3 sun_direction_;
  Rgb sun_irradiance_, sky_mean_;
};

}  // namespace flowscape
