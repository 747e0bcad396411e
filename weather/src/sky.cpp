#include "sky.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "atmosphere.h"
#include "flowscape/scenes/texture.h"
#include "sky_map.h"

namespace flowscape::sky {
namespace {

using Rgb = Eigen::Vector3f;

constexpr double kCloudAltitude = 2;      // km
constexpr double kCloudFrequency = 0.35;  // cycles per km of the coarsest octave
constexpr int kOctaves = 6;
constexpr std::uint64_t kCloudSeed = 0xc10d5;  // the pattern; cloud_shift moves over it
constexpr double kHazeDistance = 60;           // km over which far clouds fade into the haze
constexpr double kAngleSpread = 0.004;         // radians: the dome's cell size, filtered over
constexpr int kDomeRows = 320, kDomeColumns = 1280;
constexpr int kClearRows = 40, kClearColumns = 96;  // the clear sky's coarse table
constexpr double kObserverAltitude = 0.05;          // km
constexpr double kMoonShare = 2.5e-6;               // full moon / sun
// At night, in the sky's units (the top-of-atmosphere sun 1): the light a camera on a car exposes
// for (60 lux: street lamps and the road in its head lamps), a city's glow on the air at the
// horizon, its lit streets' light on cloud bases, and the brightest stars.
constexpr double kLampLight = 6e-4, kStarRadiance = 2e-7;
constexpr std::uint64_t kStarSeed = 0x57a25;
const Spectrum kCityGlow = Spectrum(1.0, 0.7, 0.45) * 2.2e-6;
const Spectrum kCityUplight = Spectrum(1.0, 0.75, 0.5) * 1.5e-5;

double luminance(const Spectrum& s) { return 0.2126 * s[0] + 0.7152 * s[1] + 0.0722 * s[2]; }
Vec3 direction(double elevation, double azimuth) {
  return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
          std::sin(elevation)};
}

// Top-of-atmosphere sunlight in the colour that makes the noon sun (60 degrees up, turbidity 2.5)
// white at the ground: a camera's fixed daylight white balance, so dawn and dusk stay warm.
Spectrum daylight_sun() {
  const Spectrum through = exp(-AirColumn(2.5).optical_depth(0, std::sin(kPi / 3)));
  return through[1] / through;
}

// The clear sky on a coarse grid of elevations (dense near the horizon, where it changes most)
// and azimuths, without the phase functions, which are applied per dome cell.
struct ClearSky {
  ClearSky(const Atmosphere& atmosphere, const Vec3& sun) : sun(sun) {
    cells.reserve(std::size_t(kClearRows) * kClearColumns);
    for (int row = 0; row < kClearRows; ++row)
      for (int column = 0; column < kClearColumns; ++column)
        cells.push_back(atmosphere.scattered(
            kObserverAltitude, direction(row_elevation(row), column_azimuth(column)), sun));
  }
  static double row_elevation(double row) {
    const double x = row / (kClearRows - 1);
    return x * x * kPi / 2;
  }
  static double column_azimuth(double column) { return column / kClearColumns * 2 * kPi; }

  Spectrum radiance(const Vec3& d) const {
    const double row =
        std::sqrt(std::asin(std::clamp(d.z(), 0.0, 1.0)) / (kPi / 2)) * (kClearRows - 1);
    double column = std::atan2(d.y(), d.x()) / (2 * kPi) * kClearColumns;
    column -= std::floor(column / kClearColumns) * kClearColumns;
    const int r0 = std::min(int(row), kClearRows - 2), c0 = int(column) % kClearColumns;
    const int c1 = (c0 + 1) % kClearColumns;
    const double fr = row - r0, fc = column - std::floor(column), cos_sun = d.dot(sun);
    const auto at = [&](int r, int c) {
      return cells[std::size_t(r) * kClearColumns + c].radiance(cos_sun);
    };
    return (1 - fr) * ((1 - fc) * at(r0, c0) + fc * at(r0, c1)) +
           fr * ((1 - fc) * at(r0 + 1, c0) + fc * at(r0 + 1, c1));
  }

  Vec3 sun;
  std::vector<Atmosphere::Scattered> cells;
};

// Henyey-Greenstein phase (1/sr): the clouds' strong forward peak, their silver lining.
double henyey_greenstein(double cos_angle, double g) {
  return (1 - g * g) / (4 * kPi * std::pow(1 + g * g - 2 * g * cos_angle, 1.5));
}

// A cloud: the light of the sun and sky above diffused through its optical depth onto its base
// (two-stream transmission of a conservative slab, T = 1 / (1 + 3/4 (1 - g) tau), g = 0.85); under
// a low sun its sides, lit as a lumpy diffuse body (albedo 1 - T) is, brightest with the sun behind
// the observer; the sunlight it scatters once towards the observer (bright where thin, near the
// sun: the silver lining); the city's light its base reflects at night; and the sky behind it
// through what is left.
Spectrum cloudy(const Spectrum& clear, double tau, double cos_to_sun, const Spectrum& sun_above,
                double sun_height, const Spectrum& sky_above, double cover,
                const Spectrum& from_below) {
  const double unscattered = std::exp(-tau), transmitted = 1 / (1 + 0.1125 * tau);
  const double diffused = std::max(transmitted - unscattered, 0.0);
  const Spectrum base = (sun_above * std::max(sun_height, 0.0) + sky_above) / kPi * diffused;
  // (sunlight grazing the layer meets other clouds on its way: the more cover, the fewer sides lit)
  const double lit_sides =
      std::pow(1 - cover, 2) * (1 - std::abs(sun_height)) * (1 - cos_to_sun) / 2;
  const Spectrum sides = sun_above * ((1 - transmitted) * lit_sides / kPi);
  return clear * unscattered + base + sides + from_below * ((1 - transmitted) / kPi) +
         sun_above * (henyey_greenstein(cos_to_sun, 0.75) * tau * unscattered);
}

}  // namespace

CloudLayer::CloudLayer(const Weather& w)
    : thickness_(12 + 40 * w.cloudiness + 60 * w.precipitation),
      // rain falls from a closed nimbostratus
      sheet_(
          std::max(tex::smoothstep(0.75, 1.0, w.cloudiness), std::min(1.0, 1.2 * w.precipitation))),
      shift_(w.cloud_shift, 0.618 * w.cloud_shift) {
  // the pattern's (1 - cloudiness) quantile over 110 km of the layer: that share is covered
  std::vector<double> values;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      values.push_back(
          tex::fbm(Vec2(x, y) * 1.73 + shift_, kCloudSeed, kCloudFrequency, kOctaves, 0).value);
  const double cover = std::clamp(w.cloudiness, 0.0, 1.0);
  const std::size_t k = std::min(values.size() - 1, std::size_t((1 - cover) * values.size()));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  threshold_ = cover <= 0 ? 1e9 : values[k];
}

double CloudLayer::distance(const Vec3& d) {
  const double r = kGroundRadius + kObserverAltitude, top = kGroundRadius + kCloudAltitude;
  return -r * d.z() + std::sqrt(r * r * (d.z() * d.z() - 1) + top * top);
}

// The octaves a footprint fades out leave the pattern unknown by their spread; the cut through
// the pattern is softened by as much, so that far clouds keep their mean cover instead of
// flickering between the cut's two sides.
double CloudLayer::density(const Vec2& at, double footprint) const {
  const Vec2 p = at + shift_;
  const double n = tex::fbm(p, kCloudSeed, kCloudFrequency, kOctaves, footprint).value;
  double lost = 0, amplitude = 1, frequency = kCloudFrequency;
  for (int k = 0; k < kOctaves; ++k, amplitude /= 2, frequency *= 2)
    lost += std::pow(amplitude * (1 - tex::visible(1 / frequency, footprint)), 2) / 6;
  const double soft = std::sqrt(lost);
  const double cumulus = tex::smoothstep(-soft, 0.6 + soft, n - threshold_);
  // the sheet mottled as stratocumulus are, on a finer pattern
  const double mottle =
      tex::fbm(p * 3.1, kCloudSeed + 7, kCloudFrequency, 4, footprint * 3.1).value;
  return cumulus + sheet_ * (0.45 + 0.25 * mottle);
}

double CloudLayer::depth(const Vec3& d, double spread) const {
  const double t = distance(d);
  const Vec3 at = t * d;
  const double slant = std::max(at.normalized().dot(d), 0.05);  // cosine at the layer
  return thickness_ * density(at.head<2>(), t * spread / slant) / std::sqrt(slant);
}

namespace {

// What lights the sky: the sun, or at night (the sun 6 degrees or more below the horizon) the full
// moon, 2.5e-6 of the sun's light (0.25 lux against 100 000).
struct SkyLight {
  Vec3 direction;
  double share;
};
SkyLight sky_light(const Weather& w, const Vec3& sun) {
  if (w.sun_elevation >= -6) return {sun, 1};
  return {direction(w.moon_elevation * kPi / 180, w.moon_azimuth * kPi / 180), kMoonShare};
}

// The glow of a city's lamps on the air, warm, strongest at the horizon.
Spectrum city_glow(const Vec3& d) {
  return kCityGlow * (0.1 + std::exp(-std::asin(std::clamp(d.z(), 0.0, 1.0)) / 0.15));
}

// Faint stars: a few cells in a thousand, seeded by the cell, dimmed through the air.
Spectrum star(int row, int column, const Vec3& d, const Spectrum& zenith_depth) {
  const double u = tex::hash01(std::uint64_t(row) * kDomeColumns + column, kStarSeed);
  if (u > 0.002) return Spectrum::Zero();
  const double brightness = kStarRadiance * std::pow(std::log(0.002 / std::max(u, 1e-9)), 2);
  return brightness * exp(-zenith_depth / std::max(d.z(), 0.05));
}

// Light on level ground: the sun (or moon) and the dome.
Spectrum level_light(const Spectrum& sun_ground, const Vec3& sun, const SkyDome& dome) {
  return sun_ground * std::max(sun.z(), 0.0) + dome.horizontal_irradiance().cast<double>().array();
}

// One exposure for the sequence: the level light E (luminance; with the lamps on, the light under
// a street lamp added) brought to 4 (what the scenes' materials were tuned under) at the reference
// sun (55 degrees, clear), to 4 (E / E_ref)^0.2 otherwise, so a dusk or an overcast day stays
// darker than noon as a photographer keeps them, and to no less than 1.8 (a night street is
// exposed for its lamps).
double exposure_for(double level_luminance, bool lamps_on) {
  const double reference = std::sin(55 * kPi / 180);
  const double measured = std::max(level_luminance + (lamps_on ? kLampLight : 0), 1e-12);
  return std::max(1.8, 4 * std::pow(measured / reference, 0.2)) / measured;
}

// A map's sky and sun in the physical sky's units (a map's own are arbitrary): scaled so that its
// light on level ground is the clear sky's under the same sun, laid over the dome; returns its
// sun's irradiance.
Spectrum sun_of_map(const SkyMap& map, double rotation_degrees, const Spectrum& clear_level,
                    SkyDome& dome) {
  const Spectrum map_level = map.sun.irradiance * std::max(map.sun.direction.z(), 0.0) +
                             horizontal_irradiance(map.radiance);
  const double scale = luminance(clear_level) / std::max(luminance(map_level), 1e-12);
  overlay_sky_map(map, rotation_degrees * kPi / 180, scale, dome);
  return map.sun.irradiance * scale;
}

}  // namespace

void set_physical_sky(const Weather& w, Environment& e) {
  const Atmosphere atmosphere(w.turbidity);
  const bool lamps_on = w.sun_elevation < 0, night = w.sun_elevation < -6;
  const SkyLight light = sky_light(w, e.sun_direction);
  const Spectrum white = daylight_sun() * light.share;
  const Vec3 sun = light.direction;
  const ClearSky clear(atmosphere, sun);
  const CloudLayer clouds(w);
  const Spectrum sun_above = white * atmosphere.transmittance(kCloudAltitude, sun.z());
  const Spectrum zenith_depth = atmosphere.air().optical_depth(0, 1, 64);
  // the clear sky's irradiance on a level surface, from the coarse table
  Spectrum sky_above = Spectrum::Zero();
  for (int row = 0; row < 16; ++row)
    for (int column = 0; column < 32; ++column) {
      const double elevation = (row + 0.5) / 16 * kPi / 2;
      const Vec3 d = direction(elevation, (column + 0.5) / 32 * 2 * kPi);
      sky_above +=
          white * clear.radiance(d) * (d.z() * std::cos(elevation) * (kPi / 32) * (2 * kPi / 32));
    }
  const Spectrum from_city = lamps_on ? kCityUplight : Spectrum::Zero();
  auto dome = std::make_shared<SkyDome>();
  dome->rows = kDomeRows, dome->columns = kDomeColumns;
  dome->radiance.resize(std::size_t(kDomeRows) * kDomeColumns);
  for (int row = 0; row < kDomeRows; ++row)
    for (int column = 0; column < kDomeColumns; ++column) {
      const Vec3 d = dome->direction(row, column);
      Spectrum open = white * clear.radiance(d);
      if (lamps_on) open += city_glow(d);
      if (night) open += star(row, column, d, zenith_depth);
      const double tau = clouds.depth(d, kAngleSpread);
      const double haze = clouds.sheet() +
                          (1 - clouds.sheet()) * std::exp(-CloudLayer::distance(d) / kHazeDistance);
      const Spectrum cloud =
          cloudy(open, tau, d.dot(sun), sun_above, sun.z(), sky_above, w.cloudiness, from_city);
      dome->radiance[std::size_t(row) * kDomeColumns + column] =
          (haze * cloud + (1 - haze) * open).matrix().cast<float>();
    }
  const Spectrum clear_sun = white * atmosphere.transmittance(kObserverAltitude, sun.z());
  const std::shared_ptr<const SkyMap> map =
      w.sky_map.empty() ? nullptr : fetched_sky_map(w.sky_map);
  const double sun_depth = sun.z() > 0 ? clouds.depth(sun, e.sun_angular_radius) : 0;
  const Spectrum sun_ground =
      map ? sun_of_map(*map, w.sky_map_rotation, clear_sun * std::max(sun.z(), 0.0) + sky_above,
                       *dome)
          : Spectrum(clear_sun * std::exp(-sun_depth));
  const Spectrum level = level_light(sun_ground, sun, *dome);
  const double exposure = exposure_for(luminance(level), lamps_on);
  for (Rgb& cell : dome->radiance) cell *= float(exposure);
  e.sun_direction = sun;
  e.sky_dome = dome;
  e.exposure = exposure;
  e.lamp_level = lamps_on ? exposure : 0;
  e.sun_irradiance = (sun_ground * exposure).matrix().cast<float>();
  e.sun_disc_visibility = 1;
  e.sky_zenith = dome->at(Vec3::UnitZ());
  e.sky_horizon = Rgb::Zero();
  for (int k = 0; k < 8; ++k) e.sky_horizon += dome->at(direction(0.05, k * kPi / 4)) / 8;
  e.ground = (level * exposure * 0.12 / kPi).matrix().cast<float>();
}

}  // namespace flowscape::sky
