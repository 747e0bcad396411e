#pragma once
// Internal: the colour pass of Renderer (see Renderer::color).
#include "embree_scene.h"
#include "flowscape/renderer/renderer.h"
#include "image_textures.h"

namespace flowscape {

ColorLayers path_trace(EmbreeScene& embree, const ImageTextures& images,
                       const Projection& projection, const FramePair& frames,
                       const RenderOptions& options, RenderStats* stats);

}  // namespace flowscape
