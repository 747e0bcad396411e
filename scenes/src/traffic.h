#pragma once
// Internal: deterministic traffic on a Layout. Vehicles follow lanes with Gipps' braking rule
// (bounded braking, never closer than a standstill gap, whatever the leader does) and a curve speed
// limit looked ahead, stop at stop lines, and cross a junction when their light is green
// (roundabouts: always), the lane they turn into has room and their way across keeps clear of
// everyone's who may cross it now. Pedestrians walk loops around blocks on the sidewalks, keeping
// their distance.
#include <vector>

#include "city_layout.h"

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
  double s;      // centre, metres along the lane
  double speed;  // wish speed, m/s (capped by the lane's)
};

struct WalkerStart {
  int loop;
  double s, speed;
};

struct SidewalkLoop {
  Path path;  // closed
};

std::vector<SidewalkLoop> sidewalk_loops(const Layout& layout);

// Tracks sampled every 1/60 s from 0 to `duration` (plus one frame), in the order given.
std::vector<Track> simulate_vehicles(const Layout& layout, const std::vector<VehicleStart>& starts,
                                     double duration, std::uint64_t seed);
std::vector<Track> simulate_walkers(const Layout& layout, const std::vector<SidewalkLoop>& loops,
                                    const std::vector<WalkerStart>& starts, double duration);

}  // namespace flowscape
