// The lobes the materials share: diffuse reflection and a rough mirror.
#include "render/bsdf.h"
#include "render/light_sampler.h"
#include "render/sampling.h"

namespace flowscape {

void first_diffuse_light(const SurfaceEvent& e, const Rgb& diffuse_part, PathState& path,
                         ShadowRay& shadow) {
  shadow =
      sample_light(e.lights, e.s, e.above(), diffuse_part, e.light_sample, e.s.smooth, kDirect);
  path.albedo += diffuse_part.cwiseProduct(e.s.albedo);
}

Turn diffuse_lobe(const SurfaceEvent& e, PathState& path, ShadowRay& shadow) {
  const Surface& s = e.s;
  if (e.first) {
    if (path.indirect_weight == 0) return Turn::Ends;
    path.throughput = path.throughput.cwiseProduct(s.albedo) * path.indirect_weight;
    path.layer = kIndirect;
    // about the smooth normal: a texture's relief shows in the sun's light, while the light from
    // everywhere else stays smooth for the denoiser
    path.origin = e.above(), path.dir = cosine_direction(s.smooth, e.lobe_sample);
    path.sky_chance = shadow.sky_chance, path.bounce_normal = s.smooth;
  } else {
    shadow =
        sample_light(e.lights, s, e.above(), path.throughput, e.light_sample, s.normal, path.layer);
    path.sky_chance = shadow.sky_chance, path.bounce_normal = s.normal;
    path.throughput = path.throughput.cwiseProduct(s.albedo);
    path.origin = e.above(), path.dir = cosine_direction(s.normal, e.lobe_sample);
  }
  path.sun_visible = false, path.spread = kScatteredSpread, path.scattered = true;
  return Turn::Reflected;
}

void begin_specular(const SurfaceEvent& e, PathState& path) {
  path.sky_chance = 0;
  if (e.first) path.layer = kSpecular;
}

Turn rough_mirror(const SurfaceEvent& e, PathState& path) {
  const Surface& s = e.s;
  path.dir = (reflect(path.dir, s.normal) + s.roughness * cosine_direction(s.normal, e.lobe_sample))
                 .normalized();
  path.origin = e.above(), path.spread += s.roughness;
  return Turn::Reflected;
}

}  // namespace flowscape
