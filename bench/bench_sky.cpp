// bench_sky [OUT_DIR]: the physical sky of weather_environment per sun elevation and cloud cover,
// beside the gradient sky it replaced (the baseline, built from the same Environment's summaries):
// build time, exposure, the zenith's and horizon's luminance before exposure, the zenith's colour
// (r/g, b/g), the sun's irradiance on level ground, and the structure of the sky (the median over
// rows of the robust std of luminance about each row's median: 0 for a gradient). With OUT_DIR,
// writes each dome as an 8-bit equirectangular image of the upper hemisphere
// (sky_<elev>_<cover>.png). The real HDR skies that scripts/fetch_sky_maps.sh fetched follow, each
// under its own sun (sky_map_<name>.png).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "flowscape/formats/image_io.h"
#include "flowscape/formats/srgb.h"
#include "flowscape/weather/weather.h"

using namespace flowscape;

namespace {

double luminance(const Eigen::Vector3f& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// Median over rows of 1.4826 * MAD of luminance about the row's median, relative to the row's
// median (robust, so the sun's disc and glow do not dominate).
double row_structure(const SkyDome& dome) {
  std::vector<double> per_row;
  for (int r = 0; r < dome.rows; r += 4) {
    std::vector<double> row;
    for (int c = 0; c < dome.columns; ++c)
      row.push_back(luminance(dome.radiance[std::size_t(r) * dome.columns + c]));
    const double m = median(row);
    for (double& v : row) v = std::abs(v - m);
    per_row.push_back(1.4826 * median(row) / std::max(m, 1e-12));
  }
  return median(per_row);
}

SkyDome gradient_dome(const Environment& e, int rows, int columns) {
  SkyDome dome{rows, columns, {}};
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      const double t = std::sqrt(dome.direction(r, c).z());
      dome.radiance.push_back(float(1 - t) * e.sky_horizon + float(t) * e.sky_zenith);
    }
  return dome;
}

Image<float> as_image(const SkyDome& dome) {
  Image<float> image(dome.columns, dome.rows, 3);
  for (int r = 0; r < dome.rows; ++r)
    for (int c = 0; c < dome.columns; ++c)
      for (int k = 0; k < 3; ++k)  // zenith at the top, azimuth increasing to the left
        image.pixel(dome.columns - 1 - c, dome.rows - 1 - r)[k] =
            dome.radiance[std::size_t(r) * dome.columns + c][k];
  return image;
}

// One line of the table for the sky of `w` (and its dome as sky_<label>.png under `out`).
void report(const Weather& w, const std::string& elevation, const std::string& cover,
            const std::filesystem::path& out, const std::string& label) {
  const auto start = std::chrono::steady_clock::now();
  const Environment e = weather_environment(w);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const SkyDome& dome = *e.sky_dome;
  const Eigen::Vector3f zenith = dome.at(Vec3::UnitZ()) / float(e.exposure);
  const Eigen::Vector3f horizon = dome.at(Vec3(1, 0, 0.03).normalized()) / float(e.exposure);
  std::printf("%-6s %-11s %8.3f %9.3g %11.4g %11.4g %11.3f %11.3f %12.4g %9.3f %9.3f\n",
              elevation.c_str(), cover.c_str(), seconds, e.exposure, luminance(zenith),
              luminance(horizon), zenith[0] / zenith[1], zenith[2] / zenith[1],
              luminance(e.sun_irradiance) / e.exposure * std::max(0.0, e.sun_direction.z()),
              row_structure(dome), row_structure(gradient_dome(e, dome.rows, dome.columns)));
  if (out.empty()) return;
  std::filesystem::create_directories(out);
  write_image(out / ("sky_" + label + ".png"), linear_to_srgb8(as_image(dome).view(), 0.6f));
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path out = argc > 1 ? argv[1] : "";
  std::printf("%-6s %-11s %8s %9s %11s %11s %11s %11s %12s %9s %9s\n", "elev", "cover", "build_s",
              "exposure", "zenith_L", "horizon_L", "zen_r/g", "zen_b/g", "sun_level", "struct",
              "gradient");
  char text[64];
  for (double elevation : {90.0, 55.0, 20.0, 5.0, 0.0, -4.0})
    for (double cover : {0.0, 0.5, 0.95}) {
      Weather w = weather_preset("sunny");
      w.sun_elevation = elevation, w.cloudiness = cover, w.cloud_shift = 17;
      std::snprintf(text, sizeof text, "%+03.0f_%03.0f", elevation, cover * 100);
      report(w, std::to_string(int(elevation)), std::to_string(cover).substr(0, 4), out, text);
    }
  // the real HDR skies that were fetched, each under its own sun
  for (const std::string& name : sky_map_names()) {
    const Weather w = under_sky(weather_preset("sunny"), name, 1);
    if (w.sky_map.empty()) continue;
    std::snprintf(text, sizeof text, "%.0f", w.sun_elevation);
    report(w, text, "map:" + name, out, "map_" + name);
  }
}
