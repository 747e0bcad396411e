#include "flowscape/formats/srgb.h"

#include <algorithm>
#include <cmath>

namespace flowscape {

std::uint8_t linear_to_srgb8(float linear) {
  const float c = std::clamp(linear, 0.f, 1.f);
  const float encoded = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1 / 2.4f) - 0.055f;
  return std::uint8_t(std::lround(255 * encoded));
}

float srgb8_to_linear(std::uint8_t encoded) {
  const float c = encoded / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

Image<std::uint8_t> linear_to_srgb8(ImageView<const float> linear, float exposure) {
  Image<std::uint8_t> out(linear.width, linear.height, linear.channels);
  for (std::size_t i = 0; i < out.data.size(); ++i)
    out.data[i] = linear_to_srgb8(exposure * linear.data[i]);
  return out;
}

}  // namespace flowscape
