#pragma once
// Weather for a sequence: sun, sky, clouds, fog, rain and wet ground, as presets and per-sequence
// random variations, recorded as JSON. Applying a weather changes how a scene looks, never its
// geometry as the ground truth sees it: fog is a medium of the colour pass, rain streaks and
// puddles are colour-only actors, wetness changes materials.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flowscape/scenes/scene.h"

namespace flowscape {

struct Weather {
  std::string preset = "sunny";
  std::string time_of_day = "day";  // what at_time_of_day set: day, dawn, dusk or an elevation
  // Degrees above the horizon, [-90, 90]: below 0 the lamps are on, below -6 it is night and the
  // moon lights the scene.
  double sun_elevation = 55;
  double sun_azimuth = 35;   // degrees, counter-clockwise from the world's x axis
  double turbidity = 2.5;    // haze of the clear sky, [1, 20]
  double cloudiness = 0.1;   // [0, 1]: share of the sky under cumulus; near 1 an overcast sheet
  double fog_density = 0;    // extinction at the ground, 1/m, [0, 1]
  double fog_height = 25;    // metres over which the fog thins by e, > 0
  double precipitation = 0;  // rain, [0, 1]: streaks and dimmer light
  double wetness = 0;        // [0, 1]: darker, glossier ground
  double puddles = 0;        // [0, 1]: share of wet road under standing water
  double wind = 0;           // [0, 1]: slant of the rain
  double cloud_shift = 0;    // km, [0, 1000]: where over the cloud pattern the sky lies
  double moon_elevation = 40, moon_azimuth = 200;  // degrees; the moon shines at night only
  // A real HDR sky above its horizon line (sky_map_names()); empty: the physical sky alone.
  std::string sky_map;
  double sky_map_rotation = 0;  // degrees the map is turned counter-clockwise
};

// sunny, cloud, fog, rain, and CARLA-like combinations: wet, wet_cloudy, soft_rain, hard_rain,
// clear_sunset, foggy_rain.
std::vector<std::string> weather_presets();
Weather weather_preset(const std::string& name);  // throws std::invalid_argument for others
// The preset varied for one sequence: sun position, haze, clouds, fog and rain strength.
Weather randomized(const Weather& preset, std::uint64_t seed);
void validate(const Weather& weather);  // throws std::invalid_argument naming the bad value

// Times of day: "day" keeps the weather's sun; "dawn" and "dusk" put it low in the east or the
// west, from 5 degrees below the horizon (blue hour) to 6 above (golden hour); "night" puts it 18
// to 40 degrees below and the moon anywhere from 10 degrees below the horizon (a moonless night)
// to 60 above; all chosen by `seed`. A number is the sun's elevation in degrees, [-90, 90].
std::vector<std::string> named_times_of_day();       // day, dawn, dusk, night
void validate_time_of_day(const std::string& time);  // throws std::invalid_argument
Weather at_time_of_day(Weather weather, const std::string& time, std::uint64_t seed);

// Real HDR skies (opt-in): CC0 Poly Haven maps from the npm package @pmndrs/assets 1.7.0 that
// scripts/fetch_sky_maps.sh fetches (sha256-checked) into sky_map_directory()
// ($FLOWSCAPE_SKY_MAPS, else ~/.cache/flowscape/pmndrs-assets-1.7.0). Each is used above a recorded
// horizon line (the land under it would be labelled sky), the physical sky below; its sun is taken
// out of the map and traced as a disc.
std::vector<std::string> sky_map_names();  // sky, park, sunrise, dawn, venice
std::filesystem::path sky_map_directory();
void validate_sky(const std::string& sky);  // "physical" or a map name; else std::invalid_argument
// "physical" returns the weather; a map name sets sky_map, a rotation chosen by `seed`, the sun's
// elevation and azimuth (and the time of day, as that elevation) from the map's sun, and no
// cloudiness (the map shows the clouds; the physical sky under its horizon line is clear). A map
// that was not fetched leaves the weather as it is, with one warning per map on diagnostics().
Weather under_sky(Weather weather, const std::string& sky, std::uint64_t seed);
// Throws std::invalid_argument, naming the map and both resolutions, when a fetched map would be
// magnified more than twice in an image of `pixels_per_radian`.
void check_sky_resolution(const std::string& sky, double pixels_per_radian);

nlohmann::json to_json(const Weather& weather);
Weather weather_from_json(const nlohmann::json& json);  // validated

// The sun and sky of a weather (and its fog), without the scene: a physical atmosphere under a
// cloud layer, brought to one exposure (Environment::exposure).
Environment weather_environment(const Weather& weather);
// Sets the scene's environment, wets its ground materials and adds the colour-only rain streaks
// (falling around `rig`, the camera's path) and puddles. `seed` places streaks and puddles.
void apply_weather(const Weather& weather, std::uint64_t seed, const PoseTrack& rig, Scene& scene);

}  // namespace flowscape
