#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <numeric>

#include "flowscape/formats/srgb.h"
#include "flowscape/release/adaptive_sampling.h"
#include "flowscape/renderer/denoise.h"
#include "flowscape/scenes/test_scenes.h"

using namespace flowscape;

namespace {

ColorLayers filled_layers(int width, int height, float value, float variance) {
  ColorLayers layers = [&] {
    const Image<float> image(width, height, 3, value);
    return ColorLayers{image, image, image, image, image, image, image};
  }();
  std::fill(layers.variance.data.begin(), layers.variance.data.end(), variance);
  return layers;
}

double mean_of(const Image<float>& image) {
  return std::accumulate(image.data.begin(), image.data.end(), 0.0) / double(image.data.size());
}

}  // namespace

TEST_CASE("adaptive sampling splits the budget into two halves and a second pass of equal mean") {
  for (const auto& [spp, share] :
       {std::pair{8, 0.25}, {6, 0.25}, {16, 0.5}, {12, 0.25}, {4, 0.125}}) {
    const SampleSplit split = sample_split(spp, share);
    CHECK(split.half == spp / 4);
    CHECK(2 * split.half + share * split.more == Approx(spp).margin(share / 2));
  }
  CHECK(sample_split(3, 0.25).half == 0);  // too few samples for two halves: uniform
  CHECK(sample_split(8, 0).half == 0);
}

TEST_CASE("the chosen pixels are the share of the highest scores, ties by position") {
  const std::vector<double> score{5, 1, 7, 7, 0, 3, 7, 2};
  const Image<std::uint8_t> top = top_pixels(score, 4, 2, 0.5);
  CHECK(top.data == std::vector<std::uint8_t>{1, 0, 1, 1, 0, 0, 1, 0});
  const Image<std::uint8_t> two = top_pixels(score, 4, 2, 0.25);  // of the three 7s, the first two
  CHECK(two.data == std::vector<std::uint8_t>{0, 0, 1, 1, 0, 0, 0, 0});
  CHECK(top_pixels(score, 4, 2, 0).data == std::vector<std::uint8_t>(8, 0));
}

TEST_CASE("the disagreement is the 3 x 3 mean of the squared sRGB difference") {
  Image<float> a(5, 4, 3, 0.f), b(5, 4, 3, 0.f);
  a.pixel(0, 0)[1] = 1;           // sRGB 255 in one channel: 255^2 at that pixel
  b.pixel(3, 2)[0] = 0.2158605f;  // sRGB 128: ((128 / 255 + 0.055) / 1.055)^2.4 (IEC 61966-2-1)
  const double corner = 255.0 * 255, centre = 128.0 * 128;
  const std::vector<double> d = disagreement(a, b);
  CHECK(d[0] == Approx(corner / 4));  // a corner averages 4 pixels
  CHECK(d[1] == Approx(corner / 6));  // an edge 6
  CHECK(d[5 + 1] == Approx(corner / 9));
  CHECK(d[5 * 2 + 3] == Approx(centre / 9));
  CHECK(d[5 * 3 + 4] == Approx(centre / 4));  // the bottom-right corner sees (3, 2)
  CHECK(d[5 * 3 + 0] == 0);
}

TEST_CASE("pooling weighs each render's means by its samples, its variance is of all the samples") {
  const ColorLayers a = filled_layers(2, 1, 1, 0.5f), b = filled_layers(2, 1, 4, 0.2f);
  const ColorLayers p = pooled(a, 2, b, 6);
  for (const Image<float>* mean : {&p.direct, &p.indirect, &p.specular, &p.other, &p.albedo})
    for (float v : mean->data) CHECK(v == Approx((2 * 1 + 6 * 4) / 8.0));
  for (float v : p.normal.data) CHECK(v == Approx(5));  // sums of the samples' normals
  // a sample's luminance: a's 2 have mean 1, variance 2 x 0.5 (E x^2 = 2), b's 6 mean 4, variance
  // 6 x 0.2 (E x^2 = 17.2); all 8: E x^2 = 13.4, mean 3.25, variance 2.8375, of the mean / 8
  for (float v : p.variance.data) CHECK(v == Approx(2.8375 / 8));
  Image<std::uint8_t> where(2, 1, 1, 0);
  where.data[1] = 1;
  const ColorLayers r = replaced(a, b, where.view());
  CHECK(r.direct.pixel(0, 0)[0] == 1);
  CHECK(r.direct.pixel(1, 0)[0] == 4);
  CHECK(r.variance.pixel(1, 0)[2] == 0.2f);
}

TEST_CASE("adaptive sampling traces the budget: halves everywhere, the second pass where chosen") {
  const int width = 8, height = 4;
  std::vector<RenderOptions> passes;
  std::vector<long> traced;
  const RenderLayers render = [&](const RenderOptions& options) {
    passes.push_back(options);
    traced.push_back(options.pixels.data
                         ? std::count(options.pixels.data, options.pixels.data + width * height, 1)
                         : width * height);
    return filled_layers(width, height, 0.01f * float(passes.size()), 0);
  };
  // brighter to the right: the halves' colours differ the more the higher a pixel's column
  const DenoiseLayers denoise = [&](const ColorLayers& layers) {
    Image<float> color = raw_color(layers);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) color.pixel(x, y)[0] *= float(1 + x);
    return color;
  };
  RenderOptions budget{8, 4, 77};
  budget.indirect_samples = 4;
  const ColorLayers layers = adaptive_color_layers(render, denoise, budget, 0.25);
  REQUIRE(passes.size() == 3);
  CHECK(passes[0].samples_per_pixel == 2);
  CHECK(passes[1].samples_per_pixel == 2);
  CHECK(passes[2].samples_per_pixel == 16);
  CHECK(passes[0].indirect_samples == 1);
  CHECK(passes[2].indirect_samples == 8);
  CHECK(passes[0].seed != passes[1].seed);
  CHECK(passes[1].seed != passes[2].seed);
  CHECK(passes[0].seed != budget.seed);
  const long samples = 2 * traced[0] + 2 * traced[1] + 16 * traced[2];
  CHECK(samples == 8 * width * height);
  // the chosen quarter: the two right-most columns, whose halves disagree most
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      CHECK(layers.direct.pixel(x, y)[0] == Approx(x >= 6 ? 0.03 : 0.015));
}

TEST_CASE(
    "adaptively sampled colour converges to the uniform colour, the same bytes on 1 or 2 "
    "threads") {
  const Scene scene = sunlit_street();
  Renderer renderer(scene);
  // the sunlit wall and the ground (the sun's disc, a sub-pixel spike, out of view)
  const Projection front = Projection::cube_face(Face::Front, 48);
  const GroundTruth truth = renderer.ground_truth(front, FramePair{});
  const RenderLayers render = [&](const RenderOptions& options) {
    return renderer.color_layers(front, FramePair{}, options);
  };
  const DenoiseLayers denoise = [&](const ColorLayers& layers) {
    return flowscape::denoise(layers, {&front, truth.depth.view(), truth.instance.view()});
  };
  const auto adaptive = [&](int threads, std::uint64_t seed) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return raw_color(adaptive_color_layers(render, denoise, {8, 4, seed}, 0.25));
  };
  const Image<float> one = adaptive(1, 3);
  CHECK(one.data == adaptive(2, 3).data);
  const double converged = mean_of(renderer.color(front, FramePair{}, {256, 4, 9}));
  // the frame's mean radiance: unbiased whichever pixels took more samples
  CHECK(mean_of(one) == Approx(converged).epsilon(0.003));
  CHECK(mean_of(adaptive(2, 4)) == Approx(converged).epsilon(0.003));
}

TEST_CASE("the renderer traces only the pixels a mask names, each as in the whole image") {
  const Scene scene = sunlit_street();
  Renderer renderer(scene);
  const Projection erp = Projection::equirectangular(16);
  Image<std::uint8_t> mask(erp.width, erp.height, 1);
  for (std::size_t i = 0; i < mask.data.size(); i += 3) mask.data[i] = 1;
  RenderOptions options{4, 4, 5};
  const Image<float> all = renderer.color(erp, FramePair{}, options);
  options.pixels = mask.view();
  const Image<float> some = renderer.color(erp, FramePair{}, options);
  for (std::size_t i = 0; i < mask.data.size(); ++i)
    for (int c = 0; c < 3; ++c)
      CHECK(some.data[3 * i + c] == (mask.data[i] ? all.data[3 * i + c] : 0.f));
  Image<std::uint8_t> wrong(erp.width, erp.height - 1, 1, 1);
  options.pixels = wrong.view();
  CHECK_THROWS_WITH(renderer.color(erp, FramePair{}, options),
                    Catch::Contains("mask of the pixels to trace is 32 x 15 x 1"));
  CHECK_THROWS_WITH(render_cube(renderer, 8, FramePair{}, &options),
                    Catch::Contains("the image 8 x 48 x 1"));
}
