// Paths of lines, arcs and clothoid transitions (scenes/src/path.h, internal): heading and
// curvature continuous, arcs equal to the circle's closed form, transitions equal to an
// independent integration of their heading.
#include <catch2/catch.hpp>
#include <cmath>

#include "flowscape/core/types.h"
#include "path.h"

using namespace flowscape;
using V2 = Eigen::Vector2d;

namespace {

double heading(const PathPoint& p) { return std::atan2(p.direction.y(), p.direction.x()); }

}  // namespace

TEST_CASE("a rounded corner turns with continuous heading and curvature") {
  // a right angle, radius 6: transitions of 6 * (pi/2) / 2 = 4.71 m, curvature rate
  // (1/6) / 4.71 = 0.0354 per m^2, so over ds the curvature changes by at most 0.0354 ds
  const Path path = rounded_polyline({V2(0, 0), V2(30, 0), V2(30, 30)}, 6, false);
  const double ds = 0.01, rate = (1.0 / 6) / (6 * kPi / 4);
  PathPoint previous = path.at(0);
  double largest_curvature = 0;
  for (double s = ds; s <= path.length(); s += ds) {
    const PathPoint p = path.at(s);
    REQUIRE(std::abs(p.curvature - previous.curvature) <= rate * ds * 1.0001 + 1e-12);
    REQUIRE(std::abs(std::remainder(heading(p) - heading(previous), 2 * kPi)) <=
            std::max(std::abs(p.curvature), std::abs(previous.curvature)) * ds + 1e-9);
    REQUIRE((p.position - previous.position).norm() == Approx(ds).epsilon(1e-6));
    largest_curvature = std::max(largest_curvature, p.curvature);
    previous = p;
  }
  CHECK(largest_curvature == Approx(1.0 / 6));
  CHECK(path.at(0).position.isApprox(V2(0, 0)));
  CHECK((path.at(path.length()).position - V2(30, 30)).norm() < 1e-9);
  CHECK(heading(path.at(path.length())) == Approx(kPi / 2));
  // symmetric about the corner's bisector: the middle of the path lies on the line y = 30 - x
  const V2 middle = path.at(path.length() / 2).position;
  CHECK(middle.x() + middle.y() == Approx(30 + 30 - 30).margin(1e-9));
}

TEST_CASE("the arc of a corner is a circle in closed form, its transitions clothoids") {
  const double radius = 6;
  const Path path = rounded_polyline({V2(0, 0), V2(40, 0), V2(40, 40)}, radius, false);
  // the arc: where the curvature is 1/r; centre from its first point and normal
  double arc_start = -1, arc_end = -1;
  for (double s = 0; s <= path.length(); s += 0.001)
    if (std::abs(path.at(s).curvature - 1 / radius) < 1e-12) {
      if (arc_start < 0) arc_start = s;
      arc_end = s;
    }
  REQUIRE(arc_start > 0);
  CHECK(arc_end - arc_start == Approx(radius * kPi / 4).margin(0.002));  // half the turn
  const PathPoint a = path.at(arc_start);
  const V2 centre = a.position + radius * V2(-a.direction.y(), a.direction.x());
  for (double s : {arc_start + 0.3, (arc_start + arc_end) / 2, arc_end - 0.2}) {
    const double angle = (s - arc_start) / radius;  // turned so far on the circle
    const V2 from_centre = a.position - centre;
    const V2 expected =
        centre + V2(std::cos(angle) * from_centre.x() - std::sin(angle) * from_centre.y(),
                    std::sin(angle) * from_centre.x() + std::cos(angle) * from_centre.y());
    CHECK((path.at(s).position - expected).norm() < 1e-9);
  }
  // the entry transition: curvature k' (s - start), heading k' (s - start)^2 / 2 from the straight
  // line, integrated independently with the midpoint rule on 200,000 steps
  const double length = radius * kPi / 4, rate = (1 / radius) / length;
  const double inside = arc_start - length / 2;  // somewhere in the transition
  const double start = inside - path.at(inside).curvature / rate;
  V2 position = path.at(start).position;
  const int steps = 200000;
  const double h = length / steps;
  for (int i = 0; i < steps; ++i) {
    const double u = (i + 0.5) * h;
    position += h * V2(std::cos(rate * u * u / 2), std::sin(rate * u * u / 2));
  }
  CHECK((path.at(start + length).position - position).norm() < 1e-8);
}

TEST_CASE("short sides shrink the corner, closed loops close, polylines stay straight") {
  const Path tight = rounded_polyline({V2(0, 0), V2(4, 0), V2(4, 4)}, 10, false);
  CHECK((tight.at(tight.length()).position - V2(4, 4)).norm() < 1e-9);
  CHECK(tight.at(0.01).curvature == Approx(0).margin(0.05));  // starts straight
  const Path loop = rounded_polyline({V2(0, 0), V2(20, 0), V2(20, 10), V2(0, 10)}, 0.5, true);
  CHECK((loop.at(loop.length()).position - loop.at(0).position).norm() < 1e-9);
  CHECK(std::abs(std::remainder(heading(loop.at(loop.length())) - heading(loop.at(0)), 2 * kPi)) <
        1e-9);
  double turned = 0;
  for (double s = 0.01; s <= loop.length(); s += 0.01)
    turned += std::remainder(heading(loop.at(s)) - heading(loop.at(s - 0.01)), 2 * kPi);
  CHECK(turned == Approx(2 * kPi).margin(1e-6));  // once round, counter-clockwise
  const Path line({V2(0, 0), V2(3, 4), V2(3, 10)});
  CHECK(line.length() == Approx(11));
  CHECK(line.at(2.5).position.isApprox(V2(1.5, 2)));
  CHECK(line.at(8).position.isApprox(V2(3, 7)));
}

TEST_CASE("a roundabout's way runs on a true circle round the centre, joined without kinks") {
  // arms 13 m long on a junction at (50, 20); a lane 1.75 m right of its arm's axis, a ring of
  // 4.75 m: every exit (right, straight, left) is reached at the exit lane's start and heading,
  // counter-clockwise round the island (turning 3 pi / 2, 0, pi / 2 in all), keeps curvature and
  // heading continuous, and the part with curvature 1/4.75 lies on that circle
  const V2 centre(50, 20), a = centre + V2(1.75, -13), da(0, 1);
  const double radius = 4.75;
  struct Exit {
    V2 b, db;
    double turn;  // heading change, counter-clockwise
  };
  const Exit exits[] = {{centre + V2(13, -1.75), V2(1, 0), 3 * kPi / 2},  // all the way round
                        {centre + V2(1.75, 13), V2(0, 1), 0},
                        {centre + V2(-13, 1.75), V2(-1, 0), kPi / 2}};
  for (const Exit& exit : exits) {
    const Path path = roundabout_path(a, da, exit.b, exit.db, centre, radius, 4.0);
    CHECK((path.at(0).position - a).norm() < 1e-12);
    CHECK((path.at(path.length()).position - exit.b).norm() < 1e-9);
    const double ds = 0.01;
    double turned = 0, largest_curvature = 0, on_ring = 0;
    PathPoint previous = path.at(0);
    for (double s = ds; s <= path.length(); s += ds) {
      const PathPoint p = path.at(s);
      const double step = std::remainder(heading(p) - heading(previous), 2 * kPi);
      REQUIRE(std::abs(step) <=
              std::max(std::abs(p.curvature), std::abs(previous.curvature)) * ds + 1e-6);
      // no jump: from a swing of at most 1/3.5 to 1/4.75 over 4 m, a rate below 0.2 / m^2
      REQUIRE(std::abs(p.curvature - previous.curvature) < 0.2 * ds);
      if (std::abs(p.curvature - 1 / radius) < 1e-12) {
        REQUIRE((p.position - centre).norm() == Approx(radius).epsilon(1e-9));
        on_ring += ds;
      }
      largest_curvature = std::max(largest_curvature, std::abs(p.curvature));
      turned += step;
      previous = p;
    }
    CHECK(turned == Approx(exit.turn).margin(1e-5));
    CHECK(on_ring > 1);
    CHECK(largest_curvature < 1 / 3.5);
  }
}
