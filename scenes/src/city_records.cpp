// City names, the validation of a CityConfig and the city's JSON record (meta.json "city").
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "city_layout.h"
#include "flowscape/scenes/city.h"

namespace flowscape {
namespace {

constexpr int kMaxActors = 200;
// Walking and standing people per map (map order as map_name's): a downtown pavement busy, a
// rural one sparse; with the release's 120 vehicles the busiest map is at the 200.
constexpr StreetLife kStreetLife[kMapCount] = {{56, 24}, {26, 8},  {14, 4}, {8, 3},
                                               {45, 15}, {50, 18}, {18, 6}, {40, 14}};
const char* const kKindNames[] = {"car",        "truck", "bus",       "bike",
                                  "pedestrian", "lorry", "motorbike", "rider"};

}  // namespace

std::string route_name(EgoRoute route) {
  static const char* const kNames[] = {"free", "drive", "turn", "lane_change"};
  return kNames[int(route)];
}

EgoRoute route_from_name(const std::string& name) {
  for (EgoRoute route : {EgoRoute::Free, EgoRoute::Drive, EgoRoute::Turn, EgoRoute::LaneChange})
    if (name == route_name(route)) return route;
  throw std::invalid_argument("unknown ego route \"" + name +
                              "\" (free, drive, turn or lane_change)");
}

std::string map_name(int map) { return map == kUserWorldMap ? "user_world" : style_of(map).name; }

StreetLife street_life(int map) {
  style_of(map);  // throws for a map that is none
  return kStreetLife[map];
}

StreetLife people_on_foot(int map, int vehicles, int walking, int standing) {
  if (map == kUserWorldMap) return {std::max(walking, 0), std::max(standing, 0)};
  const StreetLife life = street_life(map);
  const int room = std::max(0, kMaxActors - vehicles);
  if (walking >= 0 && standing < 0)  // as many standing for the walkers as the map has
    return {walking, std::min(room - std::min(walking, room),
                              int(std::lround(double(walking) * life.standing / life.walking)))};
  if (walking >= 0) return {walking, standing};
  const int left = std::max(0, room - std::max(standing, 0));
  const int asked = life.walking + (standing < 0 ? life.standing : 0);
  const auto share = [&](int count) { return asked <= left ? count : count * left / asked; };
  return {share(life.walking), standing < 0 ? share(life.standing) : standing};
}

std::string style_name(ActorStyle style) {
  return style == ActorStyle::Legacy ? "legacy" : "detailed";
}

ActorStyle style_from_name(const std::string& name) {
  for (ActorStyle style : {ActorStyle::Legacy, ActorStyle::Detailed})
    if (name == style_name(style)) return style;
  throw std::invalid_argument("unknown actor style \"" + name + "\" (detailed or legacy)");
}

std::string kind_name(ActorKind kind) { return kKindNames[int(kind)]; }

ActorKind kind_from_name(const std::string& name) {
  for (int k = 0; k < int(std::size(kKindNames)); ++k)
    if (name == kKindNames[k]) return ActorKind(k);
  throw std::invalid_argument("unknown actor kind \"" + name +
                              "\" (car, truck, bus, bike, pedestrian, lorry, motorbike or rider)");
}

void validate(const CityConfig& c) {
  if (c.world && c.map != kUserWorldMap)
    throw std::invalid_argument("a world file stands for map " + std::to_string(kUserWorldMap) +
                                ", not map " + std::to_string(c.map));
  if (!c.world) style_of(c.map);
  if (c.world && (c.vehicles > 0 || c.pedestrians > 0 || c.standing > 0 || c.draw_ego))
    throw std::invalid_argument(
        "a user world has no roads: no traffic and no ego vehicle (its actors are scripted, its "
        "rig follows a path of its own)");
  if (!c.scripted.empty() && c.actors == ActorStyle::Legacy)
    throw std::invalid_argument("scripted actors need detailed actors (not legacy)");
  for (const ScriptedActor& a : c.scripted) {
    if (!a.start) {
      waypoint_times(a.waypoints);
      continue;
    }
    if (c.world || a.kind == ActorKind::Pedestrian || !(a.speed > 0 && a.speed <= 60))
      throw std::invalid_argument(
          "an actor given a start drives on a map's roads: a vehicle, in a built-in map, at a "
          "speed in (0, 60] m/s");
  }
  if (c.vehicles < 0 || c.pedestrians < 0 || c.standing < 0)
    throw std::invalid_argument("vehicle and pedestrian counts must not be negative");
  if (c.vehicles + c.pedestrians + c.standing > kMaxActors)
    throw std::invalid_argument("at most " + std::to_string(kMaxActors) +
                                " vehicles and pedestrians (walking and standing) per map, asked "
                                "for " +
                                std::to_string(c.vehicles + c.pedestrians + c.standing));
  if (c.ego_start < 0 || c.ego_start >= 100)
    throw std::invalid_argument("ego start " + std::to_string(c.ego_start) + " is not in 0..99");
  if (!(c.lane_change_at >= 0 && c.lane_change_at <= 3600))
    throw std::invalid_argument("lane_change_at must be in [0, 3600] seconds");
  if (!(c.duration > 0 && c.duration <= 3600))
    throw std::invalid_argument("duration must be in (0, 3600] seconds");
  for (const std::string& pack : c.asset_packs) asset_pack(pack);
  for (const auto& entry : c.models)
    if (kind_from_name(entry.first) == ActorKind::Rider)
      throw std::invalid_argument("riders take no user model (a bike's model is \"bike\")");
}

nlohmann::json to_json(const City& city) {
  const CityConfig& c = city.config;
  nlohmann::json actors = nlohmann::json::array();
  for (const ActorRecord& a : city.actors) {
    nlohmann::json record = {{"instance", a.instance},
                             {"kind", kind_name(a.kind)},
                             {"lane", a.lane},
                             {"s", a.s},
                             {"speed", a.speed}};
    if (a.parked) record["parked"] = true;
    if (a.ego) record["ego"] = true;
    if (a.scripted) record["scripted"] = true;
    if (a.standing) record["standing"] = true;
    if (!a.model.empty()) record["model"] = a.model;
    if (!a.family.empty()) record["family"] = a.family;
    actors.push_back(record);
  }
  const StartPoint& ego = city.ego_spawn;
  nlohmann::json record = {{"map", c.map},
                           {"map_name", map_name(c.map)},
                           {"seed", c.seed},
                           {"vehicles", c.vehicles},
                           {"pedestrians", c.pedestrians},
                           {"ego_start", c.ego_start},
                           {"ego_route", route_name(c.ego_route)},
                           {"duration", c.duration},
                           {"models", c.models},
                           {"camera_height", city.mount.height},
                           {"ego", {{"lane", ego.lane}, {"s", ego.s}, {"tries", city.ego_tries}}},
                           {"start_points", city.start_points.size()},
                           {"actors", actors}};
  if (c.ego_route == EgoRoute::LaneChange) record["lane_change_at"] = c.lane_change_at;
  if (c.standing > 0) record["standing"] = c.standing;
  if (c.actors == ActorStyle::Legacy) return record;  // the records of flowscape 0.9, unchanged
  record["actor_style"] = style_name(c.actors);
  if (!c.asset_packs.empty()) record["asset_packs"] = c.asset_packs;
  if (c.world)
    record["world"] = {{"file", c.world->path},
                       {"metres_per_unit", c.world->metres_per_unit},
                       {"up", c.world->z_up ? "z" : "y"}};
  record["wet"] = c.wet;
  record["ego"]["drawn"] = c.draw_ego;
  record["ego"]["instance"] = city.ego_instance;
  nlohmann::json cameras = nlohmann::json::array();
  for (const Vec3& p : c.ego_cameras) cameras.push_back({p.x(), p.y(), p.z()});
  record["ego"]["cameras"] = cameras;
  return record;
}

CityConfig config_from_json(const nlohmann::json& record) {
  CityConfig c;
  const nlohmann::json actors = record.value("actors", nlohmann::json::array());
  if (record.contains("world") ||
      std::any_of(actors.begin(), actors.end(), [](auto& a) { return a.value("scripted", false); }))
    throw std::invalid_argument(
        "scene record: a scenario's city (a user world or scripted actors) is rebuilt from its "
        "scenario (meta.json \"scenario\"; city_preview --from-release)");
  try {
    c.map = record.at("map").get<int>();
    c.seed = record.at("seed").get<std::uint64_t>();
    c.vehicles = record.at("vehicles").get<int>();
    c.pedestrians = record.at("pedestrians").get<int>();
    c.standing = record.value("standing", 0);
    c.ego_start = record.value("ego_start", 0);
    c.ego_route = route_from_name(record.value("ego_route", "free"));
    c.lane_change_at = record.value("lane_change_at", 1.0);
    c.duration = record.value("duration", 4.0);
    c.models = record.value("models", std::map<std::string, std::string>{});
    c.actors = style_from_name(record.value("actor_style", "legacy"));
    c.wet = record.value("wet", false);
    c.asset_packs = record.value("asset_packs", std::vector<std::string>{});
    if (record.contains("ego") && record["ego"].contains("drawn")) {
      c.draw_ego = record["ego"]["drawn"].get<bool>();
      c.ego_cameras.clear();
      for (const auto& p : record["ego"].at("cameras"))
        c.ego_cameras.emplace_back(p.at(0).get<double>(), p.at(1).get<double>(),
                                   p.at(2).get<double>());
    }
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("scene record: ") + e.what());
  }
  validate(c);
  return c;
}

City city_from_record(const nlohmann::json& record) {
  City city = make_city(config_from_json(record));
  if (record.contains("actors") && record["actors"] != to_json(city)["actors"])
    throw std::invalid_argument(
        "scene record: this generator spawns other actors than the record lists (made by "
        "another version?)");
  return city;
}

}  // namespace flowscape
