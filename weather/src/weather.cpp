#include "flowscape/weather/weather.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "flowscape/core/files.h"
#include "flowscape/core/random.h"
#include "flowscape/scenes/shapes.h"
#include "sky.h"
#include "sky_map.h"

namespace flowscape {
namespace {

using V3 = Eigen::Vector3d;
using Rgb = Eigen::Vector3f;

Weather make(const char* name, double elevation, double azimuth, double turbidity,
             double cloudiness, double fog, double rain, double wetness, double puddles,
             double wind) {
  Weather w;
  w.preset = name, w.sun_elevation = elevation, w.sun_azimuth = azimuth, w.turbidity = turbidity;
  w.cloudiness = cloudiness, w.fog_density = fog, w.precipitation = rain, w.wetness = wetness;
  w.puddles = puddles, w.wind = wind;
  return w;
}

const std::vector<Weather>& presets() {
  static const std::vector<Weather> kPresets = {
      make("sunny", 55, 35, 2.5, 0.1, 0, 0, 0, 0, 0),
      make("cloud", 50, 35, 4, 0.9, 0, 0, 0, 0, 0),
      make("fog", 40, 60, 4, 0.6, 0.03, 0, 0.1, 0, 0),
      make("rain", 45, 35, 5, 0.85, 0.004, 0.8, 0.9, 0.4, 0.2),
      make("wet", 55, 35, 2.5, 0.1, 0, 0, 0.7, 0.2, 0),
      make("wet_cloudy", 50, 35, 4, 0.7, 0, 0, 0.8, 0.3, 0),
      make("soft_rain", 50, 35, 4, 0.6, 0.002, 0.3, 0.6, 0.2, 0.1),
      make("hard_rain", 45, 35, 6, 0.95, 0.006, 1, 1, 0.6, 0.5),
      make("clear_sunset", 8, 200, 4, 0.15, 0, 0, 0, 0, 0),
      make("foggy_rain", 40, 35, 5, 0.8, 0.02, 0.5, 0.8, 0.3, 0.1),
  };
  return kPresets;
}

void require_range(double value, double lo, double hi, const char* name) {
  if (!(value >= lo && value <= hi))
    throw std::invalid_argument(std::string("weather ") + name + " = " + std::to_string(value) +
                                " is not in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                                "]");
}

Mesh crossed_streaks(Random& random, int count, double half, double height, double wind) {
  Mesh mesh;
  const V3 fall = V3(0.6 * wind, 0, -1).normalized();
  for (int copy = 0; copy < 2; ++copy)  // two stacked layers, so the falling field wraps seamlessly
    for (int k = 0; k < count; ++k) {
      const V3 top(random.uniform(-half, half), random.uniform(-half, half),
                   (copy + random.uniform()) * height);
      const V3 bottom = top + 0.7 * fall;
      for (const V3& side : {V3(0.0075, 0, 0), V3(0, 0.0075, 0)})
        add_quad(mesh, top - side, top + side, bottom + side, bottom - side,
                 {SemanticClass::Other, 0});
    }
  return mesh;
}

// Rain streaks in a box around the rig's path, falling at 9 m/s.
Actor rain_actor(const Weather& w, Random& random, const PoseTrack& rig, Scene& scene) {
  constexpr double kHalf = 25, kHeight = 12, kSpeed = 9;
  Mesh streaks = crossed_streaks(random, int(4000 * w.precipitation), kHalf, kHeight, w.wind);
  Material streak;
  streak.kind = Material::Kind::Streak;
  streak.emission = (scene.environment.sky_horizon * 1.4f).cwiseMax(0.05f);
  // faint, as a camera's exposure smears a drop over its streak (opaque streaks moving across the
  // scene would dominate the frame-to-frame differences the flow cannot explain)
  streak.opacity = float(0.05 + 0.1 * w.precipitation);
  streaks.materials.assign(streaks.triangles.size(), add_material(scene, streak));
  Actor actor{std::uint16_t(scene.actors.size() + 1), {}, [rig](double t) {
                const V3 at = rig(t).translation();
                const double fall = std::fmod(kSpeed * t, kHeight);
                return Pose(Eigen::Translation3d(at.x(), at.y(), at.z() - 3 - fall));
              }};
  actor.parts.push_back(rigid_part(std::move(streaks)));
  actor.color_only = true;
  return actor;
}

double triangle_area(const Mesh& mesh, std::size_t t) {
  const Eigen::Vector3f &a = mesh.vertices[mesh.triangles[t][0]],
                        &b = mesh.vertices[mesh.triangles[t][1]],
                        &c = mesh.vertices[mesh.triangles[t][2]];
  return 0.5 * double((b - a).cross(c - a).norm());
}

// Standing water: flat discs a centimetre above randomly chosen spots of the road.
Actor puddle_actor(const Weather& w, Random& random, Scene& scene) {
  const Mesh& world = scene.world;
  std::vector<std::size_t> roads;
  std::vector<double> cumulative;
  double area = 0;
  for (std::size_t t = 0; t < world.triangles.size(); ++t)
    if (world.classes[t] == SemanticClass::Road) {
      area += triangle_area(world, t);
      roads.push_back(t), cumulative.push_back(area);
    }
  Material water;
  water.kind = Material::Kind::Glossy, water.albedo = {0.02f, 0.025f, 0.03f};
  water.roughness = 0.01f;
  const Paint paint{SemanticClass::Road, add_material(scene, water)};
  Mesh discs;
  const int count = roads.empty() ? 0 : std::min(3000, int(w.puddles * area / 60));
  for (int k = 0; k < count; ++k) {
    const std::size_t pick =
        std::lower_bound(cumulative.begin(), cumulative.end(), random.uniform(0, area)) -
        cumulative.begin();
    const Eigen::Vector3i& tri = world.triangles[roads[std::min(pick, roads.size() - 1)]];
    double u = random.uniform(), v = random.uniform();
    if (u + v > 1) u = 1 - u, v = 1 - v;
    const V3 a = world.vertices[tri[0]].cast<double>(), b = world.vertices[tri[1]].cast<double>(),
             c = world.vertices[tri[2]].cast<double>();
    const V3 centre = a + u * (b - a) + v * (c - a) + V3(0, 0, 0.008);
    add_cylinder(discs, Pose(Eigen::Translation3d(centre)), random.uniform(0.5, 2.2), 0.002, paint,
                 10);
  }
  Actor actor{std::uint16_t(scene.actors.size() + 1), {}, [](double) { return Pose::Identity(); }};
  actor.parts.push_back(rigid_part(std::move(discs)));
  actor.color_only = true;
  return actor;
}

// Wet ground: darker and, above a little wetness, under a clear coat like a film of water: a rough
// film on the rough asphalt (blurred reflections), mirror-like only in the puddles.
void wet_materials(const Weather& w, Scene& scene) {
  std::vector<bool> ground(scene.materials.size(), false);
  for (std::size_t t = 0; t < scene.world.triangles.size(); ++t) {
    const SemanticClass c = scene.world.classes[t];
    if (c == SemanticClass::Road || c == SemanticClass::RoadLine || c == SemanticClass::SideWalk ||
        c == SemanticClass::Ground)
      ground[scene.world.materials.empty() ? 0 : scene.world.materials[t]] = true;
  }
  for (std::size_t m = 0; m < scene.materials.size(); ++m) {
    if (!ground[m]) continue;
    Material& material = scene.materials[m];
    material.albedo *= float(1 - 0.45 * w.wetness);  // patterns modulate the darker base
    if (w.wetness > 0.3 && material.kind == Material::Kind::Diffuse) {
      material.kind = Material::Kind::Glossy;
      material.roughness = float(0.1 + 0.2 * (1 - w.wetness));
    }
  }
}

}  // namespace

std::vector<std::string> weather_presets() {
  std::vector<std::string> names;
  for (const Weather& w : presets()) names.push_back(w.preset);
  return names;
}

Weather weather_preset(const std::string& name) {
  for (const Weather& w : presets())
    if (w.preset == name) return w;
  std::string known;
  for (const Weather& w : presets()) known += (known.empty() ? "" : ", ") + w.preset;
  throw std::invalid_argument("unknown weather preset \"" + name + "\" (" + known + ")");
}

Weather randomized(const Weather& p, std::uint64_t seed) {
  Random random(seed * 0xd1342543de82ef95ull + 0x6a09e667f3bcc909ull);
  Weather w = p;
  w.sun_elevation = std::clamp(p.sun_elevation + random.uniform(-15, 15), 3.0, 85.0);
  w.sun_azimuth = std::fmod(p.sun_azimuth + random.uniform(0, 360), 360.0);
  w.turbidity = std::clamp(p.turbidity + random.uniform(-1, 1), 1.5, 10.0);
  w.cloudiness = std::clamp(p.cloudiness + random.uniform(-0.1, 0.1), 0.0, 1.0);
  w.fog_density = p.fog_density * random.uniform(0.7, 1.3);
  w.fog_height = p.fog_height * random.uniform(0.8, 1.2);
  w.precipitation = std::clamp(p.precipitation * random.uniform(0.8, 1.2), 0.0, 1.0);
  w.wetness = std::clamp(p.wetness * random.uniform(0.85, 1.15), 0.0, 1.0);
  w.puddles = std::clamp(p.puddles * random.uniform(0.7, 1.3), 0.0, 1.0);
  w.wind = std::clamp(p.wind + random.uniform(-0.1, 0.1), 0.0, 1.0);
  w.cloud_shift = std::floor(random.uniform(0, 1000));
  return w;
}

void validate(const Weather& w) {
  require_range(w.sun_elevation, -90, 90, "sun_elevation");
  require_range(w.moon_elevation, -90, 90, "moon_elevation");
  require_range(w.moon_azimuth, -360, 720, "moon_azimuth");
  require_range(w.sun_azimuth, -360, 720, "sun_azimuth");
  require_range(w.turbidity, 1, 20, "turbidity");
  require_range(w.cloudiness, 0, 1, "cloudiness");
  require_range(w.fog_density, 0, 1, "fog_density");
  require_range(w.fog_height, 0.1, 10000, "fog_height");
  require_range(w.precipitation, 0, 1, "precipitation");
  require_range(w.wetness, 0, 1, "wetness");
  require_range(w.puddles, 0, 1, "puddles");
  require_range(w.wind, 0, 1, "wind");
  require_range(w.cloud_shift, 0, 1000, "cloud_shift");
  require_range(w.sky_map_rotation, 0, 360, "sky_map_rotation");
  if (!w.sky_map.empty()) validate_sky(w.sky_map);
}

std::vector<std::string> sky_map_names() { return {"sky", "park", "sunrise", "dawn", "venice"}; }

std::filesystem::path sky_map_directory() {
  return cache_directory("FLOWSCAPE_SKY_MAPS", "pmndrs-assets-1.7.0");
}

void validate_sky(const std::string& sky) {
  const std::vector<std::string> maps = sky_map_names();
  if (sky == "physical" || std::find(maps.begin(), maps.end(), sky) != maps.end()) return;
  std::string known = "physical";
  for (const std::string& m : maps) known += ", " + m;
  throw std::invalid_argument("unknown sky \"" + sky + "\" (" + known + ")");
}

Weather under_sky(Weather w, const std::string& sky, std::uint64_t seed) {
  validate_sky(sky);
  if (sky == "physical") return w;
  const std::shared_ptr<const sky::SkyMap> map = sky::fetched_sky_map(sky);
  if (!map) return w;
  Random random(seed * 0x2545f4914f6cdd1dull + 0x1b873593a5b4c2e1ull);
  w.sky_map = sky, w.sky_map_rotation = std::floor(random.uniform(0, 360));
  w.cloudiness = 0;  // the map shows the clouds; the physical sky under its horizon line is clear
  const Vec3& sun = map->sun.direction;
  w.sun_elevation = std::asin(std::clamp(sun.z(), -1.0, 1.0)) * 180 / kPi;
  w.sun_azimuth =
      std::fmod(std::atan2(sun.y(), sun.x()) * 180 / kPi + w.sky_map_rotation + 360, 360.0);
  char elevation[32];
  std::snprintf(elevation, sizeof elevation, "%.1f", w.sun_elevation);
  w.time_of_day = elevation;
  return w;
}

void check_sky_resolution(const std::string& sky, double pixels_per_radian) {
  validate_sky(sky);
  const std::shared_ptr<const sky::SkyMap> map =
      sky == "physical" ? nullptr : sky::fetched_sky_map(sky);
  if (!map) return;
  const double map_pixels_per_radian = map->radiance.width / (2 * kPi);
  if (pixels_per_radian <= 2 * map_pixels_per_radian * (1 + 1e-9)) return;
  char text[256];
  std::snprintf(text, sizeof text,
                "sky map \"%s\" is %d x %d (%.1f pixels per radian): too small for images of %.1f "
                "pixels per radian (a map may be magnified at most 2x); render smaller images or "
                "use the physical sky",
                sky.c_str(), map->radiance.width, map->radiance.height, map_pixels_per_radian,
                pixels_per_radian);
  throw std::invalid_argument(text);
}

std::vector<std::string> named_times_of_day() { return {"day", "dawn", "dusk", "night"}; }

namespace {

// The sun elevation a numeric time of day names, or NaN for a name.
double elevation_named(const std::string& time) {
  std::size_t used = 0;
  double elevation = std::numeric_limits<double>::quiet_NaN();
  try {
    elevation = std::stod(time, &used);
  } catch (const std::exception&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  if (used != time.size() || !std::isfinite(elevation))
    throw std::invalid_argument("time of day \"" + time + "\" is not a number");
  return elevation;
}

}  // namespace

void validate_time_of_day(const std::string& time) {
  const std::vector<std::string> names = named_times_of_day();
  if (std::find(names.begin(), names.end(), time) != names.end()) return;
  const double elevation = elevation_named(time);
  if (std::isnan(elevation))
    throw std::invalid_argument("unknown time of day \"" + time +
                                "\" (day, dawn, dusk, night, or a sun elevation in degrees)");
  require_range(elevation, -90, 90, "sun_elevation of the time of day");
}

Weather at_time_of_day(Weather w, const std::string& time, std::uint64_t seed) {
  validate_time_of_day(time);
  w.time_of_day = time;
  if (time == "day") return w;
  Random random(seed * 0x9e3779b97f4a7c15ull + 0x510e527fade682d1ull);
  if (time == "dawn" || time == "dusk") {
    w.sun_elevation = random.uniform(-5, 6);
    w.sun_azimuth = (time == "dawn" ? 90 : 270) + random.uniform(-30, 30);
  } else if (time == "night") {
    w.sun_elevation = random.uniform(-40, -18), w.sun_azimuth = random.uniform(0, 360);
    w.moon_elevation = random.uniform(-10, 60), w.moon_azimuth = random.uniform(0, 360);
  } else {
    w.sun_elevation = elevation_named(time);
  }
  return w;
}

namespace {

// The JSON keys of a Weather's numbers and the members they hold, written and read from one list.
template <class W, class Visit>
void for_each_number(W& w, Visit&& visit) {
  visit("sun_elevation", w.sun_elevation), visit("sun_azimuth", w.sun_azimuth);
  visit("turbidity", w.turbidity), visit("cloudiness", w.cloudiness);
  visit("fog_density", w.fog_density), visit("fog_height", w.fog_height);
  visit("precipitation", w.precipitation), visit("wetness", w.wetness);
  visit("puddles", w.puddles), visit("wind", w.wind), visit("cloud_shift", w.cloud_shift);
  visit("moon_elevation", w.moon_elevation), visit("moon_azimuth", w.moon_azimuth);
}

}  // namespace

nlohmann::json to_json(const Weather& w) {
  nlohmann::json j = {{"preset", w.preset}, {"time_of_day", w.time_of_day}};
  for_each_number(w, [&](const char* key, double value) { j[key] = value; });
  if (!w.sky_map.empty()) j["sky_map"] = w.sky_map, j["sky_map_rotation"] = w.sky_map_rotation;
  return j;
}

Weather weather_from_json(const nlohmann::json& j) {
  Weather w;
  try {
    w = weather_preset(j.at("preset").get<std::string>());
    w.time_of_day = j.value("time_of_day", std::string("day"));
    w.sky_map = j.value("sky_map", std::string());
    w.sky_map_rotation = j.value("sky_map_rotation", 0.0);
    for_each_number(w, [&](const char* key, double& field) {
      if (j.contains(key)) field = j.at(key).get<double>();
    });
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("weather: ") + e.what());
  }
  validate(w);
  validate_time_of_day(w.time_of_day);
  return w;
}

Environment weather_environment(const Weather& w) {
  validate(w);
  Environment e;
  const double elevation = w.sun_elevation * kPi / 180, azimuth = w.sun_azimuth * kPi / 180;
  e.sun_direction = V3(std::cos(elevation) * std::cos(azimuth),
                       std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
  sky::set_physical_sky(w, e);
  e.fog.density = w.fog_density, e.fog.height = w.fog_height;
  return e;
}

namespace {

// Lamps, lit signs and windows glow once the sun has set: their night emission at the exposure.
void switch_lamps(Scene& scene) {
  const float level = float(scene.environment.lamp_level);
  if (level <= 0) return;
  for (Material& m : scene.materials) {
    if (m.night_emission.isZero()) continue;
    m.kind = Material::Kind::Emissive, m.emission = m.night_emission * level;
    if (m.night_pattern) m.pattern = m.night_pattern;
  }
}

}  // namespace

void apply_weather(const Weather& w, std::uint64_t seed, const PoseTrack& rig, Scene& scene) {
  scene.environment = weather_environment(w);
  switch_lamps(scene);
  Random random(seed ^ 0x3c6ef372fe94f82bull);
  if (w.wetness > 0) wet_materials(w, scene);
  if (w.puddles > 0) scene.actors.push_back(puddle_actor(w, random, scene));
  if (w.precipitation > 0) scene.actors.push_back(rain_actor(w, random, rig, scene));
}

}  // namespace flowscape
