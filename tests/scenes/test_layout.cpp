// The plan of a city map (scenes/src/city_layout.h, internal): bends on circles at the map's
// corners, T-junctions where inner segments are left out, crosswalks on every junction's arms.
#include <catch2/catch.hpp>
#include <cmath>

#include "city_layout.h"
#include "flowscape/core/types.h"

using namespace flowscape;
using V2 = Eigen::Vector2d;

TEST_CASE("map corners are bends: the road turns on a 15 m circle tangent to both roads") {
  for (int map = 0; map < kMapCount; ++map) {
    const Layout layout = make_layout(map, 7);
    INFO("map " << map);
    for (const int i : {0, layout.nx() - 1})
      for (const int j : {0, layout.ny() - 1}) {
        // the corner's two roads leave it inwards; the circle's centre is 15 m in along both
        const V2 node(layout.xs[i], layout.ys[j]);
        const V2 a(i == 0 ? 1 : -1, 0), b(0, j == 0 ? 1 : -1), centre = node + 15 * (a + b);
        const double half = layout.half_width_x(j), walk = layout.style.sidewalk;
        REQUIRE(layout.is_bend(layout.node(i, j)));
        // the junction box's outer corner is no longer road: the circle's outer edge (15 + half
        // from the centre) passes it at sqrt(2) (15 + half)
        CHECK(layout.area(node - (half - 0.05) * (a + b)) == Area::Block);
        for (double theta = 0.05; theta < kPi / 2; theta += 0.1) {
          const V2 out = -(std::sin(theta) * a + std::cos(theta) * b);  // from the centre
          CHECK(layout.area(centre + 15 * out) == Area::Road);
          CHECK(layout.area(centre + (15 + half - 0.05) * out) == Area::Road);
          CHECK(layout.area(centre + (15 - half + 0.05) * out) == Area::Road);
          CHECK(layout.area(centre + (15 - half - 0.05) * out) == Area::SideWalk);
          CHECK(layout.area(centre + (15 - half - walk - 0.05) * out) == Area::Block);
          const V2 beyond = centre + (15 + half + 0.05) * out;  // ground, within the bend's square
          if ((beyond - node).dot(a) > -half && (beyond - node).dot(b) > -half)
            CHECK(layout.area(beyond) == Area::Block);
        }
        // no crosswalks at a bend, and its lanes stop short of it
        for (const Crosswalk& c : layout.crosswalks) CHECK(c.node != layout.node(i, j));
        for (const Lane& lane : layout.lanes)
          if (lane.to == layout.node(i, j))
            CHECK((lane.path.at(lane.path.length()).position - node).norm() >= 15);
      }
  }
}

TEST_CASE("left-out segments make T-junctions, never dead ends, and blocks stay rectangles") {
  int left_out = 0;
  for (const int map : {1, 3, 6, 7})
    for (std::uint64_t seed = 0; seed < 4; ++seed) {
      const Layout layout = make_layout(map, seed);
      INFO("map " << map << " seed " << seed);
      for (const char open : layout.x_open) left_out += !open;
      for (const char open : layout.y_open) left_out += !open;
      for (int n = 0; n < int(layout.node_height.size()); ++n) {
        int arms = 0;
        for (int arm = 0; arm < 4; ++arm) arms += layout.has_arm(n, arm);
        CHECK((arms >= 3 || layout.is_bend(n)));
      }
      // lanes only where the road runs; every block's middle is block, its edges meet roads
      for (const Lane& lane : layout.lanes) {
        if (!layout.diagonals.empty() &&
            (lane.from == layout.diagonals[0].from || lane.from == layout.diagonals[0].to) &&
            (lane.to == layout.diagonals[0].from || lane.to == layout.diagonals[0].to))
          continue;  // the diagonal street's lanes
        const int i0 = lane.from % layout.nx(), j0 = lane.from / layout.nx(),
                  i1 = lane.to % layout.nx(), j1 = lane.to / layout.nx();
        CHECK((j0 == j1 ? layout.x_segment(std::min(i0, i1), j0)
                        : layout.y_segment(i0, std::min(j0, j1))));
      }
      for (const Block& block : layout.blocks) {
        if (block.diagonal < 0) CHECK(layout.area((block.lo + block.hi) / 2) != Area::Road);
        if (!block.inner) continue;
        const V2 middle_of_bottom((block.lo.x() + block.hi.x()) / 2, block.lo.y() - 0.5);
        const Area below = layout.area(middle_of_bottom);  // a road runs along every side (where
        // two blocks were joined, past the T-junction of the left-out segment)
        CHECK((below == Area::Road || below == Area::Junction || below == Area::Crossing));
      }
    }
  CHECK(left_out >= 16);  // at least one per map and seed on average
}

TEST_CASE("a diagonal street crosses one block on four maps: road along it, paving beside") {
  for (int map = 0; map < kMapCount; ++map)
    for (std::uint64_t seed = 0; seed < 3; ++seed) {
      const Layout layout = make_layout(map, seed);
      const bool expected = map == 0 || map == 1 || map == 5 || map == 7;
      INFO("map " << map << " seed " << seed);
      REQUIRE(layout.diagonals.size() == (expected ? 1u : 0u));
      if (!expected) continue;
      const Diagonal& d = layout.diagonals[0];
      const V2 a = layout.node_position(d.from), b = layout.node_position(d.to);
      // from a junction to the one diagonally opposite: both coordinates change
      CHECK(std::abs(a.x() - b.x()) > 50);
      CHECK(std::abs(a.y() - b.y()) > 50);
      int lanes = 0, plazas = 0;
      for (const Lane& lane : layout.lanes)
        if ((lane.from == d.from && lane.to == d.to) || (lane.from == d.to && lane.to == d.from)) {
          ++lanes;
          const V2 direction = lane.path.at(0).direction;
          CHECK(std::abs(direction.x()) > 0.3);
          CHECK(std::abs(direction.y()) > 0.3);
        }
      CHECK(lanes == 2);  // one each way
      for (const Block& block : layout.blocks) {
        if (block.diagonal < 0) continue;
        ++plazas;
        const V2 middle = (block.lo + block.hi) / 2,
                 across = V2(-(b - a).y(), (b - a).x()).normalized();
        CHECK(layout.area(middle) == Area::Road);  // the line joining the two junctions
        CHECK(layout.area(middle + (d.half_width - 0.05) * across) == Area::Road);
        CHECK(layout.area(middle + (d.half_width + 0.05) * across) == Area::SideWalk);
        CHECK(layout.area(middle - (d.half_width + 0.05) * across) == Area::SideWalk);
      }
      CHECK(plazas == 1);
    }
}
