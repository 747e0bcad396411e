#pragma once
// Test helper: actors' footprints on the ground, measured from their posed triangles, and whether
// two footprints overlap.
#include <Eigen/Geometry>
#include <algorithm>
#include <array>

#include "flowscape/scenes/skinning.h"

namespace flowscape::test {

using V2 = Eigen::Vector2d;

// An oriented rectangle in the ground plane: centre, unit axes and half extents.
struct Box2 {
  V2 centre, axis[2];
  double half[2];
};

// The footprint of an actor at time t, measured from its own triangles (every part posed).
inline Box2 footprint(const Actor& actor, double t) {
  const Pose pose = actor.pose(t);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
  for (const Part& part : actor.parts) {
    for (const Eigen::Vector3d& p : part_vertices_at(part, t))  // already in the actor's frame
      lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  const Eigen::Vector3d centre = pose * ((lo + hi) / 2);
  const Eigen::Matrix3d r = pose.linear();
  return {centre.head<2>(),
          {r.col(0).head<2>().normalized(), r.col(1).head<2>().normalized()},
          {(hi.x() - lo.x()) / 2, (hi.y() - lo.y()) / 2}};
}

inline std::array<V2, 4> corners(const Box2& b) {
  const V2 u = b.axis[0] * b.half[0], v = b.axis[1] * b.half[1];
  return {b.centre - u - v, b.centre + u - v, b.centre + u + v, b.centre - u + v};
}

// Separating-axis test of two convex quadrilaterals (touching counts as apart).
inline bool overlap(const std::array<V2, 4>& a, const std::array<V2, 4>& b) {
  for (const auto* poly : {&a, &b})
    for (int k = 0; k < 4; ++k) {
      const V2 edge = (*poly)[(k + 1) % 4] - (*poly)[k], normal(-edge.y(), edge.x());
      double a_lo = 1e18, a_hi = -1e18, b_lo = 1e18, b_hi = -1e18;
      for (const V2& p : a)
        a_lo = std::min(a_lo, normal.dot(p)), a_hi = std::max(a_hi, normal.dot(p));
      for (const V2& p : b)
        b_lo = std::min(b_lo, normal.dot(p)), b_hi = std::max(b_hi, normal.dot(p));
      if (a_hi <= b_lo || b_hi <= a_lo) return false;
    }
  return true;
}

}  // namespace flowscape::test
