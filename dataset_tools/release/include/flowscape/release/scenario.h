#pragma once
// A scenario: everything one sequence needs, in one versioned JSON file (docs/scenarios.md): the
// world (a built-in map and seed), the rig, the motion (the ego's built-in route, or the rig's own
// path through waypoints or from a pose file), the traffic, the weather, time of day and sky,
// frames and frame rate. Every sequence of a release has one (scenario_of: a planned sequence's,
// recorded in its meta.json), and `gen_flowscape --scenario FILE...` renders releases from them.
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "flowscape/release/config.h"
#include "flowscape/renderer/rig.h"
#include "flowscape/scenes/city.h"
#include "flowscape/scenes/trajectory.h"
#include "flowscape/weather/weather.h"

namespace flowscape {

inline constexpr int kScenarioSchema = 1;

// The rig's own path (a handheld camera, a drone): the ego vehicle is not drawn.
struct RigPath {
  std::vector<Waypoint> waypoints;  // or a pose file:
  std::filesystem::path pose_file;
  std::string format = "tum";  // trajectory.h's pose_format
  double rate = 10;            // poses per second of KITTI and COLMAP files
  // Whose poses the file holds: "rig" (x forward, y left, z up), "camera_frame" (a camera's x
  // right, y down, z forward, looking along the rig's x from its origin) or a camera of the rig.
  // Unless given, the format's: rig for tum, camera_frame for kitti and colmap.
  std::string poses_of;
  // How the file's world lies in ours (trajectory.h); unless given, the format's: z_up for tum,
  // y_down for kitti, gravity for colmap.
  PoseWorld world;
  // the file's world, turned into ours, placed in the map's: its origin's position and turn
  // (rig.h's yaw, pitch, roll)
  Vec3 origin_position = Vec3::Zero(), origin_yaw_pitch_roll_degrees = Vec3::Zero();
  Pose origin() const;
};

struct Scenario {
  std::string name = "scenario";
  int map = 0;  // kUserWorldMap for a world file
  std::uint64_t seed = 0;
  // A user's world model instead of a built-in map: no roads, so no traffic, and the rig has a
  // path of its own; absolute path.
  std::optional<WorldModel> world_file;
  // Actors placed one by one, after the traffic (model files absolute).
  std::vector<ScriptedActor> actors;
  std::string route = "drive";  // the ego's: drive, turn, lane_change, free (city.h's EgoRoute)
  double lane_change_at = 1.0;  // seconds: when a lane_change route changes lanes (at the soonest)
  std::optional<RigPath> path;  // instead of the ego's route
  // People walking and standing: -1, the map's own (city.h's people_on_foot; scenario_of sets
  // the numbers).
  int vehicles = 120, pedestrians = -1, standing = -1;
  // User models for actor kinds (car, truck, bus, bike, pedestrian -> a glTF or assimp file),
  // over the release's own (--model); absolute paths.
  std::map<std::string, std::string> models;
  std::string weather = "sunny", time_of_day = "day", sky = "physical";
  // Weather parameters set exactly (weather.h's Weather keys: "fog_density", "sun_elevation"...)
  // over the preset as the seed, time of day and sky leave it; empty: none.
  nlohmann::json weather_parameters = nlohmann::json::object();
  // release-wide: the scenarios of one release agree on them (the command line overrides them)
  std::string rig = "flowscape";
  std::vector<double> rig_mount;
  std::string ego = "auto";
  int frames = 100;
  double frame_rate = kFrameRate;  // frames per second, 1..240
  // The toolkit that recorded it (a release's meta.json: manifest.h's kGeneratorVersion); empty
  // in a scenario written by hand.
  std::string generator;
};

// Strict, as a config: an unknown key is named with the nearest known one; paths relative to
// `base` (the scenario file's folder). Throws std::invalid_argument naming what is wrong.
Scenario scenario_from_json(const nlohmann::json& json, const std::filesystem::path& base = {});
nlohmann::json to_json(const Scenario& scenario);
// A scenario file; its errors are FileErrors naming it.
Scenario read_scenario(const std::filesystem::path& file);
// The weather with a scenario's parameters set over it (Scenario::weather_parameters; a
// meta.json record's "exposure" is ignored). Throws std::invalid_argument naming a bad key or
// value.
Weather with_parameters(const Weather& weather, const nlohmann::json& parameters);
// For a scenario another version of the toolkit recorded: a line saying that a re-render may
// differ in bytes; else empty.
std::string version_warning(const Scenario& scenario);

// The config keys a scenario sets for its whole release (rig, rig_mount, ego, frames), and those
// of several scenarios, which must agree (a FileError naming the two files otherwise) but for the
// keys `overridden` holds (the command line's).
nlohmann::json release_keys(const Scenario& scenario);
nlohmann::json release_keys(const std::vector<std::filesystem::path>& scenario_files,
                            const nlohmann::json& overridden);

// The scenario of a planned sequence of a release: read from its file (--scenario), or what the
// plan and config make of a built-in map (its map, seed, route, traffic, weather, time, sky).
Scenario scenario_of(const ReleaseConfig& config, const SequencePlan& plan);

// The frame rates of a release's sequences, distinct and ascending ({30} without scenarios).
std::vector<double> release_frame_rates(const ReleaseConfig& config);

// The rig's pose over time (rig -> world) of a scenario with a path, its pose-file camera's mount
// taken from `rig`. Throws std::invalid_argument when the path ends before the sequence does.
PoseTrack rig_path_track(const Scenario& scenario, const Rig& rig);

}  // namespace flowscape
