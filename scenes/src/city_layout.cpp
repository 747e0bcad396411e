#include "city_layout.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "flowscape/core/random.h"

namespace flowscape {
namespace {

using V2 = Eigen::Vector2d;
using B = Style::Buildings;

// clang-format off
const Style kStyles[kMapCount] = {
    // name, nx, ny, spacing, lanes, shoulder, sidewalk, buildings, heights, fill, trees, parks,
    // hills, speed, roundabouts, highway, water, rails, tees
    {"downtown", 5, 5, 65, 85, 2, 2.0, 4.5, B::Towers, 18, 60, 0.95, 2, 0.05, 0, 11,
     false, false, false, false, 0, true},
    {"suburb", 5, 4, 85, 110, 1, 2.5, 3.0, B::Houses, 5, 8, 0.55, 6, 0.1, 0, 10,
     false, false, false, false, 0.7, true},
    {"highway", 6, 3, 120, 170, 1, 2.5, 3.0, B::Warehouses, 8, 14, 0.35, 3, 0.2, 0, 12,
     false, true},
    {"rural", 4, 3, 150, 220, 1, 1.5, 2.0, B::Farms, 5, 8, 0.12, 4, 0.3, 3, 14,
     false, false, false, false, 1.0},
    {"roundabout", 5, 5, 80, 100, 2, 2.0, 3.5, B::MidRise, 10, 22, 0.75, 3, 0.1, 0, 10, true},
    {"waterfront", 6, 4, 70, 90, 2, 2.0, 4.0, B::MidRise, 12, 30, 0.8, 4, 0.1, 0, 11,
     false, false, true, false, 0, true},
    {"industrial", 4, 4, 110, 150, 2, 2.5, 2.5, B::Warehouses, 8, 16, 0.6, 1, 0.05, 0, 11,
     false, false, false, true, 0.7},
    {"hilltown", 5, 5, 70, 90, 1, 2.5, 3.0, B::MidRise, 8, 16, 0.7, 4, 0.1, 10, 9,
     false, false, false, false, 0.6, true},
};
// clang-format on
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

int arms(const Layout& layout, int n) {
  int count = 0;
  for (int arm = 0; arm < 4; ++arm) count += layout.has_arm(n, arm);
  return count;
}

// Leaves out inner road segments at random (each with the style's share `tees`): only between two
// blocks not yet joined, so every block stays a rectangle of at most two cells, and only where
// both ends keep three roads (T-junctions, no dead ends).
void leave_out_segments(Layout& layout, Random& random) {
  const int nx = layout.nx(), ny = layout.ny();
  layout.x_open.assign(std::size_t((nx - 1) * ny), 1);
  layout.y_open.assign(std::size_t(nx * (ny - 1)), 1);
  if (layout.style.tees == 0) return;
  struct Segment {
    bool along_x;
    int i, j;
  };
  std::vector<Segment> inner;
  for (int j = 1; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) inner.push_back({true, i, j});
  for (int i = 1; i + 1 < nx; ++i)
    for (int j = 0; j + 1 < ny; ++j) inner.push_back({false, i, j});
  for (int k = int(inner.size()) - 1; k > 0; --k) std::swap(inner[k], inner[random.below(k + 1)]);
  std::vector<char> joined(std::size_t((nx - 1) * (ny - 1)), 0);  // per cell between roads
  for (const Segment& g : inner) {
    if (!random.chance(layout.style.tees)) continue;
    const int a = layout.node(g.i, g.j), b = g.along_x ? a + 1 : a + nx;
    const int c1 = g.along_x ? (g.j - 1) * (nx - 1) + g.i : g.j * (nx - 1) + g.i - 1;
    const int c2 = g.along_x ? g.j * (nx - 1) + g.i : g.j * (nx - 1) + g.i;
    if (joined[c1] || joined[c2]) continue;
    char& open = g.along_x ? layout.x_open[g.j * (nx - 1) + g.i] : layout.y_open[g.j * nx + g.i];
    open = 0;
    if (arms(layout, a) < 3 || arms(layout, b) < 3) {
      open = 1;
      continue;
    }
    joined[c1] = joined[c2] = 1;
  }
}

// A diagonal street across one inner block with roads on all four sides and junctions (not bends,
// not roundabouts) at its corners, chosen at random, either way across; one lane each way.
void add_diagonal(Layout& layout, Random& random) {
  std::vector<std::pair<int, int>> cells;
  for (int j = 0; j + 1 < layout.ny(); ++j)
    for (int i = 0; i + 1 < layout.nx(); ++i) {
      const bool closed_round = layout.x_segment(i, j) && layout.x_segment(i, j + 1) &&
                                layout.y_segment(i, j) && layout.y_segment(i + 1, j);
      bool plain_corners = true;
      for (const int n : {layout.node(i, j), layout.node(i + 1, j), layout.node(i, j + 1),
                          layout.node(i + 1, j + 1)})
        plain_corners &= !layout.is_bend(n) && !layout.is_roundabout(n);
      if (closed_round && plain_corners) cells.push_back({i, j});
    }
  if (cells.empty()) return;
  const auto [i, j] = cells[random.below(int(cells.size()))];
  const bool rising =
      random.chance(0.5);  // from (i, j) to (i + 1, j + 1), else (i + 1, j) to (i, j + 1)
  const int from = rising ? layout.node(i, j) : layout.node(i + 1, j);
  const int to = rising ? layout.node(i + 1, j + 1) : layout.node(i, j + 1);
  const V2 a = layout.node_position(from), b = layout.node_position(to);
  layout.diagonals.push_back(
      {from, to, a, (b - a).normalized(), kLaneWidth + layout.style.shoulder});
  add_lanes(layout, from, to, 1, 0, layout.style.speed);
  add_lanes(layout, to, from, 1, 0, layout.style.speed);
  layout.diagonal_cell = {i, j};
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
  if (is_bend(n)) return V2::Constant(bend_cut(n));
  return {half_width_y(n % nx()) + kCrosswalk, half_width_x(n / nx()) + kCrosswalk};
}

bool Layout::has_arm(int n, int arm) const {
  const int i = n % nx(), j = n / nx();
  switch (arm) {
    case 0:
      return i > 0 && x_segment(i - 1, j);
    case 1:
      return i + 1 < nx() && x_segment(i, j);
    case 2:
      return j > 0 && y_segment(i, j - 1);
    default:
      return j + 1 < ny() && y_segment(i, j);
  }
}

bool Layout::is_bend(int n) const {
  return has_arm(n, 0) != has_arm(n, 1) && has_arm(n, 2) != has_arm(n, 3);  // one each way
}

std::array<Eigen::Vector2d, 2> Layout::bend_arms(int n) const {
  return {V2(has_arm(n, 1) ? 1 : -1, 0), V2(0, has_arm(n, 3) ? 1 : -1)};
}

Eigen::Vector2d Layout::bend_centre(int n) const {
  const auto arms = bend_arms(n);
  return node_position(n) + kBendRadius * (arms[0] + arms[1]);
}

// A lane's clothoid corner of radius r needs about 1.42 r from its corner point on either side;
// the outermost lane (offset o) turns with kBendRadius + o from a corner point o further out.
double Layout::bend_cut(int n) const {
  const int lanes = std::max(lanes_along_x[n / nx()], lanes_along_y[n % nx()]);
  const double outermost = (lanes - 0.5) * kLaneWidth;
  return 1.45 * kBendRadius + 0.45 * outermost + 1;
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

int Layout::bend_at(const V2& p) const {
  for (int n : {node(0, 0), node(nx() - 1, 0), node(0, ny() - 1), node(nx() - 1, ny() - 1)}) {
    if (!is_bend(n)) continue;
    const auto arms = bend_arms(n);
    const double half = half_width_x(n / nx()), cut = bend_cut(n);
    const double u = (p - node_position(n)).dot(arms[0]), v = (p - node_position(n)).dot(arms[1]);
    if (u >= -half && v >= -half && u <= cut && v <= cut) return n;
  }
  return -1;
}

// In a bend's square: road within the half width of the centre line (straight, then the circle),
// the sidewalk inside it, the block beyond.
std::optional<Area> Layout::bend_area(const V2& p) const {
  const int n = bend_at(p);
  if (n < 0) return std::nullopt;
  const auto arms = bend_arms(n);
  const double u = (p - node_position(n)).dot(arms[0]), v = (p - node_position(n)).dot(arms[1]);
  double off = v;  // signed distance from the centre line, positive inside the bend
  if (v > kBendRadius)
    off = u;
  else if (u <= kBendRadius)
    off = kBendRadius - (p - bend_centre(n)).norm();
  const double half = half_width_x(n / nx());
  if (std::abs(off) <= half) return Area::Road;
  return off > 0 && off <= half + style.sidewalk ? Area::SideWalk : Area::Block;
}

Area Layout::area(const V2& p) const {
  const V2 low = lo(), high = hi();
  if (p.x() < low.x() || p.y() < low.y() || p.x() > high.x() || p.y() > high.y())
    return Area::Outside;
  if (const std::optional<Area> bend = bend_area(p)) return *bend;
  double to_road = 1e9;  // distance from p to the nearest road edge
  bool on_x_road = false, on_y_road = false;
  // a road segment from `from` to `to` along one axis (junction boxes included), centred on
  // `line` across it: p (at `along`, `across`) is on it or `to_road` from its edge
  const auto segment = [&](double along, double across, double from, double to, double line,
                           double half, bool& on) {
    if (along < from || along > to) return;
    const double d = std::abs(across - line) - half;
    on |= d <= 0, to_road = std::min(to_road, d);
  };
  for (int j = 0; j < ny(); ++j)
    for (int i = 0; i + 1 < nx(); ++i)
      if (x_segment(i, j))
        segment(p.x(), p.y(), xs[i] - half_width_y(i), xs[i + 1] + half_width_y(i + 1), ys[j],
                half_width_x(j), on_x_road);
  for (int i = 0; i < nx(); ++i)
    for (int j = 0; j + 1 < ny(); ++j)
      if (y_segment(i, j))
        segment(p.y(), p.x(), ys[j] - half_width_x(j), ys[j + 1] + half_width_x(j + 1), xs[i],
                half_width_y(i), on_y_road);
  if (on_x_road && on_y_road) return Area::Junction;
  for (const Crosswalk& c : crosswalks)
    if (c.band.contains(p)) return Area::Crossing;
  for (const Block& block : blocks)  // a plaza: the diagonal street, paving either side
    if (block.diagonal >= 0 && Rect{block.lo, block.hi}.contains(p)) {
      const Diagonal& d = diagonals[block.diagonal];
      return std::abs(d.offset(p)) <= d.half_width ? Area::Road : Area::SideWalk;
    }
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
  leave_out_segments(layout, random);
  for (int j = 0; j < style.ny; ++j)
    for (int i = 0; i + 1 < style.nx; ++i) {
      if (!layout.x_segment(i, j)) continue;
      const int a = layout.node(i, j), b = layout.node(i + 1, j), lanes = layout.lanes_along_x[j];
      const double speed = j == highway_row ? kHighwaySpeed : style.speed;
      add_lanes(layout, a, b, lanes, layout.median(lanes), speed);
      add_lanes(layout, b, a, lanes, layout.median(lanes), speed);
    }
  for (int i = 0; i < style.nx; ++i)
    for (int j = 0; j + 1 < style.ny; ++j) {
      if (!layout.y_segment(i, j)) continue;
      const int a = layout.node(i, j), b = layout.node(i, j + 1), lanes = layout.lanes_along_y[i];
      add_lanes(layout, a, b, lanes, layout.median(lanes), style.speed);
      add_lanes(layout, b, a, lanes, layout.median(lanes), style.speed);
    }
  if (style.diagonal) add_diagonal(layout, random);
  for (int n = 0; n < int(layout.node_height.size()); ++n)
    for (int arm = 0; arm < 4; ++arm) {
      if (!layout.has_arm(n, arm) || layout.is_bend(n)) continue;
      const V2 centre = layout.node_position(n), reach = layout.junction_reach(n);
      const double hx = layout.half_width_y(n % layout.nx()),
                   hy = layout.half_width_x(n / layout.nx());
      const double side = arm % 2 ? 1 : -1;
      const bool across_x = arm < 2;  // arms 0 and 1 run along x
      const V2 a = across_x ? centre + V2(side * hx, -hy) : centre + V2(-hx, side * hy);
      const V2 b = across_x ? centre + V2(side * reach.x(), hy) : centre + V2(hx, side * reach.y());
      layout.crosswalks.push_back({n, across_x, {a.cwiseMin(b), a.cwiseMax(b)}});
    }
  const V2 low = layout.lo(), high = layout.hi();
  const auto x_edge = [&](int i, double outside) {  // the road edge left of road line i
    return i < 0 || i >= style.nx ? outside : layout.xs[i] - layout.half_width_y(i);
  };
  const auto y_edge = [&](int j, double outside) {
    return j < 0 || j >= style.ny ? outside : layout.ys[j] - layout.half_width_x(j);
  };
  for (int j = -1; j < style.ny; ++j)
    for (int i = -1; i < style.nx; ++i) {
      const bool inner = i >= 0 && j >= 0 && i + 1 < style.nx && j + 1 < style.ny;
      // a block joined to the one before it across a left-out segment was made with that one
      if (inner && (!layout.y_segment(i, j) || !layout.x_segment(i, j))) continue;
      const int i1 = inner && !layout.y_segment(i + 1, j) ? i + 2 : i + 1;
      const int j1 = inner && !layout.x_segment(i, j + 1) ? j + 2 : j + 1;
      const double x0 = i < 0 ? low.x() : layout.xs[i] + layout.half_width_y(i);
      const double y0 = j < 0 ? low.y() : layout.ys[j] + layout.half_width_x(j);
      const bool plaza = !layout.diagonals.empty() && layout.diagonal_cell == std::pair(i, j);
      layout.blocks.push_back({V2(x0, y0),
                               V2(x_edge(i1, high.x()), y_edge(j1, high.y())),
                               inner,
                               {i >= 0, i1 < style.nx, j >= 0, j1 < style.ny},
                               plaza ? 0 : -1});
    }
  return layout;
}

}  // namespace flowscape
