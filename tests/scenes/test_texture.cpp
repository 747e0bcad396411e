#include <catch2/catch.hpp>
#include <cmath>

#include "flowscape/scenes/texture.h"

using namespace flowscape;
using namespace flowscape::tex;

TEST_CASE("value noise: in [-1, 1], its gradient is the derivative, lattice points are exact") {
  double largest = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec2 p(0.37 * k - 50, 0.11 * k + 3.3 * std::sin(k));
    const Noise n = value_noise(p, 7);
    largest = std::max(largest, std::abs(n.value));
    const double h = 1e-6;
    const double dx =
        (value_noise(p + Vec2(h, 0), 7).value - value_noise(p - Vec2(h, 0), 7).value) / (2 * h);
    const double dy =
        (value_noise(p + Vec2(0, h), 7).value - value_noise(p - Vec2(0, h), 7).value) / (2 * h);
    REQUIRE(n.gradient.x() == Approx(dx).margin(1e-5));
    REQUIRE(n.gradient.y() == Approx(dy).margin(1e-5));
  }
  CHECK(largest <= 1);
  CHECK(largest > 0.8);
  // at a lattice point the value is that point's hash and the fade's slope is 0
  const Noise at = value_noise({3, -4}, 7);
  CHECK(at.value == Approx(2 * hash01(3, -4, 7) - 1));
  CHECK(at.gradient.norm() == Approx(0).margin(1e-12));
}

TEST_CASE("fBm keeps the octaves longer than two footprints and drops those below one") {
  const Vec2 p(12.3, -4.5);
  // frequency 1: wavelengths 1, 1/2, 1/4, 1/8
  CHECK(std::abs(fbm(p, 3, 1, 4, 0).value) <= 1 + 0.5 + 0.25 + 0.125);
  // a footprint of 0.3: wavelength 1 (> 0.6) stays whole, 1/2 fades (1/2 / 0.3 - 1 = 0.67), 1/4
  // and 1/8 (< 0.3) vanish: the result equals the first two octaves alone
  const Noise blurred = fbm(p, 3, 1, 4, 0.3);
  const Noise first = fbm(p, 3, 1, 1, 0);
  const Noise two = fbm(p, 3, 1, 2, 0);
  const double second = two.value - first.value;  // the second octave at full weight
  CHECK(blurred.value == Approx(first.value + (0.5 / 0.3 - 1) * second));
  CHECK(fbm(p, 3, 1, 4, 10).value == 0);  // wider than every octave: the mean
}

TEST_CASE("box-filtered pulses and lines have the closed-form coverage") {
  // pulses of width 0.2 every 1.0: a box of width 1 always holds exactly 0.2
  for (double x : {0.0, 0.13, 0.5, 7.77}) CHECK(pulse_train(x, 1, 0.2, 1) == Approx(0.2));
  CHECK(pulse_train(0.1, 1, 0.2, 0) == 1);
  CHECK(pulse_train(0.5, 1, 0.2, 0) == 0);
  CHECK(pulse_train(0.2, 1, 0.2, 0.2) == Approx(0.5));  // half the box on the pulse
  // a line of half width 0.1 seen through a box of width 0.4 centred 0.15 away: [-0.05, 0.35]
  // overlaps [-0.1, 0.1] over 0.15
  CHECK(line_coverage(0.15, 0.1, 0.4) == Approx(0.15 / 0.4));
  CHECK(line_coverage(0.05, 0.1, 0) == 1);
  CHECK(line_coverage(0.3, 0.1, 0.1) == 0);
}

TEST_CASE("a bond's mortar averages to its joints' share and bricks are numbered per course") {
  // bricks 0.25 x 0.075 with 0.012 joints: mortar covers 1 - (1 - 0.012/0.25)(1 - 0.012/0.075)
  const Bond wide = bond({3.21, 1.7}, {0.25, 0.075}, 0.012, 0.5, 0.75);  // 3 x 10 bricks
  CHECK(wide.mortar == Approx(1 - (1 - 0.012 / 0.25) * (1 - 0.012 / 0.075)).epsilon(0.02));
  const Bond a = bond({0.1, 0.03}, {0.25, 0.075}, 0.012, 0.5, 0);
  const Bond b = bond({0.2, 0.03}, {0.25, 0.075}, 0.012, 0.5, 0);  // same brick
  const Bond c = bond({0.1, 0.1}, {0.25, 0.075}, 0.012, 0.5, 0);   // the next course
  CHECK(a.unit == b.unit);
  CHECK(a.unit != c.unit);
  CHECK(a.mortar == 0);
  CHECK(bond({0.2505, 0.03}, {0.25, 0.075}, 0.012, 0.5, 0).mortar == 1);  // on a joint
}

TEST_CASE("cells: the nearest feature point is nearer than the second, ids repeat within a cell") {
  for (int k = 0; k < 500; ++k) {
    const Vec2 p(0.731 * k, -0.377 * k);
    const Cells c = cells(p, 2, 5);
    REQUIRE(c.f1 <= c.f2);
    REQUIRE(c.f1 < 2 * std::sqrt(2.0));
  }
  CHECK(cells({1.0, 1.0}, 2, 5).id == cells({1.0001, 1.0001}, 2, 5).id);
}
