#include "flowscape/formats/flow_viz.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "flowscape/geometry/geometry.h"

namespace flowscape {
namespace {

// The 55 hues of the Middlebury wheel: red-yellow 15, yellow-green 6, green-cyan 4,
// cyan-blue 11, blue-magenta 13, magenta-red 6.
std::vector<std::array<double, 3>> make_wheel() {
  struct Segment {
    int length, ramp_channel;
    bool rising;
    int full_channel;
  };
  const Segment segments[6] = {{15, 1, true, 0},  {6, 0, false, 1}, {4, 2, true, 1},
                               {11, 1, false, 2}, {13, 0, true, 2}, {6, 2, false, 0}};
  std::vector<std::array<double, 3>> wheel;
  for (const Segment& s : segments)
    for (int i = 0; i < s.length; ++i) {
      const double ramp = std::floor(255.0 * i / s.length);
      std::array<double, 3> color{0, 0, 0};
      color[s.full_channel] = 255;
      color[s.ramp_channel] = s.rising ? ramp : 255 - ramp;
      wheel.push_back(color);
    }
  return wheel;
}

const std::vector<std::array<double, 3>>& wheel_hues() {
  static const std::vector<std::array<double, 3>> wheel = make_wheel();
  return wheel;
}

double saturation_beyond_scale(FlowWheel wheel, double radius) {
  return wheel == FlowWheel::Middlebury ? 1.0 : 1.0 / (1.0 + std::log(radius));
}

double auto_scale(ImageView<const float> uv, ImageView<const std::uint8_t> valid, FlowWheel wheel) {
  std::vector<double> magnitudes;
  for (int y = 0; y < uv.height; ++y)
    for (int x = 0; x < uv.width; ++x) {
      const float* f = uv.pixel(x, y);
      if (is_known_flow(f[0], f[1]) && (!valid.data || *valid.pixel(x, y)))
        magnitudes.push_back(std::hypot(f[0], f[1]));
    }
  if (magnitudes.empty()) return 1;
  const std::size_t rank =
      wheel == FlowWheel::Middlebury ? magnitudes.size() - 1 : magnitudes.size() * 9 / 10;
  std::nth_element(magnitudes.begin(), magnitudes.begin() + rank, magnitudes.end());
  return std::max(magnitudes[rank], 1e-9);
}

}  // namespace

void wheel_color(FlowWheel wheel, double fu, double fv, std::uint8_t rgb[3]) {
  const auto& hues = wheel_hues();
  const int n = int(hues.size());
  const double radius = std::hypot(fu, fv);
  const double position = (std::atan2(-fv, -fu) / kPi + 1) / 2 * (n - 1);
  const int k0 = int(std::floor(position)), k1 = (k0 + 1) % n;
  const double f = position - k0;
  for (int c = 0; c < 3; ++c) {
    double col = ((1 - f) * hues[k0][c] + f * hues[k1][c]) / 255.0;
    if (radius <= 1) {
      col = 1 - radius * (1 - col);
    } else if (wheel == FlowWheel::Middlebury) {
      col *= 0.75;
    } else {
      col = 1 - saturation_beyond_scale(wheel, radius) * (1 - col);
    }
    rgb[c] = std::uint8_t(std::floor(255 * col + 0.5));
  }
}

Image<std::uint8_t> flow_to_color(ImageView<const float> uv, ImageView<const std::uint8_t> valid,
                                  const FlowVizOptions& options) {
  if (uv.channels != 2) throw std::invalid_argument("flow_to_color needs a 2-channel flow");
  const double scale = options.scale > 0 ? options.scale : auto_scale(uv, valid, options.wheel);
  Image<std::uint8_t> out(uv.width, uv.height, 3);
  for (int y = 0; y < uv.height; ++y)
    for (int x = 0; x < uv.width; ++x) {
      const float* f = uv.pixel(x, y);
      if (is_known_flow(f[0], f[1]) && (!valid.data || *valid.pixel(x, y)))
        wheel_color(options.wheel, f[0] / scale, f[1] / scale, out.pixel(x, y));
    }
  return out;
}

}  // namespace flowscape
