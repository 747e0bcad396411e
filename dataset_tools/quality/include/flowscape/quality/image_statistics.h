#pragma once
// Statistics of rendered images that say how much a flow network can learn from them.
#include <cstdint>

#include "flowscape/core/image.h"

namespace flowscape {

// The share of the pixels `mask` marks (non-zero) whose grey-level gradient is below `threshold`:
// grey = the mean of the channels (0-255), gx = (I(x+1) - I(x-1)) / 2, gy likewise, |g| =
// sqrt(gx^2 + gy^2). The first and last rows are left out; panoramas wrap around horizontally
// (other images leave out their first and last columns). Flat regions carry no motion cue.
double flat_share(ImageView<const std::uint8_t> image, ImageView<const std::uint8_t> mask,
                  double threshold, bool panorama);

}  // namespace flowscape
