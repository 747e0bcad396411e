#pragma once
// The built-in actor models (scenes/showcase.h) as a contact sheet: one row per model, seen from
// the front, the side, the back and three-quarters in front, in sky light (or one row per model and
// time of day under the physical sky, a street lamp beside it and its own lamps on once the
// release's would be), as the release's path tracer and denoiser render them; each tile labelled,
// and a semantic tile after them.
#include <cstdint>
#include <string>
#include <vector>

#include "flowscape/core/image.h"
#include "flowscape/release/config.h"

namespace flowscape {

struct GalleryOptions {
  int height = 192;                 // of each tile (width 4/3 of it)
  ReleaseConfig color;              // spp, indirect_spp, denoise
  std::vector<std::string> models;  // empty: every built-in model
  int variant = 0;
  std::vector<std::string> times_of_day;  // day, dawn, dusk, night or degrees; empty: sky light
};
std::vector<std::vector<Image<std::uint8_t>>> actor_gallery(const GalleryOptions& options);

}  // namespace flowscape
