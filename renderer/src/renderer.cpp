#include "flowscape/renderer.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>

#include "embree_scene.h"
#include "path_tracer.h"

namespace flowscape {

struct Renderer::Impl {
  EmbreeScene embree;
  explicit Impl(const Scene& scene) : embree(scene) {}
};

Renderer::Renderer(const Scene& scene) : impl_(std::make_unique<Impl>(scene)) {}
Renderer::~Renderer() = default;

Image<float> Renderer::color(const Projection& projection, const FramePair& frames,
                             const RenderOptions& options, RenderStats* stats) {
  return path_trace(impl_->embree, projection, frames, options, stats);
}

GroundTruth Renderer::ground_truth(const Projection& projection, const FramePair& frames,
                                   FlowMode mode) {
  EmbreeScene& r = impl_->embree;
  r.set_times(frames.time, frames.next_time);
  const int W = projection.width, H = projection.height;
  GroundTruth gt{Image<float>(W, H, 2), Image<std::uint8_t>(W, H, 1), Image<std::uint16_t>(W, H, 1),
                 Image<float>(W, H, 1), Image<std::uint8_t>(W, H, 1)};
  const Vec3 origin = frames.rig.translation(), next_origin = frames.next_rig.translation();
  const Mat3 rotation = frames.rig.linear(), next_rotation = frames.next_rig.linear();
  const bool panorama = projection.kind == Projection::Kind::Equirectangular;
  tbb::parallel_for(0, H, [&](int y) {
    for (int x = 0; x < W; ++x) {
      const Vec2 pixel(x + 0.5, y + 0.5);
      const Vec3 direction = (rotation * projection.ray(pixel)).normalized();
      const Hit hit = r.intersect(origin, direction);
      Vec3 target_direction;  // world frame, from the rig at next_time
      double target_distance = std::numeric_limits<double>::infinity();
      if (hit.found) {
        const Vec3 point = origin + hit.distance * direction;
        const Vec3 moved = r.pose_next(hit.mesh) * (r.pose_now(hit.mesh).inverse() * point);
        target_direction = moved - next_origin;
        target_distance = target_direction.norm();
        target_direction /= target_distance;
        *gt.semantic.pixel(x, y) = std::uint8_t(r.mesh(hit.mesh).mesh->classes[hit.triangle]);
        *gt.instance.pixel(x, y) = r.mesh(hit.mesh).instance;
      } else {
        target_direction = direction;
        *gt.semantic.pixel(x, y) = std::uint8_t(SemanticClass::Sky);
      }
      *gt.depth.pixel(x, y) = float(hit.distance);
      const auto target = projection.project(next_rotation.transpose() * target_direction);
      float* f = gt.flow.pixel(x, y);
      if (!target) {
        f[0] = f[1] = kUnknownFlow;
        continue;
      }
      double u = target->x() - pixel.x();
      if (panorama) {
        const double classic = (target->x() >= W ? target->x() - W : target->x()) - pixel.x();
        u = mode == FlowMode::Wrap360 ? wrap_360(classic, W) : classic;
      }
      f[0] = float(u), f[1] = float(target->y() - pixel.y());
      *gt.valid.pixel(x, y) = !r.occluded(true, next_origin, target_direction, target_distance);
    }
  });
  return gt;
}

}  // namespace flowscape
