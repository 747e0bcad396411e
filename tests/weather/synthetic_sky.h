#pragma once
// A sky panorama with closed-form light for the sky-map tests: radiance a + b sin(e) (tinted) over
// the upper hemisphere, the ground a constant below, and optionally a Gaussian sun. Directions are
// computed here from the documented convention (weather/src/sky_map.h), not by the code under test.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "flowscape/core/image.h"
#include "flowscape/core/sha256.h"
#include "flowscape/core/types.h"

namespace flowscape::test {

struct SyntheticSky {
  int height = 256;
  double a = 0.2, b = 0.6, ground = 0.05;
  Vec3 sun = Vec3::UnitZ();  // unit
  double sun_peak = 0;       // radiance at the sun's centre; 0: no sun
  double sun_sigma = 0.014;  // radians
  Eigen::Array3d tint{0.8, 0.9, 1.1}, sun_tint{1.0, 0.95, 0.85};
};

inline Vec3 panorama_direction(int width, int height, double row, double column) {
  const double elevation = kPi / 2 - (row + 0.5) / height * kPi;
  const double azimuth = -(column + 0.5) / width * 2 * kPi;
  return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
          std::sin(elevation)};
}

inline Image<float> synthetic_sky(const SyntheticSky& s) {
  Image<float> map(2 * s.height, s.height, 3);
  for (int row = 0; row < map.height; ++row)
    for (int column = 0; column < map.width; ++column) {
      const Vec3 d = panorama_direction(map.width, map.height, row, column);
      Eigen::Array3d value = d.z() > 0 ? (s.a + s.b * d.z()) * s.tint : s.ground * s.tint;
      if (s.sun_peak > 0) {
        const double angle = std::acos(std::clamp(d.dot(s.sun), -1.0, 1.0));
        value +=
            s.sun_peak * std::exp(-angle * angle / (2 * s.sun_sigma * s.sun_sigma)) * s.sun_tint;
      }
      for (int k = 0; k < 3; ++k) map.pixel(column, row)[k] = float(value[k]);
    }
  return map;
}

// The sun's irradiance on a plane facing it: the Gaussian's integral over the sphere, 2 pi sigma^2
// (1 - sigma^2 / 3 + ...), times its peak.
inline Eigen::Array3d synthetic_sun_irradiance(const SyntheticSky& s) {
  const double sigma2 = s.sun_sigma * s.sun_sigma;
  return s.sun_peak * 2 * kPi * sigma2 * (1 - sigma2 / 3) * s.sun_tint;
}

// Pins `file` in its folder's SHA256SUMS, as scripts/fetch_sky_maps.sh pins the maps it fetches.
inline void pin(const std::filesystem::path& file) {
  std::ofstream(file.parent_path() / "SHA256SUMS", std::ios::app)
      << sha256_file(file) << "  " << file.filename().string() << "\n";
}

}  // namespace flowscape::test
