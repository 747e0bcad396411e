#include "flowscape/renderer/rolling_shutter.h"

#include <cmath>
#include <limits>

namespace flowscape {
namespace {

// f(s) = seen_at(s) - s, undefined where the point is out of view.
struct Crossing {
  const std::function<std::optional<double>(double)>& seen_at;
  std::optional<double> operator()(double s) const {
    const std::optional<double> seen = seen_at(s);
    return seen ? std::optional<double>(*seen - s) : std::nullopt;
  }
};

// Illinois (modified regula falsi) on a bracket [a, b] with f(a) f(b) < 0; nullopt where f becomes
// undefined inside it.
std::optional<double> refine(const Crossing& f, double a, double fa, double b, double fb,
                             double tolerance) {
  int kept = 0;  // which end stayed last time: -1 a, +1 b
  for (int i = 0; i < 200 && b - a > tolerance; ++i) {
    const double s = (a * fb - b * fa) / (fb - fa);
    const std::optional<double> fs = f(s);
    if (!fs) return std::nullopt;
    if (*fs == 0) return s;
    if ((*fs < 0) == (fa < 0)) {
      a = s, fa = *fs;
      if (kept == 1) fb /= 2;
      kept = 1;
    } else {
      b = s, fb = *fs;
      if (kept == -1) fa /= 2;
      kept = -1;
    }
  }
  return std::abs(fa) < std::abs(fb) ? a : b;
}

}  // namespace

int scan_steps(int lines, double scan_step) {
  return std::max(1, int(std::ceil(lines / scan_step)));
}

std::optional<double> first_crossing(const std::function<std::optional<double>(double)>& seen_at,
                                     int lines, double scan_step, double tolerance) {
  const Crossing f{seen_at};
  const int steps = scan_steps(lines, scan_step);
  double previous_s = 0;
  std::optional<double> previous = f(0);
  if (previous && *previous == 0) return 0.0;
  for (int k = 1; k <= steps; ++k) {
    const double s = double(lines) * k / steps;
    const std::optional<double> value = f(s);
    if (value && *value == 0) return s;
    if (value && previous && (*value < 0) != (*previous < 0))
      if (const auto root = refine(f, previous_s, *previous, s, *value, tolerance)) return root;
    previous_s = s, previous = value;
  }
  return std::nullopt;
}

Image<float> capture_times(const Projection& projection, const Readout& readout,
                           double frame_time) {
  Image<float> times(projection.width, projection.height, 1);
  const int lines = readout.lines(projection);
  for (int y = 0; y < projection.height; ++y)
    for (int x = 0; x < projection.width; ++x) {
      const Vec2 pixel(x + 0.5, y + 0.5);
      *times.pixel(x, y) = projection.covers(pixel)
                               ? float(frame_time + readout.offset(readout.line_of(pixel), lines))
                               : std::numeric_limits<float>::quiet_NaN();
    }
  return times;
}

}  // namespace flowscape
