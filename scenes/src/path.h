#pragma once
// Internal: a path in the ground plane with arc-length parameter, made of pieces whose curvature
// changes linearly with length: straight lines, circular arcs and clothoid transitions between
// them. Heading and curvature are continuous along a rounded_polyline, so an actor driving it at a
// smoothly changing speed turns with a continuous yaw rate (no judder).
#include <Eigen/Core>
#include <vector>

namespace flowscape {

struct PathPoint {
  Eigen::Vector2d position, direction;  // unit direction of travel
  double curvature = 0;                 // 1/m, positive turning left
};

class Path {
 public:
  Path() = default;
  explicit Path(std::vector<Eigen::Vector2d> points);  // a polyline of straight pieces
  double length() const { return pieces_.empty() ? 0 : pieces_.back().s0 + pieces_.back().length; }
  PathPoint at(double s) const;  // clamped to [0, length]

  // Where an empty path starts, and its heading.
  void start_at(const Eigen::Vector2d& start, double heading);
  // A piece from the end, continuing its heading: curvature from `curvature` changing linearly at
  // `curvature_rate` per metre over `length`.
  void append(double length, double curvature, double curvature_rate);
  // A straight piece from the end to `target` (a kink if `target` is off the current heading).
  void line_to(const Eigen::Vector2d& target);

  // A piece starting at arc length s0: curvature + curvature_rate * t over t in [0, length].
  struct Piece {
    Eigen::Vector2d start;
    double heading, curvature, curvature_rate, s0, length;
  };
  const std::vector<Piece>& pieces() const { return pieces_; }

 private:
  static PathPoint evaluate(const Piece& piece, double t);
  std::vector<Piece> pieces_;
  Eigen::Vector2d start_ = Eigen::Vector2d::Zero();
  double heading_ = 0;
};

// Straight lines joined at the corners by a circular arc of `radius` between two clothoid
// transitions (each a quarter of the turn; the whole corner shrunk where a side is short: it may
// take half of a side between two corners, all of a first or last side).
Path rounded_polyline(const std::vector<Eigen::Vector2d>& corners, double radius, bool closed);
// The same with a radius per corner, each with transitions or a plain circular arc.
Path rounded_polyline(const std::vector<Eigen::Vector2d>& corners, const std::vector<double>& radii,
                      bool closed, const std::vector<bool>& transitions);
// From `a` heading `da` to `b` heading `db` (perpendicular or parallel): straight, or two lines
// meeting at a corner rounded with `radius`.
Path turn_path(const Eigen::Vector2d& a, const Eigen::Vector2d& da, const Eigen::Vector2d& b,
               const Eigen::Vector2d& db, double radius);

// Counter-clockwise round a ring of `radius` about `centre`, from the end of a lane at `a` heading
// `da` to the start of one at `b` heading `db` (both arms pointing at the centre): a straight,
// two clothoids of length `transition` onto the ring (swinging out first where the lane is inside
// it), the ring as a circular arc, and the mirror image off it. Curvature is continuous.
Path roundabout_path(const Eigen::Vector2d& a, const Eigen::Vector2d& da, const Eigen::Vector2d& b,
                     const Eigen::Vector2d& db, const Eigen::Vector2d& centre, double radius,
                     double transition);

}  // namespace flowscape
