#pragma once
// Weather for a sequence: sun, sky, clouds, fog, rain and wet ground, as presets and per-sequence
// random variations, recorded as JSON. Applying a weather changes how a scene looks, never its
// geometry as the ground truth sees it: fog is a medium of the colour pass, rain streaks and
// puddles are colour-only actors, wetness changes materials.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flowscape/scenes/scene.h"

namespace flowscape {

struct Weather {
  std::string preset = "sunny";
  double sun_elevation = 55;  // degrees above the horizon, [0, 90]
  double sun_azimuth = 35;    // degrees, counter-clockwise from the world's x axis
  double turbidity = 2.5;     // haze of the clear sky, [1, 20]
  double cloudiness = 0.1;    // [0, 1]: 1 = overcast, the sun hidden, shadows soft
  double fog_density = 0;     // extinction at the ground, 1/m, [0, 1]
  double fog_height = 25;     // metres over which the fog thins by e, > 0
  double precipitation = 0;   // rain, [0, 1]: streaks and dimmer light
  double wetness = 0;         // [0, 1]: darker, glossier ground
  double puddles = 0;         // [0, 1]: share of wet road under standing water
  double wind = 0;            // [0, 1]: slant of the rain
};

// sunny, cloud, fog, rain, and CARLA-like combinations: wet, wet_cloudy, soft_rain, hard_rain,
// clear_sunset, foggy_rain.
std::vector<std::string> weather_presets();
Weather weather_preset(const std::string& name);  // throws std::invalid_argument for others
// The preset varied for one sequence: sun position, haze, clouds, fog and rain strength.
Weather randomized(const Weather& preset, std::uint64_t seed);
void validate(const Weather& weather);  // throws std::invalid_argument naming the bad value

nlohmann::json to_json(const Weather& weather);
Weather weather_from_json(const nlohmann::json& json);  // validated

// The sun and sky of a weather (and its fog), without the scene.
Environment weather_environment(const Weather& weather);
// Sets the scene's environment, wets its ground materials and adds the colour-only rain streaks
// (falling around `rig`, the camera's path) and puddles. `seed` places streaks and puddles.
void apply_weather(const Weather& weather, std::uint64_t seed, const PoseTrack& rig, Scene& scene);

}  // namespace flowscape
