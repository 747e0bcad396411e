#pragma once
// Internal: the plan of a city map, a grid of roads (some inner segments left out, making
// T-junctions and longer blocks) with lanes, junctions, sidewalks and blocks, and the height of
// the ground under it.
#include <array>
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "flowscape/scenes/city.h"
#include "path.h"

namespace flowscape {

struct Style {
  std::string name;
  int nx, ny;                       // road lines across x and y
  double spacing_min, spacing_max;  // between neighbouring road lines, metres
  int lanes;                        // per direction
  double shoulder, sidewalk;        // widths, metres
  enum class Buildings { Towers, Houses, MidRise, Warehouses, Farms } buildings;
  double height_min, height_max;  // of buildings
  double fill;                    // share of a block's frontage with buildings
  double trees;                   // trees per 100 m of sidewalk
  double parks;                   // share of blocks that are parks
  double hills;                   // amplitude of the terrain, metres
  double speed;                   // vehicles' wish speed, m/s
  bool roundabouts = false, highway = false, water = false, rails = false;
  double tees = 0;        // share of the inner road segments left out, making T-junctions
  bool diagonal = false;  // a diagonal street across one block (a plaza)
};
const Style& style_of(int map);

constexpr double kLaneWidth = 3.5, kCrosswalk = 4.0, kCurb = 0.15;
constexpr double kBendRadius = 15;  // of the centre line where a road bends round a map corner

struct Lane {
  int from, to;  // nodes
  int index;     // 0 = next to the centre line
  Path path;     // from the stop line of `from` to the stop line of `to`
  double speed;  // wish speed of vehicles on it
};
// Lanes side by side on one road the same way (a vehicle can change from one to the other).
inline bool side_by_side(const Lane& a, const Lane& b) {
  return a.from == b.from && a.to == b.to && std::abs(a.index - b.index) == 1;
}

struct Block {
  Eigen::Vector2d lo, hi;           // between the road edges (outer blocks reach the map's margin)
  bool inner;                       // roads on all four sides
  std::array<bool, 4> road_beside;  // a road along its side at lo.x, hi.x, lo.y, hi.y
  int diagonal = -1;                // the diagonal street across it (a plaza), or -1
};

// A street from a junction to the one diagonally opposite across a block, one lane each way.
struct Diagonal {
  int from, to;  // nodes
  Eigen::Vector2d start, direction;
  double half_width;
  // Signed distance of p from the centre line (positive on its left).
  double offset(const Eigen::Vector2d& p) const {
    return direction.x() * (p - start).y() - direction.y() * (p - start).x();
  }
};

// An axis-aligned rectangle of the ground.
struct Rect {
  Eigen::Vector2d lo, hi;
  bool contains(const Eigen::Vector2d& p, double margin = 0) const {
    return p.x() >= lo.x() - margin && p.y() >= lo.y() - margin && p.x() <= hi.x() + margin &&
           p.y() <= hi.y() + margin;
  }
  bool meets(const Rect& o) const {  // their insides overlap
    return lo.x() < o.hi.x() && hi.x() > o.lo.x() && lo.y() < o.hi.y() && hi.y() > o.lo.y();
  }
};

// A zebra crossing on an arm of a junction: the band of road between the junction's box and its
// stop lines, across the arm.
struct Crosswalk {
  int node;
  bool across_x_road;  // on an arm along x (pedestrians walk along y)
  Rect band;
};

struct Layout {
  Style style;
  std::vector<double> xs, ys;  // road centre lines
  std::vector<double> node_height;
  std::vector<int> lanes_along_x, lanes_along_y;  // lanes per direction of road j (along x) / i
  double margin = 45;
  std::vector<Lane> lanes;
  std::vector<Block> blocks;
  std::vector<Crosswalk> crosswalks;
  std::vector<Diagonal> diagonals;
  std::pair<int, int> diagonal_cell{-1, -1};  // the cell (i, j) the diagonal crosses
  // Whether the road runs from node (i, j) to (i + 1, j), and from (i, j) to (i, j + 1).
  std::vector<char> x_open, y_open;

  int nx() const { return int(xs.size()); }
  int ny() const { return int(ys.size()); }
  int node(int i, int j) const { return j * nx() + i; }
  bool x_segment(int i, int j) const { return x_open[j * (nx() - 1) + i]; }
  bool y_segment(int i, int j) const { return y_open[j * nx() + i]; }
  // The roads leaving node n towards -x, +x, -y, +y (arm 0..3).
  bool has_arm(int n, int arm) const;
  // A node with two roads at a right angle (a map's corner) is no junction but a bend: the centre
  // line runs on a circle of kBendRadius round bend_centre, tangent to both roads' centre lines,
  // and the lanes stop bend_cut from the node (where their clothoid corners start).
  bool is_bend(int n) const;
  Eigen::Vector2d bend_centre(int n) const;
  double bend_cut(int n) const;
  // The unit directions of a bend's two roads from its node.
  std::array<Eigen::Vector2d, 2> bend_arms(int n) const;
  Eigen::Vector2d node_position(int n) const { return {xs[n % nx()], ys[n / nx()]}; }
  double median(int lanes) const { return lanes >= 3 ? 2.0 : 0.0; }
  double half_width_x(int j) const;  // of the road along x at ys[j]
  double half_width_y(int i) const;  // of the road along y at xs[i]
  // Junction n reaches this far from its centre along x and along y (crossings included).
  Eigen::Vector2d junction_reach(int n) const;
  bool is_roundabout(int n) const;
  double height(const Eigen::Vector2d& p) const;  // ground (road surface) height
  Area area(const Eigen::Vector2d& p) const;
  // The bend whose square (from the node less the road's half width to the lanes' ends) holds p,
  // or -1; and what p is there.
  int bend_at(const Eigen::Vector2d& p) const;
  std::optional<Area> bend_area(const Eigen::Vector2d& p) const;
  Eigen::Vector2d lo() const { return {xs.front() - margin, ys.front() - margin}; }
  Eigen::Vector2d hi() const { return {xs.back() + margin, ys.back() + margin}; }
};

Layout make_layout(int map, std::uint64_t seed);

}  // namespace flowscape
