#include "flowscape/renderer/sensor.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "flowscape/core/random.h"

namespace flowscape {
namespace {

constexpr double kLensTransmittance = 0.9;
constexpr double kPhotonsPerLuxSecond = 4.09e15;  // per m^2, at 555 nm
constexpr double kGlareSigmas[3] = {2, 8, 32};    // pixels
constexpr double kKeyOnCurve = 0.14;              // the curve's input that shows as 20 % grey

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("sensor: ") + what);
}

// Two independent standard normal numbers (Box-Muller's pair), and a Poisson number by Knuth's
// product (for means up to 30; noisy_electrons takes the normal approximation above, within a
// fraction of a percent there).
std::pair<double, double> normal_pair(Random& random) {
  const double u = std::max(random.uniform(), 1e-300), v = random.uniform();
  const double radius = std::sqrt(-2 * std::log(u));
  const SinCos angle = sin_cos(2 * kPi * v);
  return {radius * angle.cos, radius * angle.sin};
}
double poisson(Random& random, double mean) {
  const double limit = std::exp(-mean);
  double product = random.uniform();
  int count = 0;
  while (product > limit) product *= random.uniform(), ++count;
  return count;
}

// The electrons a pixel counts from a mean of `mean`: Poisson shot noise plus Gaussian read noise
// (one Box-Muller pair serves both where the shot noise is normal).
double noisy_electrons(Random& random, double mean, double read_noise) {
  const auto [shot, read] = normal_pair(random);
  if (mean <= 0) return read_noise * read;
  if (mean > 30)
    return std::max(0.0, std::round(mean + std::sqrt(mean) * shot)) + read_noise * read;
  return poisson(random, mean) + read_noise * read;
}

// The pixel's solid angle over the image centre's, times cos(theta) for a rectilinear lens (the
// cos^4 law); a fisheye's entrance pupil turns towards the field (pupil aberration), so its
// falloff is the solid angle alone (sin(theta) / theta for an equidistant lens: 64 % at 90
// degrees).
Image<float> relative_illumination(const Projection& camera) {
  Image<float> falloff(camera.width, camera.height, 1, 1.0f);
  if (camera.wraps_around()) return falloff;
  const bool rectilinear = camera.rectilinear();
  const Vec2 centre(camera.width / 2.0, camera.height / 2.0);
  const Vec3 axis = camera.ray(centre).normalized();
  const double centre_spread = camera.pixel_spread(centre);
  tbb::parallel_for(0, camera.height, [&](int y) {
    for (int x = 0; x < camera.width; ++x) {
      const Vec2 pixel(x + 0.5, y + 0.5);
      const Vec3 ray = camera.ray(pixel);
      if (ray.isZero()) continue;
      const double spread = camera.pixel_spread(pixel) / centre_spread;
      const double cos_theta = rectilinear ? std::max(0.0, ray.normalized().dot(axis)) : 1;
      falloff.pixel(x, y)[0] = float(cos_theta * spread * spread);
    }
  });
  return falloff;
}

// Red magnified by 1 + k about the image centre, blue shrunk by 1 - k (sampled bilinearly).
void shift_colours(const cv::Mat& image, double k) {
  std::vector<cv::Mat> channels;
  cv::split(image, channels);
  const double cx = image.cols / 2.0, cy = image.rows / 2.0;
  for (int c : {0, 2}) {
    const double scale = c == 0 ? 1 + k : 1 - k;
    cv::Mat map_x(image.size(), CV_32FC1), map_y(image.size(), CV_32FC1);
    for (int y = 0; y < image.rows; ++y)
      for (int x = 0; x < image.cols; ++x) {  // the source of pixel (x, y): its centre unscaled
        map_x.at<float>(y, x) = float(cx + (x + 0.5 - cx) / scale - 0.5);
        map_y.at<float>(y, x) = float(cy + (y + 0.5 - cy) / scale - 0.5);
      }
    cv::Mat moved;
    cv::remap(channels[c], moved, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    channels[c] = moved;
  }
  cv::merge(channels, image);
}

// A Gaussian blur of standard deviation `sigma` (pixels), wide ones on a coarser level of a
// Gaussian pyramid: halved (pyrDown) while at least 4 pixels of sigma are left there, blurred by
// what is left of sigma after the pyramid's own spread, and doubled back (pyrUp). pyrDown's and
// pyrUp's 5-tap kernels each add a variance of 1 pixel^2 of their finer level and keep a point's
// centre of mass, so the blur is the same wherever a light sits on the coarse grid (a moving
// lamp's halo moves smoothly). Within 1 % of the closed form (test), for an eighth of the
// filter's taps at sigma 8 and a five-hundredth at 32.
cv::Mat gaussian_blur(const cv::Mat& image, double sigma) {
  constexpr double kCoarseSigma = 4;
  std::vector<cv::Mat> levels{image};
  double spread = 0;  // the variance the pyramid adds, in pixels^2 of `image`
  for (double scale = 1; sigma / (2 * scale) >= kCoarseSigma &&
                         std::min(levels.back().cols, levels.back().rows) >= 16;
       scale *= 2) {
    spread += 2 * scale * scale;
    levels.emplace_back();
    cv::pyrDown(levels[levels.size() - 2], levels.back());
  }
  const double coarse_sigma = std::sqrt(sigma * sigma - spread) / std::exp2(levels.size() - 1);
  cv::Mat blurred;
  cv::GaussianBlur(levels.back(), blurred, cv::Size(0, 0), coarse_sigma, coarse_sigma,
                   cv::BORDER_REFLECT);
  for (std::size_t level = levels.size() - 1; level-- > 0;) {
    cv::Mat finer;
    cv::pyrUp(blurred, finer, levels[level].size());
    blurred = finer;
  }
  return blurred;
}

// The RGGB filter's channel at a pixel.
int bayer_channel(int x, int y) { return y % 2 == 0 ? (x % 2 == 0 ? 0 : 1) : (x % 2 == 0 ? 1 : 2); }

// OpenCV's demosaicking of an RGGB mosaic in [0, 1] (as 16 bits), back to RGB floats.
Image<float> demosaic(const Image<float>& mosaic) {
  cv::Mat bits(mosaic.height, mosaic.width, CV_16UC1);
  for (int y = 0; y < mosaic.height; ++y)
    for (int x = 0; x < mosaic.width; ++x)
      bits.at<std::uint16_t>(y, x) =
          std::uint16_t(std::lround(std::clamp(mosaic.pixel(x, y)[0], 0.0f, 1.0f) * 65535));
  cv::Mat rgb;
  cv::cvtColor(bits, rgb, cv::COLOR_BayerBG2RGB);  // OpenCV names RGGB by its second row
  Image<float> out(mosaic.width, mosaic.height, 3);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 3; ++c)
        out.pixel(x, y)[c] = rgb.at<cv::Vec<std::uint16_t, 3>>(y, x)[c] / 65535.0f;
  return out;
}

}  // namespace

double key_scale(double key) {
  const auto krawczyk = [](double l) { return 1.03 - 2 / (2 + std::log10(l + 1)); };
  return std::max(krawczyk(key), 0.02) / krawczyk(1000);
}

void validate(const SensorModel& s) {
  require(s.f_number >= 0.5 && s.f_number <= 64, "f_number must be in 0.5..64");
  require(s.pixel_pitch >= 0.5e-6 && s.pixel_pitch <= 50e-6,
          "pixel_pitch must be in 0.5..50 micrometres");
  require(s.quantum_efficiency > 0 && s.quantum_efficiency <= 1,
          "quantum_efficiency must be in (0, 1]");
  require(s.full_well >= 100 && s.full_well <= 1e7, "full_well must be in 100..1e7 electrons");
  require(s.read_noise >= 0 && s.read_noise <= 1000, "read_noise must be in 0..1000 electrons");
  require(s.max_gain >= 1 && s.max_gain <= 1e4, "max_gain must be in 1..10000");
  require(s.adaptation >= 0 && s.adaptation <= 60, "adaptation must be in 0..60 seconds");
  require(s.grey > 0 && s.grey <= 0.5, "grey must be in (0, 0.5]");
  require(s.glare >= 0 && s.glare <= 0.5, "glare must be in 0..0.5");
  require(std::abs(s.chromatic_aberration) <= 0.05, "chromatic_aberration must be in -0.05..0.05");
}

double electrons_per_nit_second(const SensorModel& s) {
  return kPi * kLensTransmittance / (4 * s.f_number * s.f_number) * s.pixel_pitch * s.pixel_pitch *
         kPhotonsPerLuxSecond * s.quantum_efficiency;
}

double key_luminance(ImageView<const float> nits) {
  double log_sum = 0;
  const std::size_t pixels = std::size_t(nits.width) * nits.height;
  for (std::size_t i = 0; i < pixels; ++i)
    log_sum += std::log(std::max(0.0, luminance(nits.data + i * nits.channels)) + 1e-3);
  return std::exp(log_sum / std::max<std::size_t>(pixels, 1));
}

Exposure auto_exposure(const SensorModel& s, const Exposure& previous, double measured,
                       double elapsed, double shutter) {
  Exposure e;
  const double step = s.adaptation > 0 ? 1 - std::exp(-elapsed / s.adaptation) : 1;
  e.adapted_key = previous.adapted_key > 0
                      ? previous.adapted_key * std::pow(measured / previous.adapted_key, step)
                      : measured;
  // the electrons the key would give over the whole shutter, against its share of the full well
  const double wanted = s.grey * key_scale(e.adapted_key) * s.full_well /
                        (electrons_per_nit_second(s) * shutter * e.adapted_key);
  e.integration = std::min(1.0, wanted);
  e.gain = std::clamp(wanted, 1.0, s.max_gain);
  return e;
}

Image<float> lens_image(ImageView<const float> nits, const Projection& camera,
                        const SensorModel& s) {
  Image<float> out(nits.width, nits.height, 3);
  std::copy(nits.data, nits.data + out.data.size(), out.data.begin());
  if (s.vignetting) {
    const Image<float> falloff = relative_illumination(camera);
    for (std::size_t i = 0; i < falloff.data.size(); ++i)
      for (int c = 0; c < 3; ++c) out.data[3 * i + c] *= falloff.data[i];
  }
  const cv::Mat image(out.height, out.width, CV_32FC3, out.data.data());
  if (s.chromatic_aberration != 0) shift_colours(image, s.chromatic_aberration);
  if (s.glare <= 0) return out;
  cv::Mat spread = cv::Mat::zeros(image.size(), CV_32FC3);
  for (double sigma : kGlareSigmas) spread += gaussian_blur(image, sigma);
  cv::addWeighted(image, 1 - s.glare, spread, s.glare / 3, 0, image);
  return out;
}

Image<float> sensor_raw(ImageView<const float> sensor_nits, const SensorModel& s, const Exposure& e,
                        double shutter, std::uint64_t seed) {
  Image<float> raw(sensor_nits.width, sensor_nits.height, s.bayer ? 1 : 3);
  const double electrons_per_nit = electrons_per_nit_second(s) * shutter * e.integration;
  const double to_raw = e.gain / s.full_well;  // the converter saturates at full_well / gain
  tbb::parallel_for(0, raw.height, [&](int y) {
    for (int x = 0; x < raw.width; ++x) {
      Random random(mix_bits(seed ^ mix_bits((std::uint64_t(y) << 32) | unsigned(x))));
      for (int k = 0; k < raw.channels; ++k) {
        const int c = s.bayer ? bayer_channel(x, y) : k;
        const double mean = std::max(0.0, double(sensor_nits.pixel(x, y)[c])) * electrons_per_nit;
        const double electrons = std::clamp(
            s.noise ? noisy_electrons(random, mean, s.read_noise) : mean, 0.0, s.full_well);
        raw.pixel(x, y)[k] = float(std::min(1.0, electrons * to_raw));
      }
    }
  });
  return s.bayer ? demosaic(raw) : raw;
}

float filmic(float x) {
  x = std::max(x, 0.0f);
  return std::clamp(x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

Image<float> tone_map(ImageView<const float> raw, const SensorModel& s) {
  Image<float> display(raw.width, raw.height, raw.channels);
  const float to_scene = float(kKeyOnCurve / s.grey);
  std::transform(raw.data, raw.data + display.data.size(), display.data.begin(),
                 [to_scene](float value) { return filmic(value * to_scene); });
  return display;
}

}  // namespace flowscape
