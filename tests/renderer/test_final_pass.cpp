#include <catch2/catch.hpp>
#include <cmath>

#include "flowscape/renderer/sensor.h"
#include "flowscape/renderer/shutter.h"
#include "flowscape/scenes/shapes.h"
#include "independent_math.h"

using namespace flowscape;

namespace {

constexpr double kDistance = 10;             // metres from the camera to the glowing board's centre
constexpr double kFront = kDistance - 0.05;  // to its face
constexpr int kWidth = 64, kHeight = 64;

// A glowing board 7.2 m wide and 16 m tall (past the image's top and bottom), facing a camera at
// the origin looking along +x, under a black sky, the board sliding along -y at `board_speed`
// (m/s), in front of the camera at time `centred`.
Scene glowing_board(double board_speed, double centred = 0) {
  Scene scene;
  Environment& e = scene.environment;
  e.sky_zenith = e.sky_horizon = e.ground = e.sun_irradiance = Eigen::Vector3f::Zero();
  add_box(scene.world, Eigen::Vector3f(-200, -200, -200), Eigen::Vector3f(-199, -199, -199),
          SemanticClass::Other);  // far behind the camera: the world is not empty
  Material glow;
  glow.kind = Material::Kind::Emissive, glow.emission = {1, 1, 1};
  scene.materials = {Material{}, glow};
  Mesh board;
  add_box(board, Eigen::Vector3f(-0.05f, -3.6f, -8), Eigen::Vector3f(0.05f, 3.6f, 8),
          SemanticClass::Vehicles);
  board.materials.assign(board.triangles.size(), 1);
  Actor actor{1, {}, [board_speed, centred](double t) {
                return Pose(Eigen::Translation3d(kDistance, -board_speed * (t - centred), 0));
              }};
  actor.parts.push_back(rigid_part(std::move(board)));
  scene.actors.push_back(std::move(actor));
  return scene;
}

// The mean over rows of each column of the raw colour's first channel.
std::vector<double> column_profile(const Image<float>& color) {
  std::vector<double> profile(color.width, 0.0);
  for (int y = 0; y < color.height; ++y)
    for (int x = 0; x < color.width; ++x) profile[x] += color.pixel(x, y)[0] / color.height;
  return profile;
}

// What a column sees of the board over a box shutter, by hand: the board covers image columns
// [left + s, right + s] where s moves linearly by `blur` pixels while the shutter is open; each
// column's value is the share of its width covered, averaged over the open time.
std::vector<double> expected_profile(double left, double right, double blur) {
  std::vector<double> profile(kWidth, 0.0);
  constexpr int kSteps = 4000;
  for (int k = 0; k < kSteps; ++k) {
    const double s = blur * ((k + 0.5) / kSteps - 0.5);
    for (int x = 0; x < kWidth; ++x)
      profile[x] +=
          std::max(0.0, std::min(x + 1.0, right + s) - std::max(double(x), left + s)) / kSteps;
  }
  return profile;
}

double relative_l1(const std::vector<double>& seen, const std::vector<double>& expected) {
  double difference = 0, total = 0;
  for (std::size_t x = 0; x < seen.size(); ++x)
    difference += std::abs(seen[x] - expected[x]), total += expected[x];
  return difference / total;
}

}  // namespace

TEST_CASE("a board moving under a box shutter blurs into the closed-form profile") {
  const double focal = kWidth / 2.0 / std::tan(30 * indep::pi / 180);  // 60-degree pinhole
  // 8 pixels of blur over a 180-degree shutter (1/60 s): the board moves 8 D / f metres then
  const double speed = 8 * kFront / focal * 60, time = 0.5;
  const Scene scene = glowing_board(speed, time);
  Renderer renderer(scene);
  const Projection camera = Projection::pinhole(kWidth, kHeight, 60);
  // the board's edges at the frame's time, in image columns
  const double centre = kWidth / 2.0;
  const double left = centre - focal * 3.6 / kFront, right = centre + focal * 3.6 / kFront;
  // the ground truth's flow over a frame, times the shutter's share of it, is the blur length
  const GroundTruth truth = renderer.ground_truth(
      camera, FramePair{time, time + 1 / kFrameRate, Pose::Identity(), Pose::Identity()});
  const double flow = truth.flow.pixel(int(centre), kHeight / 2)[0];
  CHECK(flow == Approx(16).epsilon(1e-3));
  RenderOptions options{64, 1, 5};
  const ColorLayers layers = shutter_layers(
      renderer, camera, centred_shutter(time, 180), [](double) { return Pose::Identity(); },
      options);
  const double error =
      relative_l1(column_profile(raw_color(layers)), expected_profile(left, right, flow * 0.5));
  INFO("relative L1 difference from the closed-form profile: " << error);
  CHECK(error < 0.02);
  // the same still: a sharp board
  const double still_error =
      relative_l1(column_profile(renderer.color(
                      camera, FramePair{time, time, Pose::Identity(), Pose::Identity()}, options)),
                  expected_profile(left, right, 0));
  CHECK(still_error < 0.02);
  CHECK(error < 0.02);
}

TEST_CASE("the clean frame stands for the shutter's middle third, the outer thirds traced") {
  const double focal = kWidth / 2.0 / std::tan(30 * indep::pi / 180);
  const double speed = 9 * kFront / focal * 60, time = 0.5;  // 9 pixels over the shutter
  const Scene scene = glowing_board(speed, time);
  Renderer renderer(scene);
  const Projection camera = Projection::pinhole(kWidth, kHeight, 60);
  const double left = kWidth / 2.0 - focal * 3.6 / kFront,
               right = kWidth / 2.0 + focal * 3.6 / kFront;
  const CameraTrack still = [](double) { return Pose::Identity(); };
  const RenderOptions options{64, 1, 5};
  const ColorLayers clean = renderer.color_layers(
      camera, FramePair{time, time, Pose::Identity(), Pose::Identity()}, options);
  // the board at the middle times of the thirds: 3 pixels left, where it is, 3 pixels right
  const auto at = [&](double shift) { return expected_profile(left + shift, right + shift, 0); };
  std::vector<double> thirds(kWidth), outer(kWidth);
  for (int x = 0; x < kWidth; ++x)
    outer[x] = (at(-3)[x] + at(3)[x]) / 3, thirds[x] = outer[x] + at(0)[x] / 3;
  const Shutter shutter = centred_shutter(time, 180);
  const std::vector<double> seen = column_profile(
      raw_color(shutter_layers(renderer, camera, shutter, still, options, {}, clean)));
  INFO("relative L1 difference from three thirds: " << relative_l1(seen, thirds));
  CHECK(relative_l1(seen, thirds) < 0.02);
  // a black centre weighs a third: what is left is the outer thirds'
  ColorLayers black = clean;
  for (Image<float>* layer : {&black.direct, &black.indirect, &black.specular, &black.other})
    std::fill(layer->data.begin(), layer->data.end(), 0.f);
  const std::vector<double> outer_seen = column_profile(
      raw_color(shutter_layers(renderer, camera, shutter, still, options, {}, black)));
  CHECK(relative_l1(outer_seen, outer) < 0.02);
}

TEST_CASE("a translating camera blurs a still board by its flow times the shutter's share") {
  const double focal = kWidth / 2.0 / std::tan(30 * indep::pi / 180);
  const Scene scene = glowing_board(0);
  Renderer renderer(scene);
  const Projection camera = Projection::pinhole(kWidth, kHeight, 60);
  const double speed = 6 * kFront / focal * 30;  // the camera: 6 pixels of flow per frame
  const CameraTrack track = [speed](double t) {
    return Pose(Eigen::Translation3d(0, speed * (t - 1), 0));
  };
  const GroundTruth truth = renderer.ground_truth(
      camera, FramePair{1, 1 + 1 / kFrameRate, track(1), track(1 + 1 / kFrameRate)});
  const double flow = truth.flow.pixel(kWidth / 2, kHeight / 2)[0];
  CHECK(flow == Approx(6).epsilon(1e-3));
  const double left = kWidth / 2.0 - focal * 3.6 / kFront,
               right = kWidth / 2.0 + focal * 3.6 / kFront;
  for (double angle : {90.0, 270.0}) {
    const ColorLayers layers =
        shutter_layers(renderer, camera, centred_shutter(1, angle), track, {64, 1, 9});
    const std::vector<double> seen = column_profile(raw_color(layers));
    const double error = relative_l1(seen, expected_profile(left, right, flow * angle / 360));
    INFO("shutter " << angle << " degrees: relative L1 difference " << error);
    CHECK(error < 0.02);
  }
}

TEST_CASE("the shutter is cut into steps that share the samples out evenly") {
  CHECK(shutter_steps({8, 4, 0, true, 4}) == 4);
  CHECK(shutter_steps({8, 4, 0, true, 0}) == 8);
  CHECK(shutter_steps({6, 4, 0, true, 0}) == 6);
  CHECK(shutter_steps({7, 4, 0, true, 0}) == 7);
  CHECK(shutter_steps({1, 4, 0, true, 0}) == 1);
  CHECK(shutter_steps({64, 4, 0, true, 0}) == kMaxShutterSteps);
  const Shutter s = centred_shutter(1, 180);
  CHECK(s.close - s.open == Approx(1 / 60.0));
  CHECK((s.open + s.close) / 2 == Approx(1));
  const std::vector<double> times = shutter_times(s, 4);
  CHECK(times.front() == Approx(s.open + (s.close - s.open) / 8));
}

TEST_CASE("the sensor's noise has the variance of shot noise plus read noise") {
  SensorModel sensor;
  sensor.glare = 0, sensor.vignetting = false;
  const double shutter = 1 / 60.0;
  for (double nits : {0.02, 1.0, 300.0}) {  // a dark night, dusk, a day
    const Exposure exposure = auto_exposure(sensor, {}, 50, 0, shutter);
    Image<float> light(128, 128, 3, float(nits));
    const Image<float> raw = sensor_raw(light.view(), sensor, exposure, shutter, 11);
    SensorModel still = sensor;
    still.noise = false;
    const Image<float> clean = sensor_raw(light.view(), still, exposure, shutter, 11);
    // back to electrons: the mean is the light's, the variance the mean plus read noise squared
    const double to_electrons = sensor.full_well / exposure.gain;
    const double mean = clean.data[0] * to_electrons;
    CHECK(mean == Approx(nits * electrons_per_nit_second(sensor) * shutter * exposure.integration)
                      .epsilon(1e-4));
    if (mean > 0.5 * sensor.full_well) continue;  // clipping would bend the statistics
    double chi_square = 0;
    const double variance = mean + sensor.read_noise * sensor.read_noise;
    for (float value : raw.data) {
      const double electrons = value * to_electrons;
      if (mean > 20) chi_square += std::pow(electrons - mean, 2) / variance;
    }
    if (mean <= 20) continue;  // near zero the clipping at 0 bends it too
    const double n = double(raw.data.size());
    INFO(nits << " cd/m^2: " << mean << " electrons, chi-square " << chi_square << " for " << n);
    CHECK(std::abs(chi_square - n) < 4 * std::sqrt(2 * n));
  }
  // a rerun gives the same noise; another seed another
  Image<float> light(16, 16, 3, 1.0f);
  const Exposure e = auto_exposure(sensor, {}, 1, 0, shutter);
  CHECK(sensor_raw(light.view(), sensor, e, shutter, 3).data ==
        sensor_raw(light.view(), sensor, e, shutter, 3).data);
  CHECK(sensor_raw(light.view(), sensor, e, shutter, 3).data !=
        sensor_raw(light.view(), sensor, e, shutter, 4).data);
}

TEST_CASE("the auto-exposure adapts in log luminance with its time constant, within its limits") {
  SensorModel sensor;
  const double shutter = 1 / 60.0;
  const Exposure first = auto_exposure(sensor, {}, 100, 0, shutter);
  CHECK(first.adapted_key == Approx(100));  // the first frame adapts at once
  // the key exposed to grey of the full well: integration x gain x electrons = grey x full well
  const auto krawczyk = [](double l) { return 1.03 - 2 / (2 + std::log10(l + 1)); };
  CHECK(first.integration * first.gain * electrons_per_nit_second(sensor) * shutter * 100 ==
        Approx(sensor.grey * krawczyk(100) / krawczyk(1000) * sensor.full_well));
  CHECK(key_scale(1000) == Approx(1));
  CHECK(key_scale(0.3) == Approx(krawczyk(0.3) / krawczyk(1000)));
  const Exposure later = auto_exposure(sensor, first, 1000, sensor.adaptation, shutter);
  CHECK(std::log(later.adapted_key / 100) == Approx(std::log(10) * (1 - std::exp(-1))));
  // bright: a shorter integration at base gain; dark: the whole shutter at the highest gain
  const Exposure day = auto_exposure(sensor, {}, 5000, 0, shutter);
  CHECK(day.integration < 1);
  CHECK(day.gain == 1);
  const Exposure night = auto_exposure(sensor, {}, 1e-3, 0, shutter);
  CHECK(night.integration == 1);
  CHECK(night.gain == sensor.max_gain);
}

TEST_CASE("vignetting follows the lens's relative illumination; the tone curve rolls off") {
  SensorModel sensor;
  sensor.glare = 0;
  const Projection pinhole = Projection::pinhole(64, 64, 90);
  const Image<float> flat(64, 64, 3, 1.0f);
  const Image<float> seen = lens_image(flat.view(), pinhole, sensor);
  // a pinhole's cos^4 law at the pixel (0.5, 0.5): tan(theta) = |offset| / f, f = 32
  const double tan_theta = std::hypot(31.5, 31.5) / 32, cos_theta = 1 / std::hypot(1, tan_theta);
  CHECK(seen.pixel(0, 0)[0] == Approx(std::pow(cos_theta, 4)).epsilon(1e-3));
  CHECK(seen.pixel(32, 32)[0] == Approx(1).epsilon(1e-3));
  // an equidistant fisheye (r = f theta): its solid angle per pixel, sin(theta) / theta
  const Projection fisheye =
      Projection::of_lens(make_lens("equidistant", {{"width", 64},
                                                    {"height", 64},
                                                    {"K", {{20, 0, 32}, {0, 20, 32}, {0, 0, 1}}},
                                                    {"max_angle_degrees", 100}}),
                          Mat3::Identity());
  const Image<float> wide = lens_image(flat.view(), fisheye, sensor);
  const double theta = (50.5 - 32) / 20;  // the pixel (50, 32): 18.5 px right of the centre
  CHECK(wide.pixel(50, 32)[0] == Approx(std::sin(theta) / theta).epsilon(0.01));
  const Image<float> erp = lens_image(flat.view(), Projection::equirectangular(32), sensor);
  for (float value : erp.data) CHECK(value == 1.0f);  // a panorama has no lens
  // the tone curve: black stays black, grey shows as about 20 % grey, saturation near white
  CHECK(filmic(0) == 0);
  Image<float> levels(3, 1, 1);
  levels.data = {float(sensor.grey), 0.5f, 1.0f};
  const Image<float> shown = tone_map(levels.view(), sensor);
  CHECK(shown.data[0] == Approx(0.2).epsilon(0.1));
  CHECK(shown.data[1] > shown.data[0]);
  CHECK(shown.data[2] > 0.9f);
}

TEST_CASE("glare spreads a share of a bright light round it and keeps its energy") {
  SensorModel sensor;
  sensor.vignetting = false, sensor.glare = 0.05;
  Image<float> lamp(256, 256, 3, 0.0f);
  for (int c = 0; c < 3; ++c) lamp.pixel(128, 128)[c] = 1000;
  const Image<float> seen = lens_image(lamp.view(), Projection::pinhole(256, 256, 60), sensor);
  double total = 0;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) total += seen.pixel(x, y)[0];
  CHECK(total == Approx(1000).epsilon(0.01));
  CHECK(seen.pixel(128, 128)[0] > 0.95f * 1000);
  CHECK(seen.pixel(128, 138)[0] > 0);  // a halo ten pixels away
}

TEST_CASE("glare's point-spread is the closed-form mix of three Gaussians of 2, 8 and 32 pixels") {
  SensorModel sensor;
  sensor.vignetting = false;
  constexpr int kSize = 512, kCentre = 256;
  constexpr double kPower = 1e5;
  Image<float> lamp(kSize, kSize, 3, 0.0f);
  for (int c = 0; c < 3; ++c) lamp.pixel(kCentre, kCentre)[c] = float(kPower);
  const Image<float> seen = lens_image(lamp.view(), Projection::pinhole(kSize, kSize, 60), sensor);
  const auto spread = [&](double d) {  // the glare d pixels from the lamp
    double sum = 0;
    for (double sigma : {2.0, 8.0, 32.0})
      sum += std::exp(-d * d / (2 * sigma * sigma)) / (2 * kPi * sigma * sigma) / 3;
    return sensor.glare * kPower * sum;
  };
  CHECK(seen.pixel(kCentre, kCentre)[1] - (1 - sensor.glare) * kPower ==
        Approx(spread(0)).epsilon(0.02));
  for (int d : {3, 10, 24, 50, 100}) {
    INFO(d << " pixels away");
    CHECK(seen.pixel(kCentre + d, kCentre)[1] == Approx(spread(d)).epsilon(0.02));
    CHECK(seen.pixel(kCentre, kCentre - d)[0] == Approx(spread(d)).epsilon(0.02));
  }
}

TEST_CASE("lateral chromatic aberration moves red out and blue in by their share of the radius") {
  SensorModel sensor;
  sensor.vignetting = false, sensor.glare = 0, sensor.chromatic_aberration = 0.05;
  Image<float> dot(128, 128, 3, 0.0f);
  for (int c = 0; c < 3; ++c) dot.pixel(84, 64)[c] = 1;  // its centre 20.5 px right of the image's
  const Image<float> seen = lens_image(dot.view(), Projection::pinhole(128, 128, 60), sensor);
  const auto centroid = [&](int c) {
    double sum = 0, moment = 0;
    for (int y = 0; y < 128; ++y)
      for (int x = 0; x < 128; ++x)
        sum += seen.pixel(x, y)[c], moment += (x + 0.5) * seen.pixel(x, y)[c];
    return moment / sum;
  };
  CHECK(centroid(0) == Approx(64 + 20.5 * 1.05).margin(0.05));
  CHECK(centroid(1) == Approx(64 + 20.5).margin(1e-6));
  CHECK(centroid(2) == Approx(64 + 20.5 * 0.95).margin(0.05));
}

TEST_CASE("a Bayer mosaic demosaicked gives a flat colour back, channel for channel") {
  SensorModel sensor;
  sensor.noise = false;
  const double shutter = 1 / 60.0;
  const Exposure e = auto_exposure(sensor, {}, 100, 0, shutter);
  Image<float> light(32, 32, 3);
  for (int i = 0; i < 32 * 32; ++i)
    light.data[3 * i] = 40, light.data[3 * i + 1] = 100, light.data[3 * i + 2] = 250;
  const Image<float> plain = sensor_raw(light.view(), sensor, e, shutter, 1);
  sensor.bayer = true;
  const Image<float> mosaicked = sensor_raw(light.view(), sensor, e, shutter, 1);
  REQUIRE(mosaicked.channels == 3);
  for (int y = 2; y < 30; ++y)
    for (int x = 2; x < 30; ++x)
      for (int c = 0; c < 3; ++c)
        CHECK(mosaicked.pixel(x, y)[c] == Approx(plain.pixel(x, y)[c]).margin(1e-4));
}
