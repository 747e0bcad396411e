// Surfaces: for one ERP frame of each map (the default release's first sequence of the map, frame
// 30) rendered raw (no denoising), the share of non-sky pixels whose grey-level gradient is below
// 2 levels (target <= 35 % on every map), and the frame time with textures against the same frame
// without them (every material its plain mean albedo), in the same run (target <= 1.2x).
// Usage: bench_surfaces [ERP height = 256] [spp = 256] [threads = all] [--save DIR] [maps...]
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "flowscape/formats/image_io.h"
#include "flowscape/formats/srgb.h"
#include "flowscape/quality/image_statistics.h"
#include "flowscape/release/sequence.h"

using namespace flowscape;

namespace {

struct Render {
  Image<std::uint8_t> image;
  double seconds;
};

Render render(Renderer& renderer, const Projection& erp, const FramePair& pair,
              const RenderOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const Image<float> color = renderer.color(erp, pair, options);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return {linear_to_srgb8(color.view()), seconds};
}

}  // namespace

int main(int argc, char** argv) {
  int height = 256, spp = 256, threads = tbb::this_task_arena::max_concurrency();
  std::string save;
  std::vector<int> maps, numbers;
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--save" && k + 1 < argc)
      save = argv[++k];
    else
      numbers.push_back(std::atoi(argv[k]));
  }
  if (numbers.size() > 0) height = numbers[0];
  if (numbers.size() > 1) spp = numbers[1];
  if (numbers.size() > 2) threads = numbers[2];
  maps.assign(numbers.begin() + std::min<std::size_t>(3, numbers.size()), numbers.end());
  if (maps.empty()) maps = {0, 1, 2, 3, 4, 5, 6, 7};
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const ReleaseConfig config;  // the paper's FlowScape
  const int frame = 30;
  std::printf(
      "bench_surfaces: %d x %d ERP, %d spp raw, %d threads, frame %d of each map's "
      "first sequence\n",
      height, 2 * height, spp, threads, frame);
  std::printf("  %-11s %16s %16s %10s %10s %7s\n", "map", "flat, textured", "flat, plain",
              "s textured", "s plain", "ratio");
  double worst = 0, textured_total = 0, plain_total = 0;
  for (int map : maps) {
    const SequencePlan plan = plan_sequences(config)[std::size_t(map * config.sequences_per_map)];
    const Sequence sequence = make_sequence(sequence_spec(config, plan));
    Renderer renderer(sequence.city.scene);
    const FramePair pair = sequence.frame_pair(frame);
    const Projection erp = Projection::equirectangular(height);
    const GroundTruth truth = renderer.ground_truth(erp, pair);
    Image<std::uint8_t> not_sky(erp.width, erp.height, 1);
    for (std::size_t i = 0; i < not_sky.data.size(); ++i)
      not_sky.data[i] = truth.semantic.data[i] != std::uint8_t(SemanticClass::Sky);
    RenderOptions options{spp, config.max_bounces, sequence.color_seed(frame)};
    const Render textured = render(renderer, erp, pair, options);
    options.textures = false;
    const Render plain = render(renderer, erp, pair, options);
    const double flat = 100 * flat_share(textured.image.view(), not_sky.view(), 2, true);
    const double flat_plain = 100 * flat_share(plain.image.view(), not_sky.view(), 2, true);
    worst = std::max(worst, flat);
    textured_total += textured.seconds, plain_total += plain.seconds;
    std::printf("  %d %-9s %14.1f %% %14.1f %% %10.2f %10.2f %6.2fx\n", map, map_name(map).c_str(),
                flat, flat_plain, textured.seconds, plain.seconds,
                textured.seconds / plain.seconds);
    std::fflush(stdout);
    if (!save.empty()) {
      write_image(save + "/" + map_name(map) + "_textured.png", textured.image);
      write_image(save + "/" + map_name(map) + "_plain.png", plain.image);
    }
  }
  std::printf(
      "  worst flat share with textures %.1f %% (target <= 35 %%); time with textures "
      "%.2fx the plain frames (target <= 1.2x)\n",
      worst, textured_total / plain_total);
  return 0;
}
