#pragma once
// A rolling shutter: the sensor is read line by line (rows, or columns for a sensor turned by 90
// degrees), so each line sees the scene at its own time (docs/cameras.md, "Rolling shutter").
// A continuous line coordinate s in [0, lines] is captured at
//   t(s) = frame time + readout x (s / lines - 1/2),
// centred on the frame time (the middle line is the global shutter's), the same law for a line's
// pixel centres (s = line + 0.5) and for the flow's targets.
#include <functional>
#include <optional>

#include "flowscape/core/image.h"
#include "flowscape/renderer/projection.h"

namespace flowscape {

struct Readout {
  double seconds = 0;    // from the first line's capture to the last's; 0: a global shutter
  bool columns = false;  // lines are columns (read left to right), else rows (top to bottom)

  bool global() const { return seconds == 0; }
  int lines(const Projection& p) const { return columns ? p.width : p.height; }
  double line_of(Vec2 pixel) const { return columns ? pixel.x() : pixel.y(); }
  // Capture time of line coordinate s, relative to the frame time.
  double offset(double s, int lines) const { return seconds * (s / lines - 0.5); }
};

// Pixels [x0, x1) x [y0, y1) of an image.
struct PixelWindow {
  int x0, y0, x1, y1;
};
// Calls visit(capture time, its pixels) for each line of the image in readout order (for a global
// shutter once: the whole image at `frame_time`).
template <class Visit>
void for_each_line(const Projection& projection, const Readout& readout, double frame_time,
                   Visit&& visit) {
  const int W = projection.width, H = projection.height;
  if (readout.global()) return visit(frame_time, PixelWindow{0, 0, W, H});
  const int lines = readout.lines(projection);
  for (int line = 0; line < lines; ++line)
    visit(frame_time + readout.offset(line + 0.5, lines),
          readout.columns ? PixelWindow{line, 0, line + 1, H} : PixelWindow{0, line, W, line + 1});
}

// The first s in [0, lines] (earliest capture) with seen_at(s) = s, to `tolerance` lines, where
// seen_at(s) is the line at which the point is seen by the image captured at line s's time
// (nullopt: out of view then). Bracketed: seen_at(s) - s is scanned at steps of at most
// `scan_step` lines for its first change of sign between two defined values, then refined by the
// Illinois method, so it converges where fixed-point iteration s <- seen_at(s) diverges (the image
// moving faster than the readout). Roots closer together than a scan step may be missed.
// How many intervals of at most scan_step lines the scan cuts [0, lines] into; sample j is at
// lines x j / steps.
int scan_steps(int lines, double scan_step);
std::optional<double> first_crossing(const std::function<std::optional<double>(double)>& seen_at,
                                     int lines, double scan_step = 8, double tolerance = 1e-6);

// Each pixel's capture time in seconds (`frame_time` + the offset of its centre's line; 1
// channel), NaN where a lens sees nothing: the `time` output kind.
Image<float> capture_times(const Projection& projection, const Readout& readout, double frame_time);

}  // namespace flowscape
