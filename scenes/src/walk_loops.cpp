#include "walk_loops.h"

#include <algorithm>
#include <cmath>

namespace flowscape {

using V2 = Eigen::Vector2d;

double SidewalkLoop::lift(double s) const {
  double lift = kCurb;
  for (const LoopCrossing& c : crossings) {
    const double off_road = std::max(c.s_in - s, s - c.s_out);  // < 0 on the road
    lift = std::min(lift, kCurb * std::clamp(off_road / 0.5, 0.0, 1.0));
  }
  return lift;
}

namespace {

// A walking loop round the rectangle lo..hi: corners of 0.5 m with transitions, but round a bend
// a plain circle about the bend's centre (concentric with its kerb: it stays on the curved
// sidewalk).
SidewalkLoop loop_around(const Layout& layout, const V2& lo, const V2& hi, bool counter_clockwise) {
  std::vector<V2> corners{lo, V2(hi.x(), lo.y()), hi, V2(lo.x(), hi.y())};
  if (!counter_clockwise) std::reverse(corners.begin(), corners.end());
  std::vector<double> radii(corners.size(), 0.5);
  std::vector<bool> transitions(corners.size(), true);
  for (std::size_t k = 0; k < corners.size(); ++k)
    if (const int bend = layout.bend_at(corners[k]); bend >= 0)
      radii[k] = std::abs((layout.bend_centre(bend) - corners[k]).x()), transitions[k] = false;
  return {rounded_polyline(corners, radii, true, transitions), {}};
}

// The stretches of `loop` between the two blocks' facing edges (on the road between them), on
// the crosswalks there.
void find_crossings(const Layout& layout, double road_lo, double road_hi, SidewalkLoop& loop) {
  constexpr double ds = 0.01;
  const auto on_road = [&](double s) {
    const double y = loop.path.at(s).position.y();
    return y > road_lo && y < road_hi;
  };
  for (double s = 0; s < loop.path.length(); s += ds) {
    if (!on_road(s) || (s > 0 && on_road(s - ds))) continue;
    double end = s;
    while (on_road(end + ds)) end += ds;
    const V2 middle = loop.path.at((s + end) / 2).position;
    for (int k = 0; k < int(layout.crosswalks.size()); ++k)
      if (layout.crosswalks[k].band.contains(middle)) loop.crossings.push_back({s, end, k});
  }
}

}  // namespace

std::vector<SidewalkLoop> sidewalk_loops(const Layout& layout) {
  std::vector<SidewalkLoop> loops;
  const double width = layout.style.sidewalk, near = 0.3 * width + 0.2, far = 0.8 * width;
  std::vector<char> paired(layout.blocks.size(), 0);
  for (std::size_t a = 0; a < layout.blocks.size(); ++a) {
    const Block& low = layout.blocks[a];
    if (!low.inner || low.diagonal >= 0) continue;  // nobody walks round a plaza
    loops.push_back(
        loop_around(layout, low.lo + V2::Constant(far), low.hi - V2::Constant(far), false));
    if (paired[a]) continue;
    // the block right above across one road, of the same width: one loop round both
    std::size_t b = a + 1;
    while (b < layout.blocks.size() &&
           !(layout.blocks[b].inner && layout.blocks[b].diagonal < 0 && !paired[b] &&
             layout.blocks[b].lo.x() == low.lo.x() && layout.blocks[b].hi.x() == low.hi.x() &&
             layout.blocks[b].lo.y() > low.hi.y() && layout.blocks[b].lo.y() < low.hi.y() + 30))
      ++b;
    if (b == layout.blocks.size()) {
      loops.push_back(
          loop_around(layout, low.lo + V2::Constant(near), low.hi - V2::Constant(near), true));
      continue;
    }
    paired[b] = 1;
    const Block& high = layout.blocks[b];
    loops.push_back(
        loop_around(layout, low.lo + V2::Constant(near), high.hi - V2::Constant(near), true));
    find_crossings(layout, low.hi.y(), high.lo.y(), loops.back());
  }
  return loops;
}

}  // namespace flowscape
