#include "sky_map.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>

#include "flowscape/core/files.h"
#include "flowscape/core/sha256.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/weather/weather.h"

namespace flowscape::sky {
namespace {

// Above these elevations (degrees) each map shows nothing but sky: read off the maps, above the
// highest tree, mast, roof or mountain.
struct RecordedMap {
  const char* name;
  double horizon;
};
constexpr RecordedMap kMaps[] = {
    {"sky", 1}, {"park", 27}, {"sunrise", 25}, {"dawn", 12}, {"venice", 20}};

constexpr double kDegree = kPi / 180;
constexpr double kSunRadius = 4 * kDegree, kRingRadius = 6 * kDegree;
constexpr double kSunContrast = 20;  // brightest pixel / median sky: a sun to take out
constexpr double kBlend = 4 * kDegree, kLevelWindow = 20 * kDegree;

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }
Spectrum rgb(const float* p) { return {p[0], p[1], p[2]}; }

double row_elevation(const Image<float>& map, double row) {
  return kPi / 2 - (row + 0.5) / map.height * kPi;
}
double cell_solid_angle(const Image<float>& map, int row) {
  return (2 * kPi / map.width) * (kPi / map.height) * std::cos(row_elevation(map, row));
}

// The pixel of the upper hemisphere with the most luminance, and the hemisphere's median.
struct Brightest {
  int row = 0, column = 0;
  double luminance = 0, median = 0;
};
Brightest brightest_above_horizon(const Image<float>& map) {
  Brightest b;
  std::vector<double> all;
  for (int row = 0; row < map.height / 2; ++row)
    for (int column = 0; column < map.width; ++column) {
      const double l = luminance(map.pixel(column, row));
      all.push_back(l);
      if (l > b.luminance) b = {row, column, l, 0};
    }
  std::nth_element(all.begin(), all.begin() + all.size() / 2, all.end());
  b.median = all[all.size() / 2];
  return b;
}

// Calls visit(row, column, angle from `centre`) for every pixel within `radius` of it.
template <class Visit>
void for_each_pixel_near(const Image<float>& map, const Vec3& centre, double radius,
                         Visit&& visit) {
  for (int row = 0; row < map.height; ++row) {
    if (std::abs(row_elevation(map, row) - std::asin(centre.z())) > radius) continue;
    for (int column = 0; column < map.width; ++column) {
      const double angle =
          std::acos(std::clamp(map_direction(map, row, column).dot(centre), -1.0, 1.0));
      if (angle < radius) visit(row, column, angle);
    }
  }
}

// The mean over 2 half_window + 1 neighbours, cyclic (twice: a triangle of twice the width).
std::vector<Spectrum> smoothed(const std::vector<Spectrum>& line, int half_window) {
  const int n = int(line.size());
  std::vector<Spectrum> mean(n, Spectrum::Zero());
  for (int c = 0; c < n; ++c) {
    for (int k = -half_window; k <= half_window; ++k) mean[c] += line[((c + k) % n + n) % n];
    mean[c] /= 2 * half_window + 1;
  }
  return mean;
}

}  // namespace

Vec3 map_direction(const Image<float>& map, double row, double column) {
  const double elevation = row_elevation(map, row);
  const double azimuth = -(column + 0.5) / map.width * 2 * kPi;
  return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
          std::sin(elevation)};
}

Spectrum map_radiance(const Image<float>& map, const Vec3& d) {
  const double elevation = std::asin(std::clamp(d.z(), -1.0, 1.0));
  const double row =
      std::clamp((kPi / 2 - elevation) / kPi * map.height - 0.5, 0.0, double(map.height - 1));
  const double column = -std::atan2(d.y(), d.x()) / (2 * kPi) * map.width - 0.5;
  const int r0 = std::min(int(row), map.height - 2), c0 = int(std::floor(column));
  const double fr = row - r0, fc = column - c0;
  auto at = [&](int r, int c) {
    return rgb(map.pixel(((c % map.width) + map.width) % map.width, r));
  };
  return (1 - fr) * ((1 - fc) * at(r0, c0) + fc * at(r0, c0 + 1)) +
         fr * ((1 - fc) * at(r0 + 1, c0) + fc * at(r0 + 1, c0 + 1));
}

Spectrum horizontal_irradiance(const Image<float>& map) {
  Spectrum sum = Spectrum::Zero();
  for (int row = 0; row < map.height / 2; ++row) {
    const double weight = std::sin(row_elevation(map, row)) * cell_solid_angle(map, row);
    for (int column = 0; column < map.width; ++column) sum += rgb(map.pixel(column, row)) * weight;
  }
  return sum;
}

SunInMap take_out_sun(Image<float>& map) {
  const Brightest peak = brightest_above_horizon(map);
  SunInMap sun;
  sun.direction = map_direction(map, peak.row, peak.column);
  if (peak.luminance < kSunContrast * peak.median) return sun;
  Spectrum ring = Spectrum::Zero();
  double ring_weight = 0;
  for_each_pixel_near(map, sun.direction, kRingRadius, [&](int row, int column, double angle) {
    if (angle < kSunRadius) return;
    ring += rgb(map.pixel(column, row)) * cell_solid_angle(map, row);
    ring_weight += cell_solid_angle(map, row);
  });
  const Spectrum fill = ring / ring_weight;
  Vec3 centre = Vec3::Zero();
  for_each_pixel_near(map, sun.direction, kSunRadius, [&](int row, int column, double) {
    float* pixel = map.pixel(column, row);
    const Spectrum excess = (rgb(pixel) - fill) * cell_solid_angle(map, row);
    sun.irradiance += excess;
    centre += (0.2126 * excess[0] + 0.7152 * excess[1] + 0.0722 * excess[2]) *
              map_direction(map, row, column);
    for (int k = 0; k < 3; ++k) pixel[k] = float(fill[k]);
  });
  sun.direction = centre.normalized();
  sun.irradiance = sun.irradiance.max(0);
  return sun;
}

double recorded_horizon(const std::string& name) {
  for (const RecordedMap& m : kMaps)
    if (name == m.name) return m.horizon;
  throw std::invalid_argument("unknown sky map \"" + name + "\"");
}

SkyMap read_sky_map(const std::string& name, const std::string& file) {
  AnyImage any = read_any_image(file);
  const Image<float>* image = std::get_if<Image<float>>(&any);
  if (!image) throw FileError(file, "a sky map stores float or half pixels");
  if (image->channels < 3 || image->width != 2 * image->height || image->height < 16)
    throw FileError(file, "a sky map is an RGB panorama twice as wide as high, not " +
                              std::to_string(image->width) + " x " + std::to_string(image->height) +
                              " with " + std::to_string(image->channels) + " channels");
  SkyMap map{
      name, recorded_horizon(name) * kDegree, Image<float>(image->width, image->height, 3), {}};
  for (int y = 0; y < image->height; ++y)
    for (int x = 0; x < image->width; ++x)
      for (int k = 0; k < 3; ++k) {
        const float value = image->pixel(x, y)[k];
        if (!std::isfinite(value)) throw FileError(file, "holds a value that is not finite");
        map.radiance.pixel(x, y)[k] = value;
      }
  map.sun = take_out_sun(map.radiance);
  return map;
}

std::shared_ptr<const SkyMap> fetched_sky_map(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::filesystem::path, std::shared_ptr<const SkyMap>> maps;
  recorded_horizon(name);
  const std::filesystem::path file = sky_map_directory() / (name + ".exr");
  const std::lock_guard<std::mutex> lock(mutex);
  if (const auto known = maps.find(file); known != maps.end()) return known->second;
  std::shared_ptr<const SkyMap> map;
  if (std::filesystem::exists(file)) {
    require_pinned(file);  // a damaged map would move its sun without a word
    map = std::make_shared<const SkyMap>(read_sky_map(name, file.string()));
  } else
    std::fprintf(diagnostics(),
                 "warning: sky map \"%s\" not fetched (%s): the physical sky stands in "
                 "(scripts/fetch_sky_maps.sh fetches the maps)\n",
                 name.c_str(), file.c_str());
  return maps[file] = map;
}

void overlay_sky_map(const SkyMap& map, double rotation, double scale, SkyDome& dome) {
  const double cos_r = std::cos(rotation), sin_r = std::sin(rotation);
  auto map_at = [&](const Vec3& d) {  // the map turned by `rotation`
    const Vec3 unturned(cos_r * d.x() + sin_r * d.y(), cos_r * d.y() - sin_r * d.x(), d.z());
    return Spectrum(map_radiance(map.radiance, unturned).max(0) * scale);
  };
  const double row_height = kPi / 2 / dome.rows;
  const int line = std::min(dome.rows - 1, int((map.horizon + kBlend) / row_height));
  auto cell = [&](int row, int column) -> Eigen::Vector3f& {
    return dome.radiance[std::size_t(row) * dome.columns + column];
  };
  // the map's level over the dome's along the line, each smoothed over azimuth
  std::vector<Spectrum> map_line(dome.columns), dome_line(dome.columns), level(dome.columns);
  for (int c = 0; c < dome.columns; ++c)
    map_line[c] = map_at(dome.direction(line, c)), dome_line[c] = cell(line, c).cast<double>();
  const int half_window = int(kLevelWindow / (4 * kPi) * dome.columns);
  map_line = smoothed(smoothed(map_line, half_window), half_window);
  dome_line = smoothed(smoothed(dome_line, half_window), half_window);
  for (int c = 0; c < dome.columns; ++c) level[c] = map_line[c] / dome_line[c].max(1e-12);
  for (int row = 0; row < dome.rows; ++row) {
    const double elevation = (row + 0.5) * row_height;
    const double x = std::clamp((elevation - map.horizon) / kBlend, 0.0, 1.0);
    const double weight = x * x * (3 - 2 * x);
    for (int c = 0; c < dome.columns; ++c) {
      const Spectrum below = cell(row, c).cast<double>().array() * level[c];
      const Spectrum above = weight > 0 ? map_at(dome.direction(row, c)) : Spectrum::Zero();
      cell(row, c) = ((1 - weight) * below + weight * above).matrix().cast<float>();
    }
  }
}

}  // namespace flowscape::sky
