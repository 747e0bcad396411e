// Where the error of the release's colour is, per time of day (sunny; map 0's first sequence,
// frame 1, the ERP rendered directly): the relative MSE of non-sky colour (clipped to what the
// camera records, frame_quality.h's relative_mse) of the release's denoised colour against a
// converged raw render, and its ratio to the day's (target: night and dusk within 1.5x), with edge
// samples (ReleaseConfig::edge_spp, the default) and without (edge_spp 0: flowscape 0.16), with
// the seconds of path tracing of each and their ratio. Then, for the default, the same error with
// one layer (direct, indirect, specular, other) taken from the converged render: what perfect
// sampling of that layer would leave, so the largest drop names the layer to work on.
// Usage: bench_layer_error [ERP height = 256] [reference spp = 256] [times = day,dusk,night]
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "frame_quality.h"

using namespace flowscape;

namespace {

struct Traced {
  ColorLayers layers;
  double seconds;
};

Traced trace(Renderer& renderer, const Projection& erp, const FramePair& pair,
             const RenderOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ColorLayers layers = renderer.color_layers(erp, pair, options);
  return {std::move(layers),
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

}  // namespace

int main(int argc, char** argv) {
  const int height = argc > 1 ? std::atoi(argv[1]) : 256;
  const int reference_spp = argc > 2 ? std::atoi(argv[2]) : 256;
  const std::vector<std::string> times = comma_separated(argc > 3 ? argv[3] : "day,dusk,night");
  const ReleaseConfig defaults;
  const ColorSection color = color_section(defaults);
  SequenceSpec spec = sequence_spec(defaults, plan_sequences(defaults).front());
  spec.weather = "sunny";
  const int frame = 1;
  std::printf("bench_layer_error: map 0, frame %d, %d x %d ERP, sunny, reference %d spp raw\n",
              frame, height, 2 * height, reference_spp);
  std::printf("  %-6s %-22s %10s %8s %9s %8s\n", "time", "pipeline", "rel. MSE", "/ day's",
              "trace s", "time x");
  double day[2] = {0, 0};
  for (const std::string& time : times) {
    spec.time_of_day = time;
    const Sequence sequence = make_sequence(spec);
    Renderer renderer(sequence.city.scene);
    const FramePair pair = sequence.frame_pair(frame);
    const Projection erp = Projection::equirectangular(height);
    const GroundTruth truth = renderer.ground_truth(erp, pair);
    const RenderOptions options = sequence.color_options(color, frame);
    RenderOptions converged = options;
    converged.samples_per_pixel = reference_spp, converged.indirect_samples = 0;
    converged.seed = options.seed + 1;
    const ColorLayers reference_layers = renderer.color_layers(erp, pair, converged);
    const Image<float> reference = raw_color(reference_layers);
    const auto error = [&](const ColorLayers& layers) {
      return relative_mse(
          denoised_color(color, layers, erp, truth.depth.view(), truth.instance.view()), reference,
          truth, true);
    };
    RenderOptions without = options;
    without.edge_samples = 0;
    const Traced before = trace(renderer, erp, pair, without);
    const Traced now = trace(renderer, erp, pair, options);
    const double errors[2] = {error(before.layers), error(now.layers)};
    if (time == times.front()) day[0] = errors[0], day[1] = errors[1];
    const char* names[2] = {"edge_spp 0 (0.16)", "default (edge_spp 32)"};
    for (int k = 0; k < 2; ++k)
      std::printf("  %-6s %-22s %10.5f %7.2fx %9.2f %7.2fx\n", time.c_str(), names[k], errors[k],
                  errors[k] / day[k], (k ? now : before).seconds,
                  (k ? now : before).seconds / before.seconds);
    Image<float> ColorLayers::*const layers[4] = {&ColorLayers::direct, &ColorLayers::indirect,
                                                  &ColorLayers::specular, &ColorLayers::other};
    const char* layer_names[4] = {"direct", "indirect", "specular", "other"};
    std::printf("         default with one layer converged:");
    for (int l = 0; l < 4; ++l) {
      ColorLayers oracle = now.layers;
      oracle.*layers[l] = reference_layers.*layers[l];
      std::printf(" %s %.5f", layer_names[l], error(oracle));
    }
    std::printf("\n");
    std::fflush(stdout);
  }
  std::printf("  target: night and dusk within 1.5x of the day's relative MSE at equal time\n");
}
