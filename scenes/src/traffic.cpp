#include "traffic.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "flowscape/core/random.h"

namespace flowscape {
namespace {

using V2 = Eigen::Vector2d;
constexpr double kFrame = 1 / kFrameRate, kStep = kFrame / 2;  // two simulation steps per frame
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kStandstill = 2.0, kHeadway = 1.0, kAcceleration = 2.5;  // vehicles
constexpr double kLightCycle = 8.0, kApproach = 25.0;

// Safe-speed rule: with a step no longer than the headway, the gap never falls below `standstill`.
double next_speed(double speed, double wish, double gap, double standstill, double headway,
                  double acceleration) {
  const double safe = (gap - standstill) / headway;
  return std::max(0.0, std::min({speed + acceleration * kStep, wish, safe}));
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

struct Vehicle {
  double length = 0, wish = 0;
  int lane = 0, next_lane = -1;
  bool in_junction = false;
  Path connector;
  double s = 0, speed = 0, travelled = 0;
};

class Traffic {
 public:
  Traffic(const Layout& layout, const std::vector<VehicleStart>& starts, std::uint64_t seed)
      : layout_(layout),
        random_(seed),
        holder_(layout.node_height.size(), -1),
        light_offset_(layout.node_height.size()) {
    outgoing_.resize(layout.node_height.size());
    for (int l = 0; l < int(layout.lanes.size()); ++l) outgoing_[layout.lanes[l].from].push_back(l);
    for (double& offset : light_offset_) offset = random_.uniform(0, 2 * kLightCycle);
    for (const VehicleStart& start : starts) {
      Vehicle v;
      v.length = start.length, v.wish = std::min(start.speed, layout.lanes[start.lane].speed);
      v.lane = start.lane, v.s = start.s, v.next_lane = choose_next(start.lane);
      v.speed = v.wish;  // already driving; the first step brakes if the road ahead is not free
      vehicles_.push_back(std::move(v));
    }
  }

  void step(double t) {
    grant(t);
    std::vector<double> speeds(vehicles_.size());
    for (std::size_t i = 0; i < vehicles_.size(); ++i) {
      const Vehicle& v = vehicles_[i];
      speeds[i] = next_speed(v.speed, v.wish, gap(int(i)), kStandstill, kHeadway, kAcceleration);
    }
    for (std::size_t i = 0; i < vehicles_.size(); ++i) advance(int(i), speeds[i]);
    release();
  }

  Pose pose(int i) const {
    const Vehicle& v = vehicles_[i];
    const Path& path = v.in_junction ? v.connector : layout_.lanes[v.lane].path;
    return ground_pose(layout_, path.at(v.s), 0);
  }
  double travelled(int i) const { return vehicles_[i].travelled; }

 private:
  int node_of(int lane) const { return layout_.lanes[lane].to; }

  int choose_next(int lane) {
    const Lane& in = layout_.lanes[lane];
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
    return road;
  }

  Path make_connector(int lane, int next) const {
    const Lane &in = layout_.lanes[lane], &out = layout_.lanes[next];
    const PathPoint a = in.path.at(in.path.length()), b = out.path.at(0);
    if (!layout_.is_roundabout(in.to)) {
      const double cross = a.direction.x() * b.direction.y() - a.direction.y() * b.direction.x();
      return turn_path(a.position, a.direction, b.position, b.direction, cross < 0 ? 6 : 10);
    }
    // counter-clockwise round an island at the junction's centre, on an octagon's rounded corners
    const V2 centre = layout_.node_position(in.to);
    const double radius = 4.6 / std::cos(kPi / 8);
    const auto angle = [&](const V2& p) {
      return std::atan2(p.y() - centre.y(), p.x() - centre.x());
    };
    const double start = angle(a.position);
    double end = angle(b.position);
    while (end <= start + 0.3) end += 2 * kPi;
    std::vector<V2> corners{a.position};
    for (int k = -8; k < 24; ++k) {
      const double c = (k + 0.5) * kPi / 4;
      if (c > start + 0.2 && c < end - 0.2)
        corners.push_back(centre + radius * V2(std::cos(c), std::sin(c)));
    }
    corners.push_back(b.position);
    return rounded_polyline(corners, 3.0, false);
  }

  bool green(int lane, double t) const {
    const int node = node_of(lane);
    if (layout_.is_roundabout(node)) return true;
    const bool along_x = std::abs(layout_.lanes[lane].path.at(0).direction.x()) > 0.5;
    const bool x_phase = int(std::floor((t + light_offset_[node]) / kLightCycle)) % 2 == 0;
    return along_x == x_phase;
  }

  // Rear position of the last vehicle on `lane` (infinity when empty).
  double last_rear(int lane) const {
    double rear = kInf;
    for (const Vehicle& o : vehicles_)
      if (!o.in_junction && o.lane == lane) rear = std::min(rear, o.s - o.length / 2);
    return rear;
  }

  bool ahead_on_lane(int i) const {
    const Vehicle& v = vehicles_[i];
    for (std::size_t k = 0; k < vehicles_.size(); ++k)
      if (int(k) != i && !vehicles_[k].in_junction && vehicles_[k].lane == v.lane &&
          vehicles_[k].s > v.s)
        return true;
    return false;
  }

  void grant(double t) {
    for (std::size_t i = 0; i < vehicles_.size(); ++i) {
      Vehicle& v = vehicles_[i];
      const int node = node_of(v.lane);
      if (v.in_junction || holder_[node] >= 0) continue;
      const double to_stop = layout_.lanes[v.lane].path.length() - v.s - v.length / 2;
      if (to_stop > kApproach || !green(v.lane, t) || ahead_on_lane(int(i))) continue;
      if (last_rear(v.next_lane) < v.length + kStandstill + 2) continue;
      holder_[node] = int(i);
      v.connector = make_connector(v.lane, v.next_lane);
    }
  }

  // Free road ahead of vehicle i's front bumper up to the next rear bumper or stop line.
  double gap(int i) const {
    const Vehicle& v = vehicles_[i];
    const double half = v.length / 2;
    double gap = kInf;
    const auto consider = [&](double distance_to_centre, const Vehicle& o) {
      gap = std::min(gap, distance_to_centre - half - o.length / 2);
    };
    const double lane_length = layout_.lanes[v.lane].path.length();
    const bool holds = holder_[node_of(v.lane)] == i;
    if (v.in_junction) {
      for (const Vehicle& o : vehicles_)
        if (!o.in_junction && o.lane == v.next_lane) consider(v.connector.length() - v.s + o.s, o);
      return gap;
    }
    for (std::size_t k = 0; k < vehicles_.size(); ++k) {
      const Vehicle& o = vehicles_[k];
      if (int(k) == i) continue;
      if (!o.in_junction && o.lane == v.lane && o.s > v.s) consider(o.s - v.s, o);
      if (o.in_junction && o.lane == v.lane) consider(lane_length - v.s + o.s, o);
      if (holds && !o.in_junction && o.lane == v.next_lane)
        consider(lane_length - v.s + v.connector.length() + o.s, o);
    }
    if (!holds) gap = std::min(gap, lane_length - v.s - half + kStandstill - 0.5);
    return gap;
  }

  void advance(int i, double speed) {
    Vehicle& v = vehicles_[i];
    v.speed = speed, v.s += speed * kStep, v.travelled += speed * kStep;
    if (!v.in_junction && v.s > layout_.lanes[v.lane].path.length()) {
      v.s -= layout_.lanes[v.lane].path.length();
      v.in_junction = true;
    }
    if (v.in_junction && v.s > v.connector.length()) {
      v.s -= v.connector.length();
      v.in_junction = false;
      v.lane = v.next_lane;
      v.next_lane = choose_next(v.lane);
    }
  }

  void release() {
    for (int& holder : holder_) {
      if (holder < 0) continue;
      const Vehicle& v = vehicles_[holder];
      if (!v.in_junction && layout_.lanes[v.lane].from == int(&holder - holder_.data()) &&
          v.s > v.length / 2 + 0.5)
        holder = -1;
    }
  }

  const Layout& layout_;
  Random random_;
  std::vector<Vehicle> vehicles_;
  std::vector<std::vector<int>> outgoing_;
  std::vector<int> holder_;  // per junction: the vehicle crossing it, or -1
  std::vector<double> light_offset_;
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
