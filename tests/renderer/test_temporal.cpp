#include <catch2/catch.hpp>
#include <cmath>
#include <functional>

#include "flowscape/renderer/temporal.h"

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
  SECTION("within the noise both frames carry, a change is taken as noise") {
    // sigma of the difference: sqrt(0.01 + 0.01) = 0.141; 3 sigma = 0.42 (+ 5 % of 4.3)
    const ColorLayers noisy = layers_of([](double, double) { return 4.3f; });
    const ColorLayers out = temporal_layers(centre, kNoInstances.view(), {neighbour(noisy, still)});
    CHECK(out.indirect.pixel(3, 3)[0] == Approx(4.15f));
  }
  SECTION("not visible in the neighbour (occluded or out of view)") {
    const ColorLayers other = layers_of([](double, double) { return 4.2f; });
    Motion hidden(0, 0);
    hidden.valid.pixel(3, 3)[0] = 0;
    const ColorLayers out =
        temporal_layers(centre, kNoInstances.view(), {neighbour(other, hidden)});
    CHECK(out.indirect.pixel(3, 3)[0] == 4.0f);
    CHECK(out.indirect.pixel(4, 3)[0] == Approx(4.1f));
  }
  SECTION("another instance where the flow lands") {
    const ColorLayers other = layers_of([](double, double) { return 4.2f; });
    Image<std::uint16_t> car(kW, kH, 1);
    car.pixel(3, 3)[0] = 7;
    const ColorLayers out =
        temporal_layers(centre, kNoInstances.view(), {neighbour(other, still, car)});
    CHECK(out.indirect.pixel(3, 3)[0] == 4.0f);
    CHECK(out.indirect.pixel(4, 3)[0] == Approx(4.1f));
  }
  SECTION("a tap in the next stacked cube face is not read") {
    const ColorLayers other = layers_of([](double, double) { return 4.2f; });
    const Motion down(0, 1);
    const ColorLayers out =
        temporal_layers(centre, kNoInstances.view(), {neighbour(other, down)}, {.tile_height = 8});
    CHECK(out.indirect.pixel(3, 7)[0] == 4.0f);  // its tap, row 8, is in the second face
    CHECK(out.indirect.pixel(3, 6)[0] == Approx(4.1f));
  }
}
