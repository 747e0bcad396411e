#pragma once
// Internal: the colour pass of Renderer (see Renderer::color).
#include "embree_scene.h"
#include "flowscape/renderer/renderer.h"
#include "image_textures.h"
#include "lights.h"

namespace flowscape {

// `lights` are the scene's at frames.time.
ColorLayers path_trace(EmbreeScene& embree, const ImageTextures& images, const Lights& lights,
                       const Projection& projection, const FramePair& frames,
                       const RenderOptions& options, RenderStats* stats);

}  // namespace flowscape
