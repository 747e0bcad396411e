#pragma once
// Internal: writing one pixel's ground truth, shared by the global shutter (renderer.cpp) and the
// rolling shutter (rolling_truth.cpp).
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <limits>

#include "flowscape/renderer/renderer.h"
#include "render/embree_scene.h"
#include "render/image_textures.h"

namespace flowscape {

inline constexpr float kNoVector = std::numeric_limits<float>::quiet_NaN();

// Where a pixel's surface point (or, for the sky, its direction) is seen at a target moment.
struct TargetTruth {
  float u = kUnknownFlow, v = kUnknownFlow;
  std::uint8_t valid = 0;
  Vec3 moved = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());  // the point then, world
};

// Where the camera is when a pixel is captured.
struct CameraAt {
  Vec3 origin;
  Mat3 world_to_camera;  // world -> the view's camera frame (Projection::camera_to_rig)
};
CameraAt camera_at(const Pose& camera, const Projection& projection);

// Images of width x height for everything `request` asks for.
GroundTruth allocate_truth(const TruthRequest& request, int width, int height);

void put_vector(Image<float>& image, int x, int y, const Vec3& value);
void put_flow(Image<float>& flow, Image<std::uint8_t>& valid, int x, int y, const TargetTruth& t);
// A pixel outside a lens's image: nothing, in every kind.
void put_uncovered(GroundTruth& out, int x, int y);
// Depth, class and instance of the first opaque surface along the ray (the sky where none).
void put_surface(const EmbreeScene& scene, const Hit& hit, GroundTruth& out, int x, int y);
// The normals of the first opaque surface, in the view's camera frame, facing the camera.
void put_normals(const EmbreeScene& scene, const ImageTextures& images,
                 const Projection& projection, const TruthRequest& request, const CameraAt& camera,
                 const Hit& hit, const Vec3& direction, Vec2 pixel, GroundTruth& out, int x, int y);

// visit(x, y) for every pixel of the window, in parallel over 2-D blocks (a rolling shutter's
// window is a single line).
template <class Visit>
void parallel_pixels(const PixelWindow& window, Visit&& visit) {
  const tbb::blocked_range2d<int> pixels(window.y0, window.y1, window.x0, window.x1);
  tbb::parallel_for(pixels, [&](const tbb::blocked_range2d<int>& block) {
    for (int y = block.rows().begin(); y < block.rows().end(); ++y)
      for (int x = block.cols().begin(); x < block.cols().end(); ++x)
        naming_pixels([&] { visit(x, y); }, [&](int) { return std::pair{x, y}; });
  });
}

// Poses the scene for the line captured at t: set_times for a global shutter (the frame),
// set_line_time for a rolling one.
inline void pose_line(EmbreeScene& scene, const Readout& readout, double t) {
  if (readout.global())
    scene.set_times(t, {});
  else
    scene.set_line_time(t);
}

// The ground truth of a view with a rolling shutter (TruthRequest::readout; rolling_truth.cpp).
GroundTruth rolling_ground_truth(EmbreeScene& scene, const ImageTextures& images,
                                 const Projection& projection, const TruthRequest& request);

}  // namespace flowscape
