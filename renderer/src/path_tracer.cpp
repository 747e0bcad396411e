// A unidirectional path tracer in the manner of Embree's tutorials, gathering its light in the
// layers a denoiser needs (ColorLayers).
#include "path_tracer.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>

#include "lights.h"
#include "sampling.h"
#include "surface.h"

namespace flowscape {
namespace {

constexpr double kFar = std::numeric_limits<double>::infinity();

// After a diffuse event a path's cone opens this wide (radians): what it sees next is looked up
// blurred, as the average over the many directions it could have taken.
constexpr double kScatteredSpread = 0.2;

enum Layer { kOther, kDirect, kIndirect, kSpecular, kLayerCount };

// The sky a path finds: sharp from the camera and its specular chains, averaged after a diffuse
// event (whose cone is wider than the average's blocks).
Rgb sky_seen(const Lights& lights, const Vec3& dir, bool scattered) {
  return scattered ? lights.scattered_sky_radiance(dir) : lights.sky_radiance(dir);
}

// What a vehicle's window mirrors: the sky above, and near the horizon, where buildings and
// traffic across the street hide the sky, the dim radiance of the dome below it (a pane would
// otherwise mirror the horizon's glare at the grazing angles it is seen at from the street).
Rgb mirrored_by_pane(const Lights& lights, const Vec3& dir, bool scattered) {
  const double open = std::clamp(dir.z() / 0.4, 0.0, 1.0);  // sin 24 degrees
  return open * sky_seen(lights, dir, scattered) +
         (1 - open) * lights.environment.ground.cast<double>();
}

struct PathState {
  Vec3 origin, dir;
  Rgb throughput = Rgb::Ones();
  Rgb light[kLayerCount] = {Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Zero()};
  Layer layer = kOther;  // where the light the path gathers now goes
  // How much a diffuse first surface's indirect light counts on this path; 0: the path stops there
  // (RenderOptions::indirect_samples).
  double indirect_weight = 1;
  Rgb albedo = Rgb::Zero();
  Vec3 normal = Vec3::Zero();
  // The ray's cone for texture filtering (ray cones): width at the origin (m) and spread (rad).
  double width = 0, spread = 0;
  // Whether it has scattered diffusely: its cone is then so wide that a texture filtered over it is
  // its material's mean, and the sky it finds the averaged dome.
  bool scattered = false;
  // Camera rays and specular chains from the camera may see the sun disc itself; after a diffuse
  // event the sun comes through next-event estimation only (no sun caustics: they would be rare,
  // huge fireflies at these sample counts).
  bool sun_visible = true;
  // After a diffuse event that may have sampled the sky as a light: the chance it did and the
  // normal the bounce was drawn about, for the MIS weight of the sky the bounce finds.
  double sky_chance = 0;
  Vec3 bounce_normal = Vec3::Zero();
};

// Next-event estimation: a shadow ray towards the sun (the moon at night) or a lamp, and the light
// it brings if unblocked.
struct SunRay {
  BundleRay ray;
  Rgb light = Rgb::Zero();
  Layer layer = kOther;
  double sky_chance = 0;  // how likely the event picked the sky: for a bounce's MIS weight
};

// Direct light from the sun on a diffuse surface (the sun is too small to hit by chance), seen
// through the fog.
SunRay sun_ray(const Lights& lights, const Surface& s, const Vec3& origin, const Rgb& throughput,
               Vec2 u, Layer layer) {
  if (lights.sun_irradiance.isZero()) return {};  // set below the horizon or behind clouds
  const Vec3 to_sun = lights.sun_sample(u);
  const double cos_n = to_sun.dot(s.normal);
  if (cos_n <= 0 || to_sun.dot(s.geometric) <= 0) return {};
  const double fog = lights.foggy() ? std::exp(-lights.optical_depth(origin, to_sun, kFar)) : 1;
  return {
      {origin, to_sun, true},
      throughput.cwiseProduct(s.albedo).cwiseProduct(lights.sun_irradiance) * (cos_n / kPi * fog),
      layer};
}

// Direct light from a lamp on a diffuse surface (the lamp picked for the point by LampLights).
SunRay lamp_ray(const Lights& lights, const LampLights::Sample& lamp, const Surface& s,
                const Vec3& origin, const Rgb& throughput, Layer layer) {
  const double cos_n = lamp.direction.dot(s.normal);
  if (lamp.irradiance.isZero() || cos_n <= 0 || lamp.direction.dot(s.geometric) <= 0) return {};
  const double fog =
      lights.foggy() ? std::exp(-lights.optical_depth(origin, lamp.direction, lamp.distance)) : 1;
  return {{origin, lamp.direction, true, float(lamp.distance * (1 - 1e-4))},
          throughput.cwiseProduct(s.albedo).cwiseProduct(lamp.irradiance) * (cos_n / kPi * fog),
          layer};
}

// The MIS weight (balance heuristic) of a strategy of density `own` against one of `other`.
double balance(double own, double other) { return own / (own + other); }

// Direct light from the sky dome on a diffuse surface, a direction drawn by SkySampler (chosen with
// probability `chance`), weighted against the cosine bounce about `bounce_normal` that may find the
// same sky. Into the indirect layer, where the sky's light always went.
SunRay sky_ray(const Lights& lights, const Surface& s, const Vec3& origin, const Rgb& throughput,
               Vec2 u, double chance, const Vec3& bounce_normal, Layer layer) {
  const Vec3 dir = lights.sky.sample(u);
  const double cos_n = dir.dot(s.normal);
  if (cos_n <= 0 || dir.dot(s.geometric) <= 0) return {};
  const double light_pdf = chance * lights.sky.pdf(dir);
  const double bounce_pdf = std::max(0.0, dir.dot(bounce_normal)) / kPi;
  const double fog = lights.foggy() ? std::exp(-lights.optical_depth(origin, dir, kFar)) : 1;
  const Rgb light =
      throughput.cwiseProduct(s.albedo).cwiseProduct(lights.scattered_sky_radiance(dir)) *
      (cos_n / kPi * fog / (light_pdf + bounce_pdf));
  return {{origin, dir, true}, light, layer == kDirect ? kIndirect : layer};
}

// One light for a diffuse event: the sun (the moon), a lamp (picked with u.x) or the sky dome, each
// with the probability of its share of the light on the surface, chosen with u.y, which the sun's
// and the sky's samples then reuse. The sky is sampled only where the sun does not shine on the
// surface (dusk, night, clouds over the sun, faces turned from it): under the sun its shadow rays
// stay the sun's, as before.
SunRay light_ray(const Lights& lights, const Surface& s, const Vec3& origin, const Rgb& throughput,
                 Vec2 u, const Vec3& bounce_normal, Layer layer) {
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
  SunRay ray;
  if (u.y() >= 1 - sky_chance) {
    u.y() = (u.y() - (1 - sky_chance)) / sky_chance;
    ray = sky_ray(lights, s, origin, throughput, u, sky_chance, bounce_normal, layer);
  } else {
    ray = lamp_ray(lights, lamp, s, origin, throughput / (1 - sun_chance - sky_chance), layer);
  }
  ray.sky_chance = sky_chance;  // whatever was picked: a bounce's sky is weighted by it
  return ray;
}

bool russian_roulette(int bounce, double u, Rgb& throughput) {  // whether the path survives
  if (bounce < 3) return true;
  const double keep = std::clamp(throughput.maxCoeff(), 0.05, 0.95);
  if (u >= keep) return false;
  throughput /= keep;
  return true;
}

// What every path of a frame shares.
struct FrameContext {
  const EmbreeScene& embree;
  const ImageTextures& images;
  const Lights& lights;
  bool textures;
};

// The fog between the path's origin and `distance` along it: the light it scatters in, and the
// light it lets through.
void cross_fog(const Lights& lights, double distance, PathState& path) {
  if (!lights.foggy()) return;
  path.light[path.layer] +=
      path.throughput.cwiseProduct(lights.inscattered(path.origin, path.dir, distance));
  path.throughput *= std::exp(-lights.optical_depth(path.origin, path.dir, distance));
}

// A diffuse event at s after the first surface: the sun ray, the albedo, a cosine-distributed new
// direction.
void scatter_diffusely(const Lights& lights, const Surface& s, const Vec3& above, Vec2 light_sample,
                       Vec2 lobe_sample, PathState& path, SunRay& sun) {
  sun = light_ray(lights, s, above, path.throughput, light_sample, s.normal, path.layer);
  path.sky_chance = sun.sky_chance, path.bounce_normal = s.normal;
  path.throughput = path.throughput.cwiseProduct(s.albedo);
  path.origin = above, path.dir = cosine_direction(s.normal, lobe_sample);
  path.sun_visible = false, path.spread = kScatteredSpread, path.scattered = true;
}

// One bounce of a path at `hit`: the fog before it, what the path sees (sky, sun disc, emission, a
// rain streak's glow), the sun ray, and the scattered direction. Directions follow the shading
// normal; a direction it sends below the geometric surface ends the path. Returns whether the path
// goes on.
bool advance(const FrameContext& frame, const Hit& hit, const TexturedLook* look, int bounce,
             Sampler& sampler, PathState& path, SunRay& sun) {
  const Lights& lights = frame.lights;
  Vec3 &origin = path.origin, &dir = path.dir;
  Rgb& throughput = path.throughput;
  const Vec2 light_sample = sampler.next(), lobe_sample = sampler.next(), choice = sampler.next();
  cross_fog(lights, hit.found ? hit.distance : kFar, path);
  if (!hit.found) {
    // the sky a diffuse bounce finds, weighted against the sky sampled as a light there
    const double weight = path.sky_chance > 0
                              ? balance(std::max(0.0, dir.dot(path.bounce_normal)) / kPi,
                                        path.sky_chance * lights.sky.pdf(dir))
                              : 1;
    path.light[path.layer] +=
        throughput.cwiseProduct(sky_seen(lights, dir, path.scattered) * weight +
                                (path.sun_visible ? lights.sun_radiance(dir) : Rgb::Zero()));
    return false;
  }
  path.width += path.spread * hit.distance;
  const Surface s = surface_at(frame.embree, hit, origin, dir, look);
  const Material& m = *s.material;
  const double offset = 1e-4 * (1 + s.position.norm());
  if (m.kind == Material::Kind::Streak) {  // glows with its opacity and lets the rest through
    path.light[path.layer] += throughput.cwiseProduct(m.emission.cast<double>()) * m.opacity;
    throughput *= 1 - m.opacity;
    origin = s.position + offset * dir;
    return true;
  }
  const bool first = path.layer == kOther;
  if (m.kind == Material::Kind::Window) {
    // what it mirrors (both faces' Fresnel reflection, taken whole rather than sampled: a
    // window would speckle otherwise), and straight through, tinted, to what lies behind: the
    // first surface then. Light scattered in from a dark cabin is too little to follow: paths that
    // bounced before end at the pane.
    const double f = schlick(std::abs(dir.dot(s.normal)), 0.04), reflected = 2 * f / (1 + f);
    path.light[first ? kSpecular : path.layer] +=
        throughput.cwiseProduct(mirrored_by_pane(lights, reflect(dir, s.normal), path.scattered)) *
        reflected;
    if (path.layer == kIndirect) return false;
    throughput = throughput.cwiseProduct(s.albedo) * (1 - reflected);
    origin = s.position + offset * dir;
    return true;
  }
  if (first) path.normal += s.smooth;
  if (m.kind == Material::Kind::Emissive) {
    // a glow-only body (a lamp's, a lit window): seen directly and in mirrors; a lamp's light on
    // surfaces comes from its point source (Scene::lamps), as the sun's does
    const Rgb glow = m.night_pattern ? Rgb(m.emission.cast<double>().cwiseProduct(s.albedo))
                                     : Rgb(m.emission.cast<double>());
    if (path.sun_visible || !m.glow_only) path.light[path.layer] += throughput.cwiseProduct(glow);
    return false;
  }
  const Vec3 above = s.position + offset * s.geometric, below = s.position - offset * s.geometric;
  const double cos_i = -dir.dot(s.normal);
  const double fresnel = m.kind == Material::Kind::Glossy ? schlick(cos_i, 0.04) : 0;
  const bool reflects_diffusely =
      m.kind == Material::Kind::Diffuse || m.kind == Material::Kind::Glossy;
  // At the first surface the diffuse part's direct light and albedo are taken whatever the path
  // does next; half the paths then take a glossy surface's coat, half its base.
  if (first && reflects_diffusely) {
    const Rgb diffuse_part = throughput * (1 - fresnel);
    sun = light_ray(lights, s, above, diffuse_part, light_sample, s.smooth, kDirect);
    path.albedo += diffuse_part.cwiseProduct(s.albedo);
  }
  bool diffuse = m.kind == Material::Kind::Diffuse, transmitted = false;
  if (m.kind == Material::Kind::Glossy) {
    const double coat = first ? 0.5 : fresnel;
    diffuse = choice.x() >= coat;
    throughput *= diffuse ? (1 - fresnel) / (1 - coat) : fresnel / coat;
  }
  if (diffuse && first) {  // the indirect light: on a share of the paths, weighted for all
    if (path.indirect_weight == 0) return false;
    throughput = throughput.cwiseProduct(s.albedo) * path.indirect_weight;
    path.layer = kIndirect;
    // about the smooth normal: a texture's relief shows in the sun's light, while the light from
    // everywhere else stays smooth for the denoiser
    origin = above, dir = cosine_direction(s.smooth, lobe_sample);
    path.sun_visible = false, path.spread = kScatteredSpread, path.scattered = true;
    path.sky_chance = sun.sky_chance, path.bounce_normal = s.smooth;
  } else if (diffuse) {
    scatter_diffusely(lights, s, above, light_sample, lobe_sample, path, sun);
  } else {
    path.sky_chance = 0;  // a specular event: the sky it finds is not sampled as a light
    if (first) path.layer = kSpecular;
    if (m.kind == Material::Kind::Glass) {
      const double eta = s.front ? 1 / 1.5 : 1.5;
      if (choice.x() < dielectric_fresnel(cos_i, eta)) {
        origin = above, dir = reflect(dir, s.normal);
      } else {
        const double cos_t = std::sqrt(1 - eta * eta * (1 - cos_i * cos_i));
        origin = below, dir = (eta * dir + (eta * cos_i - cos_t) * s.normal).normalized();
        transmitted = true;
      }
    } else {  // Metal, or the clear coat of Glossy: a mirror blurred by the roughness
      if (m.kind == Material::Kind::Metal) throughput = throughput.cwiseProduct(s.albedo);
      dir = (reflect(dir, s.normal) + s.roughness * cosine_direction(s.normal, lobe_sample))
                .normalized();
      origin = above, path.spread += s.roughness;
    }
  }
  if ((dir.dot(s.geometric) > 0) == transmitted) return false;
  return russian_roulette(bounce, choice.y(), throughput);
}

// The textured looks of the camera hits of one pixel: one evaluation per triangle its samples hit,
// where the pixel centre's ray meets that triangle's plane, filtered over the pixel's footprint
// there (as a mip-mapped texture lookup is). The samples hitting that triangle share it, so a
// texture costs one evaluation per pixel and surface rather than one per sample, and a textured
// pixel does not flicker with its samples' jitter.
class PixelLooks {
 public:
  PixelLooks(const FrameContext& frame, const Vec3& origin, const Vec3& centre, double spread)
      : frame_(frame), origin_(origin), centre_(centre), spread_(spread) {}

  const TexturedLook& at(const Hit& hit, const Vec3& sample_dir) {
    for (int k = 0; k < count_; ++k)
      if (entries_[k].mesh == hit.mesh && entries_[k].triangle == hit.triangle)
        return entries_[k].look;
    const int slot = count_ < kSlots ? count_++ : kSlots - 1;  // the last slot is reused
    entries_[slot] = {hit.mesh, hit.triangle, look_at_centre(hit, sample_dir)};
    return entries_[slot].look;
  }

 private:
  TexturedLook look_at_centre(const Hit& hit, const Vec3& sample_dir) const {
    const EmbreeScene& embree = frame_.embree;
    const Pose& pose = embree.pose_now(hit.mesh);
    const Vec3 normal = pose.linear() * hit.normal.cast<double>();
    const Mesh& mesh = *embree.mesh(hit.mesh).mesh;
    const Vec3 corner = pose * mesh.vertices[mesh.triangles[hit.triangle][0]].cast<double>();
    const double facing = normal.dot(centre_), t = normal.dot(corner - origin_) / facing;
    if (t > 0 && std::isfinite(t) && t < 4 * hit.distance + 1)
      return textured_look(embree, frame_.images, hit, origin_ + t * centre_, centre_, spread_ * t);
    return textured_look(embree, frame_.images, hit, origin_ + hit.distance * sample_dir,
                         sample_dir, spread_ * hit.distance);
  }

  static constexpr int kSlots = 8;
  struct Entry {
    unsigned mesh, triangle;
    TexturedLook look;
  };
  const FrameContext& frame_;
  Vec3 origin_, centre_;
  double spread_;
  Entry entries_[kSlots];
  int count_ = 0;
};

// Traces up to kBundleSize paths in lock step, one Embree packet per bounce and one for the sun
// rays: the samples of one pixel (or of a few neighbours) stay coherent for the camera rays and
// the first sun rays. camera_looks: each path's pixel's.
void trace_bundle(const FrameContext& frame, PixelLooks* const* camera_looks, PathState* paths,
                  Sampler* samplers, int count, int max_bounces, std::uint64_t& rays) {
  const EmbreeScene& embree = frame.embree;
  BundleRay bundle[kBundleSize];
  Hit hits[kBundleSize];
  SunRay sun[kBundleSize];
  bool blocked[kBundleSize];
  // a sample outside a lens's image has no ray (zero) and no light
  for (int i = 0; i < count; ++i)
    bundle[i] = {paths[i].origin, paths[i].dir, !paths[i].dir.isZero()};
  for (int bounce = 0; bounce <= max_bounces; ++bounce) {
    const int alive = int(std::count_if(bundle, bundle + count, [](auto& r) { return r.active; }));
    if (alive == 0) break;
    embree.intersect(bundle, count, hits);
    rays += alive;
    for (int i = 0; i < count; ++i) {
      sun[i] = {};
      if (!bundle[i].active) continue;
      const TexturedLook* look = nullptr;
      TexturedLook own;  // a specular chain's hit: its own point
      if (frame.textures && hits[i].found && !paths[i].scattered && is_textured(embree, hits[i])) {
        if (bounce == 0) {
          look = &camera_looks[i]->at(hits[i], paths[i].dir);
        } else {
          own = textured_look(embree, frame.images, hits[i],
                              paths[i].origin + hits[i].distance * paths[i].dir, paths[i].dir,
                              paths[i].width + paths[i].spread * hits[i].distance);
          look = &own;
        }
      }
      bundle[i].active = advance(frame, hits[i], look, bounce, samplers[i], paths[i], sun[i]);
      bundle[i].origin = paths[i].origin, bundle[i].direction = paths[i].dir;
    }
    BundleRay sun_rays[kBundleSize];
    for (int i = 0; i < count; ++i) sun_rays[i] = sun[i].ray, rays += sun[i].ray.active;
    embree.occluded(sun_rays, count, blocked);
    for (int i = 0; i < count; ++i)
      if (sun[i].ray.active && !blocked[i]) paths[i].light[sun[i].layer] += sun[i].light;
  }
}

void put(Image<float>& image, int x, int y, const Rgb& value) {
  for (int c = 0; c < 3; ++c) image.pixel(x, y)[c] = float(value[c]);
}

// One pixel's samples: their keys, camera rays and textured looks, and what they gathered.
struct PixelSamples {
  PixelSamples(const FrameContext& frame, const Projection& projection, const Pose& camera,
               std::uint64_t seed, int x, int y)
      : keys(mix_bits(seed ^ mix_bits((std::uint64_t(y) << 32) | unsigned(x)))),
        camera_rays(projection, x, y),
        spread(projection.pixel_spread(Vec2(x + 0.5, y + 0.5))),
        looks(frame, camera.translation(), (camera.linear() * camera_rays({0.5, 0.5})).normalized(),
              spread) {}

  void add(const PathState& path) {
    for (int l = 0; l < kLayerCount; ++l) sums[l] += path.light[l];
    for (int l = kDirect; l <= kSpecular; ++l)
      squares[l - kDirect] += std::pow(luminance(path.light[l]), 2);
    albedo += path.albedo, normal += path.normal;
  }
  // The means of `samples` into the layers at (x, y), with the variance of each noisy layer's mean.
  void put_means(int samples, ColorLayers& out, int x, int y) const {
    Image<float>* layers[kLayerCount] = {&out.other, &out.direct, &out.indirect, &out.specular};
    const double weight = 1.0 / std::max(1, samples);
    for (int l = 0; l < kLayerCount; ++l) put(*layers[l], x, y, sums[l] * weight);
    put(out.albedo, x, y, albedo * weight);
    put(out.normal, x, y, normal);
    Rgb variance;
    for (int l = kDirect; l <= kSpecular; ++l) {
      const double mean = luminance(sums[l]) * weight;
      variance[l - kDirect] = std::max(0.0, squares[l - kDirect] * weight - mean * mean) * weight;
    }
    put(out.variance, x, y, variance);
  }

  Sampler::PixelKeys keys;
  PixelRays camera_rays;
  double spread;
  PixelLooks looks;
  Rgb sums[kLayerCount] = {Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Zero()};
  Rgb squares = Rgb::Zero();  // of the luminance of direct, indirect, specular
  Rgb albedo = Rgb::Zero();
  Vec3 normal = Vec3::Zero();
};

// Traces neighbouring pixels of a row together: as many as fill a bundle with all their samples
// (two at 8 spp), so their camera and first light rays share Embree packets. Each pixel's samples
// and their order are its own, so a pixel's colour does not depend on its neighbours.
struct PixelGroupTracer {
  const FrameContext& frame;
  const Projection& projection;
  const Pose& camera;
  const RenderOptions& options;

  void trace(int y, int x0, int x1, ColorLayers& out, std::uint64_t& rays) const {
    const int spp = options.samples_per_pixel;
    std::optional<PixelSamples> group[kBundleSize];
    for (int x = x0; x < x1; ++x)
      group[x - x0].emplace(frame, projection, camera, options.seed, x, y);
    const int chunk = std::min(spp, kBundleSize);
    for (int first = 0; first < spp; first += chunk) {
      const int per_pixel = std::min(chunk, spp - first);
      Sampler samplers[kBundleSize];
      PathState paths[kBundleSize];
      PixelLooks* looks[kBundleSize];
      int lane = 0;
      for (int x = x0; x < x1; ++x)
        for (int i = 0; i < per_pixel; ++i, ++lane)
          start(*group[x - x0], first + i, lane, samplers, paths, looks);
      naming_pixels(
          [&] { trace_bundle(frame, looks, paths, samplers, lane, options.max_bounces, rays); },
          [&](int of) {
            return std::pair{x0 + of / per_pixel, y};
          });
      lane = 0;
      for (int x = x0; x < x1; ++x)
        for (int i = 0; i < per_pixel; ++i) group[x - x0]->add(paths[lane++]);
    }
    for (int x = x0; x < x1; ++x) group[x - x0]->put_means(spp, out, x, y);
  }

 private:
  // Sets up sample `index` of `pixel` in bundle lane `lane`.
  void start(PixelSamples& pixel, int index, int lane, Sampler* samplers, PathState* paths,
             PixelLooks** looks) const {
    samplers[lane] = Sampler(pixel.keys, index, options.samples_per_pixel);
    PathState& path = paths[lane];
    path.origin = camera.translation();
    path.dir = (camera.linear() * pixel.camera_rays(samplers[lane].next())).normalized();
    path.spread = pixel.spread;
    path.indirect_weight = indirect_weight(index);
    looks[lane] = &pixel.looks;
  }
  // How much sample `index`'s indirect light counts (RenderOptions::indirect_samples).
  double indirect_weight(int index) const {
    const int indirect = options.indirect_samples, spp = options.samples_per_pixel;
    if (indirect <= 0 || indirect >= spp) return 1;
    return index < indirect ? double(spp) / indirect : 0;
  }
};

// RenderOptions::pixels: whether (x, y) is traced, and the first traced pixel of row y from x on.
bool traced(ImageView<const std::uint8_t> pixels, int x, int y) {
  return !pixels.data || *pixels.pixel(x, y);
}
int next_traced(ImageView<const std::uint8_t> pixels, int y, int x, int end) {
  while (x < end && !traced(pixels, x, y)) ++x;
  return x;
}

}  // namespace

ColorLayers color_layers_of(int width, int height) {
  const int W = width, H = height;
  return {Image<float>(W, H, 3), Image<float>(W, H, 3), Image<float>(W, H, 3),
          Image<float>(W, H, 3), Image<float>(W, H, 3), Image<float>(W, H, 3),
          Image<float>(W, H, 3)};
}

std::uint64_t path_trace(EmbreeScene& embree, const ImageTextures& images, const Lights& lights,
                         const Projection& projection, const Pose& camera,
                         const RenderOptions& options, const PixelWindow& window,
                         ColorLayers& out) {
  std::atomic<std::uint64_t> rays{0};
  const FrameContext frame{embree, images, lights, options.textures};
  const PixelGroupTracer tracer{frame, projection, camera, options};
  const int group_size = std::max(1, kBundleSize / std::max(1, options.samples_per_pixel));
  // 2-D blocks: a rolling shutter's window is a single line
  const tbb::blocked_range2d<int> pixels(window.y0, window.y1, window.x0, window.x1);
  tbb::parallel_for(pixels, [&](const tbb::blocked_range2d<int>& block) {
    std::uint64_t block_rays = 0;
    const int end = block.cols().end();
    for (int y = block.rows().begin(); y < block.rows().end(); ++y)
      for (int x = next_traced(options.pixels, y, block.cols().begin(), end); x < end;) {
        int group_end = x + 1;
        while (group_end < std::min(x + group_size, end) && traced(options.pixels, group_end, y))
          ++group_end;
        tracer.trace(y, x, group_end, out, block_rays);
        x = next_traced(options.pixels, y, group_end, end);
      }
    rays += block_rays;
  });
  return rays;
}

}  // namespace flowscape
