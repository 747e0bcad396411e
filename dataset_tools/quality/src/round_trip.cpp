#include "flowscape/quality/round_trip.h"

#include <cmath>
#include <stdexcept>

#include "flowscape/geometry/geometry.h"

namespace flowscape {
namespace {

// Bilinear sample of a 2-channel image at continuous position (px, py), pixel centres at +0.5;
// columns wrap on a panorama and clamp otherwise.
Vec2 sample(ImageView<const float> image, double px, double py, bool panorama) {
  const int W = image.width, H = image.height;
  const double x = px - 0.5, y = std::clamp(py - 0.5, 0.0, double(H - 1));
  const int x0 = int(std::floor(x)), y0 = std::min(int(y), H - 1), y1 = std::min(y0 + 1, H - 1);
  const double fx = x - x0, fy = y - y0;
  const auto column = [&](int c) { return panorama ? ((c % W) + W) % W : std::clamp(c, 0, W - 1); };
  const auto at = [&](int c, int r) {
    const float* p = image.pixel(column(c), r);
    return Vec2(p[0], p[1]);
  };
  return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
         fy * ((1 - fx) * at(x0, y1) + fx * at(x0 + 1, y1));
}

}  // namespace

RoundTrip round_trip(const RoundTripImages& in, double tolerance) {
  const int W = in.forward.width, H = in.forward.height;
  for (const auto& [w, h] : {std::pair{in.visible.width, in.visible.height},
                             {in.backward.width, in.backward.height},
                             {in.visible_back.width, in.visible_back.height}})
    if (w != W || h != H) throw std::invalid_argument("the flows and masks differ in size");
  RoundTrip trip;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const float* v = in.forward.pixel(x, y);
      if (!*in.visible.pixel(x, y) || !is_known_flow(v[0], v[1])) continue;
      double qx = x + 0.5 + v[0];
      const double qy = y + 0.5 + v[1];
      if (in.panorama) qx -= W * std::floor(qx / W);
      if (qy < 0 || qy >= H || qx < 0 || qx >= W) continue;
      if (!*in.visible_back.pixel(std::min(int(qx), W - 1), std::min(int(qy), H - 1))) continue;
      ++trip.both_ways;
      const Vec2 back = sample(in.backward, qx, qy, in.panorama);
      double du = v[0] + back.x();
      if (in.panorama) du -= W * std::round(du / W);
      trip.returned += std::hypot(du, v[1] + back.y()) <= tolerance;
    }
  return trip;
}

}  // namespace flowscape
