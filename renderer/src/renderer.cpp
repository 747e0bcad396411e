#include "flowscape/renderer/renderer.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>

#include "embree_scene.h"
#include "flowscape/stitcher/geometry.h"
#include "image_textures.h"
#include "path_tracer.h"

namespace flowscape {

struct Renderer::Impl {
  ImageTextures images;
  EmbreeScene embree;
  explicit Impl(const Scene& scene) : images(scene), embree(scene, &images) {}
};

Renderer::Renderer(const Scene& scene) : impl_(std::make_unique<Impl>(scene)) {}
Renderer::~Renderer() = default;

Image<float> raw_color(const ColorLayers& layers) {
  Image<float> sum = layers.direct;
  for (const Image<float>* layer : {&layers.indirect, &layers.specular, &layers.other})
    for (std::size_t i = 0; i < sum.data.size(); ++i) sum.data[i] += layer->data[i];
  return sum;
}

Image<float> Renderer::color(const Projection& projection, const FramePair& frames,
                             const RenderOptions& options, RenderStats* stats) {
  return raw_color(color_layers(projection, frames, options, stats));
}

ColorLayers Renderer::color_layers(const Projection& projection, const FramePair& frames,
                                   const RenderOptions& options, RenderStats* stats) {
  return path_trace(impl_->embree, impl_->images, projection, frames, options, stats);
}

namespace {

struct PixelTruth {
  float u = kUnknownFlow, v = kUnknownFlow, depth;
  std::uint8_t semantic, valid = 0;
  std::uint16_t instance = 0;
};

// Ground truth of the ray through one pixel centre (see Renderer::ground_truth).
PixelTruth trace_truth(const EmbreeScene& scene, const Projection& projection,
                       const FramePair& frames, FlowMode mode, Vec2 pixel) {
  const Vec3 origin = frames.rig.translation(), next_origin = frames.next_rig.translation();
  const Vec3 direction = (frames.rig.linear() * projection.ray(pixel)).normalized();
  const Hit hit = scene.intersect(origin, direction);
  PixelTruth truth{kUnknownFlow, kUnknownFlow, float(hit.distance),
                   std::uint8_t(SemanticClass::Sky)};
  Vec3 target_direction = direction;  // world frame, seen from the rig at next_time
  double target_distance = std::numeric_limits<double>::infinity();
  if (hit.found) {
    const Vec3 point = origin + hit.distance * direction;
    const Vec3 moved = scene.pose_next(hit.mesh) * (scene.pose_now(hit.mesh).inverse() * point);
    target_direction = moved - next_origin;
    target_distance = target_direction.norm();
    target_direction /= target_distance;
    truth.semantic = std::uint8_t(scene.mesh(hit.mesh).mesh->classes[hit.triangle]);
    truth.instance = scene.mesh(hit.mesh).instance;
  }
  const auto target = projection.project(frames.next_rig.linear().transpose() * target_direction);
  if (!target) return truth;
  double u = target->x() - pixel.x();
  if (projection.kind == Projection::Kind::Equirectangular)
    u = erp_flow_u(wrap_360(u, projection.width), pixel.x(), projection.width, mode);
  truth.u = float(u), truth.v = float(target->y() - pixel.y());
  truth.valid = !scene.occluded(true, next_origin, target_direction, target_distance);
  return truth;
}

}  // namespace

GroundTruth Renderer::ground_truth(const Projection& projection, const FramePair& frames,
                                   FlowMode mode) {
  EmbreeScene& scene = impl_->embree;
  scene.set_times(frames.time, frames.next_time);
  const int W = projection.width, H = projection.height;
  GroundTruth gt{Image<float>(W, H, 2), Image<std::uint8_t>(W, H, 1), Image<std::uint16_t>(W, H, 1),
                 Image<float>(W, H, 1), Image<std::uint8_t>(W, H, 1)};
  tbb::parallel_for(0, H, [&](int y) {
    for (int x = 0; x < W; ++x) {
      const PixelTruth t = trace_truth(scene, projection, frames, mode, Vec2(x + 0.5, y + 0.5));
      gt.flow.pixel(x, y)[0] = t.u, gt.flow.pixel(x, y)[1] = t.v;
      *gt.semantic.pixel(x, y) = t.semantic;
      *gt.instance.pixel(x, y) = t.instance;
      *gt.depth.pixel(x, y) = t.depth;
      *gt.valid.pixel(x, y) = t.valid;
    }
  });
  return gt;
}

namespace {

template <class T>
void put_face(Image<T>& cube, Face face, const Image<T>& image) {
  if (cube.data.empty()) cube = Image<T>(image.width, 6 * image.width, image.channels);
  std::copy(image.data.begin(), image.data.end(), face_view(cube.view(), face).data);
}

}  // namespace

CubeFrame render_cube(Renderer& renderer, int face_size, const FramePair& frames,
                      const RenderOptions* color_options, FlowMode mode) {
  CubeFrame cube;
  GroundTruth& all = cube.truth;
  for (Face face : kFaces) {
    const Projection projection = Projection::cube_face(face, face_size);
    const GroundTruth gt = renderer.ground_truth(projection, frames, mode);
    put_face(all.flow, face, gt.flow), put_face(all.semantic, face, gt.semantic);
    put_face(all.instance, face, gt.instance), put_face(all.depth, face, gt.depth);
    put_face(all.valid, face, gt.valid);
    if (!color_options) continue;
    ColorLayers layers = renderer.color_layers(projection, frames, *color_options);
    ColorLayers& c = cube.color;
    put_face(c.direct, face, layers.direct), put_face(c.indirect, face, layers.indirect);
    put_face(c.specular, face, layers.specular), put_face(c.other, face, layers.other);
    put_face(c.albedo, face, layers.albedo), put_face(c.normal, face, layers.normal);
    put_face(c.variance, face, layers.variance);
  }
  return cube;
}

}  // namespace flowscape
