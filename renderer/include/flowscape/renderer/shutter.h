#pragma once
// Motion blur for the final pass: a frame's colour integrated over the time its shutter is open,
// traced, not smeared: each sample at its own time, the scene and the camera where they are then
// (Embree's motion blur; Renderer::color_layers over a Shutter). The ground truth stays defined
// at the frame's time.
#include "flowscape/renderer/renderer.h"

namespace flowscape {

// `angle` degrees of a frame at `frame_rate` (180: half the frame time), centred on `time`.
Shutter centred_shutter(double time, double angle, double frame_rate = kFrameRate);

// What the final pass traces over the shutter for a frame the clean pass traced with `clean`:
// half its samples (and of those gathering indirect light; at least 1 each), half its edge
// samples, its own seed.
RenderOptions shutter_options(const RenderOptions& clean);

// The six cube faces over the shutter (render_cube's layout): their layers and, in truth, no
// instance ids and, with `depth_guide` (the a-trous denoiser's), the depth over the shutter.
CubeFrame shutter_cube(Renderer& renderer, int face_size, const Shutter& shutter,
                       const CameraTrack& camera, const RenderOptions& options, bool depth_guide);

}  // namespace flowscape
