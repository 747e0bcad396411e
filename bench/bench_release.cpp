// Release throughput: seconds per frame of the default FlowScape release (512 x 1024 ERP, six
// 256^2 cube faces, 16 spp, every modality written) on one sequence, and the projected time of the
// full 6,400-frame release; baseline: the same frames without cube faces (ERP rendered directly).
// Usage: bench_release [frames] [threads] [spp]
#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "flowscape/release/writer.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

double seconds_per_frame(ReleaseConfig config, const fs::path& out) {
  fs::remove_all(out);
  const SequencePlan plan = plan_sequences(config).front();
  const auto start = std::chrono::steady_clock::now();
  write_sequence(config, plan, out, {[] {}, [] {}});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fs::remove_all(out);
  return seconds / config.frames;
}

}  // namespace

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::atoi(argv[1]) : 4, threads = argc > 2 ? std::atoi(argv[2]) : 2;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  ReleaseConfig config;  // the paper's FlowScape
  const int full_frames = config.maps * config.sequences_per_map * config.frames;
  if (argc > 3) config.spp = std::atoi(argv[3]);
  config.maps = 1, config.sequences_per_map = 1, config.frames = frames;
  const fs::path out = fs::temp_directory_path() / "flowscape-bench-release";
  std::printf(
      "bench_release: %d frames of map00_seq00, %d threads, %d x %d ERP, %d^2 faces, %d spp\n",
      frames, threads, config.height, 2 * config.height, config.face_size, config.spp);
  const double full = seconds_per_frame(config, out);
  config.cube = false;
  const double erp_only = seconds_per_frame(config, out);
  std::printf("  release frame (cube faces + stitched ERP, all files)   %6.2f s/frame\n", full);
  std::printf("  baseline: ERP only, rendered directly (--no-cube)       %6.2f s/frame\n",
              erp_only);
  std::printf("  full release, %d frames: %.2f h   (target < 4 h on 2 cores); --no-cube: %.2f h\n",
              full_frames, full * full_frames / 3600, erp_only * full_frames / 3600);
  return 0;
}
