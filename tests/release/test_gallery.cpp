// The actor gallery (city_preview --actors): one row per model and time of day, and a vehicle's
// own lamps glowing in the night row where they are dark in the day row.
#include <catch2/catch.hpp>

#include "flowscape/release/gallery.h"

using namespace flowscape;

namespace {

double mean_level(const Image<std::uint8_t>& tile) {
  double sum = 0;
  for (std::uint8_t v : tile.data) sum += v;
  return sum / double(tile.data.size());
}

// Pixels of a lit red lamp: a saturated red, little green or blue.
int red_glow(const Image<std::uint8_t>& tile) {
  int count = 0;
  for (std::size_t i = 0; i + 2 < tile.data.size(); i += std::size_t(tile.channels))
    count += tile.data[i] > 200 && tile.data[i + 1] < 90 && tile.data[i + 2] < 90;
  return count;
}

}  // namespace

TEST_CASE("the actor gallery has a row per model and time, a vehicle's lamps lit at night") {
  GalleryOptions options;
  options.height = 72, options.color.spp = 4;
  options.models = {"hatchback"};
  options.times_of_day = {"day", "night"};
  const auto rows = actor_gallery(options);
  REQUIRE(rows.size() == 2);
  REQUIRE(rows[0].size() == 5);  // front, side, back, three-quarter, semantics
  REQUIRE(rows[1].size() == 5);
  CHECK(rows[0][4].data == rows[1][4].data);  // the same model, the same semantics
  const int back = 2;
  CHECK(mean_level(rows[1][back]) < 0.5 * mean_level(rows[0][back]));
  CHECK(red_glow(rows[0][back]) == 0);  // tail lamps unlit by day
  CHECK(red_glow(rows[1][back]) > 0);   // and glowing at night
  options.times_of_day.clear();         // sky light: one row per model
  CHECK(actor_gallery(options).size() == 1);
}
