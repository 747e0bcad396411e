// What adaptive sampling could gain (issue 37's noise lever, not in the renderer yet): at the
// default's budget of 8 samples per pixel on average, the non-sky PSNR (frame_quality.h) of
// a-trous-denoised colour when every pixel first takes 4 samples (2 indirect) and a share of the
// pixels 16 more (8 indirect), against the uniform 8 (4 indirect) of the default. The share is
// chosen two ways: by each pixel's actual error after denoising the 4 samples (an oracle: the upper
// bound of any choice), and by an estimate a renderer can make alone, the squared sRGB difference
// between the denoised halves of those 4 samples (two independent 2-sample renders), averaged over
// each pixel's 3 x 3 neighbours. Also printed: uniform 16 (8 indirect), twice the budget, and the
// seconds of the default's colour and of the estimate's two extra denoiser runs. The downtown
// frame 30 of the default release's first sequence (bench_image_quality's), direct ERP camera.
// Usage: bench_adaptive_sampling [ERP height = 128] [reference spp = 1024] [share = 0.25]
#include <tbb/global_control.h>

#include <cstdio>
#include <cstdlib>
#include <numeric>

#include "flowscape/core/profile.h"
#include "flowscape/renderer/denoise.h"
#include "frame_quality.h"

using namespace flowscape;

namespace {

// The mean of two independent renders' layers: as one render of both renders' samples.
ColorLayers pooled(ColorLayers a, const ColorLayers& b) {
  for (auto [to, from] : {std::pair{&a.direct, &b.direct},
                          {&a.indirect, &b.indirect},
                          {&a.specular, &b.specular},
                          {&a.other, &b.other},
                          {&a.albedo, &b.albedo}})
    for (std::size_t i = 0; i < to->data.size(); ++i)
      to->data[i] = (to->data[i] + from->data[i]) / 2;
  for (std::size_t i = 0; i < a.normal.data.size(); ++i) a.normal.data[i] += b.normal.data[i];
  for (std::size_t i = 0; i < a.variance.data.size(); ++i)
    a.variance.data[i] = (a.variance.data[i] + b.variance.data[i]) / 4;
  return a;
}

// The mean over each pixel's 3 x 3 neighbours (wrapping round the ERP's columns).
std::vector<double> box3(const std::vector<double>& values, int width, int height) {
  std::vector<double> out(values.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double sum = 0;
      int count = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (y + dy >= 0 && y + dy < height)
            sum += values[std::size_t(y + dy) * width + (x + dx + width) % width], ++count;
      out[std::size_t(y) * width + x] = sum / count;
    }
  return out;
}

// `base` with the `share` of its pixels of the highest `score` taken from `more`.
ColorLayers allocated(ColorLayers base, const ColorLayers& more, const std::vector<double>& score,
                      double share) {
  std::vector<std::size_t> order(score.size());
  std::iota(order.begin(), order.end(), 0);
  const auto chosen = order.begin() + std::ptrdiff_t(share * double(order.size()));
  std::partial_sort(order.begin(), chosen, order.end(),
                    [&](std::size_t a, std::size_t b) { return score[a] > score[b]; });
  for (auto it = order.begin(); it != chosen; ++it)
    for (auto [to, from] : {std::pair{&base.direct, &more.direct},
                            {&base.indirect, &more.indirect},
                            {&base.specular, &more.specular},
                            {&base.other, &more.other},
                            {&base.albedo, &more.albedo},
                            {&base.normal, &more.normal},
                            {&base.variance, &more.variance}})
      std::copy_n(&from->data[3 * *it], 3, &to->data[3 * *it]);
  return base;
}

}  // namespace

int main(int argc, char** argv) {
  const int height = argc > 1 ? std::atoi(argv[1]) : 128;
  const int reference_spp = argc > 2 ? std::atoi(argv[2]) : 1024;
  const double share = argc > 3 ? std::atof(argv[3]) : 0.25;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  const ReleaseConfig defaults;
  const int frame = 30, more_spp = 4 + int(std::lround(4 / share));
  SequenceSpec spec = sequence_spec(defaults, plan_sequences(defaults).front());
  spec.ego_route = EgoRoute::Free;  // bench_image_quality's frame
  std::printf(
      "bench_adaptive_sampling: downtown frame %d, %d x %d ERP, reference %d spp, 2 threads; "
      "adaptive: 4 spp everywhere, %d for the %.0f %% of the pixels chosen (8 on average)\n",
      frame, height, 2 * height, reference_spp, more_spp, 100 * share);
  std::printf("  %-10s %12s %12s %12s %12s %10s %12s\n", "weather", "uniform 8", "uniform 16",
              "oracle", "estimated", "8 spp: s", "estimate: s");
  for (const char* weather : {"sunny", "cloud", "fog", "rain"}) {
    spec.weather = weather;
    Setup s(spec, frame, height, reference_spp);
    const auto render = [&](int spp, std::uint64_t seed) {
      RenderOptions options = s.sequence.color_options(defaults, frame);  // the release's
      options.samples_per_pixel = spp, options.indirect_samples = spp / 2, options.seed += seed;
      return s.renderer.color_layers(s.erp, s.pair, options);
    };
    const auto denoised = [&](const ColorLayers& layers) {
      return denoise(layers, {&s.erp, s.truth.depth.view(), s.truth.instance.view()});
    };
    const auto db = [&](const ColorLayers& layers) {
      return psnr(denoised(layers), s.reference, s.truth);
    };
    double start = wall_seconds();
    const ColorLayers uniform = render(8, 2);
    const double uniform_db = db(uniform), uniform_seconds = wall_seconds() - start;
    const ColorLayers half_a = render(2, 3), half_b = render(2, 4), more = render(more_spp, 5);
    const ColorLayers base = pooled(half_a, half_b);
    start = wall_seconds();
    const std::vector<double> estimate =
        box3(squared_difference(denoised(half_a), denoised(half_b)), s.erp.width, s.erp.height);
    const double estimate_seconds = wall_seconds() - start;
    const std::vector<double> actual = squared_difference(denoised(base), s.reference);
    std::printf("  %-10s %9.2f dB %9.2f dB %9.2f dB %9.2f dB %10.3f %12.3f\n", weather, uniform_db,
                db(render(16, 6)), db(allocated(base, more, actual, share)),
                db(allocated(base, more, estimate, share)), uniform_seconds, estimate_seconds);
  }
  return 0;
}
