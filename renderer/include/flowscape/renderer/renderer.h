#pragma once
// Embree ray casting of a Scene: exact ground truth for the pixel-centre ray of every pixel.
// Each mesh gets its own BVH, built once; every frame only re-poses the instances.
#include <cstdint>
#include <memory>

#include "flowscape/core/image.h"
#include "flowscape/renderer/projection.h"
#include "flowscape/scenes/scene.h"

namespace flowscape {

// The two moments a forward flow connects, and where the rig (x forward, y left, z up) is then.
struct FramePair {
  double time = 0, next_time = 1 / kFrameRate;
  Pose rig = Pose::Identity(), next_rig = Pose::Identity();  // rig -> world
};

struct GroundTruth {
  Image<float> flow;              // 2 channels, forward flow in pixels (ERP: 360-degree or classic)
  Image<std::uint8_t> semantic;   // CARLA class id, Sky where the ray escapes
  Image<std::uint16_t> instance;  // 0 for the static world and the sky
  Image<float> depth;             // distance along the ray, metres; +infinity for the sky
  Image<std::uint8_t> valid;      // 1 where the target is in front of the camera and visible then
};

struct RenderOptions {
  int samples_per_pixel = 16;
  int max_bounces = 4;  // Russian roulette may end paths earlier after the third bounce
  std::uint64_t seed =
      0;  // with the pixel, the sample and the dimension, seeds every random number
  // Procedural patterns and image maps; false: every material's plain albedo and roughness (for
  // comparisons; alpha masks still cut holes: they are geometry).
  bool textures = true;
};

struct RenderStats {
  std::uint64_t rays = 0;  // camera, bounce and shadow rays traced
};

class Renderer {
 public:
  explicit Renderer(const Scene& scene);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Flow: the hit point, fixed on its object, moved to the object's pose at next_time and projected
  // by the camera at next_time; the sky moves with the rig's rotation only.
  GroundTruth ground_truth(const Projection& projection, const FramePair& frames,
                           FlowMode mode = FlowMode::Wrap360);

  // Linear HDR radiance (RGB) at frames.time, path traced: Lambertian, clear-coat, metal, glass
  // and emissive surfaces, sun (sampled directly) and sky, Russian roulette, a low-discrepancy
  // sampler (R2 per dimension pair, shifted per pixel). The same bytes for any thread count.
  Image<float> color(const Projection& projection, const FramePair& frames,
                     const RenderOptions& options = {}, RenderStats* stats = nullptr);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The cube rig: the six 90-degree faces at one optical centre, rendered for the same frame pair and
// stacked into N x 6N images in kFaces order (geometry.h's face_view; the layout stitch.h takes).
struct CubeFrame {
  Image<float> color;  // linear RGB; empty when not asked for
  GroundTruth truth;
};
CubeFrame render_cube(Renderer& renderer, int face_size, const FramePair& frames,
                      const RenderOptions* color_options, FlowMode mode = FlowMode::Wrap360);

}  // namespace flowscape
