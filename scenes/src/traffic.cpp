#include "traffic.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include "flowscape/core/random.h"

namespace flowscape {
namespace {

using V2 = Eigen::Vector2d;
constexpr double kFrame = 1 / kFrameRate, kStep = kFrame / 2;  // two simulation steps per frame
constexpr double kInf = std::numeric_limits<double>::infinity();
// Vehicles: gaps and headway, acceleration, the braking they plan with (behind a leader, before a
// stop line; before a curve more gently) and the lateral acceleration they accept in curves.
constexpr double kStandstill = 2.0, kHeadway = 1.0, kAcceleration = 2.5;
constexpr double kBraking = 3.0, kCurveBraking = 2.0, kLateral = 3.0, kLookAhead = 250;
constexpr double kLightCycle = 8.0, kApproach = 25.0, kSample = 0.5;

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

Pose ground_pose(const Layout& layout, const PathPoint& p, double lift) {
  const double ahead = layout.height(p.position + p.direction),
               behind = layout.height(p.position - p.direction);
  const double yaw = std::atan2(p.direction.y(), p.direction.x());
  const double pitch = std::atan2(ahead - behind, 2.0);
  const Eigen::Vector3d at(p.position.x(), p.position.y(), layout.height(p.position) + lift);
  return Pose(Eigen::Translation3d(at) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
              Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitY()));
}

// The way across a junction from one lane to another.
struct Connector {
  Path path;
  std::vector<V2> samples;  // every kSample metres
  double curvature = 0;     // the largest |curvature| on it
};

struct Vehicle {
  double length = 0, width = 0, wish = 0;
  int lane = 0, next_lane = -1;
  const Connector* connector = nullptr;  // from lane to next_lane
  int held = -1;                         // the junction it may cross (or is leaving), or -1
  bool in_junction = false;
  double s = 0, speed = 0, travelled = 0;
  // How far its body reaches sideways from its connector: half its width plus the swing of its
  // ends in the tightest curve (chord offset L^2 k / 8).
  double sweep() const { return width / 2 + length * length * connector->curvature / 8; }
};

class Traffic {
 public:
  Traffic(const Layout& layout, const std::vector<VehicleStart>& starts, std::uint64_t seed)
      : layout_(layout),
        random_(seed),
        occupants_(layout.node_height.size()),
        light_offset_(layout.node_height.size()),
        tightest_(layout.node_height.size(), 0) {
    outgoing_.resize(layout.node_height.size());
    for (int l = 0; l < int(layout.lanes.size()); ++l) outgoing_[layout.lanes[l].from].push_back(l);
    make_connectors();
    for (double& offset : light_offset_) offset = random_.uniform(0, 2 * kLightCycle);
    for (const VehicleStart& start : starts) {
      Vehicle v;
      v.length = start.length, v.width = start.width;
      v.wish = std::min(start.speed, layout.lanes[start.lane].speed);
      v.lane = start.lane, v.s = start.s;
      choose_next(v);
      vehicles_.push_back(std::move(v));
    }
    // already driving: at the speed the road ahead allows, so the first steps do not brake hard
    grant(0);
    for (std::size_t i = 0; i < vehicles_.size(); ++i)
      vehicles_[i].speed = std::min(vehicles_[i].wish, speed_limit(int(i)));
  }

  void step(double t) {
    grant(t);
    std::vector<double> speeds(vehicles_.size());
    for (std::size_t i = 0; i < vehicles_.size(); ++i) {
      const Vehicle& v = vehicles_[i];
      speeds[i] =
          std::max(0.0, std::min({v.speed + kAcceleration * kStep, v.wish, speed_limit(int(i))}));
    }
    for (std::size_t i = 0; i < vehicles_.size(); ++i) advance(int(i), speeds[i]);
    release();
  }

  Pose pose(int i) const {
    const Vehicle& v = vehicles_[i];
    const Path& path = v.in_junction ? v.connector->path : layout_.lanes[v.lane].path;
    return ground_pose(layout_, path.at(v.s), 0);
  }
  double travelled(int i) const { return vehicles_[i].travelled; }

 private:
  int node_of(int lane) const { return layout_.lanes[lane].to; }
  double lane_length(int lane) const { return layout_.lanes[lane].path.length(); }

  // Every way across every junction (into any lane of another road), and the tightest of them.
  void make_connectors() {
    for (int lane = 0; lane < int(layout_.lanes.size()); ++lane)
      for (int next : outgoing_[node_of(lane)]) {
        if (layout_.lanes[next].to == layout_.lanes[lane].from) continue;
        Connector c{make_connector(lane, next), {}, 0};
        for (double s = 0; s <= c.path.length(); s += kSample)
          c.samples.push_back(c.path.at(s).position);
        c.curvature = largest_curvature(c.path);
        tightest_[node_of(lane)] = std::max(tightest_[node_of(lane)], c.curvature);
        connectors_.emplace(std::pair(lane, next), std::move(c));
      }
  }

  void choose_next(Vehicle& v) {
    const Lane& in = layout_.lanes[v.lane];
    const V2 in_direction = in.path.at(0).direction;
    std::vector<int> roads;  // one lane per road leaving the junction (not back where it came from)
    for (int l : outgoing_[in.to]) {
      const Lane& out = layout_.lanes[l];
      if (out.to == in.from || out.index != 0) continue;
      roads.push_back(l);
    }
    std::vector<double> weights;
    for (int l : roads)
      weights.push_back(layout_.lanes[l].path.at(0).direction.dot(in_direction) > 0.5 ? 2 : 1);
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

  // Turns at a junction: right on a 6 m corner, left on 10 m. Roundabouts are driven
  // counter-clockwise on a ring round the island, one per lane (4.75 m and 8.25 m; each lane
  // 3 m inside its ring; the outer ring where the lanes differ), except right turns, which take the
  // corner.
  Path make_connector(int lane, int next) const {
    const Lane &in = layout_.lanes[lane], &out = layout_.lanes[next];
    const PathPoint a = in.path.at(in.path.length()), b = out.path.at(0);
    const double cross = a.direction.x() * b.direction.y() - a.direction.y() * b.direction.x();
    if (!layout_.is_roundabout(in.to) || cross < -0.5)
      return turn_path(a.position, a.direction, b.position, b.direction, cross < 0 ? 6 : 10);
    const int ring = std::max(in.index, out.index);
    return roundabout_path(a.position, a.direction, b.position, b.direction,
                           layout_.node_position(in.to), 4.75 + 3.5 * ring, 4.0);
  }

  bool green(int lane, double t) const {
    const int node = node_of(lane);
    if (layout_.is_roundabout(node)) return true;
    const bool along_x = std::abs(layout_.lanes[lane].path.at(0).direction.x()) > 0.5;
    const bool x_phase = int(std::floor((t + light_offset_[node]) / kLightCycle)) % 2 == 0;
    return along_x == x_phase;
  }

  // May cross the junction at the end of its lane (it holds it, or is already in it).
  bool cleared(const Vehicle& v) const { return v.in_junction || v.held == node_of(v.lane); }

  // Rear position of the last vehicle on `lane` (infinity when empty).
  double last_rear(int lane) const {
    double rear = kInf;
    for (const Vehicle& o : vehicles_)
      if (!o.in_junction && o.lane == lane) rear = std::min(rear, o.s - o.length / 2);
    return rear;
  }

  // Someone ahead on its lane who will not cross the junction the same way before it.
  bool blocked_on_lane(int i) const {
    const Vehicle& v = vehicles_[i];
    for (std::size_t k = 0; k < vehicles_.size(); ++k) {
      const Vehicle& o = vehicles_[k];
      if (int(k) != i && !o.in_junction && o.lane == v.lane && o.s > v.s &&
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
      if (v.in_junction || v.held >= 0) continue;
      const double to_stop = lane_length(v.lane) - v.s - v.length / 2;
      const double approach = std::max(kApproach, v.speed * v.speed / (2 * kBraking) + v.speed);
      if (to_stop > approach || !green(v.lane, t) || blocked_on_lane(int(i)) || !room_on_next(v))
        continue;
      const auto& others = occupants_[node];
      if (std::any_of(others.begin(), others.end(),
                      [&](int k) { return conflicts(v, vehicles_[k]); }))
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
      if (!v.in_junction && !o.in_junction && o.lane == v.lane && o.s > v.s) behind(o.s - v.s, o);
      if (cleared(v) && !o.in_junction && o.lane == v.next_lane) behind(to_next + o.s, o);
    }
    if (!cleared(v)) limit = std::min(limit, safe_speed(lane - v.s - half + kStandstill - 0.5, 0));
    double curve = std::min(
        curve_limit_squared(v.connector->path, std::max(0.0, -to_way), std::max(0.0, to_way)),
        curve_limit_squared(layout_.lanes[v.next_lane].path, 0, to_next));
    if (!v.in_junction)
      curve = std::min(curve, curve_limit_squared(layout_.lanes[v.lane].path, v.s, 0));
    const double after = to_next + lane_length(v.next_lane);
    if (tightest_[node_of(v.next_lane)] > 0)
      curve = std::min(curve, kLateral / tightest_[node_of(v.next_lane)] +
                                  2 * kCurveBraking * std::max(0.0, after));
    return std::min(limit, std::sqrt(curve));
  }

  void advance(int i, double speed) {
    Vehicle& v = vehicles_[i];
    v.speed = speed, v.s += speed * kStep, v.travelled += speed * kStep;
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
  Random random_;
  std::vector<Vehicle> vehicles_;
  std::vector<std::vector<int>> outgoing_;
  std::map<std::pair<int, int>, Connector> connectors_;  // by (lane, next lane)
  std::map<std::pair<const Connector*, const Connector*>, double> clearance_;
  std::vector<std::vector<int>> occupants_;  // per junction: the vehicles that may cross it
  std::vector<double> light_offset_;
  std::vector<double> tightest_;  // per junction: the largest curvature of a way across it
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

std::vector<SidewalkLoop> sidewalk_loops(const Layout& layout) {
  std::vector<SidewalkLoop> loops;
  const double width = layout.style.sidewalk;
  for (const Block& block : layout.blocks) {
    if (!block.inner) continue;
    for (const double inset : {0.3 * width + 0.2, 0.8 * width}) {
      const V2 lo = block.lo + V2::Constant(inset), hi = block.hi - V2::Constant(inset);
      std::vector<V2> corners{lo, V2(hi.x(), lo.y()), hi, V2(lo.x(), hi.y())};
      if (loops.size() % 2) std::reverse(corners.begin(), corners.end());  // walk both ways
      loops.push_back({rounded_polyline(corners, 0.5, true)});
    }
  }
  return loops;
}

std::vector<Track> simulate_vehicles(const Layout& layout, const std::vector<VehicleStart>& starts,
                                     double duration, std::uint64_t seed) {
  Traffic traffic(layout, starts, seed);
  std::vector<Track> tracks(starts.size(), Track{kStep, {}, {}});
  const int samples = sample_count(duration);
  for (int n = 0; n < samples; ++n) {
    if (n > 0) traffic.step(n * kStep);
    for (std::size_t i = 0; i < starts.size(); ++i) {
      tracks[i].poses.push_back(traffic.pose(int(i)));
      tracks[i].distance.push_back(traffic.travelled(int(i)));
    }
  }
  return tracks;
}

std::vector<Track> simulate_walkers(const Layout& layout, const std::vector<SidewalkLoop>& loops,
                                    const std::vector<WalkerStart>& starts, double duration) {
  constexpr double kBody = 0.6, kGap = 0.6, kWalkHeadway = 0.8;
  std::vector<double> s(starts.size()), speed(starts.size()), travelled(starts.size(), 0);
  for (std::size_t i = 0; i < starts.size(); ++i) s[i] = starts[i].s, speed[i] = starts[i].speed;
  std::vector<Track> tracks(starts.size(), Track{kStep, {}, {}});
  const int samples = sample_count(duration);
  for (int n = 0; n < samples; ++n) {
    if (n > 0) {
      std::vector<double> next(starts.size());
      for (std::size_t i = 0; i < starts.size(); ++i) {
        const double length = loops[starts[i].loop].path.length();
        double gap = kInf;
        for (std::size_t k = 0; k < starts.size(); ++k)
          if (k != i && starts[k].loop == starts[i].loop)
            gap = std::min(gap, std::fmod(s[k] - s[i] + length, length) - kBody);
        next[i] = next_speed(speed[i], starts[i].speed, gap, kGap, kWalkHeadway, 1.0);
      }
      for (std::size_t i = 0; i < starts.size(); ++i) {
        speed[i] = next[i], travelled[i] += next[i] * kStep;
        s[i] = std::fmod(s[i] + next[i] * kStep, loops[starts[i].loop].path.length());
      }
    }
    for (std::size_t i = 0; i < starts.size(); ++i) {
      tracks[i].poses.push_back(ground_pose(layout, loops[starts[i].loop].path.at(s[i]), kCurb));
      tracks[i].distance.push_back(travelled[i]);
    }
  }
  return tracks;
}

}  // namespace flowscape
