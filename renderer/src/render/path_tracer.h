#pragma once
// Internal: the colour pass of Renderer (see Renderer::color).
#include <functional>
#include <vector>

#include "flowscape/renderer/renderer.h"
#include "render/embree_scene.h"
#include "render/image_textures.h"
#include "render/lights.h"

namespace flowscape {

// The camera over a shutter (motion blur): each sample at its own time u in [0, 1) of the shutter,
// its rays at time first + u (last - first) of the shutter scene (EmbreeScene::set_shutter), the
// camera interpolated between poses at evenly spaced times over the shutter (its position
// linearly, its rotation spherically).
struct ShutterCamera {
  // its positions and rotations at u = k / (size - 1), at least 2
  std::vector<Vec3> positions;
  std::vector<Eigen::Quaterniond> rotations;
  float first = 0, last = 1;  // the shutter's open and close as times of the shutter scene
  Pose at(double u) const;
  float ray_time(double u) const { return float(first + u * (last - first)); }
};
// The camera on `track` over [open, close] in `steps` poses, in a shutter scene over
// [scene_open, scene_close].
ShutterCamera shutter_camera(const std::function<Pose(double)>& track, double open, double close,
                             double scene_open, double scene_close, int steps);

// Zero layers of width x height.
ColorLayers color_layers_of(int width, int height);
// Traces the pixels of `window` into `out` (the whole image's layers) with the scene as `embree`
// is posed and the camera at `camera` (camera -> world, as FramePair::rig); `lights` are the
// scene's at the same time. With `shutter` (the scene a shutter scene) each sample is traced at
// its own time over it instead. Returns the rays traced.
std::uint64_t path_trace(EmbreeScene& embree, const ImageTextures& images, const Lights& lights,
                         const Projection& projection, const Pose& camera,
                         const RenderOptions& options, const PixelWindow& window, ColorLayers& out,
                         const ShutterCamera* shutter = nullptr);

}  // namespace flowscape
