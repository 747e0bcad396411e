#pragma once
// Internal: a polyline in the ground plane with arc-length parameter.
#include <Eigen/Core>
#include <vector>

namespace flowscape {

struct PathPoint {
  Eigen::Vector2d position, direction;  // unit direction of travel
};

class Path {
 public:
  Path() = default;
  explicit Path(std::vector<Eigen::Vector2d> points);
  double length() const { return lengths_.empty() ? 0 : lengths_.back(); }
  PathPoint at(double s) const;  // clamped to [0, length]
  const std::vector<Eigen::Vector2d>& points() const { return points_; }

 private:
  std::vector<Eigen::Vector2d> points_;
  std::vector<double> lengths_;  // cumulative, from 0
};

// Straight lines joined by circular arcs of `radius` at the corners (smaller where a side is
// short).
Path rounded_polyline(const std::vector<Eigen::Vector2d>& corners, double radius, bool closed);
// From `a` heading `da` to `b` heading `db` (perpendicular or parallel): straight, or two lines
// meeting at a corner rounded with `radius`.
Path turn_path(const Eigen::Vector2d& a, const Eigen::Vector2d& da, const Eigen::Vector2d& b,
               const Eigen::Vector2d& db, double radius);

}  // namespace flowscape
