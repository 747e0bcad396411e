#include "render/lights.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "render/sampling.h"

namespace flowscape {
namespace {

constexpr double kLampCell = 16;  // metres
// A lamp lights points within 80 m that it gives more than 1e-6 (sky units before the exposure:
// under 1 % of a street lamp's light beneath it)
constexpr double kLampFloor = 1e-6, kLampReach = 80;
constexpr std::size_t kMaxLampCells = 1 << 22;

}  // namespace

LampLights::LampLights(const Scene& scene, double time) {
  const double level = scene.environment.lamp_level;
  if (!(level > 0) || scene.lamps.empty()) return;
  Eigen::AlignedBox2d bounds;
  for (const Lamp& lamp : scene.lamps) {
    const Pose pose = lamp.actor < 0 ? Pose::Identity() : scene.actors[lamp.actor].pose(time);
    const Rgb intensity = lamp.intensity.cast<double>() * level;
    const double brightest = luminance(intensity);
    if (!(brightest > 0)) continue;
    lamps_.push_back({pose * lamp.position, (pose.linear() * lamp.axis).normalized(),
                      lamp.cos_inner, lamp.cos_outer, intensity,
                      std::min(kLampReach, std::sqrt(brightest / (kLampFloor * level)))});
    bounds.extend(lamps_.back().position.head<2>());
  }
  if (lamps_.empty()) return;
  double reach = 0;
  for (const Posed& lamp : lamps_) reach = std::max(reach, lamp.reach);
  origin_ = bounds.min() - Vec2::Constant(reach);
  const Vec2 size = bounds.sizes() + Vec2::Constant(2 * reach);
  columns_ = int(std::ceil(size.x() / kLampCell)) + 1,
  rows_ = int(std::ceil(size.y() / kLampCell)) + 1;
  if (std::size_t(columns_) * rows_ > kMaxLampCells)
    throw std::invalid_argument("scene lamps: spread over more than " +
                                std::to_string(kMaxLampCells) + " cells of 16 m");
  cells_.resize(std::size_t(columns_) * rows_);
  float lowest = std::numeric_limits<float>::infinity();  // the world's lowest point
  for (const Eigen::Vector3f& v : scene.world.vertices) lowest = std::min(lowest, v.z());
  for (int k = 0; k < int(lamps_.size()); ++k) {
    const Posed& lamp = lamps_[k];
    const Vec2 lo = (lamp.position.head<2>() - origin_ - Vec2::Constant(lamp.reach)) / kLampCell;
    const Vec2 hi = (lamp.position.head<2>() - origin_ + Vec2::Constant(lamp.reach)) / kLampCell;
    for (int r = std::max(0, int(lo.y())); r <= std::min(rows_ - 1, int(hi.y())); ++r)
      for (int c = std::max(0, int(lo.x())); c <= std::min(columns_ - 1, int(hi.x())); ++c)
        if (may_light(lamp, origin_ + kLampCell * Vec2(c, r), std::min(double(lowest), 0.0)))
          cells_[std::size_t(r) * columns_ + c].push_back(k);
  }
}

// Whether a lamp's beam may reach the column over a cell (conservative): within its reach; a beam
// tilted down so far that it never meets the horizon reaches (height above the world's lowest
// point) x tan(its steepest angle from the vertical) sideways; any other beam stays within a wedge
// of azimuths about its axis.
bool LampLights::may_light(const Posed& lamp, const Vec2& cell_lo, double lowest) const {
  const Vec2 centre = cell_lo + Vec2::Constant(kLampCell / 2);
  const double radius = kLampCell / std::sqrt(2.0);
  const Vec2 to_cell = centre - lamp.position.head<2>();
  const double distance = to_cell.norm();
  if (distance - radius > lamp.reach) return false;
  if (lamp.cos_outer <= -1 || distance <= radius) return true;
  const double outer = std::acos(lamp.cos_outer),
               below = std::acos(std::clamp(-lamp.axis.z(), -1.0, 1.0));
  if (below + outer < kPi / 2 - 1e-6)
    return distance - radius <= (lamp.position.z() - lowest) * std::tan(below + outer);
  const double elevation = std::asin(std::clamp(lamp.axis.z(), -1.0, 1.0));
  if (outer + std::abs(elevation) >= kPi / 2 - 1e-6 || lamp.axis.head<2>().norm() < 1e-9)
    return true;
  const double half_wedge = std::asin(std::min(1.0, std::sin(outer) / std::cos(elevation)));
  const double off_axis = std::acos(std::clamp(
      to_cell.dot(lamp.axis.head<2>()) / (distance * lamp.axis.head<2>().norm()), -1.0, 1.0));
  return off_axis - std::asin(radius / distance) <= half_wedge;
}

// pbrt-v4's spot light: a smooth step in the cosine between the beam's edges.
double LampLights::beam(const Posed& lamp, const Vec3& from_lamp) const {
  if (lamp.cos_outer <= -1) return 1;
  const double c = lamp.axis.dot(from_lamp);
  if (c <= lamp.cos_outer) return 0;
  if (c >= lamp.cos_inner) return 1;
  const double t = (c - lamp.cos_outer) / (lamp.cos_inner - lamp.cos_outer);
  return t * t * (3 - 2 * t);
}

const std::vector<int>* LampLights::cell_of(const Vec3& point) const {
  const Vec2 at = (point.head<2>() - origin_) / kLampCell;
  if (!(at.x() >= 0 && at.y() >= 0 && at.x() < columns_ && at.y() < rows_)) return nullptr;
  return &cells_[std::size_t(int(at.y())) * columns_ + int(at.x())];
}

LampLights::Sample LampLights::sample(const Vec3& point, const Vec3& normal, double u) const {
  const std::vector<int>* cell = empty() ? nullptr : cell_of(point);
  if (!cell || cell->empty()) return {};
  constexpr int kMax = 256;  // weights of the cell's first 256 lamps (cells hold far fewer)
  double weights[kMax], total = 0;
  const int n = std::min(int(cell->size()), kMax);
  for (int k = 0; k < n; ++k) {
    const Posed& lamp = lamps_[(*cell)[k]];
    const Vec3 to_point = point - lamp.position;
    const double d2 = std::max(to_point.squaredNorm(), 1e-4), d = std::sqrt(d2);
    const double facing = std::max(0.0, -normal.dot(to_point) / d);
    weights[k] = luminance(lamp.intensity) * beam(lamp, to_point / d) * facing / d2;
    total += weights[k];
  }
  if (!(total > 0)) return {};
  int pick = 0;
  for (double sum = weights[0]; sum <= u * total && pick < n - 1;) sum += weights[++pick];
  const Posed& lamp = lamps_[(*cell)[pick]];
  const Vec3 to_lamp = lamp.position - point;
  const double d2 = std::max(to_lamp.squaredNorm(), 1e-4), distance = std::sqrt(d2);
  const double probability = weights[pick] / total;
  return {to_lamp / distance, distance,
          lamp.intensity * (beam(lamp, -to_lamp / distance) / d2 / probability), total};
}

namespace {

// sin(top) - sin(bottom) of a dome row: its solid angle over the azimuth it spans.
double row_band(int rows, int row) {
  const double d_elevation = kPi / 2 / rows;
  return std::sin((row + 1) * d_elevation) - std::sin(row * d_elevation);
}

// The largest block of up to 8 x 8 cells that tiles the dome.
int block_side(const SkyDome& dome) {
  int side = 8;
  while (dome.rows % side != 0 || dome.columns % side != 0) side /= 2;
  return side;
}

// The dome averaged over blocks of cells, each cell weighted by its solid angle (the light the
// block sends is the light its cells send).
SkyDome averaged(const SkyDome& dome, int side) {
  SkyDome out;
  out.rows = dome.rows / side, out.columns = dome.columns / side;
  std::vector<Eigen::Vector3d> sums(std::size_t(out.rows) * out.columns, Eigen::Vector3d::Zero());
  std::vector<double> weights(std::size_t(out.rows), 0.0);
  for (int row = 0; row < dome.rows; ++row) {
    const double weight = row_band(dome.rows, row);
    weights[std::size_t(row / side)] += weight * side;
    for (int column = 0; column < dome.columns; ++column)
      sums[std::size_t(row / side) * out.columns + column / side] +=
          weight * dome.radiance[std::size_t(row) * dome.columns + column].cast<double>();
  }
  out.radiance.resize(sums.size());
  for (std::size_t i = 0; i < sums.size(); ++i)
    out.radiance[i] = (sums[i] / weights[i / std::size_t(out.columns)]).cast<float>();
  return out;
}

}  // namespace

SkySampler::SkySampler(const SkyDome* dome, bool average)
    : dome_(dome ? averaged(*dome, average ? block_side(*dome) : 1) : SkyDome{}) {
  if (empty()) return;
  const std::size_t cells = dome_.radiance.size();
  std::vector<double> weights(cells);
  double sum = 0;
  for (int row = 0; row < dome_.rows; ++row) {
    const double solid_angle = cell_solid_angle(row);
    for (std::size_t i = std::size_t(row) * dome_.columns; i < std::size_t(row + 1) * dome_.columns;
         ++i)
      sum += weights[i] = luminance(dome_.radiance[i].cast<double>()) * solid_angle;
  }
  // every cell kept possible (the bilinear lookup reaches into dark cells from bright neighbours)
  const double floor = 1e-3 * sum / double(cells);
  cumulative_.resize(cells);
  double running = 0;
  for (std::size_t i = 0; i < cells; ++i) cumulative_[i] = running += weights[i] + floor;
  for (double& c : cumulative_) c /= running;
  for (int row = 0; row < dome_.rows; ++row)
    row_ends_.push_back(cumulative_[std::size_t(row + 1) * dome_.columns - 1]);
  level_luminance_ = luminance(dome_.horizontal_irradiance().cast<double>());
}

Rgb SkySampler::radiance(const Vec3& d) const { return dome_.at(d).cast<double>(); }

double SkySampler::cell_solid_angle(int row) const {
  return 2 * kPi / dome_.columns * row_band(dome_.rows, row);
}

// The first cell whose cumulative share exceeds u.x() (the last if none does), found in its row
// first: the same cell as a search of the whole table, without its cache misses.
Vec3 SkySampler::sample(Vec2 u) const {
  const auto row_end = std::upper_bound(row_ends_.begin(), row_ends_.end(), u.x());
  std::size_t cell = cumulative_.size() - 1;
  if (row_end != row_ends_.end()) {
    const auto first = cumulative_.begin() + (row_end - row_ends_.begin()) * dome_.columns;
    cell = std::size_t(std::upper_bound(first, first + dome_.columns, u.x()) - cumulative_.begin());
  }
  const double lo = cell == 0 ? 0 : cumulative_[cell - 1];
  const double across = std::clamp((u.x() - lo) / (cumulative_[cell] - lo), 0.0, 1.0);
  const int row = int(cell / dome_.columns), column = int(cell % dome_.columns);
  const double d_elevation = kPi / 2 / dome_.rows;
  const double sin_lo = std::sin(row * d_elevation), sin_hi = std::sin((row + 1) * d_elevation);
  const double z = sin_lo + u.y() * (sin_hi - sin_lo), r = std::sqrt(std::max(0.0, 1 - z * z));
  const SinCos phi = sin_cos(2 * kPi * (column + across) / dome_.columns);
  return {r * phi.cos, r * phi.sin, z};
}

double SkySampler::pdf(const Vec3& d) const {
  if (empty() || d.z() < 0) return 0;
  const int row =
      std::min(dome_.rows - 1, int(std::asin(std::min(d.z(), 1.0)) / (kPi / 2) * dome_.rows));
  double azimuth = std::atan2(d.y(), d.x());
  if (azimuth < 0) azimuth += 2 * kPi;
  const int column = std::min(dome_.columns - 1, int(azimuth / (2 * kPi) * dome_.columns));
  const std::size_t cell = std::size_t(row) * dome_.columns + column;
  const double p = cumulative_[cell] - (cell == 0 ? 0 : cumulative_[cell - 1]);
  return p / cell_solid_angle(row);
}

Lights::Lights(const Scene& scene, double time, bool average_sky)
    : environment(scene.environment),
      lamps(scene, time),
      sky(scene.environment.sky_dome.get(), average_sky),
      sun_frame(frame_around(environment.sun_direction)),
      sun_cos_radius(std::cos(environment.sun_angular_radius)),
      sun_irradiance(environment.sun_irradiance.cast<double>()),
      sun_disc_radiance(sun_irradiance * environment.sun_disc_visibility /
                        (2 * kPi * (1 - sun_cos_radius))),
      sky_mean(((upper_mean(environment) + environment.ground) / 2).cast<double>()),
      fog(environment.fog, environment.sun_direction, sun_irradiance, sky_mean) {}

// The sky's radiance averaged over the upper hemisphere: the table's, or for the gradient
// (1 - t) horizon + t zenith with t = sqrt(z), whose mean over z in [0, 1] is 2/3.
Eigen::Vector3f Lights::upper_mean(const Environment& e) {
  return e.sky_dome ? e.sky_dome->mean()
                    : Eigen::Vector3f(e.sky_horizon / 3 + 2 * e.sky_zenith / 3);
}

Rgb Lights::sky_radiance(const Vec3& d) const {
  if (d.z() < 0) return environment.ground.cast<double>();
  if (environment.sky_dome) return environment.sky_dome->at(d).cast<double>();
  const double t = std::sqrt(d.z());
  return ((1 - t) * environment.sky_horizon + t * environment.sky_zenith).cast<double>();
}

Rgb Lights::scattered_sky_radiance(const Vec3& d) const {
  return d.z() < 0 || sky.empty() ? sky_radiance(d) : sky.radiance(d);
}

Rgb Lights::sun_radiance(const Vec3& d) const {
  return d.dot(environment.sun_direction) < sun_cos_radius ? Rgb::Zero() : sun_disc_radiance;
}

Vec3 Lights::sun_sample(Vec2 u) const {
  const double cos_t = 1 - u.x() * (1 - sun_cos_radius), sin_t = std::sqrt(1 - cos_t * cos_t);
  const SinCos phi = sin_cos(2 * kPi * u.y());
  return sun_frame * Vec3(sin_t * phi.cos, sin_t * phi.sin, cos_t);
}

}  // namespace flowscape
