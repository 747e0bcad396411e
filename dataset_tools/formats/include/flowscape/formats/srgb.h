#pragma once
// Linear HDR colour -> 8-bit sRGB for PNG/JPEG (values above 1 clip).
#include <cstdint>

#include "flowscape/core/image.h"

namespace flowscape {

std::uint8_t linear_to_srgb8(float linear);
Image<std::uint8_t> linear_to_srgb8(ImageView<const float> linear, float exposure = 1);

}  // namespace flowscape
