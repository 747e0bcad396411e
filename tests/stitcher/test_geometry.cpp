#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

#include "flowscape/geometry/geometry.h"
#include "independent_math.h"

using namespace flowscape;

namespace {

Vec3 v(indep::V3 d) { return {d.x, d.y, d.z}; }

}  // namespace

TEST_CASE("ERP pixel coordinates follow the design conventions (paper Eq. 1)") {
  const int W = 1024;
  // centre of the image looks forward, the left edge looks backwards, top row looks up
  const Vec2 front = erp_from_direction({1, 0, 0}, W);
  CHECK(front.x() == Approx(512));
  CHECK(front.y() == Approx(256));
  CHECK(erp_from_direction({0, -1, 0}, W).x() == Approx(768));  // right of the rig: 3/4 W
  CHECK(erp_from_direction({0, 1, 0}, W).x() == Approx(256));   // left: 1/4 W
  CHECK(erp_from_direction({0, 0, 1}, W).y() == Approx(0).margin(1e-9));
  CHECK(erp_from_direction({0, 0, -1}, W).y() == Approx(512));
  for (double phi : {-3.0, -0.5, 0.0, 1.0, 3.1})
    for (double theta : {-1.5, 0.0, 0.7}) {
      const Vec2 ours = erp_from_angles({phi, theta}, W);
      const Vec2 paper = paper_forward_erp(phi, theta, W / (2 * kPi), -kPi, -kPi / 2, 0.0);
      CHECK(ours.x() == Approx(paper.x()));
      CHECK(ours.y() == Approx(paper.y()));
    }
  // Eq. 1 with a standard parallel scales x by cos(theta1)
  CHECK(paper_forward_erp(1.0, 0.2, 10, 0, 0, kPi / 3).x() == Approx(5.0));
  CHECK(paper_forward_erp(1.0, 0.2, 10, 0, 0, kPi / 3).y() == Approx(2.0));
}

TEST_CASE("ERP pixel <-> direction agrees with the hand-derived formulas and round-trips") {
  const int W = 2048;
  for (double x : {0.5, 10.25, 1023.5, 1024.0, 2047.5})
    for (double y : {0.5, 100.0, 511.5, 1023.5}) {
      const Vec3 d = direction_from_erp({x, y}, W);
      const indep::V3 e = indep::erp_direction(x, y, W);
      CHECK((d - v(e)).norm() < 1e-12);
      const Vec2 back = erp_from_direction(d, W);
      CHECK(back.x() == Approx(x).margin(1e-9));
      CHECK(back.y() == Approx(y).margin(1e-9));
    }
}

TEST_CASE("cube faces have the hand-derived axes, are right-handed and meet edge to edge") {
  const int N = 64;
  for (Face face : kFaces) {
    const FaceBasis& b = face_basis(face);
    const indep::Axes& a = indep::faces()[int(face)];
    CHECK((b.forward - v(a.forward)).norm() == 0);
    CHECK((b.right - v(a.right)).norm() == 0);
    CHECK((b.down - v(a.down)).norm() == 0);
    CHECK((b.right.cross(b.down) - b.forward).norm() < 1e-12);  // x right, y down, z forward
    CHECK(face_from_name(face_name(face)) == face);
  }
  // the lower edge of "up" and the upper edge of "down" are the edges of "front"
  for (double s : {0.0, 20.0, 64.0}) {
    CHECK((ray_from_cube(Face::Up, {s, N}, N) - ray_from_cube(Face::Front, {s, 0}, N)).norm() <
          1e-12);
    CHECK((ray_from_cube(Face::Down, {s, 0}, N) - ray_from_cube(Face::Front, {s, N}, N)).norm() <
          1e-12);
    // right edge of front = left edge of right, and so on round the rig
    CHECK((ray_from_cube(Face::Front, {N, s}, N) - ray_from_cube(Face::Right, {0, s}, N)).norm() <
          1e-12);
    CHECK((ray_from_cube(Face::Left, {N, s}, N) - ray_from_cube(Face::Front, {0, s}, N)).norm() <
          1e-12);
  }
}

TEST_CASE("cube point <-> direction round-trips and picks the face with the largest forward part") {
  const int N = 100;
  for (int face = 0; face < 6; ++face)
    for (double s : {0.3, 17.5, 50.0, 99.9})
      for (double t : {0.2, 42.0, 99.5}) {
        const indep::V3 d = indep::face_direction(face, s, t, N);
        const CubePoint p = cube_from_direction(v(d), N);
        CHECK(int(p.face) == face);
        CHECK(p.pixel.x() == Approx(s).margin(1e-9));
        CHECK(p.pixel.y() == Approx(t).margin(1e-9));
      }
  CHECK_FALSE(face_plane_from_direction(Face::Front, {-1, 0.2, 0.1}, N).has_value());
}

TEST_CASE("paper C2E (Eq. 13-14) matches the face projection, its down view is turned 180 deg") {
  const int N = 512;
  for (double phi : {-2.9, -1.2, -0.3, 0.0, 0.4, 1.4, 2.5, 3.1})
    for (double elevation : {-1.3, -0.9, -0.5, -0.1, 0.0, 0.2, 0.6, 1.0, 1.4}) {
      const Vec3 d = direction_from_angles({phi, -elevation});
      const CubePoint p = cube_from_direction(d, N);
      const Vec2 ours = p.pixel - Vec2(N / 2.0, N / 2.0);
      const Vec2 paper = paper_c2e(p.face, phi, elevation, N);
      const double sign = p.face == Face::Down ? -1 : 1;
      CHECK(paper.x() == Approx(sign * ours.x()).margin(1e-7));
      CHECK(paper.y() == Approx(sign * ours.y()).margin(1e-7));
    }
}

TEST_CASE("360-degree flow takes the short way round (paper Eq. 3, -W/2 < u <= W/2)") {
  const int W = 1000;
  CHECK(wrap_360(10, W) == 10);
  CHECK(wrap_360(-499, W) == -499);
  CHECK(wrap_360(500, W) == 500);
  CHECK(wrap_360(-500, W) == 500);
  CHECK(wrap_360(501, W) == -499);
  CHECK(wrap_360(990, W) == -10);
  CHECK(wrap_360(-990, W) == 10);
  // classic flow: the target keeps its column in [0, W), so crossing the seam costs a full W
  CHECK(erp_flow_u(-10, 995.5, W, FlowMode::Wrap360) == -10);
  CHECK(erp_flow_u(20, 995.5, W, FlowMode::Classic) == 20 - W);
  CHECK(erp_flow_u(-20, 5.5, W, FlowMode::Classic) == -20 + W);
  CHECK(erp_flow_u(3, 500.5, W, FlowMode::Classic) == 3);
}

TEST_CASE("fast_atan2 agrees with std::atan2 to 1e-10 rad in every octant") {
  double worst = 0;
  for (int i = 0; i < 20000; ++i) {
    const double angle = -kPi + 2 * kPi * (i + 0.37) / 20000, radius = 0.001 + i % 7;
    const double y = radius * std::sin(angle), x = radius * std::cos(angle);
    worst = std::max(worst, std::abs(fast_atan2(y, x) - std::atan2(y, x)));
  }
  CHECK(worst < 1e-10);                         // the series alone is good to 1e-11
  CHECK(fast_atan2(0.0, -1.0) == Approx(kPi));  // the seam belongs to +pi
  CHECK(fast_atan2(0.0, 0.0) == 0);
  CHECK(fast_atan2(-1.0, 0.0) == Approx(-kPi / 2));
}

TEST_CASE("sin_cos agrees with std::sin and std::cos in every quadrant and turn") {
  const auto worst_error = [](double range) {
    double worst = 0;
    for (int i = 0; i < 40000; ++i) {
      const double x = -range + 2 * range * (i + 0.29) / 40000;
      const SinCos sc = sin_cos(x);
      worst = std::max({worst, std::abs(sc.sin - std::sin(x)), std::abs(sc.cos - std::cos(x))});
    }
    return worst;
  };
  CHECK(worst_error(2 * kPi) < 4e-16);
  CHECK(worst_error(40 * kPi) < 1e-14);
  CHECK(sin_cos(0.0).sin == 0);
  CHECK(sin_cos(0.0).cos == 1);
  CHECK(sin_cos(kPi / 2).sin == Approx(1).epsilon(1e-15));
}
