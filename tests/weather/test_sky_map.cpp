#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <optional>

#include "flowscape/formats/image_io.h"
#include "flowscape/weather/weather.h"
#include "sky_map.h"
#include "temp_dir.h"
#include "weather/synthetic_sky.h"

using namespace flowscape;
using namespace flowscape::sky;
using test::SyntheticSky;

namespace {

double degrees(double radians) { return radians * 180 / kPi; }
double luminance(const Spectrum& s) { return 0.2126 * s[0] + 0.7152 * s[1] + 0.0722 * s[2]; }

// Points FLOWSCAPE_SKY_MAPS at a folder while it lives.
struct SkyMapFolder {
  TempDir dir;
  std::optional<std::string> before;
  SkyMapFolder() {
    if (const char* value = std::getenv("FLOWSCAPE_SKY_MAPS")) before = value;
    setenv("FLOWSCAPE_SKY_MAPS", dir.path.c_str(), 1);
  }
  ~SkyMapFolder() {
    if (before)
      setenv("FLOWSCAPE_SKY_MAPS", before->c_str(), 1);
    else
      unsetenv("FLOWSCAPE_SKY_MAPS");
  }
};

Vec3 at_elevation(double elevation_degrees, double azimuth_degrees) {
  const double e = elevation_degrees * kPi / 180, a = azimuth_degrees * kPi / 180;
  return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

}  // namespace

TEST_CASE("a sky map's pixels look where the panorama convention says") {
  Image<float> map = test::synthetic_sky({});
  // row H/4 - 1/2 is 45 degrees up; column W/4 - 1/2 a quarter turn to the right (azimuth -90)
  const Vec3 d = map_direction(map, map.height / 4.0 - 0.5, map.width / 4.0 - 0.5);
  CHECK(d.x() == Approx(0).margin(1e-12));
  CHECK(d.y() == Approx(-std::sqrt(0.5)));
  CHECK(d.z() == Approx(std::sqrt(0.5)));
  map.pixel(17, 40)[1] = 7;  // a pixel's own direction reads back its value
  CHECK(map_radiance(map, map_direction(map, 40, 17))[1] == Approx(7));
  // a sky of radiance a + b sin(e) lights level ground with 2 pi (a / 2 + b / 3)
  const SyntheticSky s;
  const Spectrum expected = 2 * kPi * (s.a / 2 + s.b / 3) * s.tint;
  const Spectrum measured = horizontal_irradiance(map);
  for (int k = 0; k < 3; ++k) CHECK(measured[k] == Approx(expected[k]).epsilon(0.005));
}

TEST_CASE("the sun taken out of a map and traced as a disc keeps the map's light on level ground") {
  SyntheticSky s;
  s.sun = at_elevation(35, 120), s.sun_peak = 4000;
  Image<float> map = test::synthetic_sky(s);
  const Spectrum original = horizontal_irradiance(map);
  const SunInMap sun = take_out_sun(map);
  INFO("sun found " << degrees(std::acos(std::min(1.0, sun.direction.dot(s.sun)))) << " deg away");
  CHECK(std::acos(std::min(1.0, sun.direction.dot(s.sun))) < 0.2 * kPi / 180);
  const Spectrum expected = test::synthetic_sun_irradiance(s);
  for (int k = 0; k < 3; ++k) CHECK(sun.irradiance[k] == Approx(expected[k]).epsilon(0.02));
  const Spectrum traced = horizontal_irradiance(map) + sun.irradiance * sun.direction.z();
  for (int k = 0; k < 3; ++k) CHECK(traced[k] == Approx(original[k]).epsilon(0.01));
  // no sun in the map: nothing taken out
  Image<float> sunless = test::synthetic_sky({});
  const std::vector<float> before = sunless.data;
  CHECK(take_out_sun(sunless).irradiance.isZero());
  CHECK(sunless.data == before);
}

TEST_CASE("the fetched sky maps keep their light on level ground with the sun traced as a disc") {
  int checked = 0;
  for (const std::string& name : sky_map_names()) {
    const std::filesystem::path file = sky_map_directory() / (name + ".exr");
    if (!std::filesystem::exists(file)) continue;  // scripts/fetch_sky_maps.sh was not run
    const Image<float> raw = std::get<Image<float>>(read_any_image(file));
    Image<float> map(raw.width, raw.height, 3);
    for (int y = 0; y < raw.height; ++y)
      for (int x = 0; x < raw.width; ++x)
        for (int k = 0; k < 3; ++k) map.pixel(x, y)[k] = raw.pixel(x, y)[k];
    const double original = luminance(horizontal_irradiance(map));
    const SunInMap sun = take_out_sun(map);
    const double traced =
        luminance(horizontal_irradiance(map) + sun.irradiance * std::max(0.0, sun.direction.z()));
    INFO(name << ": " << original << " in the map, " << traced << " with the sun traced");
    CHECK(traced == Approx(original).epsilon(0.01));
    ++checked;
  }
  WARN(checked << " fetched sky maps checked");
}

TEST_CASE("a sky map lies over the dome above its horizon line and joins the dome below it") {
  SyntheticSky s;
  s.b = 0.2;
  const SkyMap map{"park", 20 * kPi / 180, test::synthetic_sky(s), {}};
  const Environment e = weather_environment(weather_preset("sunny"));
  SkyDome dome = *e.sky_dome;
  overlay_sky_map(map, 30 * kPi / 180, 2.0, dome);
  // above the line and its 4-degree blend: the map, turned 30 degrees, at twice its radiance
  for (double elevation : {25.0, 60.0}) {
    const Spectrum expected = 2 * (s.a + s.b * std::sin(elevation * kPi / 180)) * s.tint;
    const Eigen::Vector3f seen = dome.at(at_elevation(elevation, 75));
    for (int k = 0; k < 3; ++k) CHECK(seen[k] == Approx(expected[k]).epsilon(0.01));
  }
  // under the line the dome keeps its own sky's shape, brought to the map's level at the line
  // (24 degrees, where the map shows alone), azimuth by azimuth
  const SkyDome& physical = *e.sky_dome;
  const Spectrum map_at_line = 2 * (s.a + s.b * std::sin(24.1 * kPi / 180)) * s.tint;
  Spectrum seen = Spectrum::Zero(), expected = Spectrum::Zero();
  for (int k = 0; k < 360; ++k) {
    const Spectrum own = physical.at(at_elevation(10, k)).cast<double>().array(),
                   own_at_line = physical.at(at_elevation(24.1, k)).cast<double>().array();
    seen += dome.at(at_elevation(10, k)).cast<double>().array() / 360;
    expected += own / own_at_line * map_at_line / 360;
  }
  for (int k = 0; k < 3; ++k) CHECK(seen[k] == Approx(expected[k]).epsilon(0.03));
}

TEST_CASE("under a sky map the weather takes the map's sun; a map not fetched leaves it physical") {
  const SkyMapFolder folder;
  SyntheticSky s;
  s.sun = at_elevation(20, -60), s.sun_peak = 4000;
  write_image(folder.dir.path / "park.exr", test::synthetic_sky(s));
  test::pin(folder.dir.path / "park.exr");
  const Weather sunny = weather_preset("sunny");
  const Weather w = under_sky(sunny, "park", 3);
  CHECK(w.sky_map == "park");
  CHECK(w.sun_elevation == Approx(20).margin(0.2));
  CHECK(std::remainder(w.sun_azimuth - (w.sky_map_rotation - 60), 360) == Approx(0).margin(0.3));
  CHECK(w.time_of_day == "20.0");
  CHECK(w.cloudiness == 0);
  CHECK(under_sky(sunny, "park", 4).sky_map_rotation != w.sky_map_rotation);
  const Weather back = weather_from_json(to_json(w));
  CHECK(back.sky_map == "park");
  CHECK(back.sky_map_rotation == w.sky_map_rotation);
  const Environment e = weather_environment(w);
  CHECK(std::isfinite(e.exposure));
  CHECK(e.sun_irradiance.minCoeff() > 0);
  // not fetched: the weather as it was
  const Weather physical = under_sky(sunny, "venice", 3);
  CHECK(physical.sky_map.empty());
  CHECK(to_json(physical) == to_json(sunny));
  CHECK(to_json(under_sky(sunny, "physical", 3)) == to_json(sunny));
  CHECK_THROWS_WITH(under_sky(sunny, "mars", 3), Catch::Contains("unknown sky \"mars\""));
  // a 512-column map may be magnified 2x (163 pixels per radian), not more
  CHECK_NOTHROW(check_sky_resolution("park", 162));
  CHECK_THROWS_WITH(check_sky_resolution("park", 170),
                    Catch::Contains("sky map \"park\" is 512 x 256") &&
                        Catch::Contains("170.0 pixels per radian"));
  CHECK_NOTHROW(check_sky_resolution("venice", 1000));  // not fetched: nothing to refuse
  // a broken map is a FileError naming it
  write_file(folder.dir.path / "dawn.exr", "not an exr");
  test::pin(folder.dir.path / "dawn.exr");
  CHECK_THROWS_WITH(under_sky(sunny, "dawn", 3), Catch::Contains("dawn.exr"));
  write_image(folder.dir.path / "sunrise.exr", Image<float>(64, 64, 3));
  test::pin(folder.dir.path / "sunrise.exr");
  CHECK_THROWS_WITH(under_sky(sunny, "sunrise", 3),
                    Catch::Contains("sunrise.exr") && Catch::Contains("twice as wide as high"));
}

TEST_CASE("a sky map is checked against its pinned sha256 whenever it is read") {
  const SkyMapFolder folder;
  const std::filesystem::path map = folder.dir.path / "sky.exr";
  write_image(map, test::synthetic_sky({}));
  const Weather sunny = weather_preset("sunny");
  CHECK_THROWS_WITH(under_sky(sunny, "sky", 3),
                    Catch::Contains("sky.exr: no SHA256SUMS beside it to check it against"));
  test::pin(map);
  CHECK(under_sky(sunny, "sky", 3).sky_map == "sky");
  // one flipped bit, as a disk or a copy might leave it: refused, not a sun moved by 5 degrees
  std::string bytes = file_bytes(map);
  bytes[bytes.size() / 2] ^= 1;
  write_file(folder.dir.path / "venice.exr", bytes);
  std::ofstream(folder.dir.path / "SHA256SUMS", std::ios::app)
      << sha256_file(map) << "  venice.exr\n";  // pinned as the whole map was
  CHECK_THROWS_WITH(under_sky(sunny, "venice", 3), Catch::Contains("venice.exr: sha256 ") &&
                                                       Catch::Contains("differs from the pinned"));
}
