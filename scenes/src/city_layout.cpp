#include "city_layout.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "flowscape/core/random.h"

namespace flowscape {
namespace {

using V2 = Eigen::Vector2d;
using B = Style::Buildings;

const Style kStyles[kMapCount] = {
    // name, nx, ny, spacing, lanes, shoulder, sidewalk, buildings, heights, fill, trees, parks,
    // hills, speed
    {"downtown", 5, 5, 65, 85, 2, 2.0, 4.5, B::Towers, 18, 60, 0.95, 2, 0.05, 0, 11},
    {"suburb", 5, 4, 85, 110, 1, 2.5, 3.0, B::Houses, 5, 8, 0.55, 6, 0.1, 0, 10},
    {"highway", 6, 3, 120, 170, 1, 2.5, 3.0, B::Warehouses, 8, 14, 0.35, 3, 0.2, 0, 12, false,
     true},
    {"rural", 4, 3, 150, 220, 1, 1.5, 2.0, B::Farms, 5, 8, 0.12, 4, 0.3, 3, 14},
    {"roundabout", 5, 5, 80, 100, 2, 2.0, 3.5, B::MidRise, 10, 22, 0.75, 3, 0.1, 0, 10, true},
    {"waterfront", 6, 4, 70, 90, 2, 2.0, 4.0, B::MidRise, 12, 30, 0.8, 4, 0.1, 0, 11, false, false,
     true},
    {"industrial", 4,   4, 110,  150, 2,  2.5,   2.5,   B::Warehouses, 8,
     16,           0.6, 1, 0.05, 0,   11, false, false, false,         true},
    {"hilltown", 5, 5, 70, 90, 1, 2.5, 3.0, B::MidRise, 8, 16, 0.7, 4, 0.1, 10, 9},
};
constexpr double kHighwayHeight = 5, kHighwaySpeed = 20;

std::vector<double> road_lines(int count, double lo, double hi, Random& random) {
  std::vector<double> lines{0};
  for (int k = 1; k < count; ++k) lines.push_back(lines.back() + random.uniform(lo, hi));
  const double centre = lines.back() / 2;
  for (double& x : lines) x -= centre;
  return lines;
}

// Index k with lines[k] <= x < lines[k + 1], clamped to the grid's cells.
int cell_of(const std::vector<double>& lines, double x) {
  const int k = int(std::upper_bound(lines.begin(), lines.end(), x) - lines.begin()) - 1;
  return std::clamp(k, 0, int(lines.size()) - 2);
}

void add_lanes(Layout& layout, int from, int to, int lanes, double median, double speed) {
  const V2 a = layout.node_position(from), b = layout.node_position(to);
  const V2 direction = (b - a).normalized(), right(direction.y(), -direction.x());
  const V2 reach_a = layout.junction_reach(from), reach_b = layout.junction_reach(to);
  const double cut_a =
      std::abs(direction.x()) * reach_a.x() + std::abs(direction.y()) * reach_a.y();
  const double cut_b =
      std::abs(direction.x()) * reach_b.x() + std::abs(direction.y()) * reach_b.y();
  for (int k = 0; k < lanes; ++k) {
    const V2 offset = (median / 2 + (k + 0.5) * kLaneWidth) * right;
    layout.lanes.push_back({from, to, k,
                            Path({a + offset + cut_a * direction, b + offset - cut_b * direction}),
                            speed});
  }
}

}  // namespace

const Style& style_of(int map) {
  if (map < 0 || map >= kMapCount)
    throw std::invalid_argument("map " + std::to_string(map) + " is not in 0.." +
                                std::to_string(kMapCount - 1));
  return kStyles[map];
}

double Layout::half_width_x(int j) const {
  return median(lanes_along_x[j]) / 2 + lanes_along_x[j] * kLaneWidth + style.shoulder;
}
double Layout::half_width_y(int i) const {
  return median(lanes_along_y[i]) / 2 + lanes_along_y[i] * kLaneWidth + style.shoulder;
}

Eigen::Vector2d Layout::junction_reach(int n) const {
  return {half_width_y(n % nx()) + kCrosswalk, half_width_x(n / nx()) + kCrosswalk};
}

bool Layout::is_roundabout(int n) const {
  const int i = n % nx(), j = n / nx();
  return style.roundabouts && i > 0 && j > 0 && i < nx() - 1 && j < ny() - 1;
}

double Layout::height(const V2& p) const {
  const int i = cell_of(xs, p.x()), j = cell_of(ys, p.y());
  const double u = std::clamp((p.x() - xs[i]) / (xs[i + 1] - xs[i]), 0.0, 1.0);
  const double v = std::clamp((p.y() - ys[j]) / (ys[j + 1] - ys[j]), 0.0, 1.0);
  const auto h = [&](int di, int dj) { return node_height[node(i + di, j + dj)]; };
  return (1 - v) * ((1 - u) * h(0, 0) + u * h(1, 0)) + v * ((1 - u) * h(0, 1) + u * h(1, 1));
}

Area Layout::area(const V2& p) const {
  const V2 low = lo(), high = hi();
  if (p.x() < low.x() || p.y() < low.y() || p.x() > high.x() || p.y() > high.y())
    return Area::Outside;
  const bool within_x =
      p.x() >= xs.front() - half_width_y(0) && p.x() <= xs.back() + half_width_y(nx() - 1);
  const bool within_y =
      p.y() >= ys.front() - half_width_x(0) && p.y() <= ys.back() + half_width_x(ny() - 1);
  double to_road = 1e9;  // distance from p to the nearest road edge
  bool on_x_road = false, on_y_road = false;
  for (int j = 0; j < ny() && within_x; ++j) {
    const double d = std::abs(p.y() - ys[j]) - half_width_x(j);
    on_x_road |= d <= 0, to_road = std::min(to_road, d);
  }
  for (int i = 0; i < nx() && within_y; ++i) {
    const double d = std::abs(p.x() - xs[i]) - half_width_y(i);
    on_y_road |= d <= 0, to_road = std::min(to_road, d);
  }
  if (on_x_road && on_y_road) return Area::Junction;
  if (on_x_road || on_y_road) return Area::Road;
  if (to_road <= style.sidewalk) return Area::SideWalk;
  if (style.water && p.y() < ys.front() - half_width_x(0) - style.sidewalk - 8) return Area::Water;
  return Area::Block;
}

Layout make_layout(int map, std::uint64_t seed) {
  Layout layout;
  layout.style = style_of(map);
  const Style& style = layout.style;
  Random random(seed * 0x2545f4914f6cdd1dull + std::uint64_t(map));
  layout.xs = road_lines(style.nx, style.spacing_min, style.spacing_max, random);
  layout.ys = road_lines(style.ny, style.spacing_min, style.spacing_max, random);
  const int highway_row = style.highway ? style.ny / 2 : -1;
  layout.lanes_along_x.assign(style.ny, style.lanes);
  layout.lanes_along_y.assign(style.nx, style.lanes);
  if (highway_row >= 0) layout.lanes_along_x[highway_row] = 3;
  const double phase = random.uniform(0, 2 * kPi);
  for (int j = 0; j < style.ny; ++j)
    for (int i = 0; i < style.nx; ++i) {
      const double u = double(i) / (style.nx - 1), v = double(j) / (style.ny - 1);
      double h = style.hills * std::sin(kPi * u) * std::sin(kPi * v) *
                 (0.7 + 0.3 * std::cos(2 * kPi * u + phase));
      if (j == highway_row) h = kHighwayHeight;
      layout.node_height.push_back(h);
    }
  for (int j = 0; j < style.ny; ++j)
    for (int i = 0; i + 1 < style.nx; ++i) {
      const int a = layout.node(i, j), b = layout.node(i + 1, j), lanes = layout.lanes_along_x[j];
      const double speed = j == highway_row ? kHighwaySpeed : style.speed;
      add_lanes(layout, a, b, lanes, layout.median(lanes), speed);
      add_lanes(layout, b, a, lanes, layout.median(lanes), speed);
    }
  for (int i = 0; i < style.nx; ++i)
    for (int j = 0; j + 1 < style.ny; ++j) {
      const int a = layout.node(i, j), b = layout.node(i, j + 1), lanes = layout.lanes_along_y[i];
      add_lanes(layout, a, b, lanes, layout.median(lanes), style.speed);
      add_lanes(layout, b, a, lanes, layout.median(lanes), style.speed);
    }
  const V2 low = layout.lo(), high = layout.hi();
  for (int j = -1; j < style.ny; ++j)
    for (int i = -1; i < style.nx; ++i) {
      const double x0 = i < 0 ? low.x() : layout.xs[i] + layout.half_width_y(i);
      const double x1 =
          i + 1 >= style.nx ? high.x() : layout.xs[i + 1] - layout.half_width_y(i + 1);
      const double y0 = j < 0 ? low.y() : layout.ys[j] + layout.half_width_x(j);
      const double y1 =
          j + 1 >= style.ny ? high.y() : layout.ys[j + 1] - layout.half_width_x(j + 1);
      const bool inner = i >= 0 && j >= 0 && i + 1 < style.nx && j + 1 < style.ny;
      layout.blocks.push_back(
          {V2(x0, y0), V2(x1, y1), inner, {i >= 0, i + 1 < style.nx, j >= 0, j + 1 < style.ny}});
    }
  return layout;
}

}  // namespace flowscape
