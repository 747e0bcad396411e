#pragma once
// The vector and pose types and the constants every stage shares (design.md: right-handed world,
// z up, metres, seconds, frames at 30 Hz).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace flowscape {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Pose = Eigen::Isometry3d;  // object -> world (metres; z up)

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kFrameRate = 30;  // frames per second of every sequence (design.md)

// The farthest any position of a scene, rig or path may lie from the world's origin (metres):
// 1,000 km. Embree traces in single precision (steps of 6 cm there) and aborts on coordinates
// beyond 1.8e18, so readers refuse anything farther (docs/renderer.md, "Embree's kernels").
inline constexpr double kFarthestPosition = 1e6;
// Whether every coordinate of `position` is finite and within kFarthestPosition.
inline bool within_world(const Vec3& position) {
  return position.allFinite() && position.cwiseAbs().maxCoeff() <= kFarthestPosition;
}

// The heading of a pose: the angle of its x axis in the world's xy plane (radians, left positive).
inline double yaw_of(const Pose& pose) {
  return std::atan2(pose.linear()(1, 0), pose.linear()(0, 0));
}
// An angle (radians) wrapped to [-pi, pi].
inline double wrapped_angle(double radians) { return std::remainder(radians, 2 * kPi); }

}  // namespace flowscape
