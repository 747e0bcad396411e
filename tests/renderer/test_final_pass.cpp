// The final pass: motion blur over a box shutter against the closed-form profile of a sliding
// edge (rigid, skinned, a moving camera, a rolling shutter), and the camera's sensor, exposure,
// lens and tone curve against their formulas.
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
constexpr int kWidth = 256, kHeight = 16;
const double kFocal = kWidth / 2.0 / std::tan(30 * indep::pi / 180);  // a 60-degree pinhole
// The board's edges in image columns when it is in front of the camera.
const double kLeft = kWidth / 2.0 - kFocal * 3.6 / kFront,
             kRight = kWidth / 2.0 + kFocal * 3.6 / kFront;

// The board's speed (m/s) that moves its image `pixels` over a 180-degree shutter (1/60 s).
double speed_for(double pixels) { return pixels * kFront / kFocal * 60; }

// A glowing board 7.2 m wide and 16 m tall (past the image's top and bottom), facing a camera at
// the origin looking along +x, under a black sky, the board sliding along -y at `board_speed`
// (m/s), in front of the camera at time `centred`: moved by its actor's pose, or with `skinned`
// by the one bone its vertices follow.
Scene glowing_board(double board_speed, double centred = 0, bool skinned = false) {
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
  const auto slide = [board_speed, centred](double t) {
    return Pose(Eigen::Translation3d(0, -board_speed * (t - centred), 0));
  };
  const PoseTrack place = [](double) { return Pose(Eigen::Translation3d(kDistance, 0, 0)); };
  Actor actor{1, {}, skinned ? place : PoseTrack([=](double t) { return place(t) * slide(t); })};
  if (skinned) {
    board.bones.assign(board.vertices.size(), {0, 0, 0, 0});
    board.weights.assign(board.vertices.size(), {1, 0, 0, 0});
    actor.parts.push_back({std::make_shared<const Mesh>(std::move(board)),
                           [](double) { return Pose::Identity(); },
                           [slide](double t) { return std::vector<Pose>{slide(t)}; }});
  } else {
    actor.parts.push_back(rigid_part(std::move(board)));
  }
  scene.actors.push_back(std::move(actor));
  return scene;
}

// The mean over rows [y0, y1) of each column of the raw colour's first channel.
std::vector<double> column_profile(const Image<float>& color, int y0 = 0, int y1 = kHeight) {
  std::vector<double> profile(color.width, 0.0);
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < color.width; ++x) profile[x] += color.pixel(x, y)[0] / (y1 - y0);
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

const CameraTrack kStill = [](double) { return Pose::Identity(); };

}  // namespace

TEST_CASE("a board moving under a box shutter blurs into the closed-form ramp, not copies") {
  const double time = 0.5;
  const Projection camera = Projection::pinhole(kWidth, kHeight, 60);
  for (const bool skinned : {false, true})
    for (const double blur : {8.0, 32.0, 128.0}) {
      const Scene scene = glowing_board(speed_for(blur), time, skinned);
      Renderer renderer(scene);
      // the ground truth's flow over a frame, times the shutter's share of it, is the blur length
      const GroundTruth truth = renderer.ground_truth(
          camera, FramePair{time, time + 1 / kFrameRate, Pose::Identity(), Pose::Identity()});
      const double flow = truth.flow.pixel(kWidth / 2, kHeight / 2)[0];
      CHECK(flow == Approx(2 * blur).epsilon(1e-3));
      const ColorLayers layers =
          renderer.color_layers(camera, centred_shutter(time, 180), kStill, {}, {64, 1, 5});
      const double error = relative_l1(column_profile(raw_color(layers)),
                                       expected_profile(kLeft, kRight, flow * 0.5));
      INFO((skinned ? "skinned" : "rigid") << ", " << blur << " px of blur: relative L1 " << error
                                           << " from the closed-form profile");
      CHECK(error < 0.02);
      // what the shutter's thirds (flowscape 0.13 to 0.15) gave: three copies of the edge
      std::vector<double> thirds(kWidth, 0.0);
      for (double shift : {-blur / 3, 0.0, blur / 3}) {
        const std::vector<double> copy = expected_profile(kLeft + shift, kRight + shift, 0);
        for (int x = 0; x < kWidth; ++x) thirds[x] += copy[x] / 3;
      }
      if (blur >= 32) CHECK(relative_l1(thirds, expected_profile(kLeft, kRight, blur)) > 0.02);
    }
  // the same still: a sharp board
  const Scene scene = glowing_board(0, time);
  Renderer renderer(scene);
  const double still_error = relative_l1(
      column_profile(renderer.color(
          camera, FramePair{time, time, Pose::Identity(), Pose::Identity()}, {64, 1, 5})),
      expected_profile(kLeft, kRight, 0));
  CHECK(still_error < 0.02);
}

TEST_CASE("a translating camera blurs a still board by its flow times the shutter's share") {
  const Scene scene = glowing_board(0);
  Renderer renderer(scene);
  const Projection camera = Projection::pinhole(kWidth, kHeight, 60);
  const double speed = 24 * kFront / kFocal * 30;  // the camera: 24 pixels of flow per frame
  const CameraTrack track = [speed](double t) {
    return Pose(Eigen::Translation3d(0, speed * (t - 1), 0));
  };
  const GroundTruth truth = renderer.ground_truth(
      camera, FramePair{1, 1 + 1 / kFrameRate, track(1), track(1 + 1 / kFrameRate)});
  const double flow = truth.flow.pixel(kWidth / 2, kHeight / 2)[0];
  CHECK(flow == Approx(24).epsilon(1e-3));
  for (double angle : {90.0, 270.0}) {
    const ColorLayers layers =
        renderer.color_layers(camera, centred_shutter(1, angle), track, {}, {64, 1, 9});
    const std::vector<double> seen = column_profile(raw_color(layers));
    const double error = relative_l1(seen, expected_profile(kLeft, kRight, flow * angle / 360));
    INFO("shutter " << angle << " degrees: relative L1 difference " << error);
    CHECK(error < 0.02);
  }
}

TEST_CASE("with a rolling shutter each row's blur is centred on the row's own time") {
  const double time = 0.5, blur = 32;
  const Scene scene = glowing_board(speed_for(blur), time);
  Renderer renderer(scene);
  const Projection camera = Projection::pinhole(kWidth, kHeight, 60);
  const Readout readout{0.02};  // 20 ms from the first row to the last
  const ColorLayers layers =
      renderer.color_layers(camera, centred_shutter(time, 180), kStill, readout, {64, 1, 7});
  const Image<float> color = raw_color(layers);
  const double pixels_per_second = blur * 60;  // the image moves +x at this rate
  for (int band = 0; band < 4; ++band) {
    const int y0 = 4 * band, y1 = y0 + 4;
    std::vector<double> expected(kWidth, 0.0);
    for (int y = y0; y < y1; ++y) {
      const double shift = pixels_per_second * readout.offset(y + 0.5, kHeight);
      const std::vector<double> row = expected_profile(kLeft + shift, kRight + shift, blur);
      for (int x = 0; x < kWidth; ++x) expected[x] += row[x] / (y1 - y0);
    }
    const double error = relative_l1(column_profile(color, y0, y1), expected);
    INFO("rows " << y0 << " to " << y1 << ": relative L1 " << error);
    CHECK(error < 0.02);
  }
}

TEST_CASE("the shutter is centred on the frame; the final pass traces half the samples") {
  const Shutter s = centred_shutter(1, 180);
  CHECK(s.close - s.open == Approx(1 / 60.0));
  CHECK((s.open + s.close) / 2 == Approx(1));
  const RenderOptions clean{8, 4, 3, true, 4};
  const RenderOptions over = shutter_options(clean);
  CHECK(over.samples_per_pixel == 4);
  CHECK(over.indirect_samples == 2);
  CHECK(over.edge_samples == clean.edge_samples / 2);
  CHECK(over.seed != clean.seed);
  CHECK(shutter_options({1, 4, 3, true, 1}).samples_per_pixel == 1);
  CHECK(shutter_options({1, 4, 3, true, 1}).indirect_samples == 1);
  CHECK(shutter_options({8, 4, 3, true, 0}).indirect_samples == 0);
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
