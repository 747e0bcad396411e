// Temporal reconstruction (ReleaseConfig::temporal, renderer/temporal.h) against each frame alone
// (today's default, temporal 0) in the same run, per weather and time of day: a sequence of map 0
// written by the release writer with the ERP rendered directly (--no-cube; or stitched from the
// cube faces), each variant's 8-bit colour against a converged reference of the same frames (raw,
// every sample gathering indirect light):
// - non-sky PSNR (dB) of each frame, averaged over the frames;
// - PE between consecutive frames: |I(t) - I(t+1) warped back by the exact flow|, 8-bit levels
//   averaged over the channels, over the non-sky pixels visible in both (the paper's Table II
//   measure; photoconsistency.h's WPE), and its ratio to the converged frames' PE (target: within
//   +-10 %);
// - the relative error of non-sky linear colour (sRGB decoded, frame_quality.h's relative_mse;
//   night and dusk against the day's);
// - the seconds per frame of the whole sequence (colour, ground truth, files), as a ratio to
//   temporal 0's.
// First, the peak resident memory of a sequence of the default release (the flowscape rig: ERP and
// six faces, the default outputs) at `memory height` (its faces half as wide), each frame alone and
// with each window, each in a process of its own (target: at most 4 GB at 512 x 1024).
// Usage: bench_temporal [ERP height = 64] [reference spp = 512] [frames = 6]
//                       [windows = 1,2,3] [conditions = all: sunny,cloud,fog,rain,dawn,dusk,night]
//                       [memory height = 512; 0: none] [figure.png: the middle frame of each
//                       condition, converged, frame by frame and with the widest window]
//                       [cube: the ERP stitched from six faces of half its height, as the
//                       default release makes it, against the converged faces stitched alike;
//                       "erp": rendered directly]
//                       [samples per pixel = the release's 8; a list such as 4,8,16,32: each
//                       pipeline at each, the curve of PSNR and PE against seconds per frame]
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "flowscape/core/profile.h"
#include "flowscape/formats/contact_sheet.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/formats/srgb.h"
#include "flowscape/layout/layout.h"
#include "flowscape/quality/photoconsistency.h"
#include "flowscape/release/sequence.h"
#include "flowscape/release/writer.h"
#include "flowscape/stitcher/stitch.h"
#include "frame_quality.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

// The converged frames of a sequence and their ground truth.
struct Reference {
  std::vector<GroundTruth> truth;
  std::vector<Image<float>> color;
};

Reference reference(const ReleaseConfig& config, const SequencePlan& plan, int spp) {
  const Sequence sequence = make_sequence(sequence_spec(config, plan));
  Renderer renderer(sequence.city.scene);
  const Projection erp = Projection::equirectangular(config.height);
  const CubeToErp faces_to_erp = make_cube_to_erp(config.face_size, config.height);
  Reference r;
  for (int f = 0; f < config.frames; ++f) {
    const FramePair pair = sequence.frame_pair(f);
    const RenderOptions options{spp, config.max_bounces, sequence.color_seed(f) + 1};
    r.truth.push_back(renderer.ground_truth(erp, pair));
    r.color.push_back(
        config.cube ? resample_bilinear(
                          faces_to_erp.sampling,
                          raw_color(cube_color_layers(renderer, config.face_size, pair, options)))
                    : renderer.color(erp, pair, options));
  }
  return r;
}

// PE of frame t to t + 1 over the non-sky pixels visible in both.
double consecutive_pe(const Image<std::uint8_t>& first, const Image<std::uint8_t>& second,
                      const GroundTruth& truth) {
  Image<std::uint8_t> surface(first.width, first.height, 1);
  for (std::size_t i = 0; i < surface.data.size(); ++i)
    surface.data[i] = truth.semantic.data[i] != std::uint8_t(SemanticClass::Sky);
  return photo_errors({first.view(), second.view(), truth.flow.view(), surface.view(),
                       truth.valid.view(), true})
      .wpe_visible;
}

Image<float> linear(const Image<std::uint8_t>& srgb) {
  Image<float> out(srgb.width, srgb.height, 3);
  for (std::size_t i = 0; i < out.data.size(); ++i)
    out.data[i] = float(srgb8_to_linear(srgb.data[i]));
  return out;
}

struct Figures {
  double psnr = 0, pe = 0, relative = 0, seconds = 0;
  std::string phases;                         // seconds per frame by stage
  std::vector<Image<std::uint8_t>> frames{};  // as written
};

std::string phase_line(int frames) {
  std::string line;
  char text[96];
  for (const PhaseTime& phase : phase_times()) {
    std::snprintf(text, sizeof text, "%s%s %.3f", line.empty() ? "" : ", ", phase.name.c_str(),
                  phase.seconds / frames);
    line += text;
  }
  return line;
}

Figures measure(const ReleaseConfig& config, const SequencePlan& plan, const Reference& ref,
                const fs::path& out) {
  fs::remove_all(out);
  reset_phase_times();
  const auto start = std::chrono::steady_clock::now();
  write_sequence(config, plan, out, {[] {}, [] {}});
  Figures f;
  f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
              config.frames;
  f.phases = phase_line(config.frames);
  std::vector<Image<std::uint8_t>>& frames = f.frames;
  for (int t = 0; t < config.frames; ++t)
    frames.push_back(read_image<std::uint8_t>(sequence_dir(out, plan.name) /
                                              frame_file(output_kind("color"), View(), t)));
  for (int t = 0; t < config.frames; ++t) {
    const std::size_t k = std::size_t(t);
    const Image<float> decoded = linear(frames[k]);
    f.psnr += psnr(decoded, ref.color[k], ref.truth[k]) / config.frames;
    f.relative += relative_mse(decoded, ref.color[k], ref.truth[k], true) / config.frames;
    if (t + 1 < config.frames)
      f.pe += consecutive_pe(frames[std::size_t(t)], frames[std::size_t(t) + 1],
                             ref.truth[std::size_t(t)]) /
              (config.frames - 1);
  }
  return f;
}

// Writes a sequence of the default release in a child process and prints its peak resident set.
void print_peak_memory(int height, int window, const fs::path& scratch) {
  ReleaseConfig config;
  config.maps = 1, config.sequences_per_map = 1, config.frames = 2 * window + 2;
  config.height = height, config.face_size = height / 2, config.temporal = window;
  const fs::path out = scratch / ("memory" + std::to_string(window));
  fs::remove_all(out);
  std::fflush(stdout);
  const pid_t child = fork();
  if (child == 0) {
    write_sequence(config, plan_sequences(config).front(), out, {[] {}, [] {}});
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::printf("  %-12s %d frames: %.2f GB\n",
                window == 0 ? "each frame" : ("temporal " + std::to_string(window)).c_str(),
                config.frames, double(usage.ru_maxrss) / (1024.0 * 1024.0));
    std::fflush(stdout);
    std::_Exit(0);
  }
  int status = 0;
  waitpid(child, &status, 0);
}

Image<std::uint8_t> labelled(Image<std::uint8_t> tile, const std::string& text) {
  label_tile(tile, text);
  return tile;
}

}  // namespace

int main(int argc, char** argv) {
  const int height = argc > 1 ? std::atoi(argv[1]) : 64;
  const int reference_spp = argc > 2 ? std::atoi(argv[2]) : 512;
  const int frames = argc > 3 ? std::atoi(argv[3]) : 6;
  std::vector<int> windows;
  for (const std::string& w : comma_separated(argc > 4 ? argv[4] : "1,2,3"))
    windows.push_back(std::stoi(w));
  const std::vector<std::string> conditions =
      comma_separated(argc > 5 ? argv[5] : "sunny,cloud,fog,rain,dawn,dusk,night");
  const fs::path scratch = fs::temp_directory_path() / "bench_temporal";
  const std::string figure = argc > 7 ? argv[7] : "";
  const bool cube = argc > 8 && std::string(argv[8]) == "cube";
  std::vector<int> sample_counts;
  for (const std::string& spp :
       comma_separated(argc > 9 ? argv[9] : std::to_string(ReleaseConfig{}.spp)))
    sample_counts.push_back(std::stoi(spp));
  std::vector<std::vector<Image<std::uint8_t>>> figure_rows;
  // first: the children are forked before this process starts TBB's threads
  const int memory_height = argc > 6 ? std::atoi(argv[6]) : 512;
  if (memory_height > 0) {
    std::printf("peak resident memory, default release, %d x %d ERP + 6 x %d^2 faces:\n",
                memory_height, 2 * memory_height, memory_height / 2);
    print_peak_memory(memory_height, 0, scratch);
    for (int window : windows) print_peak_memory(memory_height, window, scratch);
  }
  std::printf("bench_temporal: map 0, %d frames, %d x %d ERP (%s), reference %d spp raw\n", frames,
              height, 2 * height, cube ? "stitched from the cube faces" : "rendered directly",
              reference_spp);
  std::printf("  %-8s %-12s %8s %8s %8s %10s %9s %8s\n", "", "pipeline", "PSNR dB", "PE", "PE/conv",
              "rel. err", "s/frame", "time x");
  for (const std::string& condition : conditions) {
    ReleaseConfig config;
    config.maps = 1, config.sequences_per_map = 1, config.frames = frames;
    config.height = height, config.face_size = height / 2, config.outputs = {};
    config.cube = cube;
    const bool time_of_day = condition == "dawn" || condition == "dusk" || condition == "night";
    config.weathers = {time_of_day ? "sunny" : condition};
    config.times_of_day = {time_of_day ? condition : "day"};
    const SequencePlan plan = plan_sequences(config).front();
    const Reference ref = reference(config, plan, reference_spp);
    double converged_pe = 0;
    std::vector<Image<std::uint8_t>> converged;
    for (const Image<float>& c : ref.color) converged.push_back(linear_to_srgb8(c.view()));
    for (int t = 0; t + 1 < frames; ++t)
      converged_pe += consecutive_pe(converged[std::size_t(t)], converged[std::size_t(t) + 1],
                                     ref.truth[std::size_t(t)]) /
                      (frames - 1);
    std::printf("  %-8s %-12s %8s %8.3f %8s\n", condition.c_str(), "converged", "", converged_pe,
                "1.00");
    const std::size_t middle = std::size_t(frames / 2);
    for (int spp : sample_counts) {
      config.spp = spp;
      const std::string at = sample_counts.size() > 1 ? " " + std::to_string(spp) : "";
      config.temporal = 0;
      const Figures alone = measure(config, plan, ref, scratch / "alone");
      std::printf("  %-8s %-12s %8.2f %8.3f %8.2f %10.5f %9.2f %8.2f\n", condition.c_str(),
                  ("each frame" + at).c_str(), alone.psnr, alone.pe, alone.pe / converged_pe,
                  alone.relative, alone.seconds, 1.0);
      std::printf("      s/frame by stage: %s\n", alone.phases.c_str());
      if (spp == sample_counts.front())
        figure_rows.push_back({labelled(converged[middle], condition + ", converged"),
                               labelled(alone.frames[middle], "each frame")});
      for (int window : windows) {
        config.temporal = window;
        const Figures f =
            measure(config, plan, ref, scratch / ("temporal" + std::to_string(window)));
        if (window == windows.back() && spp == sample_counts.front())
          figure_rows.back().push_back(
              labelled(f.frames[middle], "temporal " + std::to_string(window)));
        std::printf("  %-8s %-12s %8.2f %8.3f %8.2f %10.5f %9.2f %8.2f\n", condition.c_str(),
                    ("temporal " + std::to_string(window) + at).c_str(), f.psnr, f.pe,
                    f.pe / converged_pe, f.relative, f.seconds, f.seconds / alone.seconds);
        std::printf("      s/frame by stage: %s\n", f.phases.c_str());
      }
      std::fflush(stdout);
    }
  }
  if (!figure.empty()) write_image(figure, contact_sheet(figure_rows));
  fs::remove_all(scratch);
}
