// Rolling shutter's cost: one city frame seen by a 90-degree pinhole looking sideways from the
// ego, its ground truth (forward flow), colour (release spp) and depth guide, with a global
// shutter (the baseline) and a rolling one (row readout), in the same run; and the time to pose
// the scene once (what a rolling shutter pays per line), with the city's counts.
// Usage: bench_rolling_shutter [width = 320] [readout_ms = 30] [threads = 2]
#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "flowscape/release/sequence.h"

using namespace flowscape;

namespace {

template <class Work>
double seconds(Work&& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Costs {
  double truth, color, depth;
};

Costs costs(Renderer& renderer, const Sequence& sequence, const Projection& camera,
            const TruthRequest& request, const RenderOptions& options) {
  Costs c{};
  c.truth = seconds([&] { renderer.ground_truth(camera, request); });
  c.color = seconds([&] {
    renderer.color_layers(camera, request.pair.time, request.track, request.readout, options);
  });
  c.depth =
      seconds([&] { renderer.depth(camera, request.pair.time, request.track, request.readout); });
  (void)sequence;
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  const int width = argc > 1 ? std::atoi(argv[1]) : 320;
  const double readout = (argc > 2 ? std::atof(argv[2]) : 30) / 1000;
  const int threads = argc > 3 ? std::atoi(argv[3]) : 2;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  ReleaseConfig config;
  config.frames = 3;
  const Sequence sequence = make_sequence(sequence_spec(config, plan_sequences(config).front()));
  Renderer renderer(sequence.city.scene);
  std::size_t parts = 0, skinned_vertices = 0;
  for (const Actor& actor : sequence.city.scene.actors)
    for (const Part& part : actor.parts) {
      ++parts;
      if (part.bones) skinned_vertices += part.mesh->vertices.size();
    }
  const int height = width * 3 / 4;
  const Projection camera = Projection::pinhole(width, height, 90);
  TruthRequest request = truth_plan(sequence, release_layout(config), 1, config.frames).request;
  request.pair.rig = request.pair.rig * Pose(Eigen::AngleAxisd(kPi / 2, Vec3::UnitZ()));
  const CameraTrack rig = request.track;
  request.track = [rig](double t) {
    return rig(t) * Pose(Eigen::AngleAxisd(kPi / 2, Vec3::UnitZ()));
  };
  request.pair.next_rig = request.track(request.pair.next_time);
  const RenderOptions options = sequence.color_options(color_section(config), 1);
  std::printf(
      "bench_rolling_shutter: %d x %d pinhole looking left, %d spp, %d threads; city: %zu "
      "actors, %zu parts, %zu skinned vertices\n",
      width, height, options.samples_per_pixel, threads, sequence.city.scene.actors.size(), parts,
      skinned_vertices);
  const Costs global = costs(renderer, sequence, camera, request, options);
  request.readout = {readout, false};
  const Costs rolling = costs(renderer, sequence, camera, request, options);
  std::printf("%-12s %10s %10s %10s\n", "", "truth", "colour", "depth");
  std::printf("%-12s %9.2fs %9.2fs %9.2fs\n", "global", global.truth, global.color, global.depth);
  std::printf("%-12s %9.2fs %9.2fs %9.2fs\n", "rolling", rolling.truth, rolling.color,
              rolling.depth);
  std::printf("%-12s %9.1fx %9.1fx %9.1fx\n", "ratio", rolling.truth / global.truth,
              rolling.color / global.color, rolling.depth / global.depth);
  std::printf("one pose of the scene (rolling depth less global, per line): %.2f ms\n",
              1000 * (rolling.depth - global.depth) / height);
}
