#pragma once
// Ground-truth quality of optical flow by photoconsistency (design.md): PE = mean |I1(x) - I2(x)|,
// WPE = mean |I2(x + V(x)) - I1(x)| with I2 sampled bilinearly, 8-bit intensities averaged over
// the channels, over the pixels whose flow is known and whose target lies inside the image
// (panoramas wrap horizontally). Diff = (PE - WPE) / PE; "high" quality when Diff >= 10 %.
#include <cstdint>
#include <optional>

#include "flowscape/core/image.h"

namespace flowscape {

struct PairErrors {
  double pe = 0, wpe = 0;  // means over `pixels`
  // over the pixels a visibility mask marks visible (non-occluded) and hidden (occluded), when
  // one is given
  double wpe_visible = 0, wpe_occluded = 0;
  long pixels = 0, visible_pixels = 0, occluded_pixels = 0;
};

struct PairImages {
  ImageView<const std::uint8_t> image1, image2;  // same size and channels
  ImageView<const float> flow;                   // 2 channels
  ImageView<const std::uint8_t> known = {};      // optional: 0 = no flow here (KITTI's valid bit)
  ImageView<const std::uint8_t> visible = {};  // optional: 1 = not occluded (FlowScape valid, noc)
  bool panorama = false;                       // ERP: targets wrap around horizontally
};

PairErrors photo_errors(const PairImages& pair);

// Optional per-pixel |I2(x + V) - I1(x)| (mean over channels), 0 where not counted.
PairErrors photo_errors(const PairImages& pair, Image<float>* warp_error);

double diff_percent(double pe, double wpe);  // (PE - WPE) / PE in %
const char* quality_label(double diff);      // "high" (>= 10 %) or "medium/low"

}  // namespace flowscape
