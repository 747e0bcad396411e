#pragma once
// Internal: deterministic traffic on a Layout. Vehicles follow lanes with Gipps' braking rule
// (bounded braking, never closer than a standstill gap, whatever the leader does) and a curve speed
// limit looked ahead, stop at stop lines, and cross a junction when their light is green
// (roundabouts: always), the lane they turn into has room and their way across keeps clear of
// everyone's who may cross it now. Pedestrians walk loops around blocks on the sidewalks, keeping
// their distance.
#include <vector>

#include "city_layout.h"
#include "walk_loops.h"

namespace flowscape {

// Sampled motion of one actor at a fixed step: pose and distance travelled (for wheels and gait).
struct Track {
  double step = 0;
  std::vector<Pose> poses;
  std::vector<double> distance;
  Pose pose(double t) const;  // interpolated; the first / last sample outside the sampled span
  double distance_at(double t) const;
};

struct VehicleStart {
  double length, width;
  int lane;
  double s;           // centre, metres along the lane
  double speed;       // wish speed, m/s (capped by the lane's)
  bool turn = false;  // at the first junction it turns (left or right) where it can
};

struct WalkerStart {
  int loop;
  double s, speed;
};

// Standing at p on the ground `lift` above it, pitched with the ground's slope along p's direction.
Pose ground_pose(const Layout& layout, const PathPoint& p, double lift);

struct TrafficTracks {
  std::vector<Track> vehicles, walkers;  // in the order of their starts
};

// Tracks sampled every 1/60 s from 0 to `duration` (plus one frame). Walkers cross at a crosswalk
// when its signal lets them (the road they cross has red; roundabouts: always) and no vehicle
// that may cross the junction passes it; vehicles are not let across a crosswalk with walkers.
TrafficTracks simulate_traffic(const Layout& layout, const std::vector<SidewalkLoop>& loops,
                               const std::vector<VehicleStart>& vehicles,
                               const std::vector<WalkerStart>& walkers, double duration,
                               std::uint64_t seed);

}  // namespace flowscape
