#include "flowscape/scenes/city.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "city_layout.h"
#include "city_models.h"
#include "city_world.h"
#include "flowscape/core/random.h"
#include "flowscape/scenes/model_io.h"
#include "flowscape/scenes/shapes.h"
#include "traffic.h"

namespace flowscape {
namespace {

constexpr int kStartPoints = 110, kMaxActors = 200;
constexpr double kLaneChangeStart = 8;       // metres into its lane a lane-changing ego starts
constexpr double kFrame = 2 * kTrafficStep;  // the ego's route is judged 2 x 1/30 s short
const char* const kKindNames[] = {"car",        "truck", "bus",       "bike",
                                  "pedestrian", "lorry", "motorbike", "rider"};

// A start on `lane`, s metres along it, heading along the lane, on the ground.
StartPoint start_at(const Layout& layout, int lane, double s) {
  const PathPoint p = layout.lanes[lane].path.at(s);
  const double yaw = std::atan2(p.direction.y(), p.direction.x());
  const Eigen::Vector3d at(p.position.x(), p.position.y(), layout.height(p.position));
  return {lane, s,
          Pose(Eigen::Translation3d(at) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()))};
}

std::vector<StartPoint> start_points(const Layout& layout) {
  constexpr double kEndMargin = 8;
  double usable = 0;
  for (const Lane& lane : layout.lanes)
    usable += std::max(0.0, lane.path.length() - 2 * kEndMargin);
  const double spacing = usable / kStartPoints;
  std::vector<StartPoint> points;
  double next = spacing / 2, passed = 0;
  for (int l = 0; l < int(layout.lanes.size()); ++l) {
    const double length = std::max(0.0, layout.lanes[l].path.length() - 2 * kEndMargin);
    for (; next < passed + length && int(points.size()) < kStartPoints; next += spacing)
      points.push_back(start_at(layout, l, kEndMargin + next - passed));
    passed += length;
  }
  return points;
}

// Detailed actors split trucks into box trucks and lorries, bikes into bicycles and motorbikes,
// by a hash of the vehicle's number (the random stream stays that of legacy releases).
ActorKind vehicle_kind(const Style& style, const CityConfig& config, int n, Random& random) {
  const double u = random.uniform();
  const bool warehouses = style.buildings == Style::Buildings::Warehouses;
  const double trucks = warehouses ? 0.25 : 0.08;
  const bool detailed = config.actors == ActorStyle::Detailed;
  const double split = tex::hash01(std::uint64_t(n), config.seed ^ 0x6b696e64ull);  // "kind"
  if (u < trucks)
    return detailed && split < (warehouses ? 0.5 : 0.3) ? ActorKind::Lorry : ActorKind::Truck;
  if (u < trucks + 0.07) return ActorKind::Bus;
  if (u < trucks + 0.07 + 0.12)
    return detailed && split < 0.4 ? ActorKind::Motorbike : ActorKind::Bike;
  return ActorKind::Car;
}

bool clear_of(const std::vector<VehicleStart>& placed, int lane, double s, double length) {
  for (const VehicleStart& o : placed)
    if (o.lane == lane && std::abs(o.s - s) < (o.length + length) / 2 + 4) return false;
  return true;
}

// A lane drawn with probability proportional to its length.
int random_lane(const Layout& layout, Random& random) {
  double total = 0;
  for (const Lane& lane : layout.lanes) total += lane.path.length();
  double pick = random.uniform(0, total);
  for (int l = 0; l < int(layout.lanes.size()); ++l)
    if ((pick -= layout.lanes[l].path.length()) < 0) return l;
  return int(layout.lanes.size()) - 1;
}

// Traffic where the camera sees it: a spot is taken if it lies within `near` of the ego's start,
// a metre farther with every try that failed (where the roads near the ego are full, the next
// ring fills), or one time in 500 anywhere (after 100 tries, any spot); so most actors live
// around the ego's route (bench_actor_share measures what the camera then sees).
bool near_the_ego(const Eigen::Vector2d& spot, const Eigen::Vector2d& ego, double near, int attempt,
                  Random& random) {
  return (spot - ego).norm() < near + attempt || attempt >= 100 || random.uniform(0, 1) < 0.002;
}

struct Spawned {
  std::vector<VehicleStart> vehicles;  // the ego first, then the placed ones (ScriptedActor::start)
  std::vector<ActorKind> vehicle_kinds;
  std::vector<WalkerStart> walkers;
  int placed = 0;
};

// The lane and the distance along it whose centre line passes nearest `at` (within half a lane).
std::pair<int, double> nearest_lane_point(const Layout& layout, const Eigen::Vector2d& at) {
  int lane = -1;
  double along = 0, nearest = kLaneWidth / 2;
  for (int l = 0; l < int(layout.lanes.size()); ++l)
    for (double s = 0; s <= layout.lanes[l].path.length(); s += 0.25)
      if (const double d = (layout.lanes[l].path.at(s).position - at).norm(); d < nearest)
        lane = l, along = s, nearest = d;
  if (lane < 0)
    throw std::invalid_argument("an actor's start (" + std::to_string(at.x()) + ", " +
                                std::to_string(at.y()) + ") is not within " +
                                std::to_string(kLaneWidth / 2) + " m of a lane's centre line");
  return {lane, along};
}

// The vehicles placed by hand with a start, after the ego, clear of it and of each other.
void place_scripted_vehicles(const Layout& layout, const CityConfig& config, Spawned& out) {
  for (const ScriptedActor& actor : config.scripted) {
    if (!actor.start) continue;
    const KindSize size = kind_size(actor.kind);
    const auto [lane, s] = nearest_lane_point(layout, *actor.start);
    const double length = layout.lanes[lane].path.length();
    if (length < size.length + 2 || !clear_of(out.vehicles, lane, s, size.length))
      throw std::invalid_argument("an actor's start (" + std::to_string(actor.start->x()) + ", " +
                                  std::to_string(actor.start->y()) +
                                  ") has no room: another vehicle, the ego or a junction is there");
    const double centre = std::clamp(s, size.length / 2 + 1, length - size.length / 2 - 1);
    out.vehicles.push_back({size.length, size.width, lane, centre, actor.speed, actor.turn});
    out.vehicle_kinds.push_back(actor.kind);
    ++out.placed;
  }
}

// Whether a vehicle `length` long at s on `lane` would stand within `clear` metres ahead of the ego
// on its way: its lane, or the first metres of a lane leaving the junction it drives into.
// For a lane change, the lane beside the ego's from 20 m behind it on counts as its way too.
bool in_ego_way(const Layout& layout, const StartPoint& ego, double clear, int lane, double s,
                double length, bool changing) {
  const Lane& ego_lane = layout.lanes[ego.lane];
  if (lane == ego.lane) return s + length / 2 > ego.s && s - length / 2 < ego.s + clear;
  if (changing && side_by_side(layout.lanes[lane], ego_lane))
    return s + length / 2 > ego.s - 20 && s - length / 2 < ego.s + clear;
  const double left = clear - (ego_lane.path.length() - ego.s);
  return layout.lanes[lane].from == ego_lane.to && s - length / 2 < left;
}

Spawned spawn(const Layout& layout, const std::vector<SidewalkLoop>& loops, const StartPoint& ego,
              const CityConfig& config, Random& random) {
  Spawned out;
  const KindSize car = kind_size(ActorKind::Car);
  out.vehicles.push_back({car.length, car.width, ego.lane, ego.s, layout.lanes[ego.lane].speed,
                          config.ego_route == EgoRoute::Turn});
  if (config.ego_route == EgoRoute::LaneChange) out.vehicles[0].change_at = config.lane_change_at;
  place_scripted_vehicles(layout, config, out);
  const double clear = config.ego_route == EgoRoute::Free ? 0 : kEgoClearAhead;
  const Eigen::Vector2d ego_spot = layout.lanes[ego.lane].path.at(ego.s).position;
  for (int n = 0; n < config.vehicles; ++n) {
    const ActorKind kind = vehicle_kind(layout.style, config, n, random);
    const KindSize size = kind_size(kind);
    const double wish = kind == ActorKind::Bike ? random.uniform(5, 8) : random.uniform(8, 25);
    bool placed = false;
    for (int attempt = 0; attempt < 200 && !placed; ++attempt) {
      const int lane = random_lane(layout, random);
      const double length = layout.lanes[lane].path.length();
      if (length < size.length + 4) continue;
      const double s = random.uniform(size.length / 2 + 1, length - size.length / 2 - 1);
      if (!near_the_ego(layout.lanes[lane].path.at(s).position, ego_spot, 30, attempt, random) ||
          !clear_of(out.vehicles, lane, s, size.length) ||
          (clear > 0 && in_ego_way(layout, ego, clear, lane, s, size.length,
                                   config.ego_route == EgoRoute::LaneChange)))
        continue;
      out.vehicles.push_back({size.length, size.width, lane, s, wish});
      out.vehicle_kinds.push_back(kind);
      placed = true;
    }
    if (!placed)
      throw std::invalid_argument("map " + map_name(config.map) + " has no room for " +
                                  std::to_string(config.vehicles) + " vehicles");
  }
  // walkers: some in groups of two or three, one behind the other at the same pace
  for (int n = 0; n < config.pedestrians;) {
    bool placed = false;
    for (int attempt = 0; attempt < 200 && !placed; ++attempt) {
      const int loop = random.below(int(loops.size()));
      const double length = loops[loop].path.length();
      const auto& crossings = loops[loop].crossings;
      // a third of them a few steps before a crossing (so short sequences see people cross)
      const double s = !crossings.empty() && random.chance(0.35)
                           ? std::fmod(crossings[random.below(int(crossings.size()))].s_in -
                                           random.uniform(1.5, 8) + length,
                                       length)
                           : random.uniform(0, length);
      if (!near_the_ego(loops[loop].path.at(s).position, ego_spot, 25, attempt, random)) continue;
      const int group =
          std::min(config.pedestrians - n, random.chance(0.3) ? 2 + random.below(2) : 1);
      const auto free_spot = [&](double at) {
        for (const LoopCrossing& c : loops[loop].crossings)
          if (at > c.s_in - 1 && at < c.s_out + 1) return false;  // not on a road
        return std::none_of(out.walkers.begin(), out.walkers.end(), [&](auto& w) {
          const double d = std::abs(w.s - at);
          return w.loop == loop && std::min(d, length - d) < 1.5;
        });
      };
      std::vector<double> spots;
      for (int k = 0; k < group; ++k) spots.push_back(std::fmod(s - 1.6 * k + length, length));
      if (!std::all_of(spots.begin(), spots.end(), free_spot)) continue;
      const double pace = random.uniform(1.0, 1.6);
      for (double spot : spots) out.walkers.push_back({loop, spot, pace});
      n += group;
      placed = true;
    }
    if (!placed)
      throw std::invalid_argument("map " + map_name(config.map) + " has no room for " +
                                  std::to_string(config.pedestrians) + " pedestrians");
  }
  return out;
}

// Cars parked in the shoulder along the kerb, right of the outer lane of two-way streets (not
// within 12 m of a junction, not on three-lane roads), 40 % of the slots taken, each handed to
// `place` (with the parking stream, which legacy models draw their looks from), their footprints
// among the solids moving actors keep clear of.
void park_cars(const Layout& layout, std::uint64_t seed, City& city,
               const std::function<void(const Pose&, Random&)>& place) {
  const KindSize car = kind_size(ActorKind::Car);
  if (layout.style.shoulder < car.width + 0.1) return;
  Random random(mix_bits(seed ^ 0x7061726bull));  // "park": its own stream
  std::map<std::pair<int, int>, int> outer;       // per road direction (from, to): outer lane
  for (const Lane& lane : layout.lanes) {
    int& index = outer[{lane.from, lane.to}];
    index = std::max(index, lane.index);
  }
  for (const Lane& lane : layout.lanes) {
    if (lane.index != outer[{lane.from, lane.to}] || lane.index >= 2) continue;
    const double kerb = kLaneWidth / 2 + layout.style.shoulder / 2;  // from the lane's centre
    for (double s = 12 + car.length / 2; s < lane.path.length() - 12 - car.length / 2;
         s += car.length + random.uniform(1, 5)) {
      if (!random.chance(0.4)) continue;
      const PathPoint p = lane.path.at(s);
      const Eigen::Vector2d right(p.direction.y(), -p.direction.x()),
          at = p.position + kerb * right;
      const Pose pose = ground_pose(layout, {at, p.direction, 0}, 0);
      place(pose, random);
      const Eigen::Vector2d along = p.direction * car.length / 2, side = right * car.width / 2;
      city.solids.push_back(
          {at - along - side, at + along - side, at + along + side, at - along + side});
    }
  }
}

Mesh user_model(ActorKind kind, const std::string& path, Scene& scene) {
  Material material;
  material.kind = kind == ActorKind::Pedestrian ? Material::Kind::Diffuse : Material::Kind::Glossy;
  material.albedo = {0.5f, 0.45f, 0.4f};
  const SemanticClass cls =
      kind == ActorKind::Pedestrian ? SemanticClass::Pedestrian : SemanticClass::Vehicles;
  return load_model(path, cls, kind_size(kind).length, scene, material);
}

std::map<ActorKind, Mesh> user_models(const CityConfig& config, Scene& scene) {
  std::map<ActorKind, Mesh> models;
  for (const auto& [name, path] : config.models) {
    const ActorKind kind = kind_from_name(name);
    models[kind] = user_model(kind, path, scene);
  }
  return models;
}

// A scripted actor's waypoints sampled as the traffic's tracks are, for `duration` and a frame.
Track scripted_track(const std::vector<Waypoint>& waypoints, double duration) {
  const PoseTrack path = waypoint_track(waypoints);
  const std::vector<double> times = waypoint_times(waypoints);
  Track track{kTrafficStep, {}, {}};
  double travelled = 0;
  for (int n = 0; n * kTrafficStep <= duration + kFrame; ++n) {
    const Pose pose = path(std::clamp(n * kTrafficStep, times.front(), times.back()));
    if (n > 0) travelled += (pose.translation() - track.poses.back().translation()).norm();
    track.poses.push_back(pose), track.distance.push_back(travelled);
  }
  return track;
}

std::string format_seconds(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", seconds);
  return text;
}

// Whether another lane runs beside `lane` the same way (a lane change can go there).
bool has_lane_beside(const Layout& layout, int lane) {
  return std::any_of(layout.lanes.begin(), layout.lanes.end(),
                     [&](const Lane& other) { return side_by_side(layout.lanes[lane], other); });
}

// Whether a lane change can be made on `lane` from a start 8 m in: another lane beside it, and
// room to drive until lane_change_at and change at the lane's speed before its end.
bool lane_change_fits(const Layout& layout, int lane, double change_at) {
  const double speed = layout.lanes[lane].speed;
  return has_lane_beside(layout, lane) &&
         layout.lanes[lane].path.length() >= kLaneChangeStart + change_at * speed +
                                                 std::max(kChangeMinimum, kChangeSeconds * speed) +
                                                 kChangeEndMargin;
}

// The start of try k for a lane change: kLaneChangeStart into the lane of the k-th start point
// on a lane where one fits.
StartPoint lane_change_start(const Layout& layout, const std::vector<StartPoint>& points,
                             const CityConfig& config, int k) {
  std::vector<const StartPoint*> usable;
  for (std::size_t n = 0; n < 100; ++n) {
    const StartPoint& point = points.at((std::size_t(config.ego_start) + n) % 100);
    if (lane_change_fits(layout, point.lane, config.lane_change_at)) usable.push_back(&point);
  }
  if (usable.empty())
    throw std::invalid_argument("map " + map_name(config.map) +
                                " has no road of two lanes one way long enough for a lane change "
                                "at " +
                                format_seconds(config.lane_change_at));
  return start_at(layout, usable[std::size_t(37 * k) % usable.size()]->lane, kLaneChangeStart);
}

// The ego's start on its try k (EgoRoute).
StartPoint ego_start_of_try(const Layout& layout, const std::vector<StartPoint>& points,
                            const CityConfig& config, int k) {
  if (config.ego_route == EgoRoute::LaneChange) return lane_change_start(layout, points, config, k);
  const StartPoint& point = points.at(std::size_t((config.ego_start + 37 * k) % 100));
  if (config.ego_route != EgoRoute::Turn) return point;
  const Lane& lane = layout.lanes[point.lane];
  Random random(derived_seed(config.seed, std::uint64_t(k), 0x65676f));  // "ego"
  const double before_end = random.uniform(3, std::max(3.0, 0.3 * lane.speed * config.duration));
  return start_at(layout, point.lane, std::max(3.0, lane.path.length() - before_end));
}

// How near a try's ego track comes to what its route asks by `until` seconds: 1 for driving at
// kEgoSpeedShare of its lane's speed on average (less in proportion), plus, for Turn, 1 for
// turning by kEgoTurnDegrees, for LaneChange 1 for changing lanes.
double ego_score(const Track& track, int lane_changes, double lane_speed, double until,
                 EgoRoute route) {
  const double speed = track.distance_at(until) / until;
  double score = std::min(1.0, speed / (kEgoSpeedShare * lane_speed));
  if (route == EgoRoute::LaneChange) return score + (lane_changes > 0 ? 1 : 0);
  if (route != EgoRoute::Turn) return score;
  double turned = 0;
  for (double t = 0; t <= until; t += track.step)
    turned =
        std::max(turned, std::abs(wrapped_angle(yaw_of(track.pose(t)) - yaw_of(track.pose(0)))));
  return score + std::min(1.0, turned * 180 / kPi / kEgoTurnDegrees);
}

// The traffic of a city with its ego placed as its route asks (EgoRoute), and the random stream
// as that spawn left it (the actors' looks draw from it next).
struct PlacedTraffic {
  StartPoint ego;
  int tries = 0;  // starts tried
  Random random{0};
  Spawned spawned;
  TrafficTracks tracks;
};

PlacedTraffic place_traffic(const Layout& layout, const std::vector<SidewalkLoop>& loops,
                            const std::vector<StartPoint>& points, const CityConfig& config) {
  const int tries = config.ego_route == EgoRoute::Free ? 1 : kEgoTries;
  const double full_score =
      config.ego_route == EgoRoute::Turn || config.ego_route == EgoRoute::LaneChange ? 2 : 1;
  PlacedTraffic best;
  double best_score = -1;
  for (int k = 0; k < tries; ++k) {
    PlacedTraffic now;
    now.ego = ego_start_of_try(layout, points, config, k);
    now.random = Random(config.seed * 0x9e3779b97f4a7c15ull + 17 + std::uint64_t(config.map));
    now.spawned = spawn(layout, loops, now.ego, config, now.random);
    now.tracks = simulate_traffic(layout, loops, now.spawned.vehicles, now.spawned.walkers,
                                  config.duration, config.seed);
    const double score = ego_score(
        now.tracks.vehicles[0], now.tracks.lane_changes[0], layout.lanes[now.ego.lane].speed,
        std::max(kFrame, config.duration - 2 * kFrame), config.ego_route);
    if (score > best_score) best = std::move(now), best_score = score;
    best.tries = k + 1;
    if (best_score >= full_score) break;
  }
  return best;
}

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
  if (c.world && (c.vehicles > 0 || c.pedestrians > 0 || c.draw_ego))
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
  if (c.vehicles < 0 || c.pedestrians < 0)
    throw std::invalid_argument("vehicle and pedestrian counts must not be negative");
  if (c.vehicles + c.pedestrians > kMaxActors)
    throw std::invalid_argument("at most " + std::to_string(kMaxActors) +
                                " vehicles and pedestrians per map, asked for " +
                                std::to_string(c.vehicles + c.pedestrians));
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

Pose City::rig(double t) const { return rig_track()(t); }

RigMount random_mount(std::uint64_t seed) {
  Random random(mix_bits(seed ^ 0x6d6f756e74ull));  // "mount": its own stream
  const double degree = kPi / 180;
  return {random.uniform(1.5, 2.0), random.uniform(0.2, 0.6) * degree,
          random.uniform(0.1, 0.4) * degree, random.uniform(0, 2 * kPi),
          random.uniform(0, 2 * kPi)};
}

Pose mount_pose(const RigMount& m, double distance) {
  const double pitch =
      m.pitch_amplitude * std::sin(2 * kPi * distance / RigMount::kPitchWavelength + m.pitch_phase);
  const double roll =
      m.roll_amplitude * std::sin(2 * kPi * distance / RigMount::kRollWavelength + m.roll_phase);
  return Pose(Eigen::Translation3d(0, 0, m.height)) *
         Pose(Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY())) *
         Pose(Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()));
}

PoseTrack City::rig_track() const {
  if (rig_path) return rig_path;
  return [ego = ego, distance = ego_distance, mount = mount](double t) {
    return ego(t) * mount_pose(mount, distance(t));
  };
}

namespace {

const Mesh* user_model_of(const std::map<ActorKind, Mesh>& models, ActorKind kind) {
  const auto model = models.find(kind);
  return model == models.end() ? nullptr : &model->second;
}

// flowscape 0.9's actors, in its order and from its random stream.
void add_legacy_actors(const PlacedTraffic& traffic, const std::map<ActorKind, Mesh>& models,
                       Random& random, City& city) {
  const Spawned& spawned = traffic.spawned;
  const auto add = [&](ActorKind kind, const Track& track, int lane, double s, double speed) {
    const auto instance = std::uint16_t(city.scene.actors.size() + 1);
    city.scene.actors.push_back(legacy_actor(kind, instance, std::make_shared<const Track>(track),
                                             user_model_of(models, kind), random, city.scene));
    city.actors.push_back({instance, kind, lane, s, speed});
  };
  for (std::size_t v = 1; v < spawned.vehicles.size(); ++v) {
    const VehicleStart& start = spawned.vehicles[v];
    add(spawned.vehicle_kinds[v - 1], traffic.tracks.vehicles[v], start.lane, start.s, start.speed);
  }
  for (std::size_t w = 0; w < spawned.walkers.size(); ++w) {
    const WalkerStart& start = spawned.walkers[w];
    add(ActorKind::Pedestrian, traffic.tracks.walkers[w], start.loop, start.s, start.speed);
  }
}

// The models of a city's asset packs, loaded once, and which vehicle shows one: a quarter of the
// cars, by a hash of the instance.
class PackModels {
 public:
  PackModels(const CityConfig& config, Scene& scene) {
    for (const std::string& name : config.asset_packs)
      for (const PackModel& m : asset_pack(name)) {
        Material fallback;
        fallback.kind = Material::Kind::Glossy, fallback.albedo = {0.5f, 0.45f, 0.4f};
        models_.push_back({m, std::make_shared<const Mesh>(load_model(
                                  m.path, SemanticClass::Car, m.length, scene, fallback, m.turn))});
      }
  }
  struct Pick {
    const PackModel* model = nullptr;
    std::shared_ptr<const Mesh> mesh;
  };
  Pick pick(ActorKind kind, std::uint16_t instance, std::uint64_t seed) const {
    std::vector<const std::pair<PackModel, std::shared_ptr<const Mesh>>*> fitting;
    for (const auto& m : models_)
      if (m.first.kind == kind) fitting.push_back(&m);
    const double u = tex::hash01(instance, seed ^ 0x7061636bull);  // "pack"
    if (fitting.empty() || u >= 0.25) return {};
    const auto& [model, mesh] = *fitting[std::size_t(u / 0.25 * double(fitting.size()))];
    return {&model, mesh};
  }

 private:
  std::vector<std::pair<PackModel, std::shared_ptr<const Mesh>>> models_;
};

// Adds a vehicle's or walker's actors with their records: the first is `record`'s, any after it
// the rider it carries (a Rider where the vehicle is, scripted if it is).
void add_actors(std::vector<Actor> actors, ActorRecord record, City& city) {
  for (Actor& actor : actors) {
    city.actors.push_back(record);
    city.scene.actors.push_back(std::move(actor));
    ActorRecord rider{std::uint16_t(city.scene.actors.size() + 1), ActorKind::Rider, record.lane,
                      record.s, record.speed};
    rider.scripted = record.scripted;
    record = rider;
  }
}

// A scripted actor's model: its own file's (loaded into `own`), else the release's for its kind
// (or none: the built-in one).
const Mesh* scripted_model(const ScriptedActor& actor, const std::map<ActorKind, Mesh>& models,
                           std::optional<Mesh>& own, Scene& scene) {
  if (!actor.model.empty()) own = user_model(actor.kind, actor.model, scene);
  return own ? &*own : user_model_of(models, actor.kind);
}

// The detailed actors: traffic (two-wheelers with their riders), walkers (one in eight of those in
// groups a child), the parked cars and the ego vehicle, instances in that order.
void add_detailed_actors(const PlacedTraffic& traffic, const std::map<ActorKind, Mesh>& models,
                         const std::vector<Pose>& parked, ActorLibrary& library, City& city) {
  const CityConfig& config = city.config;
  const Spawned& spawned = traffic.spawned;
  const auto next = [&] { return std::uint16_t(city.scene.actors.size() + 1); };
  const PackModels pack(config, city.scene);
  const auto vehicle = [&](ActorKind kind, std::shared_ptr<const Track> track, ActorRecord record) {
    const PackModels::Pick picked = pack.pick(kind, record.instance, config.seed);
    if (picked.model) {
      record.model = model_id(*picked.model);
      add_actors(
          library.pack_vehicle(picked.mesh, *picked.model, record.instance, std::move(track)),
          record, city);
      return;
    }
    add_actors(
        library.vehicle(kind, record.instance, std::move(track), user_model_of(models, kind)),
        record, city);
  };
  std::vector<const ScriptedActor*> placed;  // in spawn order
  for (const ScriptedActor& actor : config.scripted)
    if (actor.start) placed.push_back(&actor);
  for (std::size_t v = 1; v < spawned.vehicles.size(); ++v) {
    const VehicleStart& start = spawned.vehicles[v];
    const ActorKind kind = spawned.vehicle_kinds[v - 1];
    const auto track = std::make_shared<const Track>(traffic.tracks.vehicles[v]);
    ActorRecord record{next(), kind, start.lane, start.s, start.speed};
    if (v > placed.size()) {
      vehicle(kind, track, record);
      continue;
    }
    record.scripted = true;
    std::optional<Mesh> own;
    add_actors(library.vehicle(kind, record.instance, track,
                               scripted_model(*placed[v - 1], models, own, city.scene)),
               record, city);
  }
  for (std::size_t w = 0; w < spawned.walkers.size(); ++w) {
    const WalkerStart& start = spawned.walkers[w];
    const bool grouped =
        (w > 0 && spawned.walkers[w - 1].loop == start.loop &&
         spawned.walkers[w - 1].speed == start.speed) ||
        (w + 1 < spawned.walkers.size() && spawned.walkers[w + 1].loop == start.loop &&
         spawned.walkers[w + 1].speed == start.speed);
    const bool child =
        grouped && tex::hash01(std::uint64_t(w), config.seed ^ 0x6368696c64ull) < 0.35;
    const auto track = std::make_shared<const Track>(traffic.tracks.walkers[w]);
    add_actors({library.pedestrian(next(), track, start.speed, child,
                                   user_model_of(models, ActorKind::Pedestrian))},
               {next(), ActorKind::Pedestrian, start.loop, start.s, start.speed}, city);
  }
  for (const Pose& pose : parked) {
    ActorRecord record{next(), ActorKind::Car, -1, 0, 0};
    record.parked = true;
    const std::size_t first = city.scene.actors.size();
    vehicle(ActorKind::Car, std::make_shared<const Track>(Track{1, {pose}, {0}}), record);
    for (std::size_t a = first; a < city.scene.actors.size(); ++a)
      library.switch_off_lamps(city.scene.actors[a]);
  }
  if (config.draw_ego) {
    ActorRecord record{next(), ActorKind::Car, traffic.ego.lane, traffic.ego.s, 0};
    record.ego = true;
    city.ego_instance = record.instance;
    add_actors({library.ego(record.instance, city.rig_track(),
                            std::make_shared<const Track>(traffic.tracks.vehicles[0]),
                            city.mount.height, config.ego_cameras)},
               record, city);
  }
}

// The actors scripted by waypoints (CityConfig::scripted), after all others, each with its rider if
// it has one.
void add_scripted_actors(const std::map<ActorKind, Mesh>& models, ActorLibrary& library,
                         City& city) {
  for (const ScriptedActor& scripted : city.config.scripted) {
    if (scripted.start) continue;  // driving with the traffic: add_detailed_actors adds it
    const auto track =
        std::make_shared<const Track>(scripted_track(scripted.waypoints, city.config.duration));
    const std::vector<double> times = waypoint_times(scripted.waypoints);
    const double speed = track->distance.back() / (times.back() - times.front());
    std::optional<Mesh> own;
    const Mesh* model = scripted_model(scripted, models, own, city.scene);
    ActorRecord record{std::uint16_t(city.scene.actors.size() + 1), scripted.kind, -1, 0, speed};
    record.scripted = true;
    add_actors(
        scripted.kind == ActorKind::Pedestrian
            ? std::vector<Actor>{library.pedestrian(record.instance, track, speed, false, model)}
            : library.vehicle(scripted.kind, record.instance, track, model),
        record, city);
  }
}

// The head lamps of every vehicle but the parked ones (walkers and riders have none).
void add_head_lamps(const ActorLibrary& library, City& city) {
  for (std::size_t a = 0; a < city.scene.actors.size(); ++a)
    if (!city.actors[a].parked)
      for (const Lamp& beam : library.head_lamps(city.scene.actors[a], int(a)))
        city.scene.lamps.push_back(beam);
}

// A city of a user's world model: its static world and scripted actors, no roads and no traffic.
City make_world_city(const CityConfig& config) {
  City city;
  city.config = config;
  city.scene.world = load_world(*config.world, city.scene);
  city.area_at = [](const Eigen::Vector2d&) { return Area::Outside; };
  city.ground_height = [](const Eigen::Vector2d&) { return 0.0; };
  city.ego_spawn = {-1, 0, Pose::Identity()};
  city.ego = fixed_pose();
  city.ego_distance = [](double) { return 0.0; };
  city.mount = random_mount(config.seed);
  ActorLibrary library(city.scene, config.seed, config.wet);
  add_scripted_actors(user_models(config, city.scene), library, city);
  add_head_lamps(library, city);
  return city;
}

}  // namespace

City make_city(const CityConfig& config) {
  validate(config);
  if (config.world) return make_world_city(config);
  auto layout = std::make_shared<const Layout>(make_layout(config.map, config.seed));
  City city;
  city.config = config;
  city.solids = build_world(*layout, config.seed, city.scene);
  const std::map<ActorKind, Mesh> models = user_models(config, city.scene);
  const bool legacy = config.actors == ActorStyle::Legacy;
  std::vector<Pose> parked;
  park_cars(*layout, config.seed, city, [&](const Pose& pose, Random& random) {
    if (legacy)
      add_legacy_parked_vehicle(ActorKind::Car, pose, user_model_of(models, ActorKind::Car), random,
                                city.scene);
    else
      parked.push_back(pose);
  });
  city.start_points = start_points(*layout);
  city.area_at = [layout](const Eigen::Vector2d& p) { return layout->area(p); };
  city.ground_height = [layout](const Eigen::Vector2d& p) { return layout->height(p); };
  const std::vector<SidewalkLoop> loops = sidewalk_loops(*layout);
  PlacedTraffic traffic = place_traffic(*layout, loops, city.start_points, config);
  city.ego_spawn = traffic.ego, city.ego_tries = traffic.tries;
  const auto ego = std::make_shared<const Track>(traffic.tracks.vehicles[0]);
  city.ego = [ego](double t) { return ego->pose(t); };
  city.ego_distance = [ego](double t) { return ego->distance_at(t); };
  city.mount = random_mount(config.seed);
  if (legacy) {
    add_legacy_actors(traffic, models, traffic.random, city);
    return city;
  }
  ActorLibrary library(city.scene, config.seed, config.wet);
  add_detailed_actors(traffic, models, parked, library, city);
  add_scripted_actors(models, library, city);
  add_head_lamps(library, city);
  return city;
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
    if (!a.model.empty()) record["model"] = a.model;
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
