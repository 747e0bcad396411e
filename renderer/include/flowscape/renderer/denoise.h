#pragma once
// Denoising a path-traced frame with its layers (ColorLayers): the direct and the indirect light
// divided by the albedo (so textures, which live in the albedo, stay sharp) and the specular light
// are filtered by an edge-avoiding a-trous wavelet transform (Dammertz et al. 2010) whose weights
// stop at edges of the first surfaces' normals, their planes (depth) and instance ids, and, per
// layer, where luminance differs by more than its noise explains (the variance-guided weights of
// SVGF, Schied et al. 2017, spatial part): shadow and reflection edges stay sharp. Then the albedo
// multiplies back; the light met before any surface (sky, fog, rain) is kept as rendered. The same
// bytes for any thread count.
#include <cstdint>

#include "flowscape/core/image.h"
#include "flowscape/renderer/projection.h"
#include "flowscape/renderer/renderer.h"

namespace flowscape {

struct DenoiseGuide {
  const Projection* projection;             // the camera of the frame (rays for the depths)
  ImageView<const float> depth;             // along the pixel centres' rays; +inf for the sky
  ImageView<const std::uint16_t> instance;  // 0 for the static world
};

// Per layer: direct, indirect, specular. The defaults are the best measured on the release's
// frames (bench_image_quality): the indirect light, smooth and the noisiest, is filtered widest.
struct DenoiseOptions {
  int levels[3] = {3, 4, 2};  // a-trous steps 1, 2, 4, ... pixels
  int normal_sharpness = 4;   // weight (n_p . n_q)^(2^sharpness)
  float plane_tolerance = 2;  // in pixel footprints times the step: distance off p's plane
  // In standard deviations of the noise: weight exp(-|dl| / (k sigma)); 0: no luminance stop
  // (indirect light is smooth, and its variance from a few samples too noisy to steer by).
  float luminance_tolerance[3] = {2, 0, 2};
};

// The denoised colour (linear RGB) of one camera's frame; an ERP frame wraps around horizontally.
Image<float> denoise(const ColorLayers& layers, const DenoiseGuide& guide,
                     const DenoiseOptions& options = {});
// The six faces of a cube frame's colour with their ground truth (render_cube's), each denoised on
// its own, stacked.
Image<float> denoise_cube(const ColorLayers& color, const GroundTruth& truth,
                          const DenoiseOptions& options = {});

}  // namespace flowscape
