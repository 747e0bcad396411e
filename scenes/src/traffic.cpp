#include "traffic.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <optional>

#include "flowscape/core/random.h"

namespace flowscape {
namespace {

using V2 = Eigen::Vector2d;
constexpr double kStep = kTrafficStep, kFrame = 2 * kStep;  // tracks reach a frame (1/30 s) past
constexpr double kInf = std::numeric_limits<double>::infinity();
// Vehicles: gaps and headway, acceleration, the braking they plan with (behind a leader, before a
// stop line; before a curve more gently) and the lateral acceleration they accept in curves.
constexpr double kStandstill = 2.0, kHeadway = 1.0, kAcceleration = 2.5;
constexpr double kBraking = 3.0, kCurveBraking = 2.0, kLateral = 3.0, kLookAhead = 250;
constexpr double kLightCycle = 8.0, kApproach = 25.0, kSample = 0.5;
// Lane changes (traffic.h: kChangeSeconds, kChangeMinimum, kChangeEndMargin): without a slow
// leader a vehicle changes lanes at random this often (per second).
constexpr double kChangeRate = 0.05;
// Walkers: body length along the way, gap, headway, acceleration; how close to the kerb they ask
// to cross, and how far a vehicle's way must keep from a crosswalk with walkers on it.
constexpr double kBody = 0.6, kWalkGap = 0.6, kWalkHeadway = 0.8, kWalkAcceleration = 1.0;
constexpr double kAskToCross = 3.0, kCrosswalkMargin = 3.0;

// Walkers' safe-speed rule: with a step no longer than the headway, the gap never falls below
// `standstill`.
double next_speed(double speed, double wish, double gap, double standstill, double headway,
                  double acceleration) {
  const double safe = (gap - standstill) / headway;
  return std::max(0.0, std::min({speed + acceleration * kStep, wish, safe}));
}

// Highest speed for the next step behind something `gap` metres ahead moving at `leader_speed`.
// Gipps' rule: driving on for a headway and then braking at kBraking stops us short of where the
// leader would stop braking as hard (its stopping distance under-estimated by a step:
// v^2 / 2b - v dt). Behind a leader that brakes no harder, nobody does: approaching a standing
// obstacle the deceleration is b (1 - h / sqrt(h^2 + 2 free / b)) < b, and a follower keeps a
// headway h. The second term keeps the standstill gap whatever the leader does.
double safe_speed(double gap, double leader_speed) {
  const double free = gap - kStandstill;
  if (free <= 0) return 0;
  const double room =
      free + std::max(0.0, leader_speed * leader_speed / (2 * kBraking) - leader_speed * kStep);
  const double gipps =
      kBraking * (-kHeadway + std::sqrt(kHeadway * kHeadway + 2 * room / kBraking));
  return std::min(gipps, free / kStep);
}

// Square of the highest speed from which a vehicle `before` metres short of point s of `path` can
// brake at kCurveBraking to keep its lateral acceleration v^2 |k| within kLateral from s on. On a
// piece the curvature is linear in t, and kLateral / |k(t)| + 2 b t is convex where k keeps its
// sign: its least value is at an end or where |k| = sqrt(kLateral |k'| / 2b).
double curve_limit_squared(const Path& path, double s, double before) {
  double limit = kInf;
  for (const Path::Piece& p : path.pieces()) {
    const double t0 = std::max(0.0, s - p.s0), reach = before + p.s0 - s;
    if (t0 >= p.length) continue;
    if (reach + t0 > kLookAhead) break;
    const auto bound = [&](double t) {
      const double k = std::abs(p.curvature + p.curvature_rate * t);
      return k == 0 ? kInf : kLateral / k + 2 * kCurveBraking * (reach + t);
    };
    limit = std::min({limit, bound(t0), bound(p.length)});
    if (p.curvature_rate == 0) continue;
    const double k = std::sqrt(kLateral * std::abs(p.curvature_rate) / (2 * kCurveBraking));
    for (const double target : {k, -k}) {
      const double t = (target - p.curvature) / p.curvature_rate;
      if (t > t0 && t < p.length) limit = std::min(limit, bound(t));
    }
  }
  return limit;
}

double largest_curvature(const Path& path) {
  double largest = 0;
  for (const Path::Piece& p : path.pieces())
    largest = std::max(
        {largest, std::abs(p.curvature), std::abs(p.curvature + p.curvature_rate * p.length)});
  return largest;
}

}  // namespace

Pose ground_pose(const Layout& layout, const PathPoint& p, double lift) {
  const double ahead = layout.height(p.position + p.direction),
               behind = layout.height(p.position - p.direction);
  const double yaw = std::atan2(p.direction.y(), p.direction.x());
  const double pitch = std::atan2(ahead - behind, 2.0);
  const Eigen::Vector3d at(p.position.x(), p.position.y(), layout.height(p.position) + lift);
  return Pose(Eigen::Translation3d(at) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
              Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitY()));
}

namespace {

// The way across a junction from one lane to another.
struct Connector {
  Path path;
  std::vector<V2> samples;      // every kSample metres
  double curvature = 0;         // the largest |curvature| on it
  std::vector<int> crosswalks;  // the crosswalks of its junction it passes over
};

struct Walker {
  int loop = 0;
  double s = 0, speed = 0, wish = 0, travelled = 0;
  int crossing = -1;  // the loop crossing it may take (or is on), or -1
};

struct Vehicle {
  double length = 0, width = 0, wish = 0;
  int lane = 0, next_lane = -1;
  int change_from = -1;  // the lane it is changing from, or -1
  double change_start = 0, change_length = 0;
  const Connector* connector = nullptr;  // from lane to next_lane
  int held = -1;                         // the junction it may cross (or is leaving), or -1
  bool in_junction = false;
  bool turn_next = false;  // its next junction's way must turn (VehicleStart::turn)
  double change_at = -1;   // VehicleStart::change_at
  int changes = 0;         // lane changes begun
  double s = 0, speed = 0, travelled = 0;
  // How far its body reaches sideways from its connector: half its width plus the swing of its
  // ends in the tightest curve (chord offset L^2 k / 8).
  double sweep() const { return width / 2 + length * length * connector->curvature / 8; }
};

// On `lane` (not in a junction), a vehicle changing lanes counting on both.
bool on_lane(const Vehicle& v, int lane) {
  return !v.in_junction && (v.lane == lane || v.change_from == lane);
}

// A lane change moves sideways by the smootherstep f(u) = 6u^5 - 15u^4 + 10u^3 of the share u of
// its length driven: f' and f'' vanish at both ends, so heading and curvature stay continuous.
double smootherstep(double u) { return u * u * u * (10 + u * (-15 + 6 * u)); }
double smootherstep_slope(double u) { return 30 * u * u * (1 + u * (-2 + u)); }

// How far a vehicle changing lanes moves sideways per metre along its lane, as a share of the
// distance between the two lanes.
double change_slope(const Vehicle& v) {
  const double u = std::clamp((v.s - v.change_start) / v.change_length, 0.0, 1.0);
  return smootherstep_slope(u) / v.change_length;
}

class Traffic {
 public:
  Traffic(const Layout& layout, const std::vector<SidewalkLoop>& loops,
          const std::vector<VehicleStart>& starts, const std::vector<WalkerStart>& walkers,
          std::uint64_t seed)
      : layout_(layout),
        loops_(loops),
        random_(seed),
        occupants_(layout.node_height.size()),
        light_offset_(layout.node_height.size()),
        tightest_(layout.node_height.size(), 0),
        walkers_on_(layout.crosswalks.size(), 0) {
    for (const WalkerStart& w : walkers) walkers_.push_back({w.loop, w.s, w.speed, w.speed, 0, -1});
    outgoing_.resize(layout.node_height.size());
    for (int l = 0; l < int(layout.lanes.size()); ++l) outgoing_[layout.lanes[l].from].push_back(l);
    make_connectors();
    parallel_.resize(layout.lanes.size());
    for (int a = 0; a < int(layout.lanes.size()); ++a)
      for (int b = 0; b < int(layout.lanes.size()); ++b)
        if (side_by_side(layout.lanes[a], layout.lanes[b])) parallel_[a].push_back(b);
    for (double& offset : light_offset_) offset = random_.uniform(0, 2 * kLightCycle);
    for (const VehicleStart& start : starts) {
      Vehicle v;
      v.length = start.length, v.width = start.width;
      v.wish = std::min(start.speed, layout.lanes[start.lane].speed);
      v.lane = start.lane, v.s = start.s, v.turn_next = start.turn, v.change_at = start.change_at;
      choose_next(v);
      vehicles_.push_back(std::move(v));
    }
    // already driving: at the speed the road ahead allows, so the first steps do not brake hard
    grant(0);
    for (std::size_t i = 0; i < vehicles_.size(); ++i)
      vehicles_[i].speed = std::min(vehicles_[i].wish, speed_limit(int(i)));
  }

  void step(double t) {
    change_lanes(t);
    grant(t);
    let_walkers_cross(t);
    std::vector<double> speeds(vehicles_.size()), paces(walkers_.size());
    for (std::size_t i = 0; i < vehicles_.size(); ++i) {
      const Vehicle& v = vehicles_[i];
      speeds[i] =
          std::max(0.0, std::min({v.speed + kAcceleration * kStep, v.wish, speed_limit(int(i))}));
    }
    for (std::size_t i = 0; i < walkers_.size(); ++i) paces[i] = walker_speed(int(i));
    for (std::size_t i = 0; i < vehicles_.size(); ++i) advance(int(i), speeds[i]);
    for (std::size_t i = 0; i < walkers_.size(); ++i) walk(int(i), paces[i]);
    release();
  }

  Pose pose(int i) const {
    const Vehicle& v = vehicles_[i];
    return ground_pose(layout_, v.in_junction ? v.connector->path.at(v.s) : lane_point(v), 0);
  }
  double travelled(int i) const { return vehicles_[i].travelled; }
  int lane_changes(int i) const { return vehicles_[i].changes; }
  Pose walker_pose(int i) const {
    const Walker& w = walkers_[i];
    const SidewalkLoop& loop = loops_[w.loop];
    return ground_pose(layout_, loop.path.at(w.s), loop.lift(w.s));
  }
  double walked(int i) const { return walkers_[i].travelled; }

 private:
  int node_of(int lane) const { return layout_.lanes[lane].to; }
  double lane_length(int lane) const { return layout_.lanes[lane].path.length(); }

  // Where a vehicle on a lane is: on it, or between it and the lane it changes from.
  PathPoint lane_point(const Vehicle& v) const {
    PathPoint p = layout_.lanes[v.lane].path.at(v.s);
    if (v.change_from < 0) return p;
    const V2 away = layout_.lanes[v.change_from].path.at(v.s).position - p.position;
    const double u = std::clamp((v.s - v.change_start) / v.change_length, 0.0, 1.0);
    p.position += (1 - smootherstep(u)) * away;
    p.direction = (p.direction - change_slope(v) * away).normalized();
    return p;
  }

  // Where vehicle o is along `lane`: on it, or (negative) on its way into it across a junction,
  // in it or holding it (so that nobody changes into `lane` just ahead of one about to enter).
  std::optional<double> position_on(const Vehicle& o, int lane) const {
    if (on_lane(o, lane)) return o.s;
    if (o.next_lane != lane || !cleared(o)) return std::nullopt;
    const double to_way = o.in_junction ? -o.s : lane_length(o.lane) - o.s;
    return -to_way - o.connector->path.length();
  }

  // The nearest vehicles ahead of and behind vehicle i's place on `lane` (or -1).
  std::pair<int, int> neighbours(int i, int lane) const {
    int ahead = -1, behind = -1;
    double ahead_s = kInf, behind_s = -kInf;
    const double here = vehicles_[i].s;
    for (int k = 0; k < int(vehicles_.size()); ++k) {
      const std::optional<double> there = position_on(vehicles_[k], lane);
      if (k == i || !there) continue;
      if (*there >= here && *there < ahead_s) ahead = k, ahead_s = *there;
      if (*there<here&& * there> behind_s) behind = k, behind_s = *there;
    }
    return {ahead, behind};
  }

  // The free road between vehicle i (taken to be on `lane`) and vehicle k on `lane`, ahead of it
  // or (negative k's place minus i's) behind it.
  double body_gap(int i, int k, int lane) const {
    const double half_lengths = (vehicles_[i].length + vehicles_[k].length) / 2;
    return std::abs(*position_on(vehicles_[k], lane) - vehicles_[i].s) - half_lengths;
  }

  // Nobody on `lane` would have to brake harder than Gipps' rule plans for if vehicle i were there.
  bool room_to_change(int i, int lane) const {
    const Vehicle& v = vehicles_[i];
    const auto [ahead, behind] = neighbours(i, lane);
    if (ahead >= 0) {
      const Vehicle& o = vehicles_[ahead];
      const double gap = body_gap(i, ahead, lane);
      if (gap < kStandstill || v.speed > safe_speed(gap, o.speed)) return false;
    }
    if (behind >= 0) {
      const Vehicle& o = vehicles_[behind];
      const double gap = body_gap(i, behind, lane);
      if (gap < kStandstill || o.speed > safe_speed(gap, v.speed)) return false;
    }
    return true;
  }

  // Changes lanes on multi-lane roads: to pass a leader slower than it wishes to drive (where the
  // other lane moves faster), else now and then at random; never near the lane's end, while
  // holding a junction, or where the other lane has no room. One asked to change (change_at) does
  // so as soon as it may, into either lane beside it, and makes no other change.
  void change_lanes(double t) {
    for (int i = 0; i < int(vehicles_.size()); ++i) {
      Vehicle& v = vehicles_[i];
      if (v.in_junction || v.held >= 0 || v.change_from >= 0 || parallel_[v.lane].empty()) continue;
      const double length = std::max(kChangeMinimum, kChangeSeconds * v.speed);
      if (v.s < 2 || lane_length(v.lane) - v.s < length + kChangeEndMargin) continue;
      const int leader = neighbours(i, v.lane).first;
      const bool held_up =
          leader >= 0 && body_gap(i, leader, v.lane) < 40 && vehicles_[leader].speed < v.wish - 2;
      const bool whim = random_.chance(kChangeRate * kStep);
      const bool scripted = v.change_at >= 0, asked = scripted && t >= v.change_at && !v.changes;
      if (scripted ? !asked : !held_up && !whim) continue;
      for (const int other : parallel_[v.lane]) {
        const int other_leader = neighbours(i, other).first;
        const bool faster =
            other_leader < 0 || body_gap(i, other_leader, other) > 60 ||
            vehicles_[other_leader].speed > vehicles_[leader < 0 ? i : leader].speed + 1;
        if ((held_up && !faster && !asked) || !room_to_change(i, other)) continue;
        ++v.changes;
        v.change_from = v.lane, v.lane = other, v.change_start = v.s, v.change_length = length;
        choose_next(v);
        break;
      }
    }
  }

  // Every way across every junction (into any lane of another road), and the tightest of them.
  void make_connectors() {
    for (int lane = 0; lane < int(layout_.lanes.size()); ++lane)
      for (int next : outgoing_[node_of(lane)]) {
        if (layout_.lanes[next].to == layout_.lanes[lane].from) continue;
        Connector c{make_connector(lane, next), {}, 0, {}};
        for (double s = 0; s <= c.path.length(); s += kSample)
          c.samples.push_back(c.path.at(s).position);
        c.curvature = largest_curvature(c.path);
        for (int k = 0; k < int(layout_.crosswalks.size()); ++k) {
          const Crosswalk& crosswalk = layout_.crosswalks[k];
          if (crosswalk.node == node_of(lane) &&
              std::any_of(c.samples.begin(), c.samples.end(), [&](const V2& p) {
                return crosswalk.band.contains(p, kCrosswalkMargin);
              }))
            c.crosswalks.push_back(k);
        }
        tightest_[node_of(lane)] = std::max(tightest_[node_of(lane)], c.curvature);
        connectors_.emplace(std::pair(lane, next), std::move(c));
      }
  }

  void choose_next(Vehicle& v) {
    const Lane& in = layout_.lanes[v.lane];
    const V2 in_direction = in.path.at(0).direction;
    // one lane per road leaving the junction: not back where it came from, and no hairpin (a turn
    // of more than about 107 degrees, from or onto the diagonal street) where there is another way
    std::vector<int> roads, hairpins;
    for (int l : outgoing_[in.to]) {
      const Lane& out = layout_.lanes[l];
      if (out.to == in.from || out.index != 0) continue;
      (out.path.at(0).direction.dot(in_direction) < -0.3 ? hairpins : roads).push_back(l);
    }
    if (roads.empty()) roads = hairpins;
    const auto straight = [&](int l) {
      return layout_.lanes[l].path.at(0).direction.dot(in_direction) > 0.5;
    };
    if (v.turn_next && !std::all_of(roads.begin(), roads.end(), straight))
      roads.erase(std::remove_if(roads.begin(), roads.end(), straight), roads.end());
    v.turn_next = false;
    std::vector<double> weights;
    for (int l : roads) weights.push_back(straight(l) ? 2 : 1);
    double pick = random_.uniform(0, std::accumulate(weights.begin(), weights.end(), 0.0));
    int road = roads.back();
    for (std::size_t k = 0; k < roads.size(); ++k)
      if ((pick -= weights[k]) < 0) {
        road = roads[k];
        break;
      }
    for (int l : outgoing_[in.to])  // the same lane index on that road, or its outermost lane
      if (layout_.lanes[l].to == layout_.lanes[road].to && layout_.lanes[l].index <= in.index &&
          layout_.lanes[l].index >= layout_.lanes[road].index)
        road = l;
    v.next_lane = road;
    v.connector = &connectors_.at(std::pair(v.lane, road));
  }

  // Turns at a junction: right on a 6 m corner, left on 10 m; round a bend on a corner concentric
  // with its centre line (kBendRadius less or more the lane's offset). Roundabouts are driven
  // counter-clockwise on a ring round the island, one per lane (4.75 m and 8.25 m; each lane
  // 3 m inside its ring; the outer ring where the lanes differ), except right turns, which take the
  // corner.
  Path make_connector(int lane, int next) const {
    const Lane &in = layout_.lanes[lane], &out = layout_.lanes[next];
    const PathPoint a = in.path.at(in.path.length()), b = out.path.at(0);
    const double cross = a.direction.x() * b.direction.y() - a.direction.y() * b.direction.x();
    if (layout_.is_bend(in.to)) {  // round the bend's centre, inside lanes on smaller circles
      const V2 from_node = a.position - layout_.node_position(in.to);
      const double offset =
          std::abs(from_node.x() * a.direction.y() - from_node.y() * a.direction.x());
      return turn_path(a.position, a.direction, b.position, b.direction,
                       kBendRadius + (cross < 0 ? -offset : offset));
    }
    if (!layout_.is_roundabout(in.to) || cross < -0.5)
      return turn_path(a.position, a.direction, b.position, b.direction, cross < 0 ? 6 : 10);
    const int ring = std::max(in.index, out.index);
    return roundabout_path(a.position, a.direction, b.position, b.direction,
                           layout_.node_position(in.to), 4.75 + 3.5 * ring, 4.0);
  }

  // Lights alternate between the roads along x and those along y (roundabouts: no lights).
  bool x_phase(int node, double t) const {
    return int(std::floor((t + light_offset_[node]) / kLightCycle)) % 2 == 0;
  }

  bool green(int lane, double t) const {
    const int node = node_of(lane);
    if (layout_.is_roundabout(node) || layout_.is_bend(node)) return true;
    const bool along_x = std::abs(layout_.lanes[lane].path.at(0).direction.x()) > 0.5;
    return along_x == x_phase(node, t);
  }

  // Walkers may cross a road while the road they walk along has green.
  bool walk_signal(const Crosswalk& crosswalk, double t) const {
    return layout_.is_roundabout(crosswalk.node) ||
           crosswalk.across_x_road != x_phase(crosswalk.node, t);
  }

  // The next crossing of walker w's loop ahead of it, and how far ahead its kerb is.
  std::pair<int, double> next_crossing(const Walker& w) const {
    const SidewalkLoop& loop = loops_[w.loop];
    const double length = loop.path.length();
    int next = -1;
    double ahead = kInf;
    for (int k = 0; k < int(loop.crossings.size()); ++k) {
      const double d = std::fmod(loop.crossings[k].s_in - w.s + length, length);
      if (d < ahead) next = k, ahead = d;
    }
    return {next, ahead};
  }

  // A walker near a kerb may cross when the signal lets it and no vehicle that may cross the
  // junction passes over the crosswalk; vehicles then wait for it (grant).
  void let_walkers_cross(double t) {
    for (Walker& w : walkers_) {
      if (w.crossing >= 0) continue;
      const auto [next, ahead] = next_crossing(w);
      if (next < 0 || ahead - kBody / 2 > kAskToCross) continue;
      const int index = loops_[w.loop].crossings[next].crosswalk;
      const Crosswalk& crosswalk = layout_.crosswalks[index];
      const auto& others = occupants_[crosswalk.node];
      const bool passed = std::any_of(others.begin(), others.end(), [&](int k) {
        const auto& list = vehicles_[k].connector->crosswalks;
        return std::find(list.begin(), list.end(), index) != list.end();
      });
      if (!walk_signal(crosswalk, t) || passed) continue;
      w.crossing = next;
      ++walkers_on_[index];
    }
  }

  // Behind the walkers ahead on its loop, and before the kerb unless it may cross.
  double walker_speed(int i) const {
    const Walker& w = walkers_[i];
    const double length = loops_[w.loop].path.length();
    double gap = kInf;
    for (std::size_t k = 0; k < walkers_.size(); ++k)
      if (int(k) != i && walkers_[k].loop == w.loop)
        gap = std::min(gap, std::fmod(walkers_[k].s - w.s + length, length) - kBody);
    const auto [next, ahead] = next_crossing(w);
    if (next >= 0 && w.crossing != next) gap = std::min(gap, ahead - kBody / 2 + kWalkGap - 0.1);
    return next_speed(w.speed, w.wish, gap, kWalkGap, kWalkHeadway, kWalkAcceleration);
  }

  // Moves walker i on; it leaves a crosswalk once its body is off the road.
  void walk(int i, double speed) {
    Walker& w = walkers_[i];
    const SidewalkLoop& loop = loops_[w.loop];
    w.speed = speed, w.travelled += speed * kStep;
    w.s = std::fmod(w.s + speed * kStep, loop.path.length());
    if (w.crossing < 0) return;
    const LoopCrossing& c = loop.crossings[w.crossing];
    if (w.s > c.s_out + kBody / 2 + 0.3 && w.s < c.s_out + 10) {
      --walkers_on_[c.crosswalk];
      w.crossing = -1;
    }
  }

  // May cross the junction at the end of its lane (it holds it, or is already in it).
  bool cleared(const Vehicle& v) const { return v.in_junction || v.held == node_of(v.lane); }

  // Rear position of the last vehicle on `lane` (infinity when empty).
  double last_rear(int lane) const {
    double rear = kInf;
    for (const Vehicle& o : vehicles_)
      if (on_lane(o, lane)) rear = std::min(rear, o.s - o.length / 2);
    return rear;
  }

  // Someone ahead on its lane who will not cross the junction the same way before it.
  bool blocked_on_lane(int i) const {
    const Vehicle& v = vehicles_[i];
    for (std::size_t k = 0; k < vehicles_.size(); ++k) {
      const Vehicle& o = vehicles_[k];
      if (int(k) != i && on_lane(o, v.lane) && o.s > v.s &&
          !(cleared(o) && o.connector == v.connector))
        return true;
    }
    return false;
  }

  // The lane it turns into has room for it behind everyone already heading there.
  bool room_on_next(const Vehicle& v) const {
    double room = last_rear(v.next_lane);
    for (int k : occupants_[node_of(v.lane)])
      if (vehicles_[k].next_lane == v.next_lane) room -= vehicles_[k].length + kStandstill;
    return room >= v.length + kStandstill + 2;
  }

  // Closest approach of two ways across a junction (cached; the same way is never in conflict).
  double clearance(const Connector* a, const Connector* b) {
    const auto key = std::minmax(a, b);
    const auto cached = clearance_.find(key);
    if (cached != clearance_.end()) return cached->second;
    double closest = kInf;
    for (const V2& p : a->samples)
      for (const V2& q : b->samples) closest = std::min(closest, (p - q).squaredNorm());
    return clearance_[key] = std::sqrt(closest);
  }

  bool conflicts(const Vehicle& v, const Vehicle& o) {
    return v.connector != o.connector &&
           clearance(v.connector, o.connector) < v.sweep() + o.sweep() + 0.3;
  }

  // A vehicle near its stop line may cross when its light is green (roundabouts: always), nobody
  // ahead on its lane crosses another way, the lane it turns into has room, and its way keeps
  // clear of everyone's who may cross now: several vehicles share a junction when their ways do
  // not meet (opposite straight and right turns, followers on the same way).
  void grant(double t) {
    for (std::size_t i = 0; i < vehicles_.size(); ++i) {
      Vehicle& v = vehicles_[i];
      const int node = node_of(v.lane);
      if (v.in_junction || v.held >= 0 || v.change_from >= 0) continue;
      const double to_stop = lane_length(v.lane) - v.s - v.length / 2;
      const double approach = std::max(kApproach, v.speed * v.speed / (2 * kBraking) + v.speed);
      if (to_stop > approach || !green(v.lane, t) || blocked_on_lane(int(i)) || !room_on_next(v))
        continue;
      const auto& others = occupants_[node];
      if (std::any_of(others.begin(), others.end(),
                      [&](int k) { return conflicts(v, vehicles_[k]); }) ||
          std::any_of(v.connector->crosswalks.begin(), v.connector->crosswalks.end(),
                      [&](int c) { return walkers_on_[c] > 0; }))
        continue;
      v.held = node;
      occupants_[node].push_back(int(i));
    }
  }

  // Highest speed the road ahead allows vehicle i: behind every vehicle ahead on its way, before
  // its stop line unless it may cross, and slow enough for the curves ahead (its connector, the
  // next lane, and the tightest turn of the junction after that).
  double speed_limit(int i) const {
    const Vehicle& v = vehicles_[i];
    const double half = v.length / 2, lane = lane_length(v.lane), way = v.connector->path.length();
    double limit = kInf;
    const auto behind = [&](double distance_to_centre, const Vehicle& o) {
      limit = std::min(limit, safe_speed(distance_to_centre - half - o.length / 2, o.speed));
    };
    // where the connector and the next lane start, from v
    const double to_way = v.in_junction ? -v.s : lane - v.s, to_next = to_way + way;
    for (std::size_t k = 0; k < vehicles_.size(); ++k) {
      const Vehicle& o = vehicles_[k];
      if (int(k) == i) continue;
      if (o.in_junction && o.lane == v.lane && (o.s > v.s || !v.in_junction))
        behind(to_way + o.s, o);
      if (!v.in_junction && o.s > v.s &&
          (on_lane(o, v.lane) || (v.change_from >= 0 && on_lane(o, v.change_from))))
        behind(o.s - v.s, o);
      if (cleared(v) && on_lane(o, v.next_lane)) behind(to_next + o.s, o);
    }
    // before the stop line it may not pass yet: this lane's, or once it may cross, the next one's
    const double stop = cleared(v) ? to_next + lane_length(v.next_lane) : lane - v.s;
    limit = std::min(limit, safe_speed(stop - half + kStandstill - 0.5, 0));
    double curve = std::min(
        curve_limit_squared(v.connector->path, std::max(0.0, -to_way), std::max(0.0, to_way)),
        curve_limit_squared(layout_.lanes[v.next_lane].path, 0, to_next));
    if (!v.in_junction)
      curve = std::min(curve, curve_limit_squared(layout_.lanes[v.lane].path, v.s, 0));
    const double after = to_next + lane_length(v.next_lane);
    if (tightest_[node_of(v.next_lane)] > 0)
      curve = std::min(curve, kLateral / tightest_[node_of(v.next_lane)] +
                                  2 * kCurveBraking * std::max(0.0, after));
    if (v.change_from >= 0) limit = std::min(limit, v.change_length / kChangeSeconds);
    return std::min(limit, std::sqrt(curve));
  }

  void advance(int i, double speed) {
    Vehicle& v = vehicles_[i];
    v.speed = speed, v.travelled += speed * kStep;
    if (v.change_from >= 0) {  // along the lane a little less than along the curve driven
      const double sideways = change_slope(v) * kLaneWidth;
      v.s += speed * kStep / std::sqrt(1 + sideways * sideways);
      if (v.s >= v.change_start + v.change_length) v.change_from = -1;
    } else {
      v.s += speed * kStep;
    }
    if (!v.in_junction && v.s > lane_length(v.lane)) {
      v.s -= lane_length(v.lane);
      v.in_junction = true;
    }
    if (v.in_junction && v.s > v.connector->path.length()) {
      v.s -= v.connector->path.length();
      v.in_junction = false;
      v.lane = v.next_lane;
      choose_next(v);
    }
  }

  // A vehicle stops holding a junction once its rear is on the lane it turned into.
  void release() {
    for (std::size_t i = 0; i < vehicles_.size(); ++i) {
      Vehicle& v = vehicles_[i];
      if (v.held < 0 || v.in_junction || layout_.lanes[v.lane].from != v.held ||
          v.s <= v.length / 2 + 0.5)
        continue;
      auto& list = occupants_[v.held];
      list.erase(std::find(list.begin(), list.end(), int(i)));
      v.held = -1;
    }
  }

  const Layout& layout_;
  const std::vector<SidewalkLoop>& loops_;
  Random random_;
  std::vector<Vehicle> vehicles_;
  std::vector<Walker> walkers_;
  std::vector<std::vector<int>> outgoing_;
  std::map<std::pair<int, int>, Connector> connectors_;  // by (lane, next lane)
  std::map<std::pair<const Connector*, const Connector*>, double> clearance_;
  std::vector<std::vector<int>> occupants_;  // per junction: the vehicles that may cross it
  std::vector<double> light_offset_;
  std::vector<double> tightest_;  // per junction: the largest curvature of a way across it
  std::vector<int> walkers_on_;   // per crosswalk: the walkers that may cross it now
  std::vector<std::vector<int>> parallel_;  // per lane: the lanes beside it, the same way
};

int sample_count(double duration) { return int(std::ceil((duration + kFrame) / kStep)) + 1; }

}  // namespace

Pose Track::pose(double t) const {
  const double x = std::clamp(t / step, 0.0, double(poses.size() - 1));
  const std::size_t k = std::min(std::size_t(x), poses.size() - 1);
  if (k + 1 >= poses.size() || x == double(k)) return poses[k];
  const double w = x - double(k);
  const Pose &a = poses[k], &b = poses[k + 1];
  const Eigen::Quaterniond qa(a.linear()), qb(b.linear());
  Pose p = Pose::Identity();
  p.linear() = qa.slerp(w, qb).toRotationMatrix();
  p.translation() = (1 - w) * a.translation() + w * b.translation();
  return p;
}

double Track::distance_at(double t) const {
  const double x = std::clamp(t / step, 0.0, double(distance.size() - 1));
  const std::size_t k = std::min(std::size_t(x), distance.size() - 1);
  if (k + 1 >= distance.size()) return distance[k];
  return distance[k] + (x - double(k)) * (distance[k + 1] - distance[k]);
}

TrafficTracks simulate_traffic(const Layout& layout, const std::vector<SidewalkLoop>& loops,
                               const std::vector<VehicleStart>& vehicles,
                               const std::vector<WalkerStart>& walkers, double duration,
                               std::uint64_t seed) {
  Traffic traffic(layout, loops, vehicles, walkers, seed);
  TrafficTracks tracks{std::vector<Track>(vehicles.size(), Track{kStep, {}, {}}),
                       std::vector<Track>(walkers.size(), Track{kStep, {}, {}}),
                       std::vector<int>(vehicles.size(), 0)};
  const int samples = sample_count(duration);
  for (int n = 0; n < samples; ++n) {
    if (n > 0) traffic.step(n * kStep);
    for (std::size_t i = 0; i < vehicles.size(); ++i) {
      tracks.vehicles[i].poses.push_back(traffic.pose(int(i)));
      tracks.vehicles[i].distance.push_back(traffic.travelled(int(i)));
    }
    for (std::size_t i = 0; i < walkers.size(); ++i) {
      tracks.walkers[i].poses.push_back(traffic.walker_pose(int(i)));
      tracks.walkers[i].distance.push_back(traffic.walked(int(i)));
    }
  }
  for (std::size_t i = 0; i < vehicles.size(); ++i)
    tracks.lane_changes[i] = traffic.lane_changes(int(i));
  return tracks;
}

}  // namespace flowscape
