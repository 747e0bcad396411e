#include <catch2/catch.hpp>

#include "flowscape/quality/round_trip.h"

using namespace flowscape;

namespace {

Image<float> constant(int W, int H, float u, float v) {
  Image<float> flow(W, H, 2);
  for (std::size_t i = 0; i < flow.pixel_count(); ++i)
    flow.data[2 * i] = u, flow.data[2 * i + 1] = v;
  return flow;
}

Image<std::uint8_t> ones(int W, int H) {
  Image<std::uint8_t> mask(W, H, 1);
  std::fill(mask.data.begin(), mask.data.end(), 1);
  return mask;
}

}  // namespace

TEST_CASE("a shift and its reverse return every pixel visible both ways, and only those") {
  const int W = 16, H = 8;
  const Image<float> forward = constant(W, H, 2.25f, 1), backward = constant(W, H, -2.25f, -1);
  Image<std::uint8_t> visible = ones(W, H), back_visible = ones(W, H);
  // pinhole: targets off the right edge (x + 0.5 + 2.25 >= 16: x >= 14) and below the last row
  // (y = 7) do not count: 14 x 7 pixels
  RoundTrip trip =
      round_trip({forward.view(), visible.view(), backward.view(), back_visible.view()});
  CHECK(trip.both_ways == 14 * 7);
  CHECK(trip.returned == 14 * 7);
  // a panorama wraps: columns 14 and 15 land on 0 and 1
  trip = round_trip({forward.view(), visible.view(), backward.view(), back_visible.view(), true});
  CHECK(trip.both_ways == 16 * 7);
  CHECK(trip.share() == 1);
  // hidden at the start or at the target: left out; a wrong backward flow: counted, not returned
  *visible.pixel(3, 2) = 0;
  *back_visible.pixel(7, 4) = 0;  // target of (5, 3): 5.5 + 2.25 = 7.75, 3.5 + 1 = 4.5
  Image<float> off = backward;
  // the targets of row 5 sample row 6 between columns x + 2 and x + 3 (weights 0.75, 0.25)
  for (int x : {10, 11}) off.pixel(x, 6)[0] += 0.02f;
  trip = round_trip({forward.view(), visible.view(), off.view(), back_visible.view(), true});
  CHECK(trip.both_ways == 16 * 7 - 2);
  // (8, 5) is 0.02 off, (9, 5) 0.015; (7, 5) only 0.005, within 0.01
  CHECK(trip.returned == 16 * 7 - 2 - 2);
}
