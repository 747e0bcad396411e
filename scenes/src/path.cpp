#include "path.h"

#include <algorithm>
#include <cmath>

namespace flowscape {

using V2 = Eigen::Vector2d;

Path::Path(std::vector<V2> points) : points_(std::move(points)) {
  lengths_.assign(points_.size(), 0);
  for (std::size_t k = 1; k < points_.size(); ++k)
    lengths_[k] = lengths_[k - 1] + (points_[k] - points_[k - 1]).norm();
}

PathPoint Path::at(double s) const {
  if (points_.size() < 2) return {points_.empty() ? V2::Zero() : points_[0], V2::UnitX()};
  s = std::clamp(s, 0.0, length());
  std::size_t k = std::upper_bound(lengths_.begin(), lengths_.end(), s) - lengths_.begin();
  k = std::clamp<std::size_t>(k, 1, points_.size() - 1);
  while (k + 1 < points_.size() && lengths_[k] == lengths_[k - 1]) ++k;  // skip repeated points
  const double span = lengths_[k] - lengths_[k - 1];
  const V2 direction = span > 0 ? V2((points_[k] - points_[k - 1]) / span) : V2::UnitX();
  return {points_[k - 1] + (s - lengths_[k - 1]) * direction, direction};
}

Path rounded_polyline(const std::vector<V2>& corners, double radius, bool closed) {
  const int n = int(corners.size());
  std::vector<V2> points;
  if (!closed) points.push_back(corners.front());
  for (int k = closed ? 0 : 1; k < (closed ? n : n - 1); ++k) {
    const V2 prev = corners[(k + n - 1) % n], here = corners[k], next = corners[(k + 1) % n];
    const V2 d_in = (here - prev).normalized(), d_out = (next - here).normalized();
    const double turn = std::atan2(d_in.x() * d_out.y() - d_in.y() * d_out.x(), d_in.dot(d_out));
    if (std::abs(turn) < 1e-6) {
      points.push_back(here);
      continue;
    }
    const double tangent = std::min({radius * std::tan(std::abs(turn) / 2),
                                     (here - prev).norm() / 2, (next - here).norm() / 2});
    const double r = tangent / std::tan(std::abs(turn) / 2);
    const V2 start = here - tangent * d_in;
    const V2 normal = turn > 0 ? V2(-d_in.y(), d_in.x()) : V2(d_in.y(), -d_in.x());
    const V2 centre = start + r * normal;
    const int steps = std::max(2, int(std::ceil(std::abs(turn) / 0.12)));
    const double a0 = std::atan2(start.y() - centre.y(), start.x() - centre.x());
    for (int i = 0; i <= steps; ++i) {
      const double a = a0 + turn * i / steps;
      points.push_back(centre + r * V2(std::cos(a), std::sin(a)));
    }
  }
  if (closed)
    points.push_back(points.front());
  else
    points.push_back(corners.back());
  return Path(std::move(points));
}

Path turn_path(const V2& a, const V2& da, const V2& b, const V2& db, double radius) {
  const double cross = da.x() * db.y() - da.y() * db.x();
  if (std::abs(cross) < 1e-9) return Path({a, b});
  const double u = ((b - a).x() * db.y() - (b - a).y() * db.x()) / cross;  // a + u da on b's line
  return rounded_polyline({a, a + u * da, b}, radius, false);
}

}  // namespace flowscape
