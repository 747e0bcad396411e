#pragma once
// Internal: how people move. Walking follows the walker's track: the gait phase is the distance
// walked over the stride (stride and so cadence from the walking speed and the height), each foot
// is planted at a fixed point on the ground through its stance (rolling from the heel onto the
// flat foot and off the ball, each contact point fixed while it bears), swung to the next, and the
// legs reach their feet by two-bone inverse kinematics; the pelvis rises and falls to keep both
// feet in reach, arms swing against the legs, the head turns. A walker that stops puts its feet
// down. Riders sit on the saddle, feet on the turning pedals (or the pegs), hands on the grips.
#include <memory>

#include "../traffic.h"
#include "people.h"
#include "vehicles.h"

namespace flowscape::assets {

struct Gait {
  double step = 0.7;        // metres (a stride is two steps)
  double stance = 0.6;      // share of the cycle a foot bears weight (running: less)
  double phase = 0;         // at distance 0, cycles
  double clearance = 0.08;  // how high a swinging foot lifts, metres
  double arm_swing = 0.35;  // radians
  double look_period = 6, look_phase = 0, look_amplitude = 0.35;
  bool umbrella = false;  // the right arm holds an umbrella up
};
// A gait for a person walking at about `speed` m/s (running from 2.2 m/s), varied by `seed`.
Gait gait_for(const Skeleton& skeleton, double speed, std::uint64_t seed, bool umbrella);
// The phase of one who stands and never walks: one foot flat in mid-stance, the other mid-swing,
// which at rest is flat on the ground beside it.
inline constexpr double kStandingPhase = 0.3;

// The pose of `track` where it has covered `distance` metres (extrapolated along its first and
// last heading beyond the span it covers).
Pose pose_at_distance(const Track& track, double distance);

// Where a foot is at time t: its ankle (actor frame), heading and pitch, and whether it bears.
struct FootState {
  V3 ankle_world = V3::Zero();
  double yaw = 0, pitch = 0;  // pitch: toes up positive
  bool planted = false;
  V3 contact_world = V3::Zero();  // heel, sole or ball point that stays put while it bears
};
FootState foot_state(const Skeleton& skeleton, const Gait& gait, const Track& track, int side,
                     double t);

BoneTrack walking(const PersonModel& person, std::shared_ptr<const Track> track, Gait gait);
// The person riding `bike` along `track` (the bike's actor frame is the rider's).
BoneTrack riding(const PersonModel& person, const VehicleModel& bike,
                 std::shared_ptr<const Track> track);
// The height a rider of `bike` should have so its legs reach the pedals (clamped to adults').
double rider_height(const VehicleModel& bike);

}  // namespace flowscape::assets
