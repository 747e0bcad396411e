#include "flowscape/scenes/sky_dome.h"

#include <algorithm>
#include <cmath>

namespace flowscape {

Vec3 SkyDome::direction(double row, double column) const {
  const double elevation = (row + 0.5) / rows * kPi / 2,
               azimuth = (column + 0.5) / columns * 2 * kPi;
  return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
          std::sin(elevation)};
}

Eigen::Vector3f SkyDome::at(const Vec3& d) const {
  const double elevation = std::asin(std::clamp(d.z(), 0.0, 1.0));
  const double row = std::clamp(elevation / (kPi / 2) * rows - 0.5, 0.0, rows - 1.0);
  double column = std::atan2(d.y(), d.x()) / (2 * kPi) * columns - 0.5;
  column -= std::floor(column / columns) * columns;
  const int r0 = std::min(int(row), std::max(rows - 2, 0)), c0 = int(column) % columns;
  const int r1 = std::min(r0 + 1, rows - 1), c1 = (c0 + 1) % columns;
  const float fr = float(row - r0), fc = float(column - std::floor(column));
  const auto cell = [&](int r, int c) { return radiance[std::size_t(r) * columns + c]; };
  return (1 - fr) * ((1 - fc) * cell(r0, c0) + fc * cell(r0, c1)) +
         fr * ((1 - fc) * cell(r1, c0) + fc * cell(r1, c1));
}

namespace {

// Sum over the cells of radiance times weight(elevation) times the cell's solid angle.
Eigen::Vector3f integrate(const SkyDome& dome, double (*weight)(double)) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const double d_elevation = kPi / 2 / dome.rows, d_azimuth = 2 * kPi / dome.columns;
  for (int r = 0; r < dome.rows; ++r) {
    const double elevation = (r + 0.5) * d_elevation;
    Eigen::Vector3d row = Eigen::Vector3d::Zero();
    for (int c = 0; c < dome.columns; ++c)
      row += dome.radiance[std::size_t(r) * dome.columns + c].cast<double>();
    sum += row * (weight(elevation) * std::cos(elevation) * d_elevation * d_azimuth);
  }
  return sum.cast<float>();
}

}  // namespace

Eigen::Vector3f SkyDome::mean() const {
  return integrate(*this, [](double) { return 1.0; }) / float(2 * kPi);
}

Eigen::Vector3f SkyDome::horizontal_irradiance() const {
  return integrate(*this, [](double elevation) { return std::sin(elevation); });
}

}  // namespace flowscape
