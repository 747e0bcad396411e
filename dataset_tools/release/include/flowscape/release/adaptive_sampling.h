#pragma once
// Adaptive sampling: a frame's samples spent where its denoised colour is still wrong. Every pixel
// first takes half the budget as two independent renders (the halves); the squared difference of
// their denoised colours in 8-bit sRGB, averaged over each pixel's 3 x 3 neighbours, estimates
// where the denoised frame is worst, and the share of the pixels it ranks highest take the other
// half of the budget in a second pass, which replaces their first: a pixel's colour is the mean of
// samples whose values did not choose them (pooling the first half too would weigh its outliers
// down where they made the choice: a bias), so every pixel stays an unbiased estimate. The
// denoiser then cleans the layers.
// Measured in docs/release.md ("Adaptive sampling").
#include <cstdint>
#include <functional>
#include <vector>

#include "flowscape/renderer/renderer.h"

namespace flowscape {

// How a budget of S samples per pixel on average splits for a share s of the pixels: each half
// takes S / 4 (rounded down), the chosen pixels round((S - 2 x half) / s) more. half 0 (S < 4, or
// s = 0): uniform sampling.
struct SampleSplit {
  int half = 0, more = 0;
};
SampleSplit sample_split(int samples_per_pixel, double share);

// The layers of one image (a camera's, or the cube's stacked faces) rendered with `options`, and
// the release's denoiser on such layers.
using RenderLayers = std::function<ColorLayers(const RenderOptions& options)>;
using DenoiseLayers = std::function<Image<float>(const ColorLayers& layers)>;

// options.samples_per_pixel on average, split by sample_split, and options.indirect_samples in
// the same proportion in every pass (at least 1); each pass with its own seed, derived from
// options.seed. Uniform (render(options)) where the split has no halves. The same bytes for any
// thread count.
ColorLayers adaptive_color_layers(const RenderLayers& render, const DenoiseLayers& denoise,
                                  const RenderOptions& options, double share);

// Per pixel, the squared difference of `a` and `b` in 8-bit sRGB, summed over the channels.
std::vector<double> squared_srgb_difference(const Image<float>& a, const Image<float>& b);
// The estimate of where a denoised frame is wrong: per pixel, the squared difference of `a` and
// `b` in 8-bit sRGB (summed over the channels), averaged over its 3 x 3 neighbours in the image.
std::vector<double> disagreement(const Image<float>& a, const Image<float>& b);
// 1 for the round(share x pixels) pixels of the highest score (ties: the first in memory order),
// 0 elsewhere.
Image<std::uint8_t> top_pixels(const std::vector<double>& score, int width, int height,
                               double share);
// `base` with every layer of the pixels where `where` is non-zero taken from `by`.
ColorLayers replaced(ColorLayers base, const ColorLayers& by, ImageView<const std::uint8_t> where);

}  // namespace flowscape
