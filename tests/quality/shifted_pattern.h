#pragma once
// Images of a smooth pattern shifted by known amounts, periodic over the width (so it also wraps
// like a panorama), and constant flows: photoconsistency whose answer is known.
#include <algorithm>
#include <cmath>

#include "flowscape/core/image.h"

namespace shifted {

using flowscape::Image;

inline constexpr int W = 64, H = 48;
inline constexpr double kTwoPi = 6.283185307179586;

// A smooth pattern, periodic over the image width (so it also wraps like a panorama), 0-255.
inline double pattern(double x, double y, int c) {
  return 128 + 60 * std::sin(kTwoPi * 3 * x / W + c) * std::cos(0.21 * y) +
         40 * std::cos(kTwoPi * 5 * x / W + 0.13 * y + 2 * c);
}

inline Image<float> image_of(double dx, double dy) {  // the pattern moved by (dx, dy)
  Image<float> image(W, H, 3);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      for (int c = 0; c < 3; ++c) image.pixel(x, y)[c] = float(pattern(x - dx, y - dy, c));
  return image;
}

inline Image<float> constant_flow(double u, double v) {
  Image<float> flow(W, H, 2);
  for (std::size_t i = 0; i < flow.pixel_count(); ++i)
    flow.data[2 * i] = float(u), flow.data[2 * i + 1] = float(v);
  return flow;
}

inline Image<std::uint8_t> to8(const Image<float>& image) {
  Image<std::uint8_t> out(image.width, image.height, image.channels);
  for (std::size_t i = 0; i < image.data.size(); ++i)
    out.data[i] = std::uint8_t(std::lround(std::clamp(image.data[i], 0.0f, 255.0f)));
  return out;
}

}  // namespace shifted
