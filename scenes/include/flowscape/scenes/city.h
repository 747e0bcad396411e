#pragma once
// Procedural city maps in the manner of CARLA's towns: a road grid with lanes, sidewalks,
// crossings, buildings, vegetation and street furniture, driven by vehicles that follow lanes, keep
// their distance and stop at junctions, and walked by pedestrians on the sidewalks. Everything
// follows from (map, seed, counts): the same config gives the same scene.
#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "flowscape/scenes/model_io.h"
#include "flowscape/scenes/scene.h"
#include "flowscape/scenes/trajectory.h"

namespace flowscape {

constexpr int kMapCount = 8;
// A user's world model (CityConfig::world) stands where a map's number would: "user_world".
constexpr int kUserWorldMap = kMapCount;
// downtown, suburb, highway, rural, roundabout, waterfront, industrial, hilltown, user_world
std::string map_name(int map);

// What traffic is made of. Lorry and Motorbike appear with detailed actors only (where legacy
// ones have trucks and bikes); a Rider is the person on a bike or motorbike, an actor of its own.
enum class ActorKind : std::uint8_t { Car, Truck, Bus, Bike, Pedestrian, Lorry, Motorbike, Rider };
std::string kind_name(ActorKind kind);
ActorKind kind_from_name(const std::string& name);  // throws std::invalid_argument

// How actors look. Detailed: the built-in vehicle families and people (scenes/src/assets/),
// parked vehicles as actors with instances, the ego vehicle drawn. Legacy: flowscape 0.9's box
// models, parked cars baked into the static world, no ego (reproduces those releases byte for
// byte).
enum class ActorStyle : std::uint8_t { Legacy, Detailed };
std::string style_name(ActorStyle style);             // "legacy", "detailed"
ActorStyle style_from_name(const std::string& name);  // throws std::invalid_argument

// How the ego vehicle's start is found. Free: at start point ego_start, choosing its way at
// junctions as every vehicle does. Drive: its way kept clear of vehicles for kEgoClearAhead metres
// at spawn, and starts tried (ego_start first, then every 37th start point on; at most kEgoTries)
// until it drives at least half its lane's speed on average. Turn: as Drive, but it starts 3 m
// to 0.3 x (lane speed x duration) before the end of the start point's lane, turns left or right
// at that junction, and a start must also turn it by 45 degrees. LaneChange: as Drive, but it
// starts 8 m into a lane with another beside it going the same way (the starts tried are those
// of such lanes) and changes into that lane once there is room from lane_change_at seconds on; a
// start must also change. All judged by `duration` less two frames (a release simulates a frame
// past the last frame it records); where no try passes, the one that came closest is kept.
enum class EgoRoute : std::uint8_t { Free, Drive, Turn, LaneChange };
std::string route_name(EgoRoute route);             // "free", "drive", "turn", "lane_change"
EgoRoute route_from_name(const std::string& name);  // throws std::invalid_argument
inline constexpr int kEgoTries = 24;
inline constexpr double kEgoClearAhead = 40;  // metres
inline constexpr double kEgoTurnDegrees = 45, kEgoSpeedShare = 0.5;

// A model of an opt-in asset pack (Debian's game data): a file assimp reads, the kind it stands
// for, where it is from and its licence, which travels with the images that show it.
struct PackModel {
  std::string pack, name, path;
  ActorKind kind;
  std::string licence, copyright;
  Mat3 turn = Mat3::Identity();  // load_model's (kTorcsTurn for TORCS's cars)
  double length = 4.5;           // metres, nose to tail
  // Where its wheels go (a model without them gets built-in road wheels): axle x positions from
  // the middle, half the track, wheel radius and tyre width, metres; no axles: none added.
  std::vector<double> axles{};
  double track = 0, wheel_radius = 0, tyre_width = 0;
};
// The models of an asset pack: "torcs" (Debian's torcs-data: a Peugeot 406 (GPL-2+), a VW beetle
// and an Acura NSX (Free Art License 1.3)). Throws std::invalid_argument for another name, and
// naming the Debian package when it is not installed.
std::vector<PackModel> asset_pack(const std::string& name);
std::vector<std::string> asset_pack_names();
// How records name a pack's model: "pack/name" ("torcs/p406").
std::string model_id(const PackModel& model);

// An actor placed by hand: its kind, a user model file (or empty: the kind's built-in model, drawn
// by the seed), and either the waypoints it passes (trajectory.h: its x axis along its velocity,
// standing where the waypoints put its origin; still before the first and after the last) or, a
// vehicle in a built-in map, a start on the lane nearest `start` (within half a lane's width of its
// centre line) from which it drives with the traffic by its rules at up to `speed` (m/s), turning
// at its first junction where it can if `turn`.
struct ScriptedActor {
  ActorKind kind = ActorKind::Car;
  std::string model;
  std::vector<Waypoint> waypoints;
  std::optional<Eigen::Vector2d> start{};
  double speed = 0;
  bool turn = false;
};

struct CityConfig {
  int map = 0;  // 0 .. kMapCount - 1
  std::uint64_t seed = 0;
  int vehicles = 60, pedestrians = 60;  // at most 200 together (the ego vehicle not counted)
  // People standing or waiting on the pavements round the ego's way, alone or in groups of up to
  // four, where no walker passes (counted in the 200 too).
  int standing = 0;
  int ego_start = 0;  // index into City::start_points
  EgoRoute ego_route = EgoRoute::Free;
  double lane_change_at = 1.0;  // seconds (EgoRoute::LaneChange)
  double duration = 4.0;        // seconds of traffic to simulate (poses hold after it)
  // User models replacing the built-in ones, by kind name ("car", "pedestrian", ...): glTF
  // (.gltf/.glb) through tinygltf, anything else through assimp.
  std::map<std::string, std::string> models;
  ActorStyle actors = ActorStyle::Detailed;
  bool wet = false;  // it rains: people carry umbrellas and wear coats (detailed actors)
  // The ego vehicle is drawn (detailed actors), clear of these camera centres (rig frame).
  bool draw_ego = true;
  std::vector<Vec3> ego_cameras{Vec3::Zero()};
  // Opt-in asset packs (asset_pack): a quarter of the cars (detailed actors) are their models.
  std::vector<std::string> asset_packs{};
  // A user's world instead of the map's (map is kUserWorldMap): it has no roads, so no traffic
  // (vehicles and pedestrians 0), no start points and no ego vehicle (the rig needs a path).
  std::optional<WorldModel> world{};
  std::vector<ScriptedActor> scripted{};  // added after the others (detailed actors only)
};
void validate(const CityConfig& config);  // throws std::invalid_argument naming the bad value

// The people on foot a map has by default, walking and standing: busy downtown to sparse rural
// (docs/scenes.md).
struct StreetLife {
  int walking, standing;
};
StreetLife street_life(int map);
// The people on foot of a city of `vehicles`: `walking` and `standing` as given, where -1 stands
// for the map's street_life: standing in the map's proportion to the walkers given, or both the
// map's, scaled down to the room the vehicles (and a standing count given) leave in the 200. A
// user's world has none.
StreetLife people_on_foot(int map, int vehicles, int walking, int standing);

// A place on a lane where the ego vehicle (or an actor) can start.
struct StartPoint {
  int lane;
  double s;  // metres along the lane
  Pose pose;
};

struct ActorRecord {
  std::uint16_t instance;
  ActorKind kind;
  int lane;  // lane (vehicles) or sidewalk loop (pedestrians) it starts on; -1: none
  double s, speed;
  bool parked = false, ego = false, scripted = false;
  bool standing = false;   // a person standing (CityConfig::standing): lane -1, speed 0
  std::string model = "";  // an asset pack's model ("torcs/p406"), or empty: a built-in one
  // The built-in vehicle family it shows ("van", "city_bus", ...), or empty: a person, a user's
  // or a pack's model, the ego, a legacy box.
  std::string family = "";
};

// The light of a street lamp whose head hangs at `position` (the world's frame): 1500 cd of warm
// white straight down a cone 50-72 degrees wide, as the maps' street lights give.
Lamp street_lamp_light(const Vec3& position);

// How the camera rig sits on the ego, drawn per city seed (per sequence in a release): its height
// above the ego's origin and the sway of a sprung body, pitch and roll that oscillate with the
// distance driven (bumps every 9 m and 14 m), so a standing car is still and a moving one sways
// smoothly. Ranges: height 1.5-2.0 m, pitch amplitude 0.2-0.6 degrees, roll 0.1-0.4 degrees.
struct RigMount {
  double height = 1.7;                                                 // m
  double pitch_amplitude = 0, roll_amplitude = 0;                      // radians
  double pitch_phase = 0, roll_phase = 0;                              // radians
  static constexpr double kPitchWavelength = 9, kRollWavelength = 14;  // m
};
RigMount random_mount(std::uint64_t seed);
// The rig relative to the ego after driving `distance` metres.
Pose mount_pose(const RigMount& mount, double distance);

// Ground areas of the layout, for placing and checking things.
enum class Area : std::uint8_t { Road, Junction, SideWalk, Block, Water, Outside, Crossing };

struct City {
  CityConfig config;
  Scene scene;
  std::vector<StartPoint> start_points;        // 100 .. 120 per map
  std::vector<ActorRecord> actors;             // in scene.actors order (weather's follow)
  std::uint16_t ego_instance = 0;              // the drawn ego vehicle's, or 0
  StartPoint ego_spawn;                        // where the ego starts (EgoRoute)
  int ego_tries = 1;                           // starts tried to find it
  PoseTrack ego;                               // the ego vehicle (x forward, z up, on the road)
  Eigen::Vector2d ego_size{4.5, 1.9};          // its length and width (as traffic sees it)
  std::function<double(double)> ego_distance;  // metres the ego has driven at time t
  RigMount mount;                              // where the camera rig sits on the ego
  // Footprints (4 corners, counter-clockwise) of the buildings and other solid blocks.
  std::vector<std::array<Eigen::Vector2d, 4>> solids;
  std::function<Area(const Eigen::Vector2d&)> area_at;
  std::function<double(const Eigen::Vector2d&)> ground_height;

  // A path of the rig's own (a handheld camera, a drone: scenes/trajectory.h) instead of the ego's;
  // empty: the rig rides on the ego.
  PoseTrack rig_path;
  Pose rig(double t) const;     // the camera rig: rig_path(t), else ego(t) * mount_pose(...)
  PoseTrack rig_track() const;  // the same, as a track that does not refer to this City
};

City make_city(const CityConfig& config);

// The scene record of a sequence: the config that makes it and what it made (actor kinds and spawn
// points, the ego's start), so a scene can be reproduced and checked.
nlohmann::json to_json(const City& city);
CityConfig config_from_json(const nlohmann::json& record);  // throws std::invalid_argument
// Rebuilds the city of a record and checks that it spawns what the record lists.
City city_from_record(const nlohmann::json& record);

}  // namespace flowscape
