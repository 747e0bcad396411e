#include "flowscape/quality/photoconsistency.h"

#include <cmath>
#include <stdexcept>

#include "flowscape/geometry/geometry.h"

namespace flowscape {
namespace {

struct Sums {
  double pe = 0, wpe = 0, wpe_visible = 0, wpe_occluded = 0;
  long pixels = 0, visible = 0, occluded = 0;
};

int floor_int(float v) {  // std::floor without a libm call
  const int i = int(v);
  return i - (float(i) > v);
}

// One row of image 1 against image 2 at the flow's targets, C channels (bilinear taps, panoramas
// wrap horizontally), added to `sums`.
template <int C>
void row_errors(const PairImages& p, int y, Sums& sums, float* warp_error) {
  const int W = p.image1.width, H = p.image1.height, stride = W * C;
  const float* flow = p.flow.pixel(0, y);
  const std::uint8_t *a = p.image1.pixel(0, y), *b = p.image2.pixel(0, y);
  const std::uint8_t* known = p.known.data ? p.known.pixel(0, y) : nullptr;
  const std::uint8_t* visible = p.visible.data ? p.visible.pixel(0, y) : nullptr;
  float pe = 0, wpe = 0, wpe_visible = 0, wpe_occluded = 0;
  for (int x = 0; x < W; ++x) {
    const float u = flow[2 * x], v = flow[2 * x + 1];
    if ((known && !known[x]) || !is_known_flow(u, v)) continue;
    const float tx = float(x) + u, ty = float(y) + v;
    if (ty < 0 || ty > float(H - 1)) continue;
    if (p.panorama ? (tx < float(-W) || tx >= float(2 * W)) : (tx < 0 || tx > float(W - 1)))
      continue;
    int x0 = floor_int(tx);
    const int y0 = floor_int(ty), y1 = std::min(y0 + 1, H - 1);
    const float fx = tx - float(x0), fy = ty - float(y0);
    int x1;
    if (p.panorama) {
      x0 = x0 < 0 ? x0 + W : x0 >= W ? x0 - W : x0;
      x1 = x0 + 1 == W ? 0 : x0 + 1;
    } else {
      x1 = std::min(x0 + 1, W - 1);
    }
    const std::uint8_t* r0 = p.image2.data + std::size_t(y0) * stride;
    const std::uint8_t* r1 = p.image2.data + std::size_t(y1) * stride;
    const float w00 = (1 - fx) * (1 - fy), w10 = fx * (1 - fy), w01 = (1 - fx) * fy, w11 = fx * fy;
    float photo = 0, warped = 0;
    for (int c = 0; c < C; ++c) {
      const float i1 = a[x * C + c];
      const float sample =
          w00 * r0[x0 * C + c] + w10 * r0[x1 * C + c] + w01 * r1[x0 * C + c] + w11 * r1[x1 * C + c];
      photo += std::abs(i1 - float(b[x * C + c])), warped += std::abs(i1 - sample);
    }
    photo *= 1.0f / C, warped *= 1.0f / C;
    pe += photo, wpe += warped, ++sums.pixels;
    if (visible && visible[x]) wpe_visible += warped, ++sums.visible;
    if (visible && !visible[x]) wpe_occluded += warped, ++sums.occluded;
    if (warp_error) warp_error[x] = warped;
  }
  sums.pe += pe, sums.wpe += wpe, sums.wpe_visible += wpe_visible;
  sums.wpe_occluded += wpe_occluded;
}

void check_sizes(const PairImages& p) {
  const auto same = [&](int w, int h) { return w == p.image1.width && h == p.image1.height; };
  if (!same(p.image2.width, p.image2.height) || p.image2.channels != p.image1.channels)
    throw std::invalid_argument("the two images differ in size or channels");
  if (!same(p.flow.width, p.flow.height) || p.flow.channels != 2)
    throw std::invalid_argument("the flow's size differs from the images'");
  if ((p.known.data && !same(p.known.width, p.known.height)) ||
      (p.visible.data && !same(p.visible.width, p.visible.height)))
    throw std::invalid_argument("a mask's size differs from the images'");
}

}  // namespace

PairErrors photo_errors(const PairImages& pair) { return photo_errors(pair, nullptr); }

PairErrors photo_errors(const PairImages& p, Image<float>* warp_error) {
  check_sizes(p);
  const int W = p.image1.width, H = p.image1.height, C = p.image1.channels;
  if (warp_error) *warp_error = Image<float>(W, H, 1);
  Sums sums;
  for (int y = 0; y < H; ++y) {
    float* error_row = warp_error ? warp_error->pixel(0, y) : nullptr;
    if (C == 3)
      row_errors<3>(p, y, sums, error_row);
    else if (C == 1)
      row_errors<1>(p, y, sums, error_row);
    else
      throw std::invalid_argument("images need 1 or 3 channels");
  }
  const auto mean = [](double sum, long n) { return n ? sum / double(n) : 0.0; };
  return {mean(sums.pe, sums.pixels),
          mean(sums.wpe, sums.pixels),
          mean(sums.wpe_visible, sums.visible),
          mean(sums.wpe_occluded, sums.occluded),
          sums.pixels,
          sums.visible,
          sums.occluded};
}

double diff_percent(double pe, double wpe) { return pe > 0 ? 100 * (pe - wpe) / pe : 0; }

const char* quality_label(double diff) { return diff >= 10 ? "high" : "medium/low"; }

}  // namespace flowscape
