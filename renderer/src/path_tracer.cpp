// A unidirectional path tracer in the manner of Embree's tutorials.
#include "path_tracer.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "flowscape/core/random.h"
#include "surface.h"

namespace flowscape {
namespace {

double unit(std::uint64_t bits) { return double(bits >> 11) * 0x1.0p-53; }

// The Cranley-Patterson rotation of each pair of sample dimensions in one pixel: a hash of the
// pixel, the seed and the pair.
void pixel_shifts(std::uint64_t pixel_key, std::vector<Vec2>& shifts) {
  for (std::size_t p = 0; p < shifts.size(); ++p) {
    const std::uint64_t h = mix_bits(pixel_key ^ mix_bits(std::uint64_t(p + 1)));
    shifts[p] = {unit(h), unit(mix_bits(h))};
  }
}

// Sample `index` of a pixel: the R2 sequence (Roberts 2018) for each pair of dimensions, shifted
// by the pixel's rotation of that pair.
class Sampler {
 public:
  Sampler() = default;
  Sampler(const std::vector<Vec2>& shifts, int index) : shifts_(&shifts), index_(index) {}
  Vec2 next() {
    constexpr double kA1 = 0.7548776662466927, kA2 = 0.5698402909980532;  // 1/phi2, 1/phi2^2
    const Vec2 shift = (*shifts_)[pair_++];
    const double n = index_ + 1;
    const double a = shift.x() + n * kA1, b = shift.y() + n * kA2;
    return {a - std::floor(a), b - std::floor(b)};
  }

 private:
  const std::vector<Vec2>* shifts_ = nullptr;
  int index_ = 0, pair_ = 0;
};

// Orthonormal frame around n (Duff et al. 2017).
Mat3 frame_around(const Vec3& n) {
  const double sign = std::copysign(1.0, n.z()), a = -1 / (sign + n.z()), b = n.x() * n.y() * a;
  Mat3 m;
  m.col(0) = Vec3(1 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  m.col(1) = Vec3(b, sign + n.y() * n.y() * a, -n.y());
  m.col(2) = n;
  return m;
}

Vec3 cosine_direction(const Vec3& n, Vec2 u) {
  const double r = std::sqrt(u.x());
  const SinCos phi = sin_cos(2 * kPi * u.y());
  return frame_around(n) * Vec3(r * phi.cos, r * phi.sin, std::sqrt(std::max(0.0, 1 - u.x())));
}

Vec3 uniform_direction(Vec2 u) {
  const double z = 1 - 2 * u.x(), r = std::sqrt(std::max(0.0, 1 - z * z));
  const SinCos phi = sin_cos(2 * kPi * u.y());
  return {r * phi.cos, r * phi.sin, z};
}

Vec3 reflect(const Vec3& d, const Vec3& n) { return d - 2 * d.dot(n) * n; }

double schlick(double cos_i, double f0) {
  const double m = 1 - cos_i, m2 = m * m;
  return f0 + (1 - f0) * m2 * m2 * m;
}

// Fresnel reflectance of a smooth dielectric; 1 for total internal reflection.
double dielectric_fresnel(double cos_i, double eta) {  // eta = n_incident / n_transmitted
  const double sin2_t = eta * eta * (1 - cos_i * cos_i);
  if (sin2_t >= 1) return 1;
  const double cos_t = std::sqrt(1 - sin2_t);
  const double rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const double rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return (rs * rs + rp * rp) / 2;
}

// The sun and sky of an Environment, with what every sample needs computed once.
struct Lights {
  explicit Lights(const Environment& e)
      : environment(e),
        sun_frame(frame_around(e.sun_direction)),
        sun_cos_radius(std::cos(e.sun_angular_radius)),
        sun_irradiance(e.sun_irradiance.cast<double>()),
        sun_disc_radiance(sun_irradiance * e.sun_disc_visibility /
                          (2 * kPi * (1 - sun_cos_radius))) {}

  Rgb sky_radiance(const Vec3& d) const {
    if (d.z() < 0) return environment.ground.cast<double>();
    const double t = std::sqrt(d.z());
    return ((1 - t) * environment.sky_horizon + t * environment.sky_zenith).cast<double>();
  }
  // Radiance of the sun disc seen along d (irradiance spread over the disc's solid angle).
  Rgb sun_radiance(const Vec3& d) const {
    return d.dot(environment.sun_direction) < sun_cos_radius ? Rgb::Zero() : sun_disc_radiance;
  }
  // A direction towards the sun disc, uniform over its solid angle.
  Vec3 sun_sample(Vec2 u) const {
    const double cos_t = 1 - u.x() * (1 - sun_cos_radius), sin_t = std::sqrt(1 - cos_t * cos_t);
    const SinCos phi = sin_cos(2 * kPi * u.y());
    return sun_frame * Vec3(sin_t * phi.cos, sin_t * phi.sin, cos_t);
  }

  bool foggy() const { return environment.fog.density > 0; }
  // Optical depth of the fog along o + s d for s in [0, t] (t may be infinite).
  double optical_depth(const Vec3& o, const Vec3& d, double t) const {
    const Fog& fog = environment.fog;
    const double k = 1 / fog.height, a = fog_extinction(o.z()), b = k * d.z();
    if (std::abs(b) < 1e-12) return a * t;
    if (std::isinf(t)) return b > 0 ? a / b : std::numeric_limits<double>::infinity();
    return a * -std::expm1(-b * t) / b;
  }
  // Distance to a scattering event along o + s d for a uniform u in [0, 1); infinity for none.
  double free_flight(const Vec3& o, const Vec3& d, double u) const {
    const double k = 1 / environment.fog.height, a = fog_extinction(o.z()), b = k * d.z();
    const double depth = -std::log1p(-u);  // exponentially distributed optical depth
    if (std::abs(b) < 1e-12) return depth / a;
    const double x = depth * b / a;
    if (x >= 1) return std::numeric_limits<double>::infinity();  // leaves the fog upwards first
    return -std::log1p(-x) / b;
  }
  double fog_extinction(double z) const {
    const Fog& fog = environment.fog;
    return fog.density * std::exp(std::min(50.0, -(z - fog.base) / fog.height));
  }

  const Environment& environment;
  Mat3 sun_frame;
  double sun_cos_radius;
  Rgb sun_irradiance, sun_disc_radiance;
};

constexpr double kFar = std::numeric_limits<double>::infinity();

// After a diffuse or fog event a path's cone opens this wide (radians): what it sees next is
// looked up blurred, as the average over the many directions it could have taken.
constexpr double kScatteredSpread = 0.2;

struct PathState {
  Vec3 origin, dir;
  Rgb radiance = Rgb::Zero(), throughput = Rgb::Ones();
  // The ray's cone for texture filtering (ray cones): width at the origin (m) and spread (rad).
  double width = 0, spread = 0;
  // Whether what it meets is textured: after a diffuse or fog event the cone is so wide that a
  // texture filtered over it is its material's mean.
  bool textured = true;
  // Camera rays and specular chains from the camera may see the sun disc itself; after a diffuse
  // or fog event the sun comes through next-event estimation only (no sun caustics: they would be
  // rare, huge fireflies at these sample counts).
  bool sun_visible = true;
};

// Next-event estimation: a shadow ray towards the sun and the light it brings if unblocked.
struct SunRay {
  BundleRay ray;
  Rgb light = Rgb::Zero();
};

// Direct light from the sun on a diffuse surface (the sun is too small to hit by chance).
SunRay sun_ray(const Lights& lights, const Surface& s, const Vec3& origin, const Rgb& throughput,
               Vec2 u) {
  const Vec3 to_sun = lights.sun_sample(u);
  const double cos_n = to_sun.dot(s.normal);
  if (cos_n <= 0 || to_sun.dot(s.geometric) <= 0) return {};
  const double fog = lights.foggy() ? std::exp(-lights.optical_depth(origin, to_sun, kFar)) : 1;
  return {
      {origin, to_sun, true},
      throughput.cwiseProduct(s.albedo).cwiseProduct(lights.sun_irradiance) * (cos_n / kPi * fog)};
}

// A scattering event in the fog at `point`: the sun seen through the fog (isotropic phase
// 1 / 4 pi), then a new direction uniform over the sphere.
void scatter_in_fog(const Lights& lights, const Vec3& point, Vec2 light_sample, Vec2 lobe_sample,
                    PathState& path, SunRay& sun) {
  path.throughput = path.throughput.cwiseProduct(lights.environment.fog.albedo.cast<double>());
  const Vec3 to_sun = lights.sun_sample(light_sample);
  const double fog = std::exp(-lights.optical_depth(point, to_sun, kFar));
  sun = {{point, to_sun, true},
         path.throughput.cwiseProduct(lights.sun_irradiance) * (fog / (4 * kPi))};
  path.origin = point, path.dir = uniform_direction(lobe_sample), path.sun_visible = false;
  path.spread = kScatteredSpread, path.textured = false;
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

// One bounce of a path at `hit`: a scattering event in the fog before it, or what the path sees
// (sky, sun disc, emission, a rain streak), the sun ray, and the scattered direction. Directions
// follow the shading normal; a direction it sends below the geometric surface ends the path.
// Returns whether the path goes on.
bool advance(const FrameContext& frame, const Hit& hit, const TexturedLook* look, int bounce,
             Sampler& sampler, PathState& path, SunRay& sun) {
  const Lights& lights = frame.lights;
  Vec3 &origin = path.origin, &dir = path.dir;
  Rgb& throughput = path.throughput;
  const Vec2 flight = sampler.next(), light_sample = sampler.next(), lobe_sample = sampler.next(),
             choice = sampler.next();
  if (lights.foggy()) {
    const double distance = lights.free_flight(origin, dir, flight.x());
    if (distance < hit.distance) {
      path.width += path.spread * distance;
      scatter_in_fog(lights, origin + distance * dir, light_sample, lobe_sample, path, sun);
      return russian_roulette(bounce, choice.y(), throughput);
    }
  }
  if (!hit.found) {
    path.radiance += throughput.cwiseProduct(
        lights.sky_radiance(dir) + (path.sun_visible ? lights.sun_radiance(dir) : Rgb::Zero()));
    return false;
  }
  path.width += path.spread * hit.distance;
  const Surface s = surface_at(frame.embree, hit, origin, dir, look);
  const Material& m = *s.material;
  const double offset = 1e-4 * (1 + s.position.norm());
  if (m.kind == Material::Kind::Emissive ||
      (m.kind == Material::Kind::Streak && choice.x() < m.opacity)) {
    path.radiance += throughput.cwiseProduct(m.emission.cast<double>());
    return false;
  }
  if (m.kind == Material::Kind::Streak) {  // light passes the streak
    origin = s.position + offset * dir;
    return true;
  }
  const Vec3 above = s.position + offset * s.geometric, below = s.position - offset * s.geometric;
  const double cos_i = -dir.dot(s.normal);
  bool transmitted = false;
  bool diffuse = m.kind == Material::Kind::Diffuse;
  if (m.kind == Material::Kind::Glossy)
    diffuse = choice.x() >= schlick(cos_i, 0.04);  // coat or base
  if (diffuse) {
    sun = sun_ray(lights, s, above, throughput, light_sample);
    throughput = throughput.cwiseProduct(s.albedo);
    origin = above, dir = cosine_direction(s.normal, lobe_sample), path.sun_visible = false;
    path.spread = kScatteredSpread, path.textured = false;
  } else if (m.kind == Material::Kind::Glass) {
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
// rays: the samples of one pixel stay coherent for the camera rays and the first sun rays.
void trace_bundle(const FrameContext& frame, PixelLooks& camera_looks, PathState* paths,
                  Sampler* samplers, int count, int max_bounces, std::uint64_t& rays) {
  const EmbreeScene& embree = frame.embree;
  BundleRay bundle[kBundleSize];
  Hit hits[kBundleSize];
  SunRay sun[kBundleSize];
  bool blocked[kBundleSize];
  for (int i = 0; i < count; ++i) bundle[i] = {paths[i].origin, paths[i].dir, true};
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
      if (frame.textures && hits[i].found && paths[i].textured && is_textured(embree, hits[i])) {
        if (bounce == 0) {
          look = &camera_looks.at(hits[i], paths[i].dir);
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
      if (sun[i].ray.active && !blocked[i]) paths[i].radiance += sun[i].light;
  }
}

}  // namespace

Image<float> path_trace(EmbreeScene& embree, const ImageTextures& images,
                        const Projection& projection, const FramePair& frames,
                        const RenderOptions& options, RenderStats* stats) {
  embree.set_times(frames.time, frames.next_time);
  const int W = projection.width, H = projection.height;
  Image<float> image(W, H, 3);
  const Vec3 origin = frames.rig.translation();
  const Mat3 rotation = frames.rig.linear();
  std::atomic<std::uint64_t> rays{0};
  const Lights lights(embree.scene().environment);
  const FrameContext frame{embree, images, lights, options.textures};
  tbb::parallel_for(0, H, [&](int y) {
    std::uint64_t row_rays = 0;
    std::vector<Vec2> shifts(1 + 4 * (options.max_bounces + 1));  // camera jitter, 4 per bounce
    for (int x = 0; x < W; ++x) {
      const std::uint64_t key =
          mix_bits(options.seed ^ mix_bits((std::uint64_t(y) << 32) | unsigned(x)));
      pixel_shifts(key, shifts);
      const PixelRays camera_rays(projection, x, y);
      PixelLooks camera_looks(frame, origin, (rotation * camera_rays({0.5, 0.5})).normalized(),
                              projection.pixel_spread());
      Rgb sum = Rgb::Zero();
      for (int first = 0; first < options.samples_per_pixel; first += kBundleSize) {
        const int count = std::min(kBundleSize, options.samples_per_pixel - first);
        Sampler samplers[kBundleSize];
        PathState paths[kBundleSize];
        for (int i = 0; i < count; ++i) {
          samplers[i] = Sampler(shifts, first + i);
          const Vec2 jitter = samplers[i].next();
          paths[i].origin = origin;
          paths[i].dir = (rotation * camera_rays(jitter)).normalized();
          paths[i].spread = projection.pixel_spread();
        }
        trace_bundle(frame, camera_looks, paths, samplers, count, options.max_bounces, row_rays);
        for (int i = 0; i < count; ++i) sum += paths[i].radiance;
      }
      const Rgb mean = sum / std::max(1, options.samples_per_pixel);
      for (int c = 0; c < 3; ++c) image.pixel(x, y)[c] = float(mean[c]);
    }
    rays += row_rays;
  });
  if (stats) stats->rays = rays;
  return image;
}

}  // namespace flowscape
