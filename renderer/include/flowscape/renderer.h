#pragma once
// Embree ray casting of a Scene: exact ground truth for the pixel-centre ray of every pixel.
// Each mesh gets its own BVH, built once; every frame only re-poses the instances.
#include <cstdint>
#include <memory>

#include "flowscape/image.h"
#include "flowscape/projection.h"
#include "flowscape/scene.h"

namespace flowscape {

// The two moments a forward flow connects, and where the rig (x forward, y left, z up) is then.
struct FramePair {
  double time = 0, next_time = 1.0 / 30;
  Pose rig = Pose::Identity(), next_rig = Pose::Identity();  // rig -> world
};

struct GroundTruth {
  Image<float> flow;              // 2 channels, forward flow in pixels (ERP: 360-degree or classic)
  Image<std::uint8_t> semantic;   // CARLA class id, Sky where the ray escapes
  Image<std::uint16_t> instance;  // 0 for the static world and the sky
  Image<float> depth;             // distance along the ray, metres; +infinity for the sky
  Image<std::uint8_t> valid;      // 1 where the target is in front of the camera and visible then
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

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace flowscape
