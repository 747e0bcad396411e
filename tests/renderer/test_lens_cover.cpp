// Drops and dirt on the lens (final pass): the light through them against closed forms (a flat
// scene, a linear ramp seen inverted through a drop), the mask, and the cover's placement.
#include <catch2/catch.hpp>
#include <cmath>

#include "flowscape/renderer/lens_cover.h"

using namespace flowscape;

namespace {

Image<float> image_of(int width, int height, float (*value)(int x, int y)) {
  Image<float> image(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) image.pixel(x, y)[c] = value(x, y) * float(c + 1);
  return image;
}

}  // namespace

TEST_CASE("a drop dims a flat scene to its transmission, dirt by its scattered share") {
  const Image<float> flat = image_of(64, 48, [](int, int) { return 2.0f; });
  LensCover cover;
  cover.drops = {{Vec2(20, 20), 8}};
  const Image<float> seen = through_cover(flat.view(), cover);
  for (int c = 0; c < 3; ++c) {
    CHECK(seen.pixel(19, 19)[c] == Approx(2.0 * (c + 1) * kDropTransmission).epsilon(1e-5));
    CHECK(seen.pixel(50, 40)[c] == flat.pixel(50, 40)[c]);  // outside the drop
    // on the rim: share s of the drop's light, 1 - s of the scene's
    const double distance = (Vec2(26.5, 19.5) - Vec2(20, 20)).norm();
    const double s = drop_share(cover.drops[0], distance);
    REQUIRE((s > 0 && s < 1));
    CHECK(seen.pixel(26, 19)[c] ==
          Approx(2.0 * (c + 1) * (1 - s + s * kDropTransmission)).epsilon(1e-5));
  }
  LensCover dirty;
  dirty.dirt = Image<float>(64, 48, 1);
  std::fill(dirty.dirt.data.begin(), dirty.dirt.data.end(), 0.4f);
  const Image<float> hazy = through_cover(flat.view(), dirty);
  CHECK(hazy.pixel(30, 30)[0] == Approx(2.0 * (0.6 + 0.4 * kDirtTransmission)).epsilon(1e-5));
}

TEST_CASE("a drop shows the scene behind it inverted and wider, as a small lens does") {
  // a ramp L = 0.5 x + 3 stays a ramp under any symmetric blur away from the borders, so the pixel
  // at offset d from the drop's centre c reads T x L(c - kDropView d)
  const Image<float> ramp = image_of(200, 120, [](int x, int) { return 0.5f * (x + 0.5f) + 3; });
  LensCover cover;
  cover.drops = {{Vec2(100, 60), 12}};
  const Image<float> seen = through_cover(ramp.view(), cover);
  for (int dx : {-7, -3, 0, 4, 8}) {
    const Vec2 pixel(100 + dx + 0.5, 60.5);
    const double behind = (cover.drops[0].centre - kDropView * (pixel - cover.drops[0].centre)).x();
    CHECK(seen.pixel(100 + dx, 60)[0] ==
          Approx(kDropTransmission * (0.5 * behind + 3)).epsilon(1e-4));
  }
  // right of the centre shows what lies left of it: the drop inverts
  CHECK(seen.pixel(108, 60)[0] < seen.pixel(92, 60)[0]);
}

TEST_CASE("the mask marks what drops and dense dirt hide, and the cover is the seed's") {
  LensCover cover;
  cover.drops = {{Vec2(20, 20), 10}};
  cover.dirt = Image<float>(64, 48, 1);
  *cover.dirt.pixel(50, 40) = 0.5f, *cover.dirt.pixel(51, 40) = 0.49f;
  const Image<std::uint8_t> mask = cover_mask(cover, 64, 48);
  CHECK(*mask.pixel(20, 20) == 1);
  CHECK(*mask.pixel(28, 19) == 1);  // 8.5 px out: share 0.75
  CHECK(*mask.pixel(29, 19) == 0);  // 9.5 px out: share 0.25
  CHECK(*mask.pixel(50, 40) == 1);
  CHECK(*mask.pixel(51, 40) == 0);
  CHECK(*mask.pixel(5, 45) == 0);

  const LensCover a = lens_cover(320, 240, 12, 0.6, 42), b = lens_cover(320, 240, 12, 0.6, 42);
  REQUIRE(a.drops.size() == 12);
  for (std::size_t k = 0; k < a.drops.size(); ++k) {
    CHECK(a.drops[k].centre == b.drops[k].centre);
    CHECK((a.drops[k].radius >= 2.4 && a.drops[k].radius <= 9.6));  // 1-4 % of 240
  }
  CHECK(*std::max_element(a.dirt.data.begin(), a.dirt.data.end()) == Approx(0.6));
  CHECK(lens_cover(320, 240, 12, 0.6, 43).drops[0].centre != a.drops[0].centre);
  CHECK(lens_cover(320, 240, 0, 0, 42).empty());
}
