#pragma once
// Motion blur for the final pass: a frame's colour integrated over the time its shutter is open,
// traced, not smeared: the shutter is cut into steps, and for each the scene and the camera are
// posed at its middle time and a share of the pixel's samples traced there. The ground truth
// stays defined at the frame's time.
#include <functional>
#include <vector>

#include "flowscape/renderer/renderer.h"

namespace flowscape {

struct Shutter {
  double open = 0, close = 0;  // seconds
};
// `angle` degrees of a frame at `frame_rate` (180: half the frame time), centred on `time`.
Shutter centred_shutter(double time, double angle, double frame_rate = kFrameRate);

inline constexpr int kMaxShutterSteps = 8;
// The steps a frame's shutter is cut into: the most, up to kMaxShutterSteps, that share the
// samples (and those that gather indirect light, when not all do) out evenly.
int shutter_steps(const RenderOptions& options);
// The middle of each step: open + (k + 0.5) / steps x (close - open).
std::vector<double> shutter_times(const Shutter& shutter, int steps);

// The colour layers over the shutter: each step traced with samples_per_pixel / steps samples (its
// own seed) with the scene and `camera` posed at its time, then averaged (the normals summed), so
// the albedo and normals the denoiser is guided by follow the blur. With a rolling shutter each
// line's shutter is centred on the line's time: a step at `time` traces line l at time + its
// offset.
ColorLayers shutter_layers(Renderer& renderer, const Projection& projection, const Shutter& shutter,
                           const CameraTrack& camera, const RenderOptions& options,
                           const Readout& readout = {});
// The same with the frame's own colour `centre` (traced with `options` at the shutter's middle
// time, as the clean pass is) standing for the middle third of the shutter: each outer third is
// traced at its middle time with a quarter of the samples (and of those gathering indirect light;
// at least 1, its own seed), and the three thirds weigh the same. That is the noise of `options`'
// samples spread over the shutter (1/9 x (2 x 4 + 1) / spp) for half of them traced, in
// kCentredShutterSteps blur steps.
ColorLayers shutter_layers(Renderer& renderer, const Projection& projection, const Shutter& shutter,
                           const CameraTrack& camera, const RenderOptions& options,
                           const Readout& readout, const ColorLayers& centre);
inline constexpr int kCentredShutterSteps = 3;
// The depth of each pixel's centre ray averaged over the same times, the centre's `centre` (the
// clean pass's ground truth) with the outer thirds' (over the times it meets a surface; +infinity
// where it never does): a denoising guide that does not cut the blur trails.
Image<float> shutter_depth(Renderer& renderer, const Projection& projection, const Shutter& shutter,
                           const CameraTrack& camera, const Readout& readout,
                           const Image<float>& centre);
// The six cube faces over the shutter (render_cube's layout): their layers and, in truth, no
// instance ids and, with `depth_guide` (the a-trous denoiser's), the shutter-averaged depth.
// With `centre` (the clean pass's cube: its colour layers and ground-truth depth at the shutter's
// middle), the outer thirds traced as shutter_layers with a centre does.
CubeFrame shutter_cube(Renderer& renderer, int face_size, const Shutter& shutter,
                       const CameraTrack& camera, const RenderOptions& options, bool depth_guide,
                       const CubeFrame* centre = nullptr);

}  // namespace flowscape
