// Image quality per weather: for a fixed downtown frame (the default release's map 0, frame 30,
// the weather preset varied by the sequence's seed) rendered by the direct ERP camera as a release
// renders colour (release_color), the non-sky PSNR of 8-bit sRGB colour against a converged
// reference (raw, every sample gathering indirect light), and the seconds per frame (colour and
// denoising; the ground truth, needed by all, not counted). Rows: the raw path tracer at 16 spp
// (the baseline), the a-trous default of before, OIDN's U-Net (default and small) at several
// sample counts, and the release's default (ReleaseConfig). Targets at the default: PSNR >= 40 dB
// in every weather, at most half the baseline's time. Then the release default per time of day
// (day, dusk, night; sunny): the relative MSE of non-sky colour against the reference at the
// sequence's exposure (clipped to what the camera records, and unclipped), and the seconds per
// frame (target: night within 1.5x of day).
// Usage: bench_image_quality [ERP height = 128] [reference spp = 1024] [threads = all]
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "frame_quality.h"

using namespace flowscape;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Variant {
  std::string name;
  ReleaseConfig config;
};

Variant variant(const std::string& name, int spp, const std::string& denoise,
                const std::string& model = "default", int indirect = 0) {
  Variant v{name, ReleaseConfig{}};
  v.config.spp = spp, v.config.denoise = denoise, v.config.denoise_model = model;
  v.config.indirect_spp = indirect;
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  const ReleaseConfig defaults;
  const int height = argc > 1 ? std::atoi(argv[1]) : 128;
  const int reference_spp = argc > 2 ? std::atoi(argv[2]) : 1024;
  tbb::global_control limit(
      tbb::global_control::max_allowed_parallelism,
      argc > 3 ? std::atoi(argv[3]) : tbb::this_task_arena::max_concurrency());
  std::vector<Variant> variants{variant("raw 16 spp (baseline)", 16, "none"),
                                variant("a-trous 8 spp (4 indirect)", 8, "atrous", "default", 4)};
  for (int spp : {1, 2, 4, 8})
    for (const char* model : {"default", "small"})
      variants.push_back(variant("oidn " + std::string(model) + " " + std::to_string(spp) + " spp",
                                 spp, "oidn", model));
  for (int bounces : {3, 2}) {  // issue 37's lever: shorter indirect paths
    ReleaseConfig shorter = defaults;
    shorter.max_bounces = bounces;
    variants.push_back({"release default, " + std::to_string(bounces) + " bounces", shorter});
  }
  variants.push_back({"release default", defaults});
  const SequencePlan plan = plan_sequences(defaults).front();
  const int frame = 30;
  std::printf(
      "bench_image_quality: downtown frame %d, %d x %d ERP, reference %d spp raw (every "
      "sample indirect)\n",
      frame, height, 2 * height, reference_spp);
  std::map<std::string, double> worst, seconds;
  std::printf("  %-30s %8s %8s %8s %8s %9s\n", "", "sunny", "cloud", "fog", "rain", "s/frame");
  std::vector<std::vector<double>> table(variants.size());
  std::vector<double> sky_bias;
  SequenceSpec spec = sequence_spec(defaults, plan);
  spec.city.ego_route = EgoRoute::Free;  // the frame its figures were of
  for (const char* weather : {"sunny", "cloud", "fog", "rain"}) {
    spec.weather = weather;
    Setup s(spec, frame, height, reference_spp);
    sky_bias.push_back(
        psnr(s.reference_before_averaged_sky(frame, reference_spp), s.reference, s.truth));
    for (std::size_t k = 0; k < variants.size(); ++k) {
      const auto start = std::chrono::steady_clock::now();
      const Image<float> color = release_color(color_section(variants[k].config), s.sequence,
                                               s.renderer, s.erp, frame, s.truth);
      seconds[variants[k].name] += seconds_since(start) / 4;
      table[k].push_back(psnr(color, s.reference, s.truth));
    }
  }
  const double baseline = seconds[variants[0].name];
  for (std::size_t k = 0; k < variants.size(); ++k) {
    std::printf("  %-30s", variants[k].name.c_str());
    for (double p : table[k]) std::printf(" %5.1f dB", p);
    std::printf(" %7.3f s (%.2fx)\n", seconds[variants[k].name],
                seconds[variants[k].name] / baseline);
  }
  std::printf("  %-30s", "converged, 0.11's sky");
  for (double p : sky_bias) std::printf(" %5.1f dB", p);
  std::printf("  (the averaged sky's bias: 0.11's converged colour against this one's)\n");
  const std::vector<double>& d = table.back();
  std::printf(
      "  release default (%d spp, %d indirect, %s): worst %.1f dB (target >= 40 dB), "
      "%.2fx the baseline's time (target <= 0.5x)\n",
      defaults.spp, indirect_samples(color_section(defaults)),
      release_denoiser(color_section(defaults))->description().c_str(),
      *std::min_element(d.begin(), d.end()), seconds["release default"] / baseline);
  // the release default per time of day (sunny): noise at the sequence's exposure and cost
  std::printf("\n  %-30s %12s %12s %9s %12s %10s %12s\n", "release default, sunny", "rel. MSE",
              "(unclipped)", "s/frame", "MSE / day's", "s / day's", "0.11's sky");
  double day_mse = 0, day_seconds = 0;
  spec.weather = "sunny";
  for (const char* time : {"day", "dusk", "night"}) {
    spec.time_of_day = time;
    Setup s(spec, frame, height, reference_spp);
    const auto start = std::chrono::steady_clock::now();
    const Image<float> color =
        release_color(color_section(defaults), s.sequence, s.renderer, s.erp, frame, s.truth);
    const double took = seconds_since(start), mse = relative_mse(color, s.reference, s.truth, true);
    if (day_mse == 0) day_mse = mse, day_seconds = took;
    const double bias = relative_mse(s.reference_before_averaged_sky(frame, reference_spp),
                                     s.reference, s.truth, true);
    std::printf("  %-30s %12.3g %12.3g %9.3f %11.2fx %9.2fx %12.3g\n", time, mse,
                relative_mse(color, s.reference, s.truth, false), took, mse / day_mse,
                took / day_seconds, bias);
  }
  std::printf(
      "  target: night within 1.5x of day's relative MSE at equal time (last column: 0.11's "
      "converged colour against this one's)\n");
  return 0;
}
