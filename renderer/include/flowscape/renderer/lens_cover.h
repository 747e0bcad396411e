#pragma once
// What lies on a real lens's front element in the final pass: water drops in rain and dirt. The
// lens is focused far beyond them, so a drop shows a blurred, inverted, wider view of the scene
// behind it (it is a small lens of its own) and dirt scatters part of the light into a haze. The
// same cover stays on the lens for a whole sequence. The ground truth stays the scene's; the
// output kind `lens_mask` marks the pixels the cover hides.
#include <cstdint>
#include <vector>

#include "flowscape/core/image.h"
#include "flowscape/core/types.h"

namespace flowscape {

struct LensDrop {
  Vec2 centre;    // pixels
  double radius;  // pixels
};
struct LensCover {
  std::vector<LensDrop> drops;
  Image<float> dirt{};  // 1 channel: the share of the light dirt scatters there (empty: none)
  bool empty() const { return drops.empty() && dirt.data.empty(); }
};

// In a drop the pixel at offset d from its centre sees the scene at centre - kDropView d, blurred
// by a Gaussian of radius / 3 and dimmed to kDropTransmission; its rim (the outer kDropRim of the
// radius) fades from the drop to the clear scene. Dirt scatters its share a of the light: the pixel
// keeps (1 - a) of its own and gets a x kDirtTransmission of the scene blurred by kDirtBlur.
inline constexpr double kDropView = 3, kDropTransmission = 0.85, kDropRim = 0.2;
inline constexpr double kDirtTransmission = 0.5, kDirtBlur = 16;  // pixels

// `drops` drops of radii 1-4 % of the image's shorter side and dirt blotches up to `dirt` (0:
// none, at most 1), placed by `seed`.
LensCover lens_cover(int width, int height, int drops, double dirt, std::uint64_t seed);
// The light (RGB) as the lens sees it through the cover.
Image<float> through_cover(ImageView<const float> light, const LensCover& cover);
// 1 where the cover hides the scene: inside a drop but its rim's outer half, or dirt of at least
// 0.5; 0 elsewhere.
Image<std::uint8_t> cover_mask(const LensCover& cover, int width, int height);
// How much of a drop is at a distance from its centre: 1 inside, falling linearly to 0 over the
// rim.
double drop_share(const LensDrop& drop, double distance);

}  // namespace flowscape
