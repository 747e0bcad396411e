#include "path.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "flowscape/core/types.h"

namespace flowscape {
namespace {

using V2 = Eigen::Vector2d;

V2 unit(double angle) { return {std::cos(angle), std::sin(angle)}; }

// integral over [0, t] of (cos, sin) of heading + curvature u + rate u^2 / 2: Gauss-Legendre with
// 8 nodes on pieces of at most 1 m (a clothoid has no elementary closed form; this is exact to
// about 1e-12 m for the turns of a city).
V2 clothoid_offset(double heading, double curvature, double rate, double t) {
  static constexpr std::array<double, 4> kNodes{0.1834346424956498, 0.5255324099163290,
                                                0.7966664774136267, 0.9602898564975363};
  static constexpr std::array<double, 4> kWeights{0.3626837833783620, 0.3137066458778873,
                                                  0.2223810344533745, 0.1012285362903763};
  const int intervals = std::max(1, int(std::ceil(t)));
  const double h = t / intervals;
  V2 sum = V2::Zero();
  for (int i = 0; i < intervals; ++i) {
    const double mid = (i + 0.5) * h;
    for (int k = 0; k < 4; ++k)
      for (double side : {-1.0, 1.0}) {
        const double u = mid + side * kNodes[k] * h / 2;
        sum += kWeights[k] * h / 2 * unit(heading + curvature * u + rate * u * u / 2);
      }
  }
  return sum;
}

// A corner's curve, appended to `path`: a clothoid transition, an arc of `radius`, a transition;
// each transition turns a quarter of `turn`, so curvature rises and falls linearly.
void append_corner(Path& path, double turn, double radius, bool transitions = true) {
  const double curvature = (turn > 0 ? 1 : -1) / radius;
  if (!transitions) return path.append(radius * std::abs(turn), curvature, 0);
  const double transition = radius * std::abs(turn) / 2;
  path.append(transition, 0, curvature / transition);
  path.append(radius * std::abs(turn) - transition, curvature, 0);
  path.append(transition, curvature, -curvature / transition);
}

// Distance from the corner back to where its curve starts (and on to where it ends: symmetric).
double tangent_length(double turn, double radius, bool transitions = true) {
  if (!transitions) return radius * std::tan(std::abs(turn) / 2);
  Path curve;
  append_corner(curve, turn, radius);
  const PathPoint end = curve.at(curve.length());
  return end.position.x() - end.position.y() * std::cos(turn) / std::sin(turn);
}

// How a lane `offset` metres right of an arm's axis joins a ring of `radius` round the junction
// centre, driven counter-clockwise: in the arm's frame (heading +y, towards the centre) two
// clothoids of length `transition`, curvature 0 -> swing -> 1 / radius, the swing solved (by
// bisection) so that the ring they end on is centred on the arm's axis.
struct RingJoin {
  double swing;
  V2 end;         // where the ring starts, relative to its centre
  double before;  // distance from the start of the clothoids to the centre, along the arm
};

V2 ring_centre_of(double offset, double radius, double swing, double transition, V2* end) {
  Path join;
  join.start_at(V2(offset, 0), kPi / 2);
  join.append(transition, 0, swing / transition);
  join.append(transition, swing, (1 / radius - swing) / transition);
  const PathPoint p = join.at(join.length());
  *end = p.position;
  return p.position + radius * V2(-p.direction.y(), p.direction.x());
}

RingJoin ring_join(double offset, double radius, double transition) {
  double lo = -0.5, hi = 0;  // swing (to the right): the centre moves left as it falls to 0
  V2 end;
  const auto centre_x = [&](double swing) {
    return ring_centre_of(offset, radius, swing, transition, &end).x();
  };
  if (centre_x(lo) < 0 || centre_x(hi) > 0)
    throw std::logic_error("a lane " + std::to_string(offset) + " m off the axis cannot join a " +
                           std::to_string(radius) + " m ring");
  for (int k = 0; k < 60; ++k) (centre_x((lo + hi) / 2) > 0 ? lo : hi) = (lo + hi) / 2;
  const V2 centre = ring_centre_of(offset, radius, lo, transition, &end);
  return {lo, end - centre, centre.y()};
}

}  // namespace

Path::Path(std::vector<V2> points) {
  if (points.empty()) return;
  start_ = points.front();
  for (const V2& point : points) line_to(point);
}

void Path::start_at(const V2& start, double heading) { start_ = start, heading_ = heading; }

void Path::line_to(const V2& target) {
  const V2 end = at(length()).position, step = target - end;
  if (step.norm() == 0) return;
  pieces_.push_back({end, std::atan2(step.y(), step.x()), 0, 0, length(), step.norm()});
}

void Path::append(double length, double curvature, double curvature_rate) {
  if (length <= 0) return;
  const PathPoint end = at(this->length());
  pieces_.push_back({end.position, std::atan2(end.direction.y(), end.direction.x()), curvature,
                     curvature_rate, this->length(), length});
}

PathPoint Path::evaluate(const Piece& p, double t) {
  const double heading = p.heading + p.curvature * t + p.curvature_rate * t * t / 2;
  V2 offset;
  if (p.curvature_rate != 0)
    offset = clothoid_offset(p.heading, p.curvature, p.curvature_rate, t);
  else if (p.curvature != 0)  // a circular arc, in closed form
    offset = V2(std::sin(heading) - std::sin(p.heading), std::cos(p.heading) - std::cos(heading)) /
             p.curvature;
  else
    offset = t * unit(p.heading);
  return {p.start + offset, unit(heading), p.curvature + p.curvature_rate * t};
}

PathPoint Path::at(double s) const {
  if (pieces_.empty()) return {start_, unit(heading_), 0};
  s = std::clamp(s, 0.0, length());
  const auto piece = std::upper_bound(pieces_.begin(), pieces_.end(), s,
                                      [](double v, const Piece& p) { return v < p.s0; });
  const Piece& p = *(piece == pieces_.begin() ? piece : piece - 1);
  return evaluate(p, std::min(s - p.s0, p.length));
}

Path rounded_polyline(const std::vector<V2>& corners, double radius, bool closed) {
  return rounded_polyline(corners, std::vector<double>(corners.size(), radius), closed,
                          std::vector<bool>(corners.size(), true));
}

Path rounded_polyline(const std::vector<V2>& corners, const std::vector<double>& radii, bool closed,
                      const std::vector<bool>& transitions) {
  const int n = int(corners.size());
  struct Corner {
    V2 start;  // where the curve leaves the straight line
    double heading, turn, radius;
    bool transitions;
  };
  std::vector<Corner> rounded;
  for (int k = closed ? 0 : 1; k < (closed ? n : n - 1); ++k) {
    const V2 prev = corners[(k + n - 1) % n], here = corners[k], next = corners[(k + 1) % n];
    const V2 d_in = (here - prev).normalized(), d_out = (next - here).normalized();
    const double turn = std::atan2(d_in.x() * d_out.y() - d_in.y() * d_out.x(), d_in.dot(d_out));
    if (std::abs(turn) < 1e-6 || std::abs(turn) > 3.1) continue;  // straight on, or a U-turn
    // the curve scales with its radius; shrink it to fit: at most half of a side shared with
    // another corner, all of an open polyline's first or last side
    const auto share = [&](int end) { return !closed && (end == 0 || end == n - 1) ? 1.0 : 0.5; };
    const double room =
        std::min((here - prev).norm() * share(k - 1), (next - here).norm() * share(k + 1));
    const double tangent = tangent_length(turn, radii[k], transitions[k]);
    const double fit = std::min(1.0, room / tangent);
    rounded.push_back({here - fit * tangent * d_in, std::atan2(d_in.y(), d_in.x()), turn,
                       fit * radii[k], transitions[k]});
  }
  Path path;
  const V2 first = closed && !rounded.empty() ? rounded.front().start : corners.front();
  path.start_at(first, 0);
  for (const Corner& c : rounded) {
    path.line_to(c.start);
    if (path.length() == 0) path.start_at(first, c.heading);
    append_corner(path, c.turn, c.radius, c.transitions);
  }
  path.line_to(closed ? first : corners.back());
  return path;
}

Path turn_path(const V2& a, const V2& da, const V2& b, const V2& db, double radius) {
  const double cross = da.x() * db.y() - da.y() * db.x();
  if (std::abs(cross) < 1e-9) return Path({a, b});
  const double u = ((b - a).x() * db.y() - (b - a).y() * db.x()) / cross;  // a + u da on b's line
  return rounded_polyline({a, a + u * da, b}, radius, false);
}

}  // namespace flowscape

namespace flowscape {

Path roundabout_path(const V2& a, const V2& da, const V2& b, const V2& db, const V2& centre,
                     double radius, double transition) {
  const auto right = [](const V2& d) { return V2(d.y(), -d.x()); };
  const RingJoin in = ring_join((a - centre).dot(right(da)), radius, transition);
  const RingJoin out = ring_join((b - centre).dot(right(db)), radius, transition);
  const double straight = (centre - a).dot(da) - in.before;
  if (straight < 0)
    throw std::logic_error("a roundabout's ring does not fit before its stop lines");
  // the ring's start and end in the world: the entry's end in the entry arm's frame, the exit's
  // the mirror image (x -> -x) of an entry on the exit arm, whose frame heads along -db
  const V2 start = in.end.x() * right(da) + in.end.y() * da;
  const V2 end = -out.end.x() * right(-db) - out.end.y() * db;
  double turn = std::atan2(end.y(), end.x()) - std::atan2(start.y(), start.x());
  while (turn <= 0) turn += 2 * kPi;
  Path path;
  path.start_at(a, std::atan2(da.y(), da.x()));
  path.append(straight, 0, 0);
  path.append(transition, 0, in.swing / transition);
  path.append(transition, in.swing, (1 / radius - in.swing) / transition);
  path.append(radius * turn, 1 / radius, 0);
  path.append(transition, 1 / radius, (out.swing - 1 / radius) / transition);
  path.append(transition, out.swing, -out.swing / transition);
  path.line_to(b);
  return path;
}

}  // namespace flowscape
