#include "flowscape/quality/image_statistics.h"

#include <cmath>
#include <stdexcept>

namespace flowscape {

double flat_share(ImageView<const std::uint8_t> image, ImageView<const std::uint8_t> mask,
                  double threshold, bool panorama) {
  if (mask.width != image.width || mask.height != image.height)
    throw std::invalid_argument("flat_share: the mask and the image differ in size");
  const int W = image.width, H = image.height;
  const auto grey = [&](int x, int y) {
    x = (x + W) % W;
    const std::uint8_t* p = image.pixel(x, y);
    double sum = 0;
    for (int c = 0; c < image.channels; ++c) sum += p[c];
    return sum / image.channels;
  };
  long flat = 0, counted = 0;
  for (int y = 1; y + 1 < H; ++y)
    for (int x = panorama ? 0 : 1; x < (panorama ? W : W - 1); ++x) {
      if (*mask.pixel(x, y) == 0) continue;
      const double gx = (grey(x + 1, y) - grey(x - 1, y)) / 2,
                   gy = (grey(x, y + 1) - grey(x, y - 1)) / 2;
      ++counted;
      flat += std::hypot(gx, gy) < threshold;
    }
  return counted ? double(flat) / counted : 0;
}

}  // namespace flowscape
