// Where the rig rides on the ego vehicle: its random mount and the sway along the road.
#include <cmath>

#include "flowscape/core/random.h"
#include "flowscape/scenes/city.h"

namespace flowscape {

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

}  // namespace flowscape
