#include "path.h"

#include <algorithm>
#include <array>
#include <cmath>

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
void append_corner(Path& path, double turn, double radius) {
  const double curvature = (turn > 0 ? 1 : -1) / radius;
  const double transition = radius * std::abs(turn) / 2;
  path.append(transition, 0, curvature / transition);
  path.append(radius * std::abs(turn) - transition, curvature, 0);
  path.append(transition, curvature, -curvature / transition);
}

// Distance from the corner back to where its curve starts (and on to where it ends: symmetric).
double tangent_length(double turn, double radius) {
  Path curve;
  append_corner(curve, turn, radius);
  const PathPoint end = curve.at(curve.length());
  return end.position.x() - end.position.y() * std::cos(turn) / std::sin(turn);
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
  const int n = int(corners.size());
  struct Corner {
    V2 start;  // where the curve leaves the straight line
    double heading, turn, radius;
  };
  std::vector<Corner> rounded;
  for (int k = closed ? 0 : 1; k < (closed ? n : n - 1); ++k) {
    const V2 prev = corners[(k + n - 1) % n], here = corners[k], next = corners[(k + 1) % n];
    const V2 d_in = (here - prev).normalized(), d_out = (next - here).normalized();
    const double turn = std::atan2(d_in.x() * d_out.y() - d_in.y() * d_out.x(), d_in.dot(d_out));
    if (std::abs(turn) < 1e-6 || std::abs(turn) > 3.1) continue;  // straight on, or a U-turn
    // the curve scales with its radius; shrink it to at most half of each side
    const double room = std::min((here - prev).norm(), (next - here).norm()) / 2;
    const double tangent = tangent_length(turn, radius), fit = std::min(1.0, room / tangent);
    rounded.push_back(
        {here - fit * tangent * d_in, std::atan2(d_in.y(), d_in.x()), turn, fit * radius});
  }
  Path path;
  const V2 first = closed && !rounded.empty() ? rounded.front().start : corners.front();
  path.start_at(first, 0);
  for (const Corner& c : rounded) {
    path.line_to(c.start);
    if (path.length() == 0) path.start_at(first, c.heading);
    append_corner(path, c.turn, c.radius);
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
