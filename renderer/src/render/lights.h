#pragma once
// Internal: the sun, the sky, the lamps and the air (the fog, fog_medium.h) of a scene, with what
// every sample needs computed once per frame. The fog is integrated in closed form along every ray
// segment (transmittance and single scattering), so it adds no noise.
#include <Eigen/Core>
#include <vector>

#include "flowscape/scenes/scene.h"
#include "render/fog_medium.h"

namespace flowscape {

using Rgb = Eigen::Vector3d;

inline double luminance(const Rgb& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

// The lamps of a frame (Scene::lamps) posed at its time, and one picked for a point: a grid of
// 16 m cells over the ground lists the lamps whose light reaches each cell above a floor; a point
// picks one of its cell's lamps in proportion to the irradiance it would give there (intensity x
// beam x cosine on the surface / distance^2: on a diffuse surface, the light itself), so hundreds
// of lamps cost a handful of weights per shading point.
class LampLights {
 public:
  LampLights(const Scene& scene, double time);
  bool empty() const { return lamps_.empty(); }
  struct Sample {
    Vec3 direction = Vec3::Zero();  // towards the lamp (unit)
    double distance = 0;
    Rgb irradiance = Rgb::Zero();  // on a surface facing the lamp, over the pick's probability
    double total = 0;  // the weights of all the point's lamps: about the lamps' irradiance there
  };
  // A lamp for `point` on a surface facing `normal`, picked with u in [0, 1); none (zero
  // irradiance) where no lamp reaches.
  Sample sample(const Vec3& point, const Vec3& normal, double u) const;

 private:
  struct Posed {
    Vec3 position, axis;
    double cos_inner, cos_outer;
    Rgb intensity;
    double reach;  // metres within which it lights a point
  };
  double beam(const Posed& lamp, const Vec3& from_lamp) const;
  bool may_light(const Posed& lamp, const Vec2& cell_lo, double lowest) const;
  const std::vector<int>* cell_of(const Vec3& point) const;
  std::vector<Posed> lamps_;
  Vec2 origin_ = Vec2::Zero();
  int columns_ = 0, rows_ = 0;
  std::vector<std::vector<int>> cells_;
};

// The sky dome as scattered light sees it (only a scene with a SkyDome has one): the dome averaged
// over blocks of up to 8 x 8 cells (2.25 degrees at the release's 320 x 1280 dome, a tenth of the
// cone a diffuse bounce opens), which stays in the cache where the full table does not; and as a
// light: a cell of it picked in proportion to its luminance times its solid angle, a direction
// uniform over the cell's solid angle (pbrt's piecewise-constant environment sampling).
class SkySampler {
 public:
  // average false: the dome's own cells (TracingBaseline::full_sky_when_scattered)
  explicit SkySampler(const SkyDome* dome, bool average = true);
  bool empty() const { return dome_.radiance.empty(); }
  Rgb radiance(const Vec3& d) const;  // d.z() >= 0: the averaged dome's
  Vec3 sample(Vec2 u) const;
  double pdf(const Vec3& d) const;                             // per steradian; 0 below the horizon
  double level_luminance() const { return level_luminance_; }  // on a level surface

 private:
  double cell_solid_angle(int row) const;
  SkyDome dome_;                    // the averaged one
  std::vector<double> cumulative_;  // over the cells, row-major, ending at 1
  std::vector<double> row_ends_;    // cumulative_ at each row's last cell: searched first
  double level_luminance_ = 0;
};

struct Lights {
  Lights(const Scene& scene, double time, bool average_sky = true);  // SkySampler's average

  Rgb sky_radiance(const Vec3& d) const;
  // The same as a path sees it after a diffuse event: SkySampler's averaged dome.
  Rgb scattered_sky_radiance(const Vec3& d) const;
  // Radiance of the sun disc seen along d (irradiance spread over the disc's solid angle).
  Rgb sun_radiance(const Vec3& d) const;
  // A direction towards the sun disc, uniform over its solid angle.
  Vec3 sun_sample(Vec2 u) const;

  const Environment& environment;
  LampLights lamps;
  SkySampler sky;
  Mat3 sun_frame;
  double sun_cos_radius;
  Rgb sun_irradiance, sun_disc_radiance, sky_mean;
  FogMedium fog;  // the air between (fog_medium.h)

 private:
  static Eigen::Vector3f upper_mean(const Environment& environment);
};

}  // namespace flowscape
