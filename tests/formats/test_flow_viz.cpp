#include <array>
#include <catch2/catch.hpp>

#include "flowscape/formats/flow_viz.h"

using namespace flowscape;

namespace {

// Colour of one flow vector at scale 1. Expected values come from the Middlebury wheel by hand:
// hues RY 15, YG 6, GC 4, CB 11, BM 13, MR 6; position (atan2(-v, -u) / pi + 1) / 2 * 54.
std::array<int, 3> color(FlowWheel wheel, double u, double v) {
  std::uint8_t rgb[3];
  wheel_color(wheel, u, v, rgb);
  return {rgb[0], rgb[1], rgb[2]};
}

}  // namespace

TEST_CASE("flow colours follow the Middlebury wheel") {
  for (FlowWheel wheel : {FlowWheel::Middlebury, FlowWheel::PanoFlow}) {
    CHECK(color(wheel, 0, 0) == std::array<int, 3>{255, 255, 255});  // no motion: white
    CHECK(color(wheel, -1, 0) == std::array<int, 3>{0, 209, 255});   // left: hue 27, CB step 2
    CHECK(color(wheel, 0, -1) == std::array<int, 3>{88, 0, 255});    // up: between hues 40 and 41
    CHECK(color(wheel, 0, 1) == std::array<int, 3>{255, 230, 0});    // down: between 13 and 14
    CHECK(color(wheel, -0.5, 0) == std::array<int, 3>{128, 232, 255});  // half way to white
  }
}

TEST_CASE("beyond the scale: Middlebury darkens, the PanoFlow wheel lowers saturation") {
  CHECK(color(FlowWheel::Middlebury, -2, 0) == std::array<int, 3>{0, 157, 191});  // 75 %
  // saturation 1 / (1 + ln(e)) = 1/2: the same colour as half the scale
  CHECK(color(FlowWheel::PanoFlow, -2.718281828459045, 0) == std::array<int, 3>{128, 232, 255});
}

TEST_CASE("flow_to_color scales, and draws unknown and invalid flow black") {
  Image<float> uv(3, 1, 2, 0.f);
  uv.pixel(0, 0)[0] = -4;  // the largest flow: full colour with the Middlebury scale
  uv.pixel(1, 0)[0] = 1e10f;
  uv.pixel(2, 0)[0] = -2;
  Image<std::uint8_t> valid(3, 1, 1, 1);
  const Image<std::uint8_t> rgb =
      flow_to_color(uv.view(), valid.view(), {FlowWheel::Middlebury, 0});
  CHECK(std::array<int, 3>{rgb.pixel(0, 0)[0], rgb.pixel(0, 0)[1], rgb.pixel(0, 0)[2]} ==
        std::array<int, 3>{0, 209, 255});
  CHECK(std::array<int, 3>{rgb.pixel(1, 0)[0], rgb.pixel(1, 0)[1], rgb.pixel(1, 0)[2]} ==
        std::array<int, 3>{0, 0, 0});
  CHECK(std::array<int, 3>{rgb.pixel(2, 0)[0], rgb.pixel(2, 0)[1], rgb.pixel(2, 0)[2]} ==
        std::array<int, 3>{128, 232, 255});
  *valid.pixel(0, 0) = 0;
  const Image<std::uint8_t> masked =
      flow_to_color(uv.view(), valid.view(), {FlowWheel::Middlebury, 4});
  CHECK(masked.pixel(0, 0)[1] == 0);
}
