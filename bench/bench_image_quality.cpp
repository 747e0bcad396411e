// Image quality per weather: for a fixed downtown frame (the default release's map 0, frame 30,
// the weather preset varied by the sequence's seed) rendered by the direct ERP camera, the
// non-sky PSNR of 8-bit sRGB colour against a raw reference of many samples, for the raw path
// tracer at 16 spp (the baseline) and the release's default (ReleaseConfig: spp, indirect_spp,
// a-trous), with the seconds per frame of each (colour and denoising; the ground truth, needed by
// both, not counted). Targets: PSNR >= 40 dB in every weather, at most half the baseline's time.
// Usage: bench_image_quality [ERP height = 128] [spp = release default] [indirect spp = release
// default] [reference spp = 1024] [threads = all]
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "flowscape/formats/srgb.h"
#include "flowscape/release/sequence.h"
#include "flowscape/renderer/denoise.h"

using namespace flowscape;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double psnr(const Image<float>& image, const Image<float>& reference, const GroundTruth& truth) {
  const Image<std::uint8_t> a = linear_to_srgb8(image.view()),
                            b = linear_to_srgb8(reference.view());
  double squared = 0;
  long count = 0;
  for (std::size_t i = 0; i < truth.semantic.data.size(); ++i) {
    if (truth.semantic.data[i] == std::uint8_t(SemanticClass::Sky)) continue;
    for (int c = 0; c < 3; ++c) {
      const double d = double(a.data[3 * i + c]) - b.data[3 * i + c];
      squared += d * d, ++count;
    }
  }
  return 10 * std::log10(255.0 * 255.0 / std::max(squared / count, 1e-12));
}

}  // namespace

int main(int argc, char** argv) {
  const ReleaseConfig config;
  const int height = argc > 1 ? std::atoi(argv[1]) : 128;
  const int spp = argc > 2 ? std::atoi(argv[2]) : config.spp;
  const int indirect_spp = argc > 3 ? std::atoi(argv[3]) : config.indirect_spp;
  const int reference_spp = argc > 4 ? std::atoi(argv[4]) : 1024;
  tbb::global_control limit(
      tbb::global_control::max_allowed_parallelism,
      argc > 5 ? std::atoi(argv[5]) : tbb::this_task_arena::max_concurrency());
  const SequencePlan plan = plan_sequences(config).front();
  const int frame = 30;
  std::printf("bench_image_quality: downtown frame %d, %d x %d ERP, reference %d spp raw\n", frame,
              height, 2 * height, reference_spp);
  std::printf("  %-7s %18s %18s %12s %12s %7s\n", "weather", "PSNR raw 16 spp", "PSNR default",
              "s raw 16", "s default", "ratio");
  double worst = 1e9, raw_total = 0, default_total = 0;
  for (const char* weather : {"sunny", "cloud", "fog", "rain"}) {
    SequenceSpec spec = sequence_spec(config, plan);
    spec.weather = weather;
    const Sequence sequence = make_sequence(spec);
    Renderer renderer(sequence.city.scene);
    const FramePair pair = sequence.frame_pair(frame);
    const Projection erp = Projection::equirectangular(height);
    const GroundTruth truth = renderer.ground_truth(erp, pair);
    const std::uint64_t seed = sequence.color_seed(frame);
    const Image<float> reference =
        renderer.color(erp, pair, {reference_spp, config.max_bounces, seed + 1});
    auto start = std::chrono::steady_clock::now();
    const Image<float> raw = renderer.color(erp, pair, {16, config.max_bounces, seed});
    const double raw_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    RenderOptions options{spp, config.max_bounces, seed};
    options.indirect_samples = std::min(indirect_spp, spp);
    const ColorLayers layers = renderer.color_layers(erp, pair, options);
    const Image<float> denoised =
        denoise(layers, {&erp, truth.depth.view(), truth.instance.view()});
    const double default_seconds = seconds_since(start);
    const double raw_psnr = psnr(raw, reference, truth),
                 default_psnr = psnr(denoised, reference, truth);
    worst = std::min(worst, default_psnr);
    raw_total += raw_seconds, default_total += default_seconds;
    std::printf("  %-7s %15.1f dB %15.1f dB %12.3f %12.3f %6.2fx\n", weather, raw_psnr,
                default_psnr, raw_seconds, default_seconds, default_seconds / raw_seconds);
    std::fflush(stdout);
  }
  std::printf(
      "  default: %d spp (%d indirect) + a-trous; worst PSNR %.1f dB (target >= 40 dB), "
      "time %.2fx the raw 16 spp frames (target <= 0.5x)\n",
      spp, std::min(indirect_spp, spp), worst, default_total / raw_total);
  return 0;
}
