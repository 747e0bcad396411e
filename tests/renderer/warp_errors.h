#pragma once
// Photoconsistency of two rendered frames under ground-truth flow, measured independently of the
// library's gt_quality: mean |I2(x + V) - I1(x)| over the channels in 8-bit sRGB with bilinear
// sampling, over the pixels whose target is visible and inside the image.
#include <algorithm>
#include <cmath>

#include "flowscape/formats/srgb.h"
#include "flowscape/renderer/renderer.h"

struct WarpErrors {
  double pe = 0, wpe = 0;
  double noise = 0;    // between two renders of the first frame with other seeds
  double wpe_off = 0;  // of a flow one pixel off
  int pixels = 0;
};

inline double srgb8(const flowscape::Image<float>& linear, double x, double y, int c) {
  const int x0 = int(std::floor(x - 0.5)), y0 = int(std::floor(y - 0.5));
  const double fx = x - 0.5 - x0, fy = y - 0.5 - y0;
  double sum = 0;
  for (int k = 0; k < 4; ++k) {
    const int xi = std::clamp(x0 + k % 2, 0, linear.width - 1),
              yi = std::clamp(y0 + k / 2, 0, linear.height - 1);
    sum += (k % 2 ? fx : 1 - fx) * (k / 2 ? fy : 1 - fy) *
           flowscape::linear_to_srgb8(linear.pixel(xi, yi)[c]);
  }
  return sum;
}

inline double mean_abs_difference(const flowscape::Image<float>& a, double ax, double ay,
                                  const flowscape::Image<float>& b, double bx, double by) {
  double sum = 0;
  for (int c = 0; c < 3; ++c) sum += std::abs(srgb8(a, ax, ay, c) - srgb8(b, bx, by, c));
  return sum / 3;
}

inline WarpErrors warp_errors(const flowscape::Image<float>& first,
                              const flowscape::Image<float>& again,
                              const flowscape::Image<float>& second,
                              const flowscape::GroundTruth& truth) {
  WarpErrors e;
  const int W = first.width, H = first.height;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const float* f = truth.flow.pixel(x, y);
      const double px = x + 0.5, py = y + 0.5, tx = px + f[0], ty = py + f[1];
      if (!*truth.valid.pixel(x, y) || tx < 1 || ty < 1 || tx > W - 1 || ty > H - 1) continue;
      e.pe += mean_abs_difference(second, px, py, first, px, py);
      e.wpe += mean_abs_difference(second, tx, ty, first, px, py);
      e.wpe_off += mean_abs_difference(second, tx + 1, ty, first, px, py);
      e.noise += mean_abs_difference(again, px, py, first, px, py);
      ++e.pixels;
    }
  if (e.pixels) e.pe /= e.pixels, e.wpe /= e.pixels, e.noise /= e.pixels, e.wpe_off /= e.pixels;
  return e;
}
