// A unidirectional path tracer in the manner of Embree's tutorials, gathering its light in the
// layers a denoiser needs (ColorLayers).
#include "render/path_tracer.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>

#include "render/bsdf.h"
#include "render/light_sampler.h"
#include "render/sampling.h"

namespace flowscape {
namespace {

constexpr double kFar = std::numeric_limits<double>::infinity();

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
  const ShutterCamera* shutter;  // null: every sample at the scene's `now`
};

// The fog between the path's origin and `distance` along it: the light it scatters in, and the
// light it lets through.
void cross_fog(const FogMedium& fog, double distance, PathState& path) {
  if (!fog.present()) return;
  const double depth = fog.optical_depth(path.origin, path.dir, distance);
  path.light[path.layer] +=
      path.throughput.cwiseProduct(fog.inscattered(path.origin, path.dir, depth));
  path.throughput *= std::exp(-depth);
}

// One bounce of a path at `hit`: the fog before it, the sky and sun disc where it finds nothing,
// else what the surface's material does (bsdf.h). Directions follow the shading normal; a
// direction sent below the geometric surface ends the path. Returns whether the path goes on.
bool advance(const FrameContext& frame, const Hit& hit, const TexturedLook* look, int bounce,
             Sampler& sampler, PathState& path, ShadowRay& shadow) {
  const Lights& lights = frame.lights;
  const Vec2 light_sample = sampler.next(), lobe_sample = sampler.next(), choice = sampler.next();
  cross_fog(lights.fog, hit.found ? hit.distance : kFar, path);
  if (!hit.found) {
    const Vec3& dir = path.dir;
    path.light[path.layer] += path.throughput.cwiseProduct(
        sky_seen(lights, dir, path.scattered) * found_sky_weight(lights, path, dir) +
        (path.sun_visible ? lights.sun_radiance(dir) : Rgb::Zero()));
    return false;
  }
  path.width += path.spread * hit.distance;
  const Surface s = surface_at(frame.embree, hit, path.origin, path.dir, look);
  const Bsdf& bsdf = bsdf_of(s.material->kind);
  const SurfaceEvent event{
      lights,      s,     1e-4 * (1 + s.position.norm()), path.layer == kOther, light_sample,
      lobe_sample, choice};
  if (event.first && bsdf.ends_other()) {
    path.met_surface = true;
    if (path.other_only) return false;
  }
  if (event.first && !bsdf.see_through()) path.normal += s.smooth;
  const Turn turn = bsdf.interact(event, path, shadow);
  if (turn == Turn::Ends || turn == Turn::PassesThrough) return turn == Turn::PassesThrough;
  if ((path.dir.dot(s.geometric) > 0) == (turn == Turn::Transmitted)) return false;
  return russian_roulette(bounce, choice.y(), path.throughput);
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
  // Over a shutter the surface moves in the pixel: the look at the sample's own point, shared by
  // the pixel's samples that met the triangle within the footprint of it on the mesh (where its
  // texture sits): their looks, filtered over the footprint, would hardly differ.
  const TexturedLook& moving_at(const Hit& hit, const Vec3& origin, const Vec3& dir) {
    const double footprint = spread_ * hit.distance;
    const Mesh& rest = *frame_.embree.mesh(hit.mesh).rest;
    const Eigen::Vector3i& tri = rest.triangles[hit.triangle];
    const Vec3 on_mesh = (1.0 - hit.u - hit.v) * rest.vertices[tri[0]].cast<double>() +
                         double(hit.u) * rest.vertices[tri[1]].cast<double>() +
                         double(hit.v) * rest.vertices[tri[2]].cast<double>();
    for (int k = 0; k < count_; ++k)
      if (entries_[k].mesh == hit.mesh && entries_[k].triangle == hit.triangle &&
          (entries_[k].on_mesh - on_mesh).norm() < footprint)
        return entries_[k].look;
    const int slot = count_ < kSlots ? count_++ : kSlots - 1;
    entries_[slot] = {hit.mesh, hit.triangle,
                      textured_look(frame_.embree, frame_.images, hit, origin + hit.distance * dir,
                                    dir, footprint),
                      on_mesh};
    return entries_[slot].look;
  }

 private:
  TexturedLook look_at_centre(const Hit& hit, const Vec3& sample_dir) const {
    const EmbreeScene& embree = frame_.embree;
    const Pose pose = embree.pose_of(hit);
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
    Vec3 on_mesh = Vec3::Zero();  // over a shutter: where it was looked up
  };
  const FrameContext& frame_;
  Vec3 origin_, centre_;
  double spread_;
  Entry entries_[kSlots];
  int count_ = 0;
};

// Traces up to kBundleSize paths in lock step, one Embree packet per bounce and one for the shadow
// rays: the samples of one pixel (or of a few neighbours) stay coherent for the camera rays and
// the first shadow rays. camera_looks: each path's pixel's.
void trace_bundle(const FrameContext& frame, PixelLooks* const* camera_looks, PathState* paths,
                  Sampler* samplers, int count, int max_bounces, std::uint64_t& rays) {
  const EmbreeScene& embree = frame.embree;
  BundleRay bundle[kBundleSize];
  Hit hits[kBundleSize];
  ShadowRay shadows[kBundleSize];
  bool blocked[kBundleSize];
  // a sample outside a lens's image has no ray (zero) and no light
  for (int i = 0; i < count; ++i)
    bundle[i] = {paths[i].origin, paths[i].dir, !paths[i].dir.isZero(),
                 std::numeric_limits<float>::infinity(), paths[i].time};
  for (int bounce = 0; bounce <= max_bounces; ++bounce) {
    const int alive = int(std::count_if(bundle, bundle + count, [](auto& r) { return r.active; }));
    if (alive == 0) break;
    embree.intersect(bundle, count, hits);
    rays += alive;
    for (int i = 0; i < count; ++i) {
      shadows[i] = {};
      if (!bundle[i].active) continue;
      const TexturedLook* look = nullptr;
      TexturedLook own;  // a specular chain's hit: its own point
      if (frame.textures && hits[i].found && !paths[i].scattered && is_textured(embree, hits[i])) {
        if (bounce == 0) {
          look = frame.shutter ? &camera_looks[i]->moving_at(hits[i], paths[i].origin, paths[i].dir)
                               : &camera_looks[i]->at(hits[i], paths[i].dir);
        } else {
          own = textured_look(embree, frame.images, hits[i],
                              paths[i].origin + hits[i].distance * paths[i].dir, paths[i].dir,
                              paths[i].width + paths[i].spread * hits[i].distance);
          look = &own;
        }
      }
      bundle[i].active = advance(frame, hits[i], look, bounce, samplers[i], paths[i], shadows[i]);
      bundle[i].origin = paths[i].origin, bundle[i].direction = paths[i].dir;
    }
    BundleRay shadow_rays[kBundleSize];
    for (int i = 0; i < count; ++i) {
      shadow_rays[i] = shadows[i].ray, shadow_rays[i].time = paths[i].time;
      rays += shadows[i].ray.active;
    }
    embree.occluded(shadow_rays, count, blocked);
    for (int i = 0; i < count; ++i)
      if (shadows[i].ray.active && !blocked[i])
        paths[i].light[shadows[i].layer] += shadows[i].light;
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
    surface_samples += path.met_surface;
    const double other = luminance(path.light[kOther]);
    other_low = std::min(other_low, other), other_high = std::max(other_high, other);
  }
  // Whether the samples disagree on the 'other' light they met (an emitter's or the sky's edge, a
  // lamp smaller than the pixel) by more than kEdgeContrast (white is 1).
  bool on_edge() const { return other_high - other_low > kEdgeContrast; }
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
  int surface_samples = 0;  // those that met a surface (PathState::met_surface)
  double other_low = std::numeric_limits<double>::infinity(), other_high = -other_low;
  static constexpr double kEdgeContrast = 0.05;
};

// Which pixels are on an edge (PixelSamples::on_edge), over a window grown by a pixel each way
// within the image: the window's traced pixels from their samples, the others next to them from
// probes of the same samples (other-only camera paths: the 'other' light a path meets before its
// first surface is the same whether it goes on or not). So a pixel's edge samples depend on its
// neighbours' samples as a render of the whole image has them, whatever the call traces (a rolling
// shutter's line, RenderOptions::pixels).
struct EdgeMarks {
  enum State : std::uint8_t { kUnseen, kSmooth, kEdge };
  EdgeMarks(const PixelWindow& w, const Projection& image)
      : region{std::max(0, w.x0 - 1), std::max(0, w.y0 - 1), std::min(image.width, w.x1 + 1),
               std::min(image.height, w.y1 + 1)},
        state(std::size_t(region.x1 - region.x0) * (region.y1 - region.y0), kUnseen),
        traced(state.size(), 0),
        surface_samples(state.size(), 0) {}
  std::size_t at(int x, int y) const {
    return std::size_t(y - region.y0) * (region.x1 - region.x0) + (x - region.x0);
  }
  void mark_state(const PixelSamples& pixel, int x, int y) {
    state[at(x, y)] = pixel.on_edge() ? kEdge : kSmooth;
  }
  void mark(const PixelSamples& pixel, int x, int y) {  // a traced pixel
    mark_state(pixel, x, y);
    traced[at(x, y)] = 1, surface_samples[at(x, y)] = pixel.surface_samples;
  }
  template <class Visit>
  bool any_next_to(int x, int y, const Visit& visit) const {  // (x, y) and its 8 neighbours
    for (int v = std::max(y - 1, region.y0); v <= std::min(y + 1, region.y1 - 1); ++v)
      for (int u = std::max(x - 1, region.x0); u <= std::min(x + 1, region.x1 - 1); ++u)
        if (visit(at(u, v))) return true;
    return false;
  }
  // An untraced pixel next to a traced one that is not on an edge itself: its state decides.
  bool needs_probe(int x, int y) const {
    return !traced[at(x, y)] &&
           any_next_to(x, y, [&](std::size_t k) { return traced[k] && state[k] == kSmooth; });
  }
  // Whether (x, y) or a pixel next to it is on an edge: an emitter smaller than a pixel that none
  // of its own samples met shows in a neighbour's.
  bool near_edge(int x, int y) const {
    return any_next_to(x, y, [&](std::size_t k) { return state[k] == kEdge; });
  }
  PixelWindow region;
  std::vector<std::uint8_t> state, traced;
  std::vector<int> surface_samples;
};

// Adds a pixel's edge samples (`edge_other`: the sum of their 'other' light, `edge_surface`: how
// many met a surface) to its layers of `samples` samples, `surface` of which met a surface. The
// coverage is decoupled from the shading, as multisample antialiasing does: 'other' becomes the
// mean of all samples, the surface layers the mean light of the samples that met a surface times
// the share of all samples that did (a ratio estimator), so their noise at an edge no longer
// follows the few samples' coverage.
void add_edge_samples(ColorLayers& out, int x, int y, int samples, int surface, int edges,
                      const Rgb& edge_other, int edge_surface) {
  const double all = samples + edges;
  float* other = out.other.pixel(x, y);
  for (int c = 0; c < 3; ++c) other[c] = float((other[c] * samples + edge_other[c]) / all);
  if (surface == 0) return;  // no sample saw the surface's light: it stays unknown (zero)
  const double coverage = (surface + edge_surface) / all / (double(surface) / samples);
  for (Image<float>* layer : {&out.direct, &out.indirect, &out.specular, &out.albedo})
    for (int c = 0; c < 3; ++c) layer->pixel(x, y)[c] *= float(coverage);
  for (int c = 0; c < 3; ++c) out.variance.pixel(x, y)[c] *= float(coverage * coverage);
}

// Traces neighbouring pixels of a row together: as many as fill a bundle with all their samples
// (two at 8 spp), so their camera and first light rays share Embree packets. Each pixel's samples
// and their order are its own, so a pixel's colour does not depend on its neighbours.
struct PixelGroupTracer {
  const FrameContext& frame;
  const Projection& projection;
  const Pose& camera;
  const RenderOptions& options;

  void trace(int y, int x0, int x1, ColorLayers& out, EdgeMarks& marks, std::uint64_t& rays) const {
    const int spp = options.samples_per_pixel;
    std::optional<PixelSamples> group[kBundleSize];
    trace_samples(group, y, x0, x1, 0, spp, false, rays,
                  [&](int x, const PathState& path) { group[x - x0]->add(path); });
    for (int x = x0; x < x1; ++x) {
      group[x - x0]->put_means(spp, out, x, y);
      marks.mark(*group[x - x0], x, y);
    }
  }

  // Marks the pixels of row y in [x0, x1) by probes of their own samples (EdgeMarks).
  void probe(int y, int x0, int x1, EdgeMarks& marks, std::uint64_t& rays) const {
    std::optional<PixelSamples> group[kBundleSize];
    trace_samples(group, y, x0, x1, 0, options.samples_per_pixel, true, rays,
                  [&](int x, const PathState& path) { group[x - x0]->add(path); });
    for (int x = x0; x < x1; ++x) marks.mark_state(*group[x - x0], x, y);
  }

  // The edge samples (RenderOptions::edge_samples) of the pixels of row y in [x0, x1): the
  // samples after each pixel's own, each only as far as its first surface.
  void trace_edges(int y, int x0, int x1, const EdgeMarks& marks, ColorLayers& out,
                   std::uint64_t& rays) const {
    const int spp = options.samples_per_pixel;
    std::optional<PixelSamples> group[kBundleSize];
    Rgb other[kBundleSize];
    int surface[kBundleSize] = {};
    std::fill(other, other + kBundleSize, Rgb::Zero());
    trace_samples(group, y, x0, x1, spp, options.edge_samples, true, rays,
                  [&](int x, const PathState& path) {
                    other[x - x0] += path.light[kOther], surface[x - x0] += path.met_surface;
                  });
    for (int x = x0; x < x1; ++x)
      add_edge_samples(out, x, y, spp, marks.surface_samples[marks.at(x, y)],
                       options.edge_samples - spp, other[x - x0], surface[x - x0]);
  }

 private:
  // Traces samples [first, last) of each pixel of row y in [x0, x1) (set up in `group`), whole
  // or as other-only camera paths, a bundle at a time, pixel after pixel (a pixel's samples in
  // order), handing each path to take(x, path).
  template <class Take>
  void trace_samples(std::optional<PixelSamples>* group, int y, int x0, int x1, int first, int last,
                     bool other_only, std::uint64_t& rays, const Take& take) const {
    Sampler samplers[kBundleSize];
    PathState paths[kBundleSize];
    PixelLooks* looks[kBundleSize];
    int owners[kBundleSize], lane = 0;
    const auto flush = [&] {
      naming_pixels(
          [&] { trace_bundle(frame, looks, paths, samplers, lane, options.max_bounces, rays); },
          [&](int of) {
            return std::pair{owners[of], y};
          });
      for (int i = 0; i < lane; ++i) take(owners[i], paths[i]);
      lane = 0;
    };
    for (int x = x0; x < x1; ++x) {
      group[x - x0].emplace(frame, projection, camera, options.seed, x, y);
      for (int index = first; index < last; ++index) {
        paths[lane] = {};
        owners[lane] = x;
        start(*group[x - x0], index, lane++, samplers, paths, looks, other_only);
        if (lane == kBundleSize) flush();
      }
    }
    if (lane > 0) flush();
  }
  // Sets up sample `index` of `pixel` in bundle lane `lane`.
  void start(PixelSamples& pixel, int index, int lane, Sampler* samplers, PathState* paths,
             PixelLooks** looks, bool other_only) const {
    samplers[lane] = Sampler(pixel.keys, index, options.samples_per_pixel);
    PathState& path = paths[lane];
    path.other_only = other_only;
    const ShutterCamera* shutter = frame.shutter;
    const double u = shutter ? samplers[lane].time() : 0;
    const Pose sample_camera = shutter ? shutter->at(u) : camera;
    path.time = shutter ? shutter->ray_time(u) : 0.0f;
    path.origin = sample_camera.translation();
    path.dir = (sample_camera.linear() * pixel.camera_rays(samplers[lane].next())).normalized();
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

// Calls trace(y, x0, x1, rays) in parallel for the runs of neighbouring pixels of a row of
// `window` that `wanted(x, y)` picks, at most `longest` long (2-D blocks: a rolling shutter's
// window is a single line). Returns the rays traced.
template <class Wanted, class Trace>
std::uint64_t for_each_run(const PixelWindow& window, int longest, const Wanted& wanted,
                           const Trace& trace) {
  std::atomic<std::uint64_t> rays{0};
  const tbb::blocked_range2d<int> pixels(window.y0, window.y1, window.x0, window.x1);
  tbb::parallel_for(pixels, [&](const tbb::blocked_range2d<int>& block) {
    std::uint64_t block_rays = 0;
    const int begin = block.cols().begin(), end = block.cols().end();
    for (int y = block.rows().begin(); y < block.rows().end(); ++y)
      for (int x = begin; x < end;) {
        if (!wanted(x, y)) {
          ++x;
          continue;
        }
        int run_end = x + 1;
        while (run_end < std::min(x + longest, end) && wanted(run_end, y)) ++run_end;
        trace(y, x, run_end, block_rays);
        x = run_end;
      }
    rays += block_rays;
  });
  return rays;
}

}  // namespace

Pose ShutterCamera::at(double u) const {
  const double position = std::clamp(u, 0.0, 1.0) * double(positions.size() - 1);
  const std::size_t k = std::min(std::size_t(position), positions.size() - 2);
  const double share = position - double(k);
  Pose pose = Pose::Identity();
  pose.linear() = rotations[k].slerp(share, rotations[k + 1]).toRotationMatrix();
  pose.translation() = (1 - share) * positions[k] + share * positions[k + 1];
  return pose;
}

ShutterCamera shutter_camera(const std::function<Pose(double)>& track, double open, double close,
                             double scene_open, double scene_close, int steps) {
  ShutterCamera camera;
  for (int k = 0; k < steps; ++k) {
    const Pose pose = track(open + (close - open) * k / (steps - 1));
    camera.positions.push_back(pose.translation());
    camera.rotations.emplace_back(pose.linear());
  }
  const double span = scene_close - scene_open;
  camera.first = float((open - scene_open) / span),
  camera.last = float((close - scene_open) / span);
  return camera;
}

ColorLayers color_layers_of(int width, int height) {
  const int W = width, H = height;
  return {Image<float>(W, H, 3), Image<float>(W, H, 3), Image<float>(W, H, 3),
          Image<float>(W, H, 3), Image<float>(W, H, 3), Image<float>(W, H, 3),
          Image<float>(W, H, 3)};
}

std::uint64_t path_trace(EmbreeScene& embree, const ImageTextures& images, const Lights& lights,
                         const Projection& projection, const Pose& camera,
                         const RenderOptions& options, const PixelWindow& window, ColorLayers& out,
                         const ShutterCamera* shutter) {
  const FrameContext frame{embree, images, lights, options.textures, shutter};
  const PixelGroupTracer tracer{frame, projection, camera, options};
  const auto traced = [&](int x, int y) {  // RenderOptions::pixels
    return !options.pixels.data || *options.pixels.pixel(x, y);
  };
  const int spp = options.samples_per_pixel;
  EdgeMarks marks(window, projection);
  std::uint64_t rays = for_each_run(
      window, std::max(1, kBundleSize / std::max(1, spp)), traced,
      [&](int y, int x0, int x1, std::uint64_t& r) { tracer.trace(y, x0, x1, out, marks, r); });
  if (options.edge_samples <= spp) return rays;
  const int longest = std::max(1, kBundleSize / 2);
  rays += for_each_run(
      marks.region, longest, [&](int x, int y) { return marks.needs_probe(x, y); },
      [&](int y, int x0, int x1, std::uint64_t& r) { tracer.probe(y, x0, x1, marks, r); });
  rays += for_each_run(
      window, longest, [&](int x, int y) { return traced(x, y) && marks.near_edge(x, y); },
      [&](int y, int x0, int x1, std::uint64_t& r) {
        tracer.trace_edges(y, x0, x1, marks, out, r);
      });
  return rays;
}

}  // namespace flowscape
