#pragma once
// Linear HDR colour -> 8-bit sRGB for PNG/JPEG (values above 1 clip), and back.
#include <cstdint>

#include "flowscape/core/image.h"

namespace flowscape {

std::uint8_t linear_to_srgb8(float linear);
float srgb8_to_linear(std::uint8_t encoded);  // the inverse: 0..255 -> [0, 1]
Image<std::uint8_t> linear_to_srgb8(ImageView<const float> linear, float exposure = 1);

}  // namespace flowscape
