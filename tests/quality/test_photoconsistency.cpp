#include <catch2/catch.hpp>
#include <string>

#include "flowscape/geometry/geometry.h"
#include "flowscape/quality/photoconsistency.h"
#include "shifted_pattern.h"

using namespace flowscape;
using namespace shifted;

TEST_CASE("a known shift gives WPE near 0 and a large PE while a wrong flow does not") {
  const Image<std::uint8_t> first = to8(image_of(0, 0)), second = to8(image_of(3.4, -1.7));
  const Image<float> right = constant_flow(3.4, -1.7), wrong = constant_flow(-3.4, 1.7);
  const PairErrors good = photo_errors({first.view(), second.view(), right.view()});
  const PairErrors bad = photo_errors({first.view(), second.view(), wrong.view()});
  INFO("good: PE " << good.pe << " WPE " << good.wpe << "; wrong: WPE " << bad.wpe);
  CHECK(good.pe > 20);
  CHECK(good.wpe < 0.05 * good.pe);  // bilinear sampling of a smooth pattern
  CHECK(bad.wpe > 0.8 * bad.pe);
  CHECK(diff_percent(good.pe, good.wpe) > 90);
  CHECK(std::string(quality_label(diff_percent(good.pe, good.wpe))) == "high");
  CHECK(std::string(quality_label(diff_percent(bad.pe, bad.wpe))) == "medium/low");
  // pixels whose target leaves the image are not counted: 4 columns (x + 3.4 > 63) and 2 rows
  CHECK(good.pixels == (W - 4) * (H - 2));
}

TEST_CASE("a panorama turned across its seam is warped back through the wrap") {
  const Image<std::uint8_t> first = to8(image_of(0, 0)), turned = to8(image_of(5.5, 0));
  const Image<float> flow = constant_flow(5.5, 0);
  PairImages pair{first.view(), turned.view(), flow.view()};
  pair.panorama = true;
  const PairErrors wrapped = photo_errors(pair);
  CHECK(wrapped.pixels == W * H);  // every target is inside after wrapping
  CHECK(wrapped.wpe < 0.05 * wrapped.pe);
  pair.panorama = false;
  CHECK(photo_errors(pair).pixels == (W - 6) * H);
}

TEST_CASE("unknown flow and masks decide which pixels count") {
  const Image<std::uint8_t> first = to8(image_of(0, 0)), second = to8(image_of(2, 0));
  Image<float> flow = constant_flow(2, 0);
  Image<std::uint8_t> known(W, H, 1), visible(W, H, 1);
  std::fill(known.data.begin(), known.data.end(), 1);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < 10; ++x) *known.pixel(x, y) = 0, flow.pixel(x, y)[0] = 40;  // junk, invalid
  flow.pixel(20, 20)[0] = kUnknownFlow;
  for (int y = 0; y < H / 2; ++y)
    for (int x = 0; x < W; ++x) *visible.pixel(x, y) = 1;
  const PairErrors e =
      photo_errors({first.view(), second.view(), flow.view(), known.view(), visible.view()});
  CHECK(e.pixels == (W - 10 - 2) * H - 1);
  CHECK(e.visible_pixels == (W - 10 - 2) * H / 2 - 1);
  CHECK(e.wpe < 0.05 * e.pe);
}
