#pragma once
// Flow as colour, on the Middlebury colour wheel (Baker et al. 2011): hue = direction,
// saturation = magnitude / scale. Unknown or invalid flow is drawn black.
#include <cstdint>

#include "flowscape/core/image.h"

namespace flowscape {

enum class FlowWheel {
  Middlebury,  // classic: scale = largest magnitude; beyond the scale, colours darken to 75 %
  PanoFlow,    // the paper's: beyond the scale, saturation falls as 1 / (1 + ln(m / scale))
};

struct FlowVizOptions {
  FlowWheel wheel = FlowWheel::PanoFlow;
  // <= 0: automatic. Middlebury: the largest known magnitude. PanoFlow: the 90th percentile of
  // the known magnitudes, so a few huge panoramic displacements do not wash out the rest.
  double scale = 0;
};

// RGB colour of one flow vector already divided by the scale (|f| = 1 at the scale).
void wheel_color(FlowWheel wheel, double fu, double fv, std::uint8_t rgb[3]);

Image<std::uint8_t> flow_to_color(ImageView<const float> uv, ImageView<const std::uint8_t> valid,
                                  const FlowVizOptions& options);

}  // namespace flowscape
