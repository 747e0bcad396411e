#include "flowscape/release/adaptive_sampling.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "flowscape/core/profile.h"
#include "flowscape/core/random.h"
#include "flowscape/formats/srgb.h"

namespace flowscape {
namespace {

// A pass of `samples` per pixel: the indirect ones in the budget's proportion, its own seed.
RenderOptions pass_options(const RenderOptions& budget, int samples, int pass) {
  RenderOptions options = budget;
  options.samples_per_pixel = samples;
  const int indirect = budget.indirect_samples, total = budget.samples_per_pixel;
  options.indirect_samples =
      indirect <= 0 || indirect >= total
          ? 0
          : std::max(1, int(std::lround(double(samples) * indirect / total)));
  options.seed = mix_bits(budget.seed + std::uint64_t(pass) + 1);
  return options;
}

// The mean over each pixel's 3 x 3 neighbours inside the image.
std::vector<double> box3(const std::vector<double>& values, int width, int height) {
  std::vector<double> out(values.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double sum = 0;
      int count = 0;
      for (int v = std::max(0, y - 1); v <= std::min(height - 1, y + 1); ++v)
        for (int u = std::max(0, x - 1); u <= std::min(width - 1, x + 1); ++u)
          sum += values[std::size_t(v) * width + u], ++count;
      out[std::size_t(y) * width + x] = sum / count;
    }
  return out;
}

}  // namespace

std::vector<double> squared_srgb_difference(const Image<float>& a, const Image<float>& b) {
  std::vector<double> out(a.pixel_count(), 0.0);
  tbb::parallel_for(std::size_t(0), out.size(), [&](std::size_t i) {
    for (std::size_t c = 3 * i; c < 3 * i + 3; ++c)
      out[i] += std::pow(double(linear_to_srgb8(a.data[c])) - linear_to_srgb8(b.data[c]), 2);
  });
  return out;
}

SampleSplit sample_split(int samples_per_pixel, double share) {
  const int half = share > 0 ? samples_per_pixel / 4 : 0;
  if (half == 0) return {};
  return {half, int(std::lround((samples_per_pixel - 2 * half) / share))};
}

std::vector<double> disagreement(const Image<float>& a, const Image<float>& b) {
  return box3(squared_srgb_difference(a, b), a.width, a.height);
}

Image<std::uint8_t> top_pixels(const std::vector<double>& score, int width, int height,
                               double share) {
  std::vector<std::size_t> order(score.size());
  std::iota(order.begin(), order.end(), 0);
  const auto chosen =
      order.begin() + std::ptrdiff_t(std::lround(std::clamp(share, 0.0, 1.0) * score.size()));
  std::nth_element(order.begin(), chosen, order.end(), [&](std::size_t a, std::size_t b) {
    return score[a] != score[b] ? score[a] > score[b] : a < b;
  });
  Image<std::uint8_t> top(width, height, 1);
  for (auto it = order.begin(); it != chosen; ++it) top.data[*it] = 1;
  return top;
}

ColorLayers replaced(ColorLayers base, const ColorLayers& by, ImageView<const std::uint8_t> where) {
  tbb::parallel_for(std::size_t(0), where.pixel_count(), [&](std::size_t i) {
    if (where.data[i])
      for (auto [to, from] : {std::pair{&base.direct, &by.direct},
                              {&base.indirect, &by.indirect},
                              {&base.specular, &by.specular},
                              {&base.other, &by.other},
                              {&base.albedo, &by.albedo},
                              {&base.normal, &by.normal},
                              {&base.variance, &by.variance}})
        std::copy_n(&from->data[3 * i], 3, &to->data[3 * i]);
  });
  return base;
}

ColorLayers adaptive_color_layers(const RenderLayers& render, const DenoiseLayers& denoise,
                                  const RenderOptions& options, double share) {
  const SampleSplit split = sample_split(options.samples_per_pixel, share);
  if (split.half == 0) return render(options);
  const ColorLayers half_a = render(pass_options(options, split.half, 0));
  const ColorLayers half_b = render(pass_options(options, split.half, 1));
  const Image<std::uint8_t> chosen = [&] {
    const ScopedPhase phase("adaptive sampling: estimate");
    return top_pixels(disagreement(denoise(half_a), denoise(half_b)), half_a.direct.width,
                      half_a.direct.height, share);
  }();
  RenderOptions more = pass_options(options, split.more, 2);
  more.pixels = chosen.view();
  return replaced(pooled(half_a, split.half, half_b, split.half), render(more), chosen.view());
}

}  // namespace flowscape
