// Adaptive sampling against uniform sampling (release/adaptive_sampling.h, issue 37's noise
// lever): the non-sky PSNR (frame_quality.h) of a-trous-denoised colour and the seconds of colour
// and denoising, for the default's uniform 8 samples per pixel (4 indirect), uniform 16 (twice the
// budget), the release's adaptive sampling at 8 and 6 samples on average (the given share of the
// pixels taking the second pass), and an oracle at 8: the same passes, the share chosen by each
// pixel's actual error after denoising the first half (the upper bound of any choice). The
// downtown frame 30 of the default release's first sequence (bench_image_quality's), direct ERP
// camera, 2 threads.
// Usage: bench_adaptive_sampling [ERP height = 128] [reference spp = 1024] [share = 0.25]
#include <tbb/global_control.h>

#include <cstdio>
#include <cstdlib>

#include "flowscape/core/profile.h"
#include "flowscape/release/adaptive_sampling.h"
#include "flowscape/renderer/denoise.h"
#include "frame_quality.h"

using namespace flowscape;

namespace {

// adaptive_color_layers' passes (with seeds of their own) with the share chosen by each pixel's
// actual error after denoising the pooled halves.
ColorLayers oracle(const Setup& s, const RenderLayers& render, const DenoiseLayers& denoised,
                   const RenderOptions& budget, double share) {
  const SampleSplit split = sample_split(budget.samples_per_pixel, share);
  const auto pass = [&](int spp, std::uint64_t seed) {
    RenderOptions options = budget;
    options.samples_per_pixel = spp, options.indirect_samples = spp / 2;
    options.seed += seed;
    return options;
  };
  const ColorLayers half =
      pooled(render(pass(split.half, 11)), split.half, render(pass(split.half, 12)), split.half);
  const Image<std::uint8_t> chosen = top_pixels(
      squared_srgb_difference(denoised(half), s.reference), s.erp.width, s.erp.height, share);
  RenderOptions more = pass(split.more, 13);
  more.pixels = chosen.view();
  return replaced(half, render(more), chosen.view());
}

}  // namespace

int main(int argc, char** argv) {
  const int height = argc > 1 ? std::atoi(argv[1]) : 128;
  const int reference_spp = argc > 2 ? std::atoi(argv[2]) : 1024;
  const double share = argc > 3 ? std::atof(argv[3]) : 0.25;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  const ReleaseConfig defaults;
  const int frame = 30;
  SequenceSpec spec = sequence_spec(defaults, plan_sequences(defaults).front());
  spec.city.ego_route = EgoRoute::Free;  // bench_image_quality's frame
  std::printf(
      "bench_adaptive_sampling: downtown frame %d, %d x %d ERP, reference %d spp, 2 threads; "
      "adaptive: %.0f %% of the pixels take the second pass\n",
      frame, height, 2 * height, reference_spp, 100 * share);
  std::printf("  %-7s %11s %11s %11s %11s %11s %11s %11s %11s\n", "weather", "uniform 8",
              "uniform 16", "oracle 8", "adaptive 8", "adaptive 6", "uniform 8:s", "adapt. 8:s",
              "adapt. 6:s");
  for (const char* weather : {"sunny", "cloud", "fog", "rain"}) {
    spec.weather = weather;
    Setup s(spec, frame, height, reference_spp);
    const RenderOptions release = s.sequence.color_options(color_section(defaults), frame);
    const auto options = [&](int spp) {
      RenderOptions o = release;
      o.samples_per_pixel = spp, o.indirect_samples = spp / 2;
      return o;
    };
    const RenderLayers render = [&](const RenderOptions& o) {
      return s.renderer.color_layers(s.erp, s.pair, o);
    };
    const DenoiseLayers denoised = [&](const ColorLayers& layers) {
      return denoise(layers, {&s.erp, s.truth.depth.view(), s.truth.instance.view()});
    };
    // The denoised colour of `layers`' and its seconds with them.
    const auto timed = [&](const std::function<ColorLayers()>& layers) {
      const double start = wall_seconds();
      const Image<float> color = denoised(layers());
      return std::pair{psnr(color, s.reference, s.truth), wall_seconds() - start};
    };
    const auto adaptive = [&](int spp) {
      return timed([&] { return adaptive_color_layers(render, denoised, options(spp), share); });
    };
    const auto [uniform_db, uniform_s] = timed([&] { return render(options(8)); });
    const auto [adaptive_db, adaptive_s] = adaptive(8);
    const auto [adaptive6_db, adaptive6_s] = adaptive(6);
    std::printf(
        "  %-7s %8.2f dB %8.2f dB %8.2f dB %8.2f dB %8.2f dB %11.3f %11.3f %11.3f\n", weather,
        uniform_db, timed([&] { return render(options(16)); }).first,
        psnr(denoised(oracle(s, render, denoised, options(8), share)), s.reference, s.truth),
        adaptive_db, adaptive6_db, uniform_s, adaptive_s, adaptive6_s);
  }
  return 0;
}
