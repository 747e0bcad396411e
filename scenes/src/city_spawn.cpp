#include "city_spawn.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "flowscape/core/random.h"

namespace flowscape {
namespace {

constexpr int kStartPoints = 110;
constexpr double kLaneChangeStart = 8;  // metres into its lane a lane-changing ego starts

// A start on `lane`, s metres along it, heading along the lane, on the ground.
StartPoint start_at(const Layout& layout, int lane, double s) {
  const PathPoint p = layout.lanes[lane].path.at(s);
  const double yaw = std::atan2(p.direction.y(), p.direction.x());
  const Eigen::Vector3d at(p.position.x(), p.position.y(), layout.height(p.position));
  return {lane, s,
          Pose(Eigen::Translation3d(at) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()))};
}

}  // namespace

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

namespace {

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

}  // namespace

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

namespace {

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

}  // namespace

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
        std::max(kRouteFrame, config.duration - 2 * kRouteFrame), config.ego_route);
    if (score > best_score) best = std::move(now), best_score = score;
    best.tries = k + 1;
    if (best_score >= full_score) break;
  }
  return best;
}

}  // namespace flowscape
