#include "flowscape/renderer/renderer.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "camera/cube_faces.h"
#include "flowscape/core/profile.h"
#include "flowscape/geometry/geometry.h"
#include "render/embree_scene.h"
#include "render/image_textures.h"
#include "render/path_tracer.h"
#include "render/truth.h"

namespace flowscape {

struct Renderer::Impl {
  ImageTextures images;
  EmbreeScene embree;
  // The lights at the time of the last colour asked for: a frame's views (six faces, a rig's
  // cameras) share them.
  std::unique_ptr<const Lights> lights;
  double lights_time = 0;
  bool lights_average_sky = true;
  explicit Impl(const Scene& scene) : images(scene), embree(scene, &images) {}

  TracingBaseline baseline;

  const Lights& lights_at(double time) {
    const bool average_sky = !baseline.full_sky_when_scattered;
    if (!lights || lights_time != time || lights_average_sky != average_sky)
      lights = std::make_unique<const Lights>(embree.scene(), time, average_sky),
      lights_time = time, lights_average_sky = average_sky;
    return *lights;
  }
};

namespace {

// RenderOptions::pixels, where set, must be a one-channel mask of the image's size.
void require_mask_size(const char* caller, ImageView<const std::uint8_t> mask, int width,
                       int height) {
  if (mask.data && (mask.width != width || mask.height != height || mask.channels != 1))
    throw std::invalid_argument(std::string(caller) + ": the mask of the pixels to trace is " +
                                std::to_string(mask.width) + " x " + std::to_string(mask.height) +
                                " x " + std::to_string(mask.channels) + ", the image " +
                                std::to_string(width) + " x " + std::to_string(height) + " x 1");
}

// Pixel i's variance of `a` pooled with `b`'s (before their means are): each render's second
// moment of a sample's luminance is its variance of the mean times its samples plus its mean
// squared.
void pool_variance(ColorLayers& a, int a_samples, const ColorLayers& b, int b_samples,
                   std::size_t i) {
  const double n = a_samples + b_samples;
  const Image<float>* a_means[3] = {&a.direct, &a.indirect, &a.specular};
  const Image<float>* b_means[3] = {&b.direct, &b.indirect, &b.specular};
  const auto mean_at = [i](const Image<float>& layer) {
    const float* p = &layer.data[3 * i];
    return luminance(Rgb(p[0], p[1], p[2]));
  };
  for (int l = 0; l < 3; ++l) {
    const double ma = mean_at(*a_means[l]), mb = mean_at(*b_means[l]);
    const double moment = (a_samples * a.variance.data[3 * i + l] + ma * ma) * a_samples +
                          (b_samples * b.variance.data[3 * i + l] + mb * mb) * b_samples;
    const double mean = (a_samples * ma + b_samples * mb) / n;
    a.variance.data[3 * i + l] = float(std::max(0.0, moment / n - mean * mean) / n);
  }
}

}  // namespace

Renderer::Renderer(const Scene& scene) : impl_(std::make_unique<Impl>(scene)) {}
Renderer::~Renderer() = default;

void Renderer::trace_as(const TracingBaseline& baseline) { impl_->baseline = baseline; }

Image<float> raw_color(const ColorLayers& layers) {
  Image<float> sum = layers.direct;
  for (const Image<float>* layer : {&layers.indirect, &layers.specular, &layers.other})
    for (std::size_t i = 0; i < sum.data.size(); ++i) sum.data[i] += layer->data[i];
  return sum;
}

ColorLayers pooled(ColorLayers a, int a_samples, const ColorLayers& b, int b_samples) {
  const double n = a_samples + b_samples, wa = a_samples / n, wb = b_samples / n;
  tbb::parallel_for(std::size_t(0), a.direct.pixel_count(), [&](std::size_t i) {
    pool_variance(a, a_samples, b, b_samples, i);
    for (std::size_t c = 3 * i; c < 3 * i + 3; ++c) {
      for (auto [to, from] : {std::pair{&a.direct, &b.direct},
                              {&a.indirect, &b.indirect},
                              {&a.specular, &b.specular},
                              {&a.other, &b.other},
                              {&a.albedo, &b.albedo}})
        to->data[c] = float(wa * to->data[c] + wb * from->data[c]);
      a.normal.data[c] += b.normal.data[c];
    }
  });
  return a;
}

Image<float> Renderer::color(const Projection& projection, const FramePair& frames,
                             const RenderOptions& options, RenderStats* stats) {
  return raw_color(color_layers(projection, frames, options, stats));
}

ColorLayers Renderer::color_layers(const Projection& projection, const FramePair& frames,
                                   const RenderOptions& options, RenderStats* stats) {
  return color_layers(
      projection, frames.time, [&](double) { return frames.rig; }, {}, options, stats);
}

ColorLayers Renderer::color_layers(const Projection& projection, double time,
                                   const CameraTrack& camera, const Readout& readout,
                                   const RenderOptions& options, RenderStats* stats) {
  require_mask_size("color_layers", options.pixels, projection.width, projection.height);
  ColorLayers out = color_layers_of(projection.width, projection.height);
  std::uint64_t rays = 0;
  for_each_line(projection, readout, time, [&](double t, const PixelWindow& window) {
    pose_line(impl_->embree, readout, t);
    rays += path_trace(impl_->embree, impl_->images, impl_->lights_at(t), projection, camera(t),
                       options, window, out);
  });
  if (stats) stats->rays = rays;
  return out;
}

namespace {

// The shutter scene's span: from the first line's opening to the last line's closing.
Shutter capture_span(const Projection& projection, const Readout& readout, const Shutter& shutter) {
  if (readout.global()) return shutter;
  const int lines = readout.lines(projection);
  return {shutter.open + readout.offset(0.5, lines),
          shutter.close + readout.offset(lines - 0.5, lines)};
}

// Poses `embree` over the capture with motion blur, then calls visit(the line's camera over its
// shutter, the line's middle time, its pixels) for each line (one for a global shutter).
template <class Visit>
void over_shutter(EmbreeScene& embree, const Projection& projection, const Shutter& shutter,
                  const CameraTrack& camera, const Readout& readout, Visit&& visit) {
  const Shutter span = capture_span(projection, readout, shutter);
  embree.set_shutter(span.open, span.close, EmbreeScene::shutter_steps(span.close - span.open));
  const double middle = (shutter.open + shutter.close) / 2;
  const int camera_steps = EmbreeScene::shutter_steps(shutter.close - shutter.open);
  for_each_line(projection, readout, middle, [&](double t, const PixelWindow& window) {
    const ShutterCamera line =
        shutter_camera(camera, shutter.open + (t - middle), shutter.close + (t - middle), span.open,
                       span.close, camera_steps);
    visit(line, t, window);
  });
}

// A line's camera at the kShutterDepthTimes times the depth guide is cast at, spread over its
// shutter, and those times as the shutter scene's.
struct DepthTimes {
  std::array<Pose, Renderer::kShutterDepthTimes> cameras;
  std::array<float, Renderer::kShutterDepthTimes> times;
};
DepthTimes depth_times(const ShutterCamera& line) {
  DepthTimes out;
  for (int k = 0; k < Renderer::kShutterDepthTimes; ++k) {
    const double u = (k + 0.5) / Renderer::kShutterDepthTimes;
    out.cameras[std::size_t(k)] = line.at(u), out.times[std::size_t(k)] = line.ray_time(u);
  }
  return out;
}

// The depth along the camera ray `ray` averaged over those times where it meets a surface
// (+infinity where it never does).
float depth_over_shutter(const EmbreeScene& embree, const DepthTimes& at, const Vec3& ray) {
  double sum = 0;
  int met = 0;
  for (std::size_t k = 0; k < at.cameras.size(); ++k) {
    const Pose& pose = at.cameras[k];
    const Hit hit =
        embree.intersect(pose.translation(), (pose.linear() * ray).normalized(), at.times[k]);
    if (hit.found) sum += hit.distance, ++met;
  }
  return met > 0 ? float(sum / met) : std::numeric_limits<float>::infinity();
}

}  // namespace

ColorLayers Renderer::color_layers(const Projection& projection, const Shutter& shutter,
                                   const CameraTrack& camera, const Readout& readout,
                                   const RenderOptions& options, RenderStats* stats) {
  require_mask_size("color_layers", options.pixels, projection.width, projection.height);
  ColorLayers out = color_layers_of(projection.width, projection.height);
  std::uint64_t rays = 0;
  over_shutter(impl_->embree, projection, shutter, camera, readout,
               [&](const ShutterCamera& line, double t, const PixelWindow& window) {
                 rays += path_trace(impl_->embree, impl_->images, impl_->lights_at(t), projection,
                                    line.at(0.5), options, window, out, &line);
               });
  if (stats) stats->rays = rays;
  return out;
}

Image<float> Renderer::depth(const Projection& projection, const Shutter& shutter,
                             const CameraTrack& camera, const Readout& readout) {
  Image<float> depth(projection.width, projection.height, 1);
  const EmbreeScene& embree = impl_->embree;
  over_shutter(impl_->embree, projection, shutter, camera, readout,
               [&](const ShutterCamera& line, double, const PixelWindow& window) {
                 const DepthTimes at = depth_times(line);
                 parallel_pixels(window, [&](int x, int y) {
                   const Vec3 ray = projection.ray(Vec2(x + 0.5, y + 0.5));
                   *depth.pixel(x, y) = ray.isZero() ? std::numeric_limits<float>::quiet_NaN()
                                                     : depth_over_shutter(embree, at, ray);
                 });
               });
  return depth;
}

Image<float> Renderer::depth(const Projection& projection, double time, const CameraTrack& camera,
                             const Readout& readout) {
  Image<float> depth(projection.width, projection.height, 1);
  for_each_line(projection, readout, time, [&](double t, const PixelWindow& window) {
    pose_line(impl_->embree, readout, t);
    const Pose pose = camera(t);
    parallel_pixels(window, [&](int x, int y) {
      const Vec3 ray = projection.ray(Vec2(x + 0.5, y + 0.5));
      *depth.pixel(x, y) =
          ray.isZero()
              ? std::numeric_limits<float>::quiet_NaN()
              : float(
                    impl_->embree.intersect(pose.translation(), (pose.linear() * ray).normalized())
                        .distance);
    });
  });
  return depth;
}

namespace {

// What every pixel of one ground-truth call shares.
struct TruthContext {
  const EmbreeScene& scene;
  const ImageTextures& images;
  const Projection& projection;
  const TruthRequest& request;
  FlowMode mode;
  bool single_rays;             // TracingBaseline's
  std::vector<Moment> targets;  // the pair's next moment, then request.more
  CameraAt camera;              // at the frame's time
};

// Flow: the hit point, fixed on its object, moved to the object's pose at the target's time and
// projected by the camera then; the sky moves with the rig's rotation only. Valid: nothing hides
// the moved point from the camera then, which `visibility` (inactive where it cannot be seen)
// decides.
TargetTruth trace_target(const TruthContext& c, int k, const Hit& hit, const Vec3& point,
                         const Vec3& direction, Vec2 pixel, BundleRay& visibility) {
  const Moment& target = c.targets[std::size_t(k)];
  const Vec3 target_origin = target.rig.translation();
  TargetTruth truth;
  Vec3 target_direction = direction;  // world frame, seen from the rig at the target's time
  double target_distance = std::numeric_limits<double>::infinity();
  if (hit.found) {
    truth.moved = c.scene.point_at_target(k, hit, point);
    target_direction = truth.moved - target_origin;
    target_distance = target_direction.norm();
    target_direction /= target_distance;
  }
  visibility = {target_origin, target_direction, true, visibility_far(target_distance)};
  if (hit.found && c.request.camera_on_rig && c.scene.mesh(hit.mesh).on_rig) {
    truth.u = truth.v = 0;  // fixed to the camera: seen at the same pixel then, exactly
    return truth;
  }
  const auto projected = c.projection.project(target.rig.linear().transpose() * target_direction);
  if (!projected) {
    visibility.active = false;
    return truth;
  }
  double u = projected->x() - pixel.x();
  if (c.projection.wraps_around())
    u = erp_flow_u(wrap_360(u, c.projection.width), pixel.x(), c.projection.width, c.mode);
  truth.u = float(u), truth.v = float(projected->y() - pixel.y());
  return truth;
}

// A pixel of a ground-truth call: its centre, and where it goes in the output.
struct TruthPixel {
  Vec2 centre;
  int x, y;
};

// The ray through a pixel centre, in the world (inactive outside a lens's image).
BundleRay truth_ray(const TruthContext& c, Vec2 pixel) {
  const Pose& rig = c.request.pair.rig;
  const Vec3 camera_ray = c.projection.ray(pixel);
  if (camera_ray.isZero()) return {};
  return {rig.translation(), (rig.linear() * camera_ray).normalized(), true};
}

// Embree's answers for up to kBundleSize rays: one packet (coherent rays: neighbouring pixels'
// camera rays, their visibility rays from one target viewpoint), or each ray alone
// (TracingBaseline::single_rays). The same hits either way.
void intersect_all(const TruthContext& c, const BundleRay* rays, int count, Hit* hits) {
  if (!c.single_rays) return c.scene.intersect_scene(rays, count, hits);
  for (int i = 0; i < count; ++i)
    naming_lane(i, [&] {
      hits[i] = rays[i].active ? c.scene.intersect(rays[i].origin, rays[i].direction) : Hit{};
    });
}

void occluded_all(const TruthContext& c, int target, const BundleRay* rays, int count,
                  bool* blocked) {
  if (!c.single_rays) return c.scene.occluded(target, rays, count, blocked);
  for (int i = 0; i < count; ++i)
    naming_lane(i, [&] { blocked[i] = rays[i].active && c.scene.occluded(target, rays[i]); });
}

// Every asked-for kind of up to kBundleSize pixels, into `out`: their camera rays traced together,
// then each target's visibility rays together.
void trace_bundle_truth(const TruthContext& c, const TruthPixel* pixels, int count,
                        GroundTruth& out) {
  BundleRay rays[kBundleSize];
  Hit hits[kBundleSize];
  for (int i = 0; i < count; ++i) rays[i] = truth_ray(c, pixels[i].centre);
  intersect_all(c, rays, count, hits);
  const std::size_t targets = c.targets.size();
  std::vector<TargetTruth> found(targets * kBundleSize);
  std::vector<BundleRay> visibility(targets * kBundleSize);
  Vec3 points[kBundleSize];
  for (int i = 0; i < count; ++i) {
    if (!rays[i].active) continue;
    points[i] = rays[i].origin + hits[i].distance * rays[i].direction;
    for (std::size_t k = 0; k < targets; ++k)
      found[k * kBundleSize + i] = trace_target(c, int(k), hits[i], points[i], rays[i].direction,
                                                pixels[i].centre, visibility[k * kBundleSize + i]);
  }
  for (std::size_t k = 0; k < targets; ++k) {
    bool blocked[kBundleSize];
    occluded_all(c, int(k), &visibility[k * kBundleSize], count, blocked);
    for (int i = 0; i < count; ++i)
      found[k * kBundleSize + i].valid = visibility[k * kBundleSize + i].active && !blocked[i];
  }
  for (int i = 0; i < count; ++i) {
    const auto [centre, x, y] = pixels[i];
    if (!rays[i].active) {
      put_uncovered(out, x, y);
      continue;
    }
    const Hit& hit = hits[i];
    put_surface(c.scene, hit, out, x, y);
    for (std::size_t k = 1; k < targets; ++k)
      put_flow(out.more[k - 1].flow, out.more[k - 1].valid, x, y, found[k * kBundleSize + i]);
    const TargetTruth& next = found[i];
    put_flow(out.flow, out.valid, x, y, next);
    if (c.request.scene_flow)
      put_vector(out.scene_flow, x, y,
                 hit.found ? Vec3(c.camera.world_to_camera * (next.moved - points[i]))
                           : Vec3::Constant(kNoVector));
    if (c.request.normal || c.request.shading_normal)
      put_normals(c.scene, c.images, c.projection, c.request, c.camera, hit, rays[i].direction,
                  centre, out, x, y);
  }
}

void trace_truth(const TruthContext& c, const TruthPixel* pixels, int count, GroundTruth& out) {
  naming_pixels([&] { trace_bundle_truth(c, pixels, count, out); },
                [&](int lane) {
                  return std::pair{pixels[lane].x, pixels[lane].y};
                });
}

// A row's pixels, kBundleSize neighbours at a time.
void trace_truth_row(const TruthContext& c, int y, GroundTruth& out) {
  TruthPixel pixels[kBundleSize];
  for (int x0 = 0; x0 < c.projection.width; x0 += kBundleSize) {
    const int count = std::min(kBundleSize, c.projection.width - x0);
    for (int i = 0; i < count; ++i) pixels[i] = {Vec2(x0 + i + 0.5, y + 0.5), x0 + i, y};
    trace_truth(c, pixels, count, out);
  }
}

TruthContext truth_context(EmbreeScene& scene, const ImageTextures& images,
                           const Projection& projection, const TruthRequest& request, FlowMode mode,
                           bool single_rays) {
  TruthContext c{scene,
                 images,
                 projection,
                 request,
                 mode,
                 single_rays,
                 {{request.pair.next_time, request.pair.next_rig}},
                 camera_at(request.pair.rig, projection)};
  c.targets.insert(c.targets.end(), request.more.begin(), request.more.end());
  std::vector<double> times;
  for (const Moment& target : c.targets) times.push_back(target.time);
  scene.set_times(request.pair.time, times);
  return c;
}

}  // namespace

GroundTruth Renderer::ground_truth(const Projection& projection, const FramePair& frames,
                                   FlowMode mode) {
  return ground_truth(projection, TruthRequest{frames}, mode);
}

GroundTruth Renderer::ground_truth(const Projection& projection, const TruthRequest& request,
                                   FlowMode mode) {
  if (!request.readout.global())
    return rolling_ground_truth(impl_->embree, impl_->images, projection, request);
  const TruthContext c = truth_context(impl_->embree, impl_->images, projection, request, mode,
                                       impl_->baseline.single_rays);
  GroundTruth gt = allocate_truth(request, projection.width, projection.height);
  tbb::parallel_for(0, projection.height, [&](int y) { trace_truth_row(c, y, gt); });
  return gt;
}

GroundTruth Renderer::ground_truth_at(const Projection& projection, const TruthRequest& request,
                                      const std::vector<Vec2>& pixels, FlowMode mode) {
  if (!request.readout.global())
    throw std::invalid_argument("ground truth at chosen pixels: global shutters only");
  const TruthContext c = truth_context(impl_->embree, impl_->images, projection, request, mode,
                                       impl_->baseline.single_rays);
  GroundTruth gt = allocate_truth(request, int(pixels.size()), 1);
  const std::size_t batches = (pixels.size() + kBundleSize - 1) / kBundleSize;
  tbb::parallel_for(std::size_t(0), batches, [&](std::size_t batch) {
    TruthPixel chosen[kBundleSize];
    const std::size_t first = batch * kBundleSize;
    const int count = int(std::min<std::size_t>(kBundleSize, pixels.size() - first));
    for (int i = 0; i < count; ++i) chosen[i] = {pixels[first + i], int(first + i), 0};
    trace_truth(c, chosen, count, gt);
  });
  return gt;
}

CubeFrame render_cube(Renderer& renderer, int face_size, const FramePair& frames,
                      const RenderOptions* color_options, FlowMode mode) {
  return render_cube(renderer, face_size, TruthRequest{frames}, color_options, mode);
}

CubeFrame render_cube(Renderer& renderer, int face_size, const TruthRequest& request,
                      const RenderOptions* color_options, FlowMode mode) {
  CubeFrame cube;
  GroundTruth& all = cube.truth;
  all.more.resize(request.more.size());
  for (Face face : kFaces) {
    const Projection projection = Projection::cube_face(face, face_size);
    const GroundTruth gt = [&] {
      const ScopedPhase phase("cube faces: ground truth");
      return on_face(face, [&] { return renderer.ground_truth(projection, request, mode); });
    }();
    put_face(all.flow, face, gt.flow), put_face(all.semantic, face, gt.semantic);
    put_face(all.instance, face, gt.instance), put_face(all.depth, face, gt.depth);
    put_face(all.valid, face, gt.valid);
    for (std::size_t k = 0; k < gt.more.size(); ++k)
      put_face(all.more[k].flow, face, gt.more[k].flow),
          put_face(all.more[k].valid, face, gt.more[k].valid);
    for (auto [image, faces] : {std::pair{&gt.scene_flow, &all.scene_flow},
                                {&gt.normal, &all.normal},
                                {&gt.shading_normal, &all.shading_normal}})
      if (!image->data.empty()) put_face(*faces, face, *image);
  }
  if (color_options)
    cube.color = cube_color_layers(renderer, face_size, request.pair, *color_options);
  return cube;
}

ColorLayers cube_color_layers(Renderer& renderer, int face_size, const FramePair& frames,
                              const RenderOptions& options) {
  const ImageView<const std::uint8_t> mask = options.pixels;
  require_mask_size("cube_color_layers", mask, face_size, 6 * face_size);
  const ScopedPhase phase("cube faces: path tracing");
  ColorLayers color;
  for (Face face : kFaces) {
    RenderOptions face_options = options;
    if (mask.data) face_options.pixels = face_view(mask, face);
    put_face(color, face, on_face(face, [&] {
               return renderer.color_layers(Projection::cube_face(face, face_size), frames,
                                            face_options);
             }));
  }
  return color;
}

}  // namespace flowscape
