#include "flowscape/release/scenario.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "flowscape/core/files.h"
#include "flowscape/core/names.h"
#include "flowscape/layout/meta.h"
#include "flowscape/release/manifest.h"
#include "flowscape/renderer/calibration_file.h"
#include "flowscape/scenes/city.h"
#include "flowscape/weather/weather.h"
#include "json_integer.h"

namespace flowscape {
namespace {

// poses_of for a pose file of a camera's frames looking along the rig's forward axis.
constexpr const char* kCameraFramePoses = "camera_frame";

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("scenario: " + what);
}

// Every key of `object` is one of `known` (a misspelt one: the nearest suggested).
void require_known(const nlohmann::json& object, const std::vector<std::string>& known,
                   const std::string& where) {
  require(object.is_object(), where + " must be an object");
  for (const auto& [key, value] : object.items())
    require(std::find(known.begin(), known.end(), key) != known.end(),
            where + "unknown key \"" + key + "\"" + did_you_mean(key, known));
}

template <class T>
T value(const nlohmann::json& object, const char* key, T fallback, const std::string& where) {
  if (!object.contains(key)) return fallback;
  try {
    return object.at(key).get<T>();
  } catch (const nlohmann::json::exception&) {
    throw std::invalid_argument("scenario: " + where + "\"" + key + "\" has the wrong type");
  }
}

// A whole number in lo..hi, exactly: no fraction truncated, nothing wrapped.
template <class T>
T integer(const nlohmann::json& object, const char* key, T fallback, T lo, T hi,
          const std::string& where) {
  if (!object.contains(key)) return fallback;
  try {
    return json_integer<T>(object.at(key), key, lo, hi);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("scenario: " + where + e.what());
  }
}

Vec3 vector3(const nlohmann::json& j, const std::string& what) {
  require(j.is_array() && j.size() == 3 &&
              std::all_of(j.begin(), j.end(), [](const auto& v) { return v.is_number(); }),
          what + " must be 3 numbers");
  const Vec3 v(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
  require(v.allFinite(), what + " must be finite");
  return v;
}

nlohmann::json array3(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json merged(nlohmann::json base, const nlohmann::json& over) {
  for (const auto& [key, value] : over.items()) base[key] = value;
  return base;
}

int map_number(const nlohmann::json& map) {
  if (map.is_number_integer()) {
    require(map.get<int>() >= 0 && map.get<int>() < kMapCount,
            "world \"map\" must be 0.." + std::to_string(kMapCount - 1) + " or a map's name");
    return map.get<int>();
  }
  std::vector<std::string> names;
  for (int m = 0; m < kMapCount; ++m) names.push_back(map_name(m));
  const std::string name = map.is_string() ? map.get<std::string>() : "";
  const auto found = std::find(names.begin(), names.end(), name);
  require(found != names.end(),
          "world \"map\": no map \"" + name + "\"" + did_you_mean(name, names));
  return int(found - names.begin());
}

Waypoint waypoint_from_json(const nlohmann::json& j, const std::string& list, std::size_t k) {
  const std::string where = list + "waypoint " + std::to_string(k) + ": ";
  require_known(j, {"position", "time", "speed", "yaw_pitch_roll_degrees"}, where);
  require(j.contains("position"), where + "needs a \"position\" [x, y, z] (metres)");
  Waypoint w{vector3(j.at("position"), where + "position"), {}, {}, {}};
  if (j.contains("time")) w.time = value<double>(j, "time", 0, where);
  if (j.contains("speed")) w.speed = value<double>(j, "speed", 0, where);
  if (j.contains("yaw_pitch_roll_degrees"))
    w.yaw_pitch_roll_degrees =
        vector3(j.at("yaw_pitch_roll_degrees"), where + "yaw_pitch_roll_degrees");
  return w;
}

nlohmann::json to_json(const Waypoint& w) {
  nlohmann::json j = {{"position", array3(w.position)}};
  if (w.time) j["time"] = *w.time;
  if (w.speed) j["speed"] = *w.speed;
  if (w.yaw_pitch_roll_degrees) j["yaw_pitch_roll_degrees"] = array3(*w.yaw_pitch_roll_degrees);
  return j;
}

// A path's waypoints (`where` names whose in errors), checked as waypoint_times checks them.
std::vector<Waypoint> waypoints_from_json(const nlohmann::json& points, const std::string& where) {
  require(points.is_array(), where + "\"waypoints\" must be a list");
  std::vector<Waypoint> waypoints;
  for (std::size_t k = 0; k < points.size(); ++k)
    waypoints.push_back(waypoint_from_json(points[k], where, k));
  try {
    waypoint_times(waypoints);
  } catch (const std::invalid_argument& e) {
    require(false, where + e.what());
  }
  return waypoints;
}

nlohmann::json waypoints_json(const std::vector<Waypoint>& waypoints) {
  nlohmann::json points = nlohmann::json::array();
  for (const Waypoint& w : waypoints) points.push_back(to_json(w));
  return points;
}

// A file a scenario names, relative to its folder, made absolute (so that the scenario a meta.json
// records finds it from anywhere); a FileError "no such <what>" when it is not there, and says so
// for a folder or a device.
std::filesystem::path existing_file(const std::filesystem::path& base, const std::string& file,
                                    const std::string& what) {
  const std::filesystem::path path = std::filesystem::absolute(base / file).lexically_normal();
  if (!std::filesystem::exists(path)) throw FileError(path, "no such " + what);
  if (std::filesystem::is_directory(path)) throw FileError(path, "is a folder, expected a " + what);
  if (!std::filesystem::is_regular_file(path))
    throw FileError(path, "not a regular file, expected a " + what);
  return path;
}

// A world file's "units": a unit's name or metres per unit.
double metres_per_unit(const nlohmann::json& units) {
  static const std::map<std::string, double> kUnits = {{"metres", 1},
                                                       {"centimetres", 0.01},
                                                       {"millimetres", 0.001},
                                                       {"feet", 0.3048},
                                                       {"inches", 0.0254}};
  if (units.is_number()) {
    const double metres = units.get<double>();
    require(metres >= 1e-6 && metres <= 1e6,
            "world \"units\" must be 1e-6..1e6 metres per unit (a micrometre to 1,000 km)");
    return metres;
  }
  const std::string name = units.is_string() ? units.get<std::string>() : "";
  std::vector<std::string> names;
  for (const auto& [known, metres] : kUnits) names.push_back(known);
  const auto found = kUnits.find(name);
  require(found != kUnits.end(),
          "world \"units\": \"" + name +
              "\" is not metres, centimetres, millimetres, feet, inches or a number (metres per "
              "unit)" +
              did_you_mean(name, names));
  return found->second;
}

std::vector<WorldClass> world_classes(const nlohmann::json& list) {
  require(list.is_array() && !list.empty(),
          "world \"classes\" must list [\"pattern\", \"Class\"] pairs, first match wins "
          "(\"*\" takes the rest)");
  std::vector<WorldClass> classes;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const nlohmann::json& pair = list[k];
    const std::string where = "world classes " + std::to_string(k) + ": ";
    require(pair.is_array() && pair.size() == 2 && pair[0].is_string() && pair[1].is_string(),
            where + "must be [\"pattern\", \"Class\"]");
    try {
      classes.push_back({pair[0].get<std::string>(), class_from_name(pair[1].get<std::string>())});
    } catch (const std::invalid_argument& e) {
      require(false, where + e.what());
    }
  }
  return classes;
}

// {"map", "seed"} | {"file", "units", "up", "classes", "seed"}
void world_from_json(const nlohmann::json& world, const std::filesystem::path& base, Scenario& s) {
  require_known(world, {"map", "seed", "file", "units", "up", "classes"}, "world: ");
  s.seed = integer<std::uint64_t>(world, "seed", 0, 0, std::numeric_limits<std::uint64_t>::max(),
                                  "world: ");
  if (!world.contains("file")) {
    require(!world.contains("units") && !world.contains("up") && !world.contains("classes"),
            "world: \"units\", \"up\" and \"classes\" are a world file's");
    s.map = world.contains("map") ? map_number(world.at("map")) : 0;
    return;
  }
  require(!world.contains("map"), "world: give a \"map\" or a \"file\", not both");
  require(world.contains("units") && world.contains("up"),
          "world: a world file needs its \"units\" (metres, centimetres, millimetres, feet, "
          "inches, or metres per unit) and its \"up\" axis (y or z)");
  WorldModel model;
  model.path =
      existing_file(base, value<std::string>(world, "file", "", "world: "), "world file").string();
  model.metres_per_unit = metres_per_unit(world.at("units"));
  const std::string up = value<std::string>(world, "up", "", "world: ");
  require(up == "y" || up == "z", "world: \"up\" must be y or z");
  model.z_up = up == "z";
  model.classes = world_classes(world.value("classes", nlohmann::json()));
  s.world_file = std::move(model);
  s.map = kUserWorldMap;
  s.vehicles = s.pedestrians = s.standing = 0;
}

nlohmann::json world_json(const Scenario& s) {
  if (!s.world_file) return {{"map", map_name(s.map)}, {"seed", s.seed}};
  nlohmann::json classes = nlohmann::json::array();
  for (const WorldClass& c : s.world_file->classes)
    classes.push_back({c.pattern, class_name(c.cls)});
  return {{"file", s.world_file->path},
          {"units", s.world_file->metres_per_unit},
          {"up", s.world_file->z_up ? "z" : "y"},
          {"classes", classes},
          {"seed", s.seed}};
}

// {"kind", "model", "waypoints"} | {"kind", "model", "start", "speed", "turn"}
ScriptedActor actor_from_json(const nlohmann::json& j, std::size_t k,
                              const std::filesystem::path& base) {
  const std::string where = "actor " + std::to_string(k) + ": ";
  require_known(j, {"kind", "model", "waypoints", "start", "speed", "turn"}, where);
  require(j.contains("kind") && (j.contains("waypoints") != j.contains("start")),
          where + "needs a \"kind\" and either \"waypoints\" or a \"start\" [x, y] on a road");
  ScriptedActor actor;
  try {
    actor.kind = kind_from_name(value<std::string>(j, "kind", "", where));
  } catch (const std::invalid_argument& e) {
    require(false, where + e.what());
  }
  require(actor.kind != ActorKind::Rider, where + "a rider comes with its bike or motorbike");
  if (j.contains("model"))
    actor.model =
        existing_file(base, value<std::string>(j, "model", "", where), "model file").string();
  if (j.contains("waypoints")) {
    require(!j.contains("speed") && !j.contains("turn"),
            where + "\"speed\" and \"turn\" go with a \"start\" (waypoints have their own)");
    actor.waypoints = waypoints_from_json(j.at("waypoints"), where);
    return actor;
  }
  const std::vector<double> start = value<std::vector<double>>(j, "start", {}, where);
  require(start.size() == 2 && std::isfinite(start[0]) && std::isfinite(start[1]),
          where + "\"start\" must be [x, y] (metres, on a lane of the map)");
  actor.start = Eigen::Vector2d(start[0], start[1]);
  actor.speed = value<double>(j, "speed", 0, where);
  actor.turn = value<bool>(j, "turn", false, where);
  require(actor.kind != ActorKind::Pedestrian && actor.speed > 0 && actor.speed <= 60,
          where + "an actor with a start is a vehicle with a \"speed\" in (0, 60] m/s");
  return actor;
}

nlohmann::json actors_json(const std::vector<ScriptedActor>& actors) {
  nlohmann::json list = nlohmann::json::array();
  for (const ScriptedActor& a : actors) {
    nlohmann::json actor = {{"kind", kind_name(a.kind)}};
    if (a.start)
      actor["start"] = {a.start->x(), a.start->y()}, actor["speed"] = a.speed,
      actor["turn"] = a.turn;
    else
      actor["waypoints"] = waypoints_json(a.waypoints);
    if (!a.model.empty()) actor["model"] = a.model;
    list.push_back(actor);
  }
  return list;
}

// "z_up" | "y_down" | "gravity" | {"up": [x, y, z]} (trajectory.h's PoseWorld)
PoseWorld world_frame_from_json(const nlohmann::json& j) {
  if (j.is_object()) {
    require_known(j, {"up"}, "motion world_frame: ");
    require(j.contains("up"), "motion \"world_frame\": {\"up\": [x, y, z]} in the file's world");
    const Vec3 up = vector3(j.at("up"), "motion world_frame up");
    require(up.norm() > 1e-9, "motion world_frame up must not be zero");
    return {"up", up};
  }
  const std::string frame = j.is_string() ? j.get<std::string>() : "";
  require(frame == "z_up" || frame == "y_down" || frame == "gravity",
          "motion \"world_frame\" must be z_up, y_down, gravity or {\"up\": [x, y, z]}");
  return {frame, Vec3::UnitZ()};
}

void origin_from_json(const nlohmann::json& j, RigPath& path) {
  require_known(j, {"position", "yaw_pitch_roll_degrees"}, "motion origin: ");
  if (j.contains("position")) {
    path.origin_position = vector3(j.at("position"), "origin position");
    require(within_world(path.origin_position), "origin position must lie within 1,000 km");
  }
  if (j.contains("yaw_pitch_roll_degrees"))
    path.origin_yaw_pitch_roll_degrees =
        vector3(j.at("yaw_pitch_roll_degrees"), "origin yaw_pitch_roll_degrees");
}

// {"route": ...} | {"waypoints": [...]} | {"pose_file", "format", "rate", "poses_of", "origin"}
void motion_from_json(const nlohmann::json& j, const std::filesystem::path& base, Scenario& s) {
  require_known(j,
                {"route", "lane_change_at", "waypoints", "pose_file", "format", "rate", "poses_of",
                 "world_frame", "origin"},
                "motion: ");
  const int kinds =
      int(j.contains("route")) + int(j.contains("waypoints")) + int(j.contains("pose_file"));
  require(kinds == 1,
          "motion: give one of \"route\" (the ego's: drive, turn, lane_change, free), "
          "\"waypoints\" or \"pose_file\" (the rig's own path)");
  if (j.contains("route")) {
    s.route = value<std::string>(j, "route", "drive", "motion: ");
    try {
      route_from_name(s.route);
    } catch (const std::invalid_argument& e) {
      require(false, std::string("motion: ") + e.what());
    }
    require(!j.contains("lane_change_at") || s.route == "lane_change",
            "motion \"lane_change_at\" is for the lane_change route");
    s.lane_change_at = value<double>(j, "lane_change_at", s.lane_change_at, "motion: ");
    require(s.lane_change_at >= 0 && s.lane_change_at <= 3600,
            "motion \"lane_change_at\" must be in 0..3600 seconds");
    return;
  }
  RigPath path;
  if (j.contains("waypoints")) {
    path.waypoints = waypoints_from_json(j.at("waypoints"), "motion: ");
  } else {
    const std::string file = value<std::string>(j, "pose_file", "", "motion: ");
    path.format = value<std::string>(j, "format", "tum", "motion: ");
    path.rate = value<double>(j, "rate", 10.0, "motion: ");
    try {
      pose_format(path.format);
    } catch (const std::invalid_argument& e) {
      require(false, std::string("motion: ") + e.what());
    }
    const bool tum = path.format == "tum";
    path.poses_of = value<std::string>(j, "poses_of", tum ? "rig" : kCameraFramePoses, "motion: ");
    path.world = world_frame_from_json(
        j.value("world_frame", nlohmann::json(tum                      ? "z_up"
                                              : path.format == "kitti" ? "y_down"
                                                                       : "gravity")));
    require(path.rate > 0 && std::isfinite(path.rate), "motion \"rate\" must be positive");
    path.pose_file = existing_file(base, file, "pose file");
    if (j.contains("origin")) origin_from_json(j.at("origin"), path);
  }
  require((!j.contains("origin") && !j.contains("world_frame")) || !path.pose_file.empty(),
          "motion \"origin\" and \"world_frame\" are a pose file's");
  s.path = std::move(path);
}

nlohmann::json motion_json(const Scenario& s) {
  if (!s.path && s.route == "lane_change")
    return {{"route", s.route}, {"lane_change_at", s.lane_change_at}};
  if (!s.path) return {{"route", s.route}};
  if (s.path->pose_file.empty()) return {{"waypoints", waypoints_json(s.path->waypoints)}};
  const PoseWorld& world = s.path->world;
  return {{"pose_file", s.path->pose_file.string()},
          {"format", s.path->format},
          {"rate", s.path->rate},
          {"poses_of", s.path->poses_of},
          {"world_frame", world.frame == "up" ? nlohmann::json{{"up", array3(world.up)}}
                                              : nlohmann::json(world.frame)},
          {"origin",
           {{"position", array3(s.path->origin_position)},
            {"yaw_pitch_roll_degrees", array3(s.path->origin_yaw_pitch_roll_degrees)}}}};
}

}  // namespace

Weather with_parameters(const Weather& weather, const nlohmann::json& parameters) {
  const nlohmann::json record = to_json(weather);
  std::vector<std::string> known;
  for (const auto& [key, value] : record.items())
    if (key != "preset") known.push_back(key);
  for (const auto& [key, value] : parameters.items())
    require(key == "exposure" || std::find(known.begin(), known.end(), key) != known.end(),
            "weather: unknown parameter \"" + key + "\"" + did_you_mean(key, known));
  nlohmann::json set = merged(record, parameters);
  set.erase("exposure");  // what a meta.json record adds: the sky's, not a parameter
  try {
    return weather_from_json(set);
  } catch (const std::exception& e) {
    throw std::invalid_argument(std::string("scenario: weather: ") + e.what());
  }
}

Pose RigPath::origin() const {
  Pose pose = Pose::Identity();
  const Vec3& a = origin_yaw_pitch_roll_degrees;
  pose.linear() = yaw_pitch_roll(a[0], a[1], a[2]);
  pose.translation() = origin_position;
  return pose;
}

Scenario scenario_from_json(const nlohmann::json& j, const std::filesystem::path& base) {
  require_known(
      j,
      {"flowscape_scenario", "name", "world", "rig", "rig_mount", "ego", "motion", "traffic",
       "models", "weather", "time_of_day", "sky", "frames", "frame_rate", "generator", "actors"},
      "");
  require(j.value("flowscape_scenario", 0) == kScenarioSchema,
          "\"flowscape_scenario\": " + std::to_string(kScenarioSchema) +
              " must say the schema version (this is flowscape's scenario schema " +
              std::to_string(kScenarioSchema) + ")");
  Scenario s;
  s.name = value<std::string>(j, "name", s.name, "");
  s.generator = value<std::string>(j, "generator", "", "");
  world_from_json(j.value("world", nlohmann::json::object()), base, s);
  s.rig = value<std::string>(j, "rig", s.rig, "");
  if (s.rig.ends_with(".json") || is_calibration_file(s.rig))  // a file beside the scenario
    s.rig = existing_file(base, s.rig, "rig file").string();
  s.rig_mount = value<std::vector<double>>(j, "rig_mount", {}, "");
  s.ego = value<std::string>(j, "ego", s.ego, "");
  require(s.ego == "auto" || s.ego == "on" || s.ego == "off", "\"ego\" must be auto, on or off");
  if (j.contains("motion")) motion_from_json(j.at("motion"), base, s);
  require(!s.path || s.ego != "on",
          "a rig with its own path (waypoints, a pose file) has no ego "
          "vehicle under it: \"ego\" must be off or auto");
  require(!s.world_file || s.path,
          "a world file has no roads for an ego vehicle: give the rig \"waypoints\" or a "
          "\"pose_file\" in \"motion\"");
  const nlohmann::json traffic = j.value("traffic", nlohmann::json::object());
  require_known(traffic, {"vehicles", "pedestrians", "standing"}, "traffic: ");
  s.vehicles = integer(traffic, "vehicles", s.vehicles, 0, 200, "traffic: ");
  s.pedestrians = integer(traffic, "pedestrians", s.pedestrians, -1, 200, "traffic: ");
  // a scenario a release recorded before people stood had none
  s.standing =
      integer(traffic, "standing", s.generator.empty() ? s.standing : 0, -1, 200, "traffic: ");
  const int road_users = s.vehicles + std::max(s.pedestrians, 0) + std::max(s.standing, 0);
  require(road_users <= 200, "traffic: vehicles + pedestrians + standing must be in 0..200");
  require(!s.world_file || road_users == 0,
          "traffic: a world file has no roads or sidewalks for traffic (place \"actors\" "
          "with waypoints)");
  const nlohmann::json actors = j.value("actors", nlohmann::json::array());
  require(actors.is_array(), "\"actors\" must be a list");
  for (std::size_t k = 0; k < actors.size(); ++k) {
    s.actors.push_back(actor_from_json(actors[k], k, base));
    require(!s.world_file || !s.actors.back().start,
            "actor " + std::to_string(k) +
                ": a world file has no roads to start on (give it "
                "\"waypoints\")");
  }
  const nlohmann::json models = j.value("models", nlohmann::json::object());
  require(models.is_object(), "\"models\" must map actor kinds to model files");
  for (const auto& [kind, file] : models.items()) {
    try {
      kind_from_name(kind);
    } catch (const std::invalid_argument& e) {
      require(false, std::string("models: ") + e.what());
    }
    require(file.is_string(), "models: \"" + kind + "\" must name a model file");
    s.models[kind] = existing_file(base, file.get<std::string>(), "model file").string();
  }
  if (j.contains("weather") && j.at("weather").is_object()) {
    s.weather_parameters = j.at("weather");
    s.weather = value<std::string>(s.weather_parameters, "preset", s.weather, "weather: ");
    s.weather_parameters.erase("preset");
  } else {
    s.weather = value<std::string>(j, "weather", s.weather, "");
  }
  s.time_of_day = value<std::string>(j, "time_of_day", s.time_of_day, "");
  s.sky = value<std::string>(j, "sky", s.sky, "");
  try {
    weather_preset(s.weather), validate_time_of_day(s.time_of_day), validate_sky(s.sky);
    with_parameters(weather_preset(s.weather), s.weather_parameters);
  } catch (const std::invalid_argument& e) {
    require(false, e.what());
  }
  s.frames = integer(j, "frames", s.frames, 2, 999999, "");
  require(s.frames >= 2 && s.frames <= 999999, "\"frames\" must be in 2..999999");
  s.frame_rate = value<double>(j, "frame_rate", s.frame_rate, "");
  require(s.frame_rate >= 1 && s.frame_rate <= 240, "\"frame_rate\" must be in 1..240");
  return s;
}

nlohmann::json to_json(const Scenario& s) {
  nlohmann::json j = {
      {"flowscape_scenario", kScenarioSchema},
      {"name", s.name},
      {"world", world_json(s)},
      {"rig", s.rig},
      {"ego", s.ego},
      {"motion", motion_json(s)},
      {"traffic",
       {{"vehicles", s.vehicles}, {"pedestrians", s.pedestrians}, {"standing", s.standing}}},
      {"weather", s.weather_parameters.empty()
                      ? nlohmann::json(s.weather)
                      : merged({{"preset", s.weather}}, s.weather_parameters)},
      {"time_of_day", s.time_of_day},
      {"sky", s.sky},
      {"frames", s.frames},
      {"frame_rate", s.frame_rate}};
  if (!s.rig_mount.empty()) j["rig_mount"] = s.rig_mount;
  if (!s.generator.empty()) j["generator"] = s.generator;
  if (!s.models.empty()) j["models"] = s.models;
  if (!s.actors.empty()) j["actors"] = actors_json(s.actors);
  return j;
}

std::string version_warning(const Scenario& s) {
  if (s.generator.empty() || s.generator == kGeneratorVersion) return "";
  return "scenario \"" + s.name + "\" was recorded by " + s.generator + "; this is " +
         kGeneratorVersion + ": its sequence may differ in bytes from the one recorded";
}

Scenario read_scenario(const std::filesystem::path& file) {
  try {
    return scenario_from_json(read_json(file), file.parent_path());
  } catch (const std::invalid_argument& e) {
    throw FileError(file, e.what());
  }
}

nlohmann::json release_keys(const Scenario& s) {
  nlohmann::json keys = {{"rig", s.rig}, {"ego", s.ego}, {"frames", s.frames}};
  if (!s.rig_mount.empty()) keys["rig_mount"] = s.rig_mount;
  return keys;
}

nlohmann::json release_keys(const std::vector<std::filesystem::path>& files,
                            const nlohmann::json& overridden) {
  nlohmann::json keys;
  std::filesystem::path first;
  for (const std::filesystem::path& file : files) {
    nlohmann::json these = release_keys(read_scenario(file));
    for (const auto& [key, value] : overridden.items()) these.erase(key);
    if (keys.is_null()) {
      keys = these, first = file;
      continue;
    }
    for (const auto& [key, value] : these.items())
      if (keys.value(key, nlohmann::json()) != value)
        throw FileError(file, "\"" + key + "\" is " + value.dump() + " here and " +
                                  keys.value(key, nlohmann::json()).dump() + " in " +
                                  first.string() + ": the scenarios of one release share it " +
                                  "(or set it for all on the command line)");
  }
  return keys;
}

Scenario scenario_of(const ReleaseConfig& config, const SequencePlan& plan) {
  Scenario s = plan.scenario_file.empty() ? Scenario{} : read_scenario(plan.scenario_file);
  if (plan.scenario_file.empty()) {
    s.name = plan.name, s.map = plan.map, s.seed = plan.seed;
    s.route = config.ego_routes == "free" ? "free" : plan.turns ? "turn" : "drive";
    s.vehicles = config.vehicles, s.pedestrians = config.pedestrians, s.standing = config.standing;
    for (const auto& [kind, file] : config.models)
      s.models[kind] = std::filesystem::absolute(file).string();
    s.weather = plan.weather, s.time_of_day = plan.time_of_day, s.sky = plan.sky;
  }
  s.rig = config.rig, s.rig_mount = config.rig_mount, s.ego = config.ego;  // the release's
  s.frames = config.frames;
  const StreetLife people = people_on_foot(s.map, s.vehicles, s.pedestrians, s.standing);
  s.pedestrians = people.walking, s.standing = people.standing;
  s.generator = kGeneratorVersion;  // what renders it now
  return s;
}

std::vector<double> release_frame_rates(const ReleaseConfig& config) {
  std::set<double> rates;
  for (const std::string& file : config.scenarios) rates.insert(read_scenario(file).frame_rate);
  if (rates.empty()) rates.insert(kFrameRate);
  return {rates.begin(), rates.end()};
}

PoseTrack rig_path_track(const Scenario& s, const Rig& rig) {
  const double needed = s.frames / s.frame_rate;
  if (s.path->pose_file.empty()) {
    const double end = waypoint_times(s.path->waypoints).back();
    require(end >= needed - 1e-9, "the waypoints end at " + std::to_string(end) + " s; " +
                                      std::to_string(s.frames) + " frames need " +
                                      std::to_string(needed) + " s");
    return waypoint_track(s.path->waypoints);
  }
  const std::vector<TimedPose> poses =
      read_pose_file(s.path->pose_file, pose_format(s.path->format), s.path->rate);
  if (poses.back().time < needed - 1e-9)
    throw FileError(s.path->pose_file, "its poses end at " + std::to_string(poses.back().time) +
                                           " s; " + std::to_string(s.frames) + " frames need " +
                                           std::to_string(needed) + " s");
  Pose camera_to_rig = Pose::Identity();
  if (s.path->poses_of == kCameraFramePoses) {
    camera_to_rig.linear() = look(0, 0, 0);
  } else if (s.path->poses_of != "rig") {
    const auto camera =
        std::find_if(rig.cameras.begin(), rig.cameras.end(),
                     [&](const RigCamera& c) { return c.name == s.path->poses_of; });
    require(camera != rig.cameras.end(), "motion \"poses_of\": the rig has no camera \"" +
                                             s.path->poses_of +
                                             "\" (\"rig\", \"camera_frame\" or a camera's name)");
    camera_to_rig = camera->mount();
  }
  Pose world = Pose::Identity();
  try {
    world.linear() = ours_from_file_world(s.path->world, poses);
  } catch (const std::invalid_argument& e) {
    throw FileError(s.path->pose_file, e.what());
  }
  return [track = interpolated_track(poses), placed = s.path->origin() * world,
          rig_from_camera = camera_to_rig.inverse()](double t) {
    return placed * track(t) * rig_from_camera;
  };
}

}  // namespace flowscape
