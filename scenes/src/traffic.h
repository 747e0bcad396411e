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

inline constexpr double kTrafficStep = 1.0 / 60;  // seconds per simulation step
// Lane changes: over 3 s at the speed when it starts (at least 20 m), no faster until it is done
// (lateral acceleration at most 3.5 * 5.77 / 3^2 = 2.2 m/s^2), done 12 m before the lane's end.
inline constexpr double kChangeSeconds = 3.0, kChangeMinimum = 20.0, kChangeEndMargin = 12.0;

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
  // From this time on (seconds; negative: never) it changes into a lane beside its own as soon as
  // there is room, once, and no other change is made on a whim.
  double change_at = -1;
};

struct WalkerStart {
  int loop;
  double s, speed;
};

// Standing at p on the ground `lift` above it, pitched with the ground's slope along p's direction.
Pose ground_pose(const Layout& layout, const PathPoint& p, double lift);

struct TrafficTracks {
  std::vector<Track> vehicles, walkers;  // in the order of their starts
  std::vector<int> lane_changes;         // per vehicle: the lane changes it began
};

// Tracks sampled every kTrafficStep from 0 to `duration` (plus one frame). Walkers cross at a
// crosswalk when its signal lets them (the road they cross has red; roundabouts: always) and no
// vehicle that may cross the junction passes it; vehicles are not let across a crosswalk with
// walkers.
TrafficTracks simulate_traffic(const Layout& layout, const std::vector<SidewalkLoop>& loops,
                               const std::vector<VehicleStart>& vehicles,
                               const std::vector<WalkerStart>& walkers, double duration,
                               std::uint64_t seed);

}  // namespace flowscape
