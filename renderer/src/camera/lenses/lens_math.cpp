#include "camera/lenses/lens_math.h"

#include <algorithm>
#include <stdexcept>

namespace flowscape::lens {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

double number(const nlohmann::json& p, const char* key, std::optional<double> fallback) {
  if (!p.is_object() || !p.contains(key)) {
    require(fallback.has_value(), std::string("lens parameter \"") + key + "\" is missing");
    return *fallback;
  }
  const nlohmann::json& v = p.at(key);
  require(v.is_number() && std::isfinite(v.get<double>()),
          std::string("lens parameter \"") + key + "\" must be a finite number");
  return v.get<double>();
}

std::vector<double> numbers(const nlohmann::json& p, const char* key, std::size_t count,
                            std::optional<std::vector<double>> fallback) {
  if (!p.is_object() || !p.contains(key)) {
    require(fallback.has_value(), std::string("lens parameter \"") + key + "\" is missing");
    return *fallback;
  }
  const nlohmann::json& v = p.at(key);
  const std::string what = std::string("lens parameter \"") + key + "\" must be a list of " +
                           std::to_string(count) + " finite numbers";
  require(v.is_array() && v.size() == count, what);
  std::vector<double> out;
  for (const nlohmann::json& x : v) {
    require(x.is_number() && std::isfinite(x.get<double>()), what);
    out.push_back(x.get<double>());
  }
  return out;
}

Intrinsics intrinsics(const nlohmann::json& p) {
  const std::string what =
      "lens parameter \"K\" must be 3 rows of 3 finite numbers "
      "[[fx, 0, cx], [0, fy, cy], [0, 0, 1]]";
  require(p.is_object() && p.contains("K") && p.at("K").is_array(), what);
  const nlohmann::json& k = p.at("K");
  std::vector<std::vector<double>> rows;
  if (k.size() == 9) {  // flat, row by row, as cv::FileStorage writes a matrix's "data"
    const std::vector<double> flat = numbers(p, "K", 9);
    for (int r = 0; r < 3; ++r) rows.emplace_back(flat.begin() + 3 * r, flat.begin() + 3 * r + 3);
  } else {
    require(k.size() == 3, what + " (or 9 numbers row by row)");
    for (const nlohmann::json& row : k) rows.push_back(numbers({{"K", row}}, "K", 3));
  }
  require(rows[0][1] == 0 && rows[1][0] == 0 && rows[2] == std::vector<double>{0, 0, 1}, what);
  require(rows[0][0] > 0 && rows[1][1] > 0, "lens focal lengths fx, fy must be positive");
  return {rows[0][0], rows[1][1], rows[0][2] + 0.5, rows[1][2] + 0.5};
}

int dimension(const nlohmann::json& p, const char* key) {
  const double v = number(p, key);
  require(v >= 2 && v <= 16384 && v == std::floor(v),
          std::string("lens parameter \"") + key + "\" must be a whole number in 2..16384");
  return int(v);
}

double solve_increasing(const std::function<double(double)>& f,
                        const std::function<double(double)>& slope, double y, double lo,
                        double hi) {
  double x = 0.5 * (lo + hi);
  for (int i = 0; i < 100; ++i) {
    const double value = f(x) - y;
    if (value == 0) return x;
    (value < 0 ? lo : hi) = x;
    const double d = slope(x);
    double next = d > 0 ? x - value / d : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - x) <= 1e-15 * std::max(1.0, std::abs(x))) return next;
    x = next;
  }
  return x;
}

double increasing_until(const std::function<double(double)>& f, double limit) {
  constexpr int kSteps = 20000;
  double previous = f(0);
  for (int i = 1; i <= kSteps; ++i) {
    const double x = limit * i / kSteps, value = f(x);
    if (!(value > previous)) return limit * (i - 1) / kSteps;
    previous = value;
  }
  return limit;
}

void RadialLens::finish(int width, int height, double fx, double fy, double cx, double cy,
                        double max_angle) {
  width_ = width, height_ = height, fx_ = fx, fy_ = fy, cx_ = cx, cy_ = cy;
  max_angle_ = max_angle;
  require(fx > 0 && fy > 0, "lens focal lengths must be positive");
  require(max_angle > 0 && max_angle < kPi, "lens max_angle_degrees must be in (0, 180)");
  require(increasing_until([this](double t) { return radius(t); }, max_angle) >= max_angle,
          "lens distortion folds back before max_angle_degrees: the model cannot reach it");
}

std::optional<Vec3> RadialLens::ray(Vec2 pixel) const {
  const Vec2 m((pixel.x() - cx_) / fx_, (pixel.y() - cy_) / fy_);
  const double rho = m.norm();
  if (rho > radius(max_angle_)) return std::nullopt;  // outside the image circle
  if (rho == 0) return Vec3::UnitZ();
  const double theta =
      solve_increasing([this](double t) { return radius(t); },
                       [this](double t) { return radius_slope(t); }, rho, 0, max_angle_);
  const double s = std::sin(theta) / rho;
  return Vec3(s * m.x(), s * m.y(), std::cos(theta));
}

std::optional<Vec2> RadialLens::project(const Vec3& d) const {
  const double r = std::hypot(d.x(), d.y()), theta = std::atan2(r, d.z());
  if (theta > max_angle_ || !(d.squaredNorm() > 0)) return std::nullopt;
  if (r == 0) return Vec2(cx_, cy_);
  const double g = radius(theta) / r;
  return Vec2(cx_ + fx_ * g * d.x(), cy_ + fy_ * g * d.y());
}

}  // namespace flowscape::lens
