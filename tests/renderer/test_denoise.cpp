#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <vector>

#include "flowscape/core/random.h"
#include "flowscape/renderer/denoise.h"

using namespace flowscape;

namespace {

constexpr int kSize = 256;
constexpr double kWallDistance = 5;  // m ahead of the camera, facing it

// A flat wall filling a 90-degree pinhole camera: its indirect light is albedo x (irradiance +
// noise), grey noise of deviation `noise` per pixel; the other light layers are empty.
struct Wall {
  Projection camera = Projection::pinhole(kSize, kSize, 90);
  ColorLayers layers{Image<float>(kSize, kSize, 3), Image<float>(kSize, kSize, 3),
                     Image<float>(kSize, kSize, 3), Image<float>(kSize, kSize, 3),
                     Image<float>(kSize, kSize, 3), Image<float>(kSize, kSize, 3),
                     Image<float>(kSize, kSize, 3)};
  Image<float> depth{kSize, kSize, 1};
  Image<std::uint16_t> instance{kSize, kSize, 1};

  Wall(const std::function<double(int, int)>& albedo,
       const std::function<double(int, int)>& irradiance, double noise) {
    Random random(7);
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const Vec3 ray = camera.ray(Vec2(x + 0.5, y + 0.5)).normalized();
        *depth.pixel(x, y) = float(kWallDistance / ray.x());  // the rig looks along +x
        // Box-Muller: one normal deviate per pixel, the same in every channel
        const double n =
            std::sqrt(-2 * std::log(1 - random.uniform())) * std::cos(2 * kPi * random.uniform());
        const double a = albedo(x, y);
        for (int c = 0; c < 3; ++c) {
          layers.albedo.pixel(x, y)[c] = float(a);
          layers.indirect.pixel(x, y)[c] = float(a * (irradiance(x, y) + noise * n));
          layers.normal.pixel(x, y)[c] = c == 0 ? -1.0f : 0.0f;
        }
        layers.variance.pixel(x, y)[1] = float(a * a * noise * noise);
      }
  }
  Image<float> denoised() const {
    return denoise(layers, {&camera, depth.view(), instance.view()});
  }
};

double mean_of_column(const Image<float>& image, int x) {
  double sum = 0;
  for (int y = 32; y < kSize - 32; ++y) sum += image.pixel(x, y)[0];
  return sum / (kSize - 64);
}

// The noise a cascade of a-trous levels leaves of white noise, from its taps alone: the filter is
// separable, its 1D kernel the [1 2 1] / 4 B-spline taps dilated by 1, 2, 4, ... convolved; white
// noise comes out scaled by the root of the sum of the squared 2D weights, (sum k^2) in 1D squared.
double cascade_noise_factor(int levels) {
  std::vector<double> kernel{1};
  for (int level = 0; level < levels; ++level) {
    const int step = 1 << level;
    std::vector<double> wider(kernel.size() + 2 * step, 0);
    for (std::size_t i = 0; i < kernel.size(); ++i)
      for (int t = -1; t <= 1; ++t) wider[i + step + t * step] += kernel[i] * (t == 0 ? 0.5 : 0.25);
    kernel = wider;
  }
  double squares = 0;
  for (double k : kernel) squares += k * k;
  return squares;  // (sum k^2)^2 over 2D, rooted: the factor on the deviation
}

}  // namespace

TEST_CASE("the denoiser keeps the edge between two instances sharp") {
  // indirect light 1 on the left half (instance 1), 0.2 on the right (instance 2), albedo 0.5
  const auto albedo = [](int, int) { return 0.5; };
  const auto irradiance = [](int x, int) { return x < kSize / 2 ? 1.0 : 0.2; };
  Wall wall(albedo, irradiance, 0.1);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) *wall.instance.pixel(x, y) = x < kSize / 2 ? 1 : 2;
  const Image<float> split = wall.denoised();
  // the columns next to the edge keep their side's light (the noise left: below 0.002 in a mean
  // over 192 rows)
  CHECK(mean_of_column(split, kSize / 2 - 1) == Approx(0.5).margin(0.005));
  CHECK(mean_of_column(split, kSize / 2) == Approx(0.1).margin(0.005));
  // one instance: the indirect light (no luminance stop) is blurred across: the guide does it
  wall.instance.data.assign(wall.instance.data.size(), 1);
  const Image<float> blurred = wall.denoised();
  CHECK(mean_of_column(blurred, kSize / 2 - 1) < 0.45);
  CHECK(mean_of_column(blurred, kSize / 2) > 0.15);
}

TEST_CASE("a high-contrast albedo pattern survives denoising: it lives in the albedo") {
  // a one-pixel checker of albedo 0.05 and 0.9 under uniform light 1 with 10 % noise
  const auto albedo = [](int x, int y) { return (x + y) % 2 ? 0.9 : 0.05; };
  const Wall wall(
      albedo, [](int, int) { return 1.0; }, 0.1);
  const Image<float> out = wall.denoised();
  double squared_raw = 0, squared_denoised = 0;
  int count = 0;
  for (int y = 32; y < kSize - 32; ++y)
    for (int x = 32; x < kSize - 32; ++x, ++count) {
      const double expected = albedo(x, y);
      squared_raw += std::pow(wall.layers.indirect.pixel(x, y)[0] / expected - 1, 2);
      squared_denoised += std::pow(out.pixel(x, y)[0] / expected - 1, 2);
    }
  const double raw = std::sqrt(squared_raw / count), denoised = std::sqrt(squared_denoised / count);
  INFO("relative rms error: raw " << raw << ", denoised " << denoised);
  CHECK(raw == Approx(0.1).epsilon(0.05));
  CHECK(denoised < 0.02);  // every pixel within 2 % rms of albedo x light: no contrast lost
}

TEST_CASE("on a flat lit wall the denoiser lowers the noise as its filter cascade predicts") {
  const Wall wall([](int, int) { return 0.5; }, [](int, int) { return 1.0; }, 0.2);
  const Image<float> out = wall.denoised();
  double squared_raw = 0, squared_denoised = 0;
  int count = 0;
  const int margin = 1 << DenoiseOptions{}.levels[1];  // beyond the widest step from the border
  for (int y = margin; y < kSize - margin; ++y)
    for (int x = margin; x < kSize - margin; ++x, ++count) {
      squared_raw += std::pow(wall.layers.indirect.pixel(x, y)[0] - 0.5, 2);
      squared_denoised += std::pow(out.pixel(x, y)[0] - 0.5, 2);
    }
  const double factor = std::sqrt(squared_raw / squared_denoised);
  const double predicted = 1 / cascade_noise_factor(DenoiseOptions{}.levels[1]);
  INFO("noise lowered " << factor << " times; the plain cascade predicts " << predicted);
  CHECK(factor == Approx(predicted).epsilon(0.15));
  CHECK(factor > 10);
}
