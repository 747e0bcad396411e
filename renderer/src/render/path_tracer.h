#pragma once
// Internal: the colour pass of Renderer (see Renderer::color).
#include "flowscape/renderer/renderer.h"
#include "render/embree_scene.h"
#include "render/image_textures.h"
#include "render/lights.h"

namespace flowscape {

// Zero layers of width x height.
ColorLayers color_layers_of(int width, int height);
// Traces the pixels of `window` into `out` (the whole image's layers) with the scene as `embree`
// is posed and the camera at `camera` (camera -> world, as FramePair::rig); `lights` are the
// scene's at the same time. Returns the rays traced.
std::uint64_t path_trace(EmbreeScene& embree, const ImageTextures& images, const Lights& lights,
                         const Projection& projection, const Pose& camera,
                         const RenderOptions& options, const PixelWindow& window, ColorLayers& out);

}  // namespace flowscape
