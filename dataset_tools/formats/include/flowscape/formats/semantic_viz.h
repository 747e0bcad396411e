#pragma once
// Semantic class ids as colours: CARLA's CityScapes palette (design.md); unknown ids are black.
#include <array>
#include <cstdint>

#include "flowscape/core/image.h"

namespace flowscape {

std::array<std::uint8_t, 3> semantic_color(std::uint8_t class_id);
Image<std::uint8_t> semantic_to_color(ImageView<const std::uint8_t> ids);

}  // namespace flowscape
