#include <catch2/catch.hpp>

#include "flowscape/quality/image_statistics.h"

using namespace flowscape;

TEST_CASE("flat share: ramps steeper and gentler than the threshold, masks, the ERP seam") {
  Image<std::uint8_t> image(20, 10, 3), all(20, 10, 1, 1);
  // columns 0-9: a ramp of 3 grey levels per pixel along x (|g| = 3); columns 10-19: constant
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 20; ++x)
      for (int c = 0; c < 3; ++c) image.pixel(x, y)[c] = std::uint8_t(x < 10 ? 100 + 3 * x : 130);
  // rows 1..8 count; as a plain image columns 1..18: columns 1-8 steep, 9 has (130-124)/2 = 3
  // (steep), 10 has (130-127)/2 = 1.5 (flat), 11-18 flat
  CHECK(flat_share(image.view(), all.view(), 2, false) == Approx(9.0 / 18));
  // as a panorama, columns 0 and 19 count too: column 0 sees (103 - 130) / 2 (steep), column 19
  // sees (100 - 130) / 2 (steep)
  CHECK(flat_share(image.view(), all.view(), 2, true) == Approx(9.0 / 20));
  Image<std::uint8_t> left(20, 10, 1, 0);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 5; ++x) *left.pixel(x, y) = 1;
  CHECK(flat_share(image.view(), left.view(), 2, false) == Approx(0));
  CHECK(flat_share(image.view(), all.view(), 4, false) == Approx(1));  // 3 < 4 everywhere
}
