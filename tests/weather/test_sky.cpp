// The physical sky (weather/src/atmosphere.h, sky.h) against closed forms of an exponential
// atmosphere and the CIE standard clear sky (ISO 15469 / CIE S 011: the published relative
// luminance distribution of a clear sky).
#include <catch2/catch.hpp>
#include <cmath>

#include "atmosphere.h"
#include "flowscape/weather/weather.h"
#include "sky.h"

using namespace flowscape;

namespace {

constexpr double kTop = 100;  // km, the atmosphere's thickness
const Eigen::Array3d kRayleigh(5.802e-3, 13.558e-3, 33.1e-3);
const Eigen::Array3d kOzone(0.650e-3, 1.881e-3, 0.085e-3);

// Optical depth of a layer of extinction beta exp(-h / H) between the ground and the top.
Eigen::Array3d vertical_depth(const Eigen::Array3d& beta, double height) {
  return beta * height * (1 - std::exp(-kTop / height));
}

double luminance(const Eigen::Vector3f& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

Vec3 direction(double elevation_deg, double azimuth_deg) {
  const double e = elevation_deg * kPi / 180, a = azimuth_deg * kPi / 180;
  return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

Environment clear_sky(double sun_elevation, double turbidity = 2.5) {
  Weather w = weather_preset("sunny");
  w.sun_elevation = sun_elevation, w.sun_azimuth = 0, w.turbidity = turbidity, w.cloudiness = 0;
  return weather_environment(w);
}

// The sky's luminance before the exposure.
double sky_luminance(const Environment& e, const Vec3& d) {
  return luminance(e.sky_dome->at(d)) / e.exposure;
}

// CIE standard general sky, type 12 (clear, low turbidity): relative luminance L / L_zenith of a
// sky element at zenith angle z and angle chi from the sun, with the sun at zenith angle z_sun.
double cie_clear_sky(double z, double chi, double z_sun) {
  const double a = -1, b = -0.32, c = 10, d = -3, e = 0.45;
  const auto gradation = [&](double zenith) { return 1 + a * std::exp(b / std::cos(zenith)); };
  const auto indicatrix = [&](double angle) {
    return 1 + c * (std::exp(d * angle) - std::exp(d * kPi / 2)) +
           e * std::cos(angle) * std::cos(angle);
  };
  return indicatrix(chi) * gradation(z) / (indicatrix(z_sun) * gradation(0));
}

}  // namespace

TEST_CASE("the air column's vertical optical depth is the closed form of its profiles") {
  for (double turbidity : {1.0, 2.5, 6.0}) {
    const sky::AirColumn air(turbidity);
    const Eigen::Array3d depth = air.optical_depth(0, 1, 2048);
    // Rayleigh (H = 8 km), haze (H = 1.2 km) with Preetham's turbidity (tau_haze = (T - 1) tau_air
    // at 550 nm, Angstrom exponent 1.3 about it) and ozone's 30 km tent (an integral of 15 km)
    const Eigen::Array3d haze_colour(std::pow(550.0 / 680, 1.3), 1, std::pow(550.0 / 440, 1.3));
    const Eigen::Array3d expected =
        vertical_depth(kRayleigh, 8) +
        haze_colour * (turbidity - 1) * kRayleigh[1] * 8 * (1 - std::exp(-kTop / 1.2)) +
        kOzone * 15;
    for (int c = 0; c < 3; ++c) CHECK(depth[c] == Approx(expected[c]).epsilon(0.002));
  }
}

TEST_CASE("a level ray's optical depth follows Chapman's grazing-incidence airmass") {
  // exponential air over a sphere, seen level from the ground: tau = beta H sqrt(pi x / 2)
  // (1 + 1 / (8 x)), x = R / H (Chapman's function at 90 degrees); the blue channel, where
  // ozone's share is under 0.2 %
  const sky::AirColumn air(1.0);
  const double x = sky::kGroundRadius / 8;
  const double expected = kRayleigh[2] * 8 * std::sqrt(kPi * x / 2) * (1 + 1 / (8 * x));
  CHECK(air.optical_depth(0, 0, 4096)[2] == Approx(expected).epsilon(0.005));
}

TEST_CASE("sun and view at the zenith: single scattering is the column times its transmittance") {
  // light from the top scattered at altitude h straight down crosses the whole column once,
  // whatever h: L = exp(-tau) integral beta(h) dh, per unit irradiance and phase
  const sky::Atmosphere atmosphere(2.5);
  const sky::Atmosphere::Scattered s = atmosphere.scattered(0, Vec3::UnitZ(), Vec3::UnitZ(), 400);
  const Eigen::Array3d through = exp(-atmosphere.air().optical_depth(0, 1, 2048));
  const Eigen::Array3d rayleigh = through * vertical_depth(kRayleigh, 8);
  for (int c = 0; c < 3; ++c) CHECK(s.rayleigh[c] == Approx(rayleigh[c]).epsilon(0.01));
  CHECK(atmosphere.transmittance(0, 1)[1] == Approx(through[1]).epsilon(0.002));
  // below the horizon the planet's shadow: no sunlight at the ground
  CHECK(atmosphere.transmittance(0, std::sin(-2 * kPi / 180)).maxCoeff() == 0);
}

TEST_CASE("the clear sky's luminance follows the CIE standard clear sky") {
  for (double elevation : {30.0, 55.0}) {
    const Environment e = clear_sky(elevation, 2.5);
    const double zenith = sky_luminance(e, Vec3::UnitZ()), z_sun = (90 - elevation) * kPi / 180;
    for (double d_elevation : {15.0, 40.0, 70.0})
      for (double azimuth : {60.0, 120.0, 180.0}) {
        const Vec3 d = direction(d_elevation, azimuth);
        const double chi = std::acos(d.dot(e.sun_direction));
        const double cie = cie_clear_sky((90 - d_elevation) * kPi / 180, chi, z_sun);
        INFO("sun " << elevation << ", view " << d_elevation << "/" << azimuth);
        CHECK(sky_luminance(e, d) / zenith == Approx(cie).epsilon(0.3));
      }
  }
}

TEST_CASE("sky colours: a blue noon, a red low sun, a dark sky in the planet's shadow") {
  const Environment noon = clear_sky(90), dusk = clear_sky(-4), low = clear_sky(2);
  const Eigen::Vector3f zenith = noon.sky_dome->at(Vec3::UnitZ());
  CHECK(zenith[2] > 1.3f * zenith[1]);
  CHECK(zenith[1] > zenith[0]);
  // the sun 2 degrees up: its light reddened through some 20 airmasses, and so is the horizon
  // under it, while the zenith stays blue
  CHECK(low.sun_irradiance[0] > 2 * low.sun_irradiance[2]);
  const Eigen::Vector3f under_sun = low.sky_dome->at(direction(1, 0));
  CHECK(under_sun[0] > under_sun[2]);
  // 4 degrees below the horizon: no sunlight, a sky hundreds of times darker than noon's, still
  // bluest at the zenith and brightest towards the set sun
  CHECK(dusk.sun_irradiance.maxCoeff() == 0);
  CHECK(sky_luminance(dusk, Vec3::UnitZ()) < sky_luminance(noon, Vec3::UnitZ()) / 100);
  const Eigen::Vector3f dusk_zenith = dusk.sky_dome->at(Vec3::UnitZ());
  CHECK(dusk_zenith[2] > dusk_zenith[0]);
  CHECK(sky_luminance(dusk, direction(5, 0)) > 2 * sky_luminance(dusk, direction(5, 180)));
  // and one exposure per sequence brightens dusk, less than its light fell
  CHECK(dusk.exposure > 30 * noon.exposure);
  const auto level = [](const Environment& e) {
    return luminance(e.sky_dome->horizontal_irradiance()) +
           luminance(e.sun_irradiance) * std::max(0.0, e.sun_direction.z());
  };
  CHECK(level(dusk) < 0.5 * level(noon));
}

TEST_CASE("a sky dome's table integrates as a sphere does") {
  SkyDome dome{90, 360, std::vector<Eigen::Vector3f>(90 * 360, Eigen::Vector3f(1, 2, 3))};
  const Eigen::Vector3f mean = dome.mean(), level = dome.horizontal_irradiance();
  for (int c = 0; c < 3; ++c) {
    CHECK(mean[c] == Approx(c + 1).epsilon(1e-3));
    CHECK(level[c] == Approx(kPi * (c + 1)).epsilon(1e-3));  // pi L for a uniform sky
  }
  // a sky growing with sin(elevation): its table is read back between the cells
  for (int r = 0; r < dome.rows; ++r)
    for (int c = 0; c < dome.columns; ++c)
      dome.radiance[std::size_t(r) * dome.columns + c].setConstant(float(dome.direction(r, c).z()));
  for (double elevation : {3.0, 33.3, 61.0})
    CHECK(dome.at(direction(elevation, 77))[0] ==
          Approx(std::sin(elevation * kPi / 180)).margin(2e-4));
}

TEST_CASE("clouds cover the share of the sky the weather asks for, and hide the sun behind them") {
  for (double cover : {0.2, 0.5, 0.7}) {  // below 0.75, where the overcast sheet begins
    Weather w = weather_preset("sunny");
    w.cloudiness = cover;
    int covered = 0, n = 0;
    for (int patch = 0; patch < 12; ++patch) {  // the sky over a few km, at shifts 70 km apart
      w.cloud_shift = 70.0 * patch;
      const sky::CloudLayer layer(w);
      for (double elevation = 40; elevation < 90; elevation += 2)  // near the zenith: fine detail
        for (double azimuth = 0; azimuth < 360; azimuth += 2, ++n)
          covered += layer.depth(direction(elevation, azimuth), 0.001) > 0;
    }
    INFO("cover " << cover);
    CHECK(double(covered) / n == Approx(cover).margin(0.1));
  }
  // a sun behind a cloud gives no direct light, one in a gap its clear-sky light
  Weather w = weather_preset("sunny");
  w.cloudiness = 0.5, w.sun_elevation = 60, w.sun_azimuth = 0;
  double hidden = -1, shining = -1;  // cloud shifts that put the sun behind a cloud, in a gap
  for (double shift = 0; shift < 100 && (hidden < 0 || shining < 0); ++shift) {
    w.cloud_shift = shift;
    const double depth = sky::CloudLayer(w).depth(direction(60, 0), 0.005);
    if (depth > 5 && hidden < 0) hidden = shift;
    if (depth == 0 && shining < 0) shining = shift;
  }
  REQUIRE(hidden >= 0);
  REQUIRE(shining >= 0);
  const Environment open = clear_sky(60);
  const double clear = luminance(open.sun_irradiance) / open.exposure;
  for (const auto& [shift, expected] : {std::pair{hidden, 0.0}, {shining, clear}}) {
    w.cloud_shift = shift;
    const Environment e = weather_environment(w);
    CHECK(luminance(e.sun_irradiance) / e.exposure == Approx(expected).margin(0.01 * clear));
  }
}

TEST_CASE("times of day set the sun and are recorded") {
  const Weather day = weather_preset("sunny");
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    const Weather dawn = at_time_of_day(day, "dawn", seed),
                  dusk = at_time_of_day(day, "dusk", seed);
    CHECK(dawn.sun_elevation >= -5);
    CHECK(dawn.sun_elevation <= 6);
    CHECK(std::cos((dawn.sun_azimuth - 90) * kPi / 180) > 0.8);   // in the east
    CHECK(std::cos((dusk.sun_azimuth - 270) * kPi / 180) > 0.8);  // in the west
  }
  CHECK(at_time_of_day(day, "day", 3).sun_elevation == day.sun_elevation);
  CHECK(at_time_of_day(day, "-2.5", 3).sun_elevation == -2.5);
  const Weather dusk = at_time_of_day(day, "dusk", 7);
  CHECK(to_json(weather_from_json(to_json(dusk))) == to_json(dusk));
  CHECK(to_json(dusk).at("time_of_day") == "dusk");
  for (const char* bad : {"noon", "-91", "91", "12deg", "nan", ""})
    CHECK_THROWS_AS(validate_time_of_day(bad), std::invalid_argument);
}

TEST_CASE("at night the moon lights the scene and the lamps are on; by day they are off") {
  Weather w = weather_preset("sunny");
  w.cloudiness = 0, w.sun_azimuth = 0;
  const Environment day = weather_environment(w);
  CHECK(day.lamp_level == 0);
  w.sun_elevation = -3;  // after sunset: the lamps go on, no sunlight is left
  const Environment dusk = weather_environment(w);
  CHECK(dusk.lamp_level == dusk.exposure);
  CHECK(dusk.sun_irradiance.maxCoeff() == 0);
  Weather night = at_time_of_day(w, "night", 5);
  CHECK(night.sun_elevation <= -18);
  night.moon_elevation = 40, night.moon_azimuth = 120;
  const Environment moonlit = weather_environment(night);
  CHECK(moonlit.lamp_level == moonlit.exposure);
  CHECK((moonlit.sun_direction - direction(40, 120)).norm() <
        1e-9);  // the moon takes the sun's place
  // the full moon: 2.5e-6 of the sun's light at the same height, through the same air
  w.sun_elevation = 40, w.sun_azimuth = 120;
  const Environment sun = weather_environment(w);
  CHECK(luminance(moonlit.sun_irradiance) / moonlit.exposure ==
        Approx(2.5e-6 * luminance(sun.sun_irradiance) / sun.exposure).epsilon(1e-4));
  // a moonless night sky is far darker than a moonlit one, which is far darker than day
  night.moon_elevation = -10;
  const Environment moonless = weather_environment(night);
  CHECK(sky_luminance(moonless, direction(60, 300)) < sky_luminance(moonlit, direction(60, 300)));
  CHECK(sky_luminance(moonlit, direction(60, 300)) < 1e-4 * sky_luminance(sun, direction(60, 300)));
}
