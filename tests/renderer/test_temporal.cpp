#include <catch2/catch.hpp>
#include <cmath>
#include <functional>

#include "flowscape/renderer/temporal.h"
#include "flowscape/scenes/test_scenes.h"

using namespace flowscape;

namespace {

constexpr int kW = 32, kH = 16;

using Field = std::function<float(double x, double y)>;  // a layer's value at a pixel position

// Layers whose every light layer holds `light` at the pixel centres (shifted by `shift` pixels:
// the content seen `shift` further along), a surface everywhere (normal up), variance `variance`.
ColorLayers layers_of(const Field& light, double shift_x = 0, double shift_y = 0,
                      float variance = 0.01f) {
  ColorLayers l{Image<float>(kW, kH, 3), Image<float>(kW, kH, 3), Image<float>(kW, kH, 3),
                Image<float>(kW, kH, 3), Image<float>(kW, kH, 3), Image<float>(kW, kH, 3),
                Image<float>(kW, kH, 3)};
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) {
        const float v = light(x + 0.5 - shift_x, y + 0.5 - shift_y);
        l.direct.pixel(x, y)[c] = v, l.indirect.pixel(x, y)[c] = v;
        l.specular.pixel(x, y)[c] = v, l.other.pixel(x, y)[c] = v;
        l.albedo.pixel(x, y)[c] = 0.5f, l.normal.pixel(x, y)[c] = c == 2 ? 1.0f : 0.0f;
        l.variance.pixel(x, y)[c] = variance;
      }
  return l;
}

// A constant flow field and a validity everywhere.
struct Motion {
  Image<float> flow{kW, kH, 2};
  Image<std::uint8_t> valid{kW, kH, 1};
  Motion(double dx, double dy) {
    for (int i = 0; i < kW * kH; ++i)
      flow.data[2 * i] = float(dx), flow.data[2 * i + 1] = float(dy);
    std::fill(valid.data.begin(), valid.data.end(), std::uint8_t(1));
  }
};

const Image<std::uint16_t> kNoInstances(kW, kH, 1);

TemporalNeighbour neighbour(const ColorLayers& layers, const Motion& motion,
                            const Image<std::uint16_t>& instance = kNoInstances) {
  return {&layers, instance.view(), motion.flow.view(), motion.valid.view()};
}

float ramp(double x, double y) { return float(1 + 0.05 * x + 0.02 * y); }

}  // namespace

TEST_CASE("temporal: neighbours moved by the exact flow average to the centre's light") {
  // Frame t + 1 sees the content 2.25 px right and 0.5 px down, frame t - 1 as far the other way;
  // bilinear reads of a linear ramp are exact, so every layer comes back as the centre's.
  const ColorLayers centre = layers_of(ramp), next = layers_of(ramp, 2.25, 0.5),
                    previous = layers_of(ramp, -2.25, -0.5);
  const Motion forward(2.25, 0.5), backward(-2.25, -0.5);
  const ColorLayers out = temporal_layers(
      centre, kNoInstances.view(), {neighbour(next, forward), neighbour(previous, backward)});
  // Away from the border, where some taps fall off the image
  for (int y = 1; y < kH - 1; ++y)
    for (int x = 3; x < kW - 3; ++x) {
      INFO(x << ", " << y);
      CHECK(out.indirect.pixel(x, y)[0] == Approx(centre.indirect.pixel(x, y)[0]).epsilon(1e-5));
      // three frames taken: the variance of their mean is a third of one frame's
      CHECK(out.variance.pixel(x, y)[1] == Approx(0.01f / 3).epsilon(1e-5));
    }
}

TEST_CASE("temporal: noise averages out, the mean of the three frames' values exactly") {
  // Integer motion: each neighbour's tap is one pixel, so the result is (c + n + p) / 3 exactly.
  const Field centre_light = [](double x, double y) { return float(std::fmod(x * 7 + y * 3, 5)); };
  const ColorLayers centre = layers_of(centre_light, 0, 0, 100.0f);
  ColorLayers next = layers_of(centre_light, 3, 0, 100.0f),
              previous = layers_of(centre_light, -3, 0, 100.0f);
  for (float& v : next.direct.data) v += 0.3f;
  for (float& v : previous.direct.data) v -= 0.6f;
  const Motion forward(3, 0), backward(-3, 0);
  const ColorLayers out = temporal_layers(
      centre, kNoInstances.view(), {neighbour(next, forward), neighbour(previous, backward)});
  for (int y = 0; y < kH; ++y)
    for (int x = 3; x < kW - 3; ++x)
      CHECK(out.direct.pixel(x, y)[0] == Approx(centre.direct.pixel(x, y)[0] - 0.1f).margin(1e-5));
}

TEST_CASE("temporal: the ERP's neighbours are read across its seam") {
  // A pattern periodic over the width: moving 5 px right from the last columns wraps to the first.
  const Field periodic = [](double x, double) {
    return float(2 + std::sin(2 * 3.141592653589793 * x / kW));
  };
  const ColorLayers centre = layers_of(periodic), next = layers_of(periodic, 5, 0);
  ColorLayers off = next;
  for (float& v : off.indirect.data) v += 0.5f;  // as the seam is read: what wrapping must fetch
  const Motion forward(5, 0);
  const ColorLayers out = temporal_layers(centre, kNoInstances.view(), {neighbour(off, forward)},
                                          {.sigmas = 1000, .wraps = true});
  for (int x = kW - 5; x < kW; ++x)  // these pixels' taps wrapped around
    CHECK(out.indirect.pixel(x, 4)[0] ==
          Approx(centre.indirect.pixel(x, 4)[0] + 0.25f).epsilon(1e-5));
}

TEST_CASE(
    "temporal: history is dropped where the shading changed, was hidden or is another object") {
  const Field flat = [](double, double) { return 4.0f; };
  const ColorLayers centre = layers_of(flat, 0, 0, 0.01f);
  const Motion still(0, 0);
  SECTION("a lamp switched off: its light is rejected, the centre's kept as it was") {
    const ColorLayers dark = layers_of([](double, double) { return 0.5f; });
    const ColorLayers out = temporal_layers(centre, kNoInstances.view(), {neighbour(dark, still)});
    CHECK(out.direct.pixel(3, 3)[0] == 4.0f);
    CHECK(out.other.pixel(3, 3)[0] == 4.0f);
    CHECK(out.variance.pixel(3, 3)[0] == 0.01f);
  }
  SECTION("within the noise both frames carry, a pixel's change is taken as noise") {
    // sigma of the difference: sqrt(0.01 + 0.01) = 0.141, 2 sigma = 0.28 at the pixel; of the
    // 3 x 3 means 0.047, 2 sigma = 0.094 > 0.25 / 9
    ColorLayers noisy = centre;
    for (int c = 0; c < 3; ++c) noisy.indirect.pixel(3, 3)[c] = 4.25f;
    const ColorLayers out = temporal_layers(centre, kNoInstances.view(), {neighbour(noisy, still)});
    CHECK(out.indirect.pixel(3, 3)[0] == Approx(4.125f));
  }
  SECTION("the same change over every pixel is not noise: the 3 x 3 means show it") {
    const ColorLayers brighter = layers_of([](double, double) { return 4.3f; });
    const ColorLayers out =
        temporal_layers(centre, kNoInstances.view(), {neighbour(brighter, still)});
    CHECK(out.indirect.pixel(3, 3)[0] == 4.0f);
  }
  SECTION("not visible in the neighbour (occluded or out of view)") {
    const ColorLayers other = layers_of([](double, double) { return 4.02f; });
    Motion hidden(0, 0);
    hidden.valid.pixel(3, 3)[0] = 0;
    const ColorLayers out =
        temporal_layers(centre, kNoInstances.view(), {neighbour(other, hidden)});
    CHECK(out.indirect.pixel(3, 3)[0] == 4.0f);
    CHECK(out.indirect.pixel(4, 3)[0] == Approx(4.01f));
  }
  SECTION("another instance where the flow lands") {
    const ColorLayers other = layers_of([](double, double) { return 4.02f; });
    Image<std::uint16_t> car(kW, kH, 1);
    car.pixel(3, 3)[0] = 7;
    const ColorLayers out =
        temporal_layers(centre, kNoInstances.view(), {neighbour(other, still, car)});
    CHECK(out.indirect.pixel(3, 3)[0] == 4.0f);
    CHECK(out.indirect.pixel(4, 3)[0] == Approx(4.01f));
  }
  SECTION("a tap in the next stacked cube face is not read") {
    const ColorLayers other = layers_of([](double, double) { return 4.02f; });
    const Motion down(0, 1);
    const ColorLayers out =
        temporal_layers(centre, kNoInstances.view(), {neighbour(other, down)}, {.tile_height = 8});
    CHECK(out.indirect.pixel(3, 7)[0] == 4.0f);  // its tap, row 8, is in the second face
    CHECK(out.indirect.pixel(3, 6)[0] == Approx(4.01f));
  }
}

namespace {

// The sunlit street (a checkered wall 10 m ahead, the ground) at dusk-like light, with a car that
// brakes hard (12 m/s to a stop at 8 m/s^2, crossing the view) and a lamp by the wall that goes out
// between frames 2 and 3 (its post drops under the ground): what history must not smear.
constexpr double kFrameTime = 1.0 / 30;

Scene braking_car_and_lamp() {
  Scene scene = sunlit_street();
  scene.actors[0].pose = [](double t) {
    const double v = 12, a = 8, s = t < v / a ? v * t - a * t * t / 2 : v * v / (2 * a);
    return Pose(Eigen::Translation3d(6, 2 - s, -0.7));
  };
  Actor post{8, {}, [](double t) {
               return Pose(Eigen::Translation3d(8, 6, t < 2.5 * kFrameTime ? 0.0 : -50.0));
             }};
  Mesh head;
  add_box(head, Eigen::Vector3f(-0.1f, -0.1f, 3), Eigen::Vector3f(0.1f, 0.1f, 3.2f),
          SemanticClass::Pole);
  head.materials.assign(head.triangles.size(), 0);
  post.parts.push_back(rigid_part(std::move(head)));
  scene.actors.push_back(std::move(post));
  Lamp lamp;
  lamp.intensity = {6, 5.2f, 4}, lamp.actor = 1;
  scene.lamps.push_back(lamp);
  scene.environment.lamp_level = 1;
  return scene;
}

// Mean |difference| of raw colour over the pixels `where` marks.
double mean_error(const Image<float>& image, const Image<float>& reference,
                  const std::vector<char>& where) {
  double sum = 0;
  long count = 0;
  for (std::size_t i = 0; i < where.size(); ++i)
    if (where[i])
      for (int c = 0; c < 3; ++c)
        sum += std::abs(image.data[3 * i + c] - reference.data[3 * i + c]), ++count;
  return sum / std::max(count, 1L);
}

}  // namespace

TEST_CASE("temporal: no trail where a lamp goes out and a car brakes hard") {
  const Scene scene = braking_car_and_lamp();
  Renderer renderer(scene);
  const Projection camera = Projection::pinhole(64, 64, 100);
  const auto pair = [](int f) { return FramePair{f * kFrameTime, (f + 1) * kFrameTime}; };
  const int centre = 2;
  std::vector<ColorLayers> raw;
  std::vector<GroundTruth> truth;
  for (int f = 0; f <= 4; ++f) {
    raw.push_back(renderer.color_layers(camera, pair(f), {8, 4, std::uint64_t(100 + f)}));
    truth.push_back(renderer.ground_truth(camera, pair(f)));
  }
  TruthRequest window{pair(centre)};
  for (int f : {0, 1, 3, 4}) window.more.push_back({f * kFrameTime, Pose::Identity()});
  const GroundTruth to = renderer.ground_truth(camera, window);
  const auto reconstruct = [&](const TemporalOptions& options) {
    std::vector<TemporalNeighbour> neighbours;
    std::size_t k = 0;
    for (int f : {0, 1, 3, 4})
      neighbours.push_back({&raw[std::size_t(f)], truth[std::size_t(f)].instance.view(),
                            to.more[k].flow.view(), to.more[k].valid.view()}),
          ++k;
    return raw_color(
        temporal_layers(raw[centre], truth[centre].instance.view(), neighbours, options));
  };
  const Image<float> converged = renderer.color(camera, pair(centre), {512, 4, 99});
  const Image<float> next = renderer.color(camera, pair(centre + 1), {512, 4, 98});
  // Where the lamp's light went and where the car was or will be: the pixels history could smear
  std::vector<char> lamp(converged.pixel_count()), changed(converged.pixel_count()),
      all(converged.pixel_count(), 1);
  double went_out = 0;  // the lamp's light there (red channel), summed
  for (std::size_t i = 0; i < changed.size(); ++i) {
    lamp[i] =
        converged.data[3 * i] - next.data[3 * i] > 0.05f && truth[centre].instance.data[i] == 0;
    bool car = false;
    for (const GroundTruth& t : truth) car = car || t.instance.data[i] == 7;
    changed[i] = lamp[i] || car;
    if (lamp[i]) went_out += converged.data[3 * i] - next.data[3 * i];
  }
  const long lamp_pixels = std::count(lamp.begin(), lamp.end(), 1);
  REQUIRE(lamp_pixels > 100);
  REQUIRE(std::count(changed.begin(), changed.end(), 1) > lamp_pixels + 100);
  // The lamp's light lost by a reconstruction, as a share of the light that went out: a trail of
  // the dark frames after it
  const auto lost = [&](const Image<float>& image) {
    double sum = 0;
    for (std::size_t i = 0; i < lamp.size(); ++i)
      if (lamp[i]) sum += converged.data[3 * i] - image.data[3 * i];
    return sum / went_out;
  };
  const Image<float> alone = raw_color(raw[centre]);
  const Image<float> kept = reconstruct({}),
                     smeared = reconstruct({.sigmas = 1e9f, .relative_tolerance = 1e9f});
  INFO("lost: alone " << lost(alone) << ", reconstructed " << lost(kept) << ", no rejection "
                      << lost(smeared));
  CHECK(std::abs(lost(kept)) < 0.05);  // no trail
  CHECK(lost(smeared) > 0.3);          // which history without rejection would leave (2 of 5)
  // and no more error than the frame alone where lamp and car changed, less everywhere
  CHECK(mean_error(kept, converged, changed) <= mean_error(alone, converged, changed));
  CHECK(mean_error(kept, converged, all) < 0.8 * mean_error(alone, converged, all));
}
