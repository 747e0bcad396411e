#pragma once
// Tiles of 8-bit RGB images laid out in rows (for previews, dataset cards and contact sheets).
#include <cstdint>
#include <string>
#include <vector>

#include "flowscape/core/image.h"

namespace flowscape {

// Each row's tiles side by side, rows stacked; tiles of a row share their height, narrower rows
// are padded with black on the right.
Image<std::uint8_t> contact_sheet(const std::vector<std::vector<Image<std::uint8_t>>>& rows);
// Writes `text` in white on a dark band across the top-left of an RGB tile (sized to the tile).
void label_tile(Image<std::uint8_t>& tile, const std::string& text);

// At most `width` pixels wide (aspect kept), by area averaging.
Image<std::uint8_t> shrink_to_width(const Image<std::uint8_t>& image, int width);

}  // namespace flowscape
