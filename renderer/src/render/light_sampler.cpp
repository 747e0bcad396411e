// Next-event estimation over the sun (the moon), the lamp grid and the sky dome.
#include "render/light_sampler.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace flowscape {
namespace {

constexpr double kFar = std::numeric_limits<double>::infinity();

// Direct light from the sun on a diffuse surface (the sun is too small to hit by chance), seen
// through the fog.
ShadowRay sun_ray(const Lights& lights, const Surface& s, const Vec3& origin, const Rgb& throughput,
                  Vec2 u, Layer layer) {
  if (lights.sun_irradiance.isZero()) return {};  // set below the horizon or behind clouds
  const Vec3 to_sun = lights.sun_sample(u);
  const double cos_n = to_sun.dot(s.normal);
  if (cos_n <= 0 || to_sun.dot(s.geometric) <= 0) return {};
  const double fog = lights.fog.transmittance(origin, to_sun, kFar);
  return {
      {origin, to_sun, true},
      throughput.cwiseProduct(s.albedo).cwiseProduct(lights.sun_irradiance) * (cos_n / kPi * fog),
      layer};
}

// Direct light from a lamp on a diffuse surface (the lamp picked for the point by LampLights).
ShadowRay lamp_ray(const Lights& lights, const LampLights::Sample& lamp, const Surface& s,
                   const Vec3& origin, const Rgb& throughput, Layer layer) {
  const double cos_n = lamp.direction.dot(s.normal);
  if (lamp.irradiance.isZero() || cos_n <= 0 || lamp.direction.dot(s.geometric) <= 0) return {};
  const double fog = lights.fog.transmittance(origin, lamp.direction, lamp.distance);
  return {{origin, lamp.direction, true, float(lamp.distance * (1 - 1e-4))},
          throughput.cwiseProduct(s.albedo).cwiseProduct(lamp.irradiance) * (cos_n / kPi * fog),
          layer};
}

// The MIS weight (balance heuristic) of a strategy of density `own` against one of `other`.
double balance(double own, double other) { return own / (own + other); }

// Direct light from the sky dome on a diffuse surface, a direction drawn by SkySampler (chosen with
// probability `chance`), weighted against the cosine bounce about `bounce_normal` that may find the
// same sky. Into the indirect layer, where the sky's light always went.
ShadowRay sky_ray(const Lights& lights, const Surface& s, const Vec3& origin, const Rgb& throughput,
                  Vec2 u, double chance, const Vec3& bounce_normal, Layer layer) {
  const Vec3 dir = lights.sky.sample(u);
  const double cos_n = dir.dot(s.normal);
  if (cos_n <= 0 || dir.dot(s.geometric) <= 0) return {};
  const double light_pdf = chance * lights.sky.pdf(dir);
  const double bounce_pdf = std::max(0.0, dir.dot(bounce_normal)) / kPi;
  const double fog = lights.fog.transmittance(origin, dir, kFar);
  const Rgb light =
      throughput.cwiseProduct(s.albedo).cwiseProduct(lights.scattered_sky_radiance(dir)) *
      (cos_n / kPi * fog / (light_pdf + bounce_pdf));
  return {{origin, dir, true}, light, layer == kDirect ? kIndirect : layer};
}

}  // namespace

Rgb sky_seen(const Lights& lights, const Vec3& dir, bool scattered) {
  return scattered ? lights.scattered_sky_radiance(dir) : lights.sky_radiance(dir);
}

ShadowRay sample_light(const Lights& lights, const Surface& s, const Vec3& origin,
                       const Rgb& throughput, Vec2 u, const Vec3& bounce_normal, Layer layer) {
  const double sun_share = luminance(lights.sun_irradiance) *
                           std::max(0.0, s.normal.dot(lights.environment.sun_direction));
  const bool sky = !lights.sky.empty() && sun_share == 0;
  if (lights.lamps.empty() && !sky) return sun_ray(lights, s, origin, throughput, u, layer);
  const LampLights::Sample lamp =
      lights.lamps.empty() ? LampLights::Sample{} : lights.lamps.sample(origin, s.normal, u.x());
  const double sky_share = sky ? lights.sky.level_luminance() * (1 + s.normal.z()) / 2 : 0;
  const double total = sun_share + lamp.total + sky_share;
  if (!(total > 0)) return {};
  const double sun_chance = sun_share / total, sky_chance = sky_share / total;
  if (u.y() < sun_chance) {
    u.y() /= sun_chance;
    return sun_ray(lights, s, origin, throughput / sun_chance, u, layer);
  }
  ShadowRay ray;
  if (u.y() >= 1 - sky_chance) {
    u.y() = (u.y() - (1 - sky_chance)) / sky_chance;
    ray = sky_ray(lights, s, origin, throughput, u, sky_chance, bounce_normal, layer);
  } else {
    ray = lamp_ray(lights, lamp, s, origin, throughput / (1 - sun_chance - sky_chance), layer);
  }
  ray.sky_chance = sky_chance;  // whatever was picked: a bounce's sky is weighted by it
  return ray;
}

double found_sky_weight(const Lights& lights, const PathState& path, const Vec3& dir) {
  if (!(path.sky_chance > 0)) return 1;
  return balance(std::max(0.0, dir.dot(path.bounce_normal)) / kPi,
                 path.sky_chance * lights.sky.pdf(dir));
}

}  // namespace flowscape
