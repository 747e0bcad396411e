// What each output kind costs a release frame: the ray casting of its ground truth over the ERP
// and the six cube faces, its encoding and writing, and its bytes, against the baseline in the
// same run: the frame's colour (cube faces path traced at the release's samples and denoised) and
// the ground truth of the six kinds every release has. Median of the repeats; the same frame of
// map 0's first sequence as a release renders it.
// Usage: bench_outputs [ERP height = 512] [face size = 256] [repeats = 3] [threads = 2]
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>

#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/release/sequence.h"
#include "flowscape/renderer/denoise.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

double median_seconds(int repeats, const std::function<void()>& work) {
  std::vector<double> seconds;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    work();
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  return seconds[seconds.size() / 2];
}

// The ground truth of every view of the frame: the ERP and, with faces, the six faces.
void render_truth(Renderer& renderer, const ReleaseConfig& config, const TruthRequest& request) {
  renderer.ground_truth(Projection::equirectangular(config.height), request);
  if (config.cube) render_cube(renderer, config.face_size, request, nullptr);
}

// Seconds and bytes to write one image of every view as the kind's file.
struct Written {
  double seconds = 0;
  std::uintmax_t bytes = 0;
};
Written write_views(const fs::path& dir, const ReleaseConfig& config, const OutputKind& kind,
                    const Image<float>& erp, const Image<float>& cube) {
  Written w;
  w.seconds = median_seconds(1, [&] {
    const auto put = [&](const fs::path& path, ImageView<const float> image) {
      if (kind.is_flow())
        write_flo(path, image);
      else
        write_image(path, image);
      w.bytes += fs::file_size(path);
    };
    put(dir / ("erp" + std::string(kind.extension)), erp.view());
    if (config.cube)
      for (Face face : kFaces)
        put(dir / (std::string(face_name(face)) + std::string(kind.extension)),
            face_view(cube.view(), face));
  });
  return w;
}

}  // namespace

int main(int argc, char** argv) {
  ReleaseConfig config;
  config.height = argc > 1 ? std::atoi(argv[1]) : 512;
  config.face_size = argc > 2 ? std::atoi(argv[2]) : 256;
  const int repeats = argc > 3 ? std::atoi(argv[3]) : 3,
            threads = argc > 4 ? std::atoi(argv[4]) : 2;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  config.maps = 1, config.sequences_per_map = 1, config.frames = 6;
  const Sequence sequence = make_sequence(sequence_spec(config, plan_sequences(config).front()));
  Renderer renderer(sequence.city.scene);
  const int frame = 3;
  std::printf(
      "bench_outputs: %s frame %d, %d x %d ERP + 6 x %d^2 faces, %d threads, median of %d\n",
      map_name(0).c_str(), frame, config.height, 2 * config.height, config.face_size, threads,
      repeats);

  const RenderOptions options = sequence.color_options(color_section(config), frame);
  const TruthRequest base{sequence.frame_pair(frame)};
  const double color = median_seconds(repeats, [&] {
    const CubeFrame cube = render_cube(renderer, config.face_size, base, &options);
    denoise_cube(cube.color, cube.truth);
  });
  const double six = median_seconds(repeats, [&] { render_truth(renderer, config, base); });
  std::printf("  baseline: colour (6 faces, %d spp, denoised)        %7.3f s\n", config.spp, color);
  std::printf(
      "  baseline: the six kinds' ground truth (7 views)     %7.3f s  (%.1f %% of colour)\n", six,
      100 * six / color);

  const fs::path dir = fs::temp_directory_path() / "flowscape-bench-outputs";
  fs::create_directories(dir);
  struct Variant {
    const char* kind;
    std::function<void(TruthRequest&)> ask;
  };
  const Moment back = sequence.moment(frame - 1), ahead2 = sequence.moment(frame + 2),
               back2 = sequence.moment(frame - 2);
  const std::vector<Variant> variants{
      {"flow_backward + valid_backward", [&](TruthRequest& r) { r.more = {back}; }},
      {"flow_gap2 + valid_gap2", [&](TruthRequest& r) { r.more = {ahead2}; }},
      {"flow_backward_gap2 + valid_...", [&](TruthRequest& r) { r.more = {back2}; }},
      {"scene_flow", [](TruthRequest& r) { r.scene_flow = true; }},
      {"normal", [](TruthRequest& r) { r.normal = true; }},
      {"normal_shading", [](TruthRequest& r) { r.shading_normal = true; }},
  };
  std::printf("  %-32s %9s %9s %11s %9s\n", "kind (over the six)", "render s", "write s",
              "bytes/frame", "of colour");
  for (const Variant& v : variants) {
    TruthRequest request = base;
    v.ask(request);
    const double render = median_seconds(repeats, [&] { render_truth(renderer, config, request); });
    GroundTruth erp = renderer.ground_truth(Projection::equirectangular(config.height), request);
    CubeFrame cube = render_cube(renderer, config.face_size, request, nullptr);
    const bool flow = !request.more.empty();
    const Image<float>& erp_image = flow                 ? erp.more[0].flow
                                    : request.scene_flow ? erp.scene_flow
                                    : request.normal     ? erp.normal
                                                         : erp.shading_normal;
    const Image<float>& cube_image = flow                 ? cube.truth.more[0].flow
                                     : request.scene_flow ? cube.truth.scene_flow
                                     : request.normal     ? cube.truth.normal
                                                          : cube.truth.shading_normal;
    const OutputKind& kind = output_kind(flow                 ? "flow"
                                         : request.scene_flow ? "scene_flow"
                                         : request.normal     ? "normal"
                                                              : "normal_shading");
    Written written = write_views(dir, config, kind, erp_image, cube_image);
    if (flow) {  // and its valid mask
      const auto put = [&](const fs::path& path, const Image<std::uint8_t>& mask) {
        write_image(path, mask);
        written.bytes += fs::file_size(path);
      };
      written.seconds += median_seconds(1, [&] {
        put(dir / "erp.png", erp.more[0].valid);
        for (Face face : kFaces) {
          const auto view = face_view(cube.truth.more[0].valid.view(), face);
          Image<std::uint8_t> copy(view.width, view.height, 1);
          std::copy(view.data, view.data + view.pixel_count(), copy.data.begin());
          put(dir / (std::string(face_name(face)) + ".png"), copy);
        }
      });
    }
    const double extra = std::max(0.0, render - six) + written.seconds;
    std::printf("  %-32s %9.3f %9.3f %9.0f kB %8.1f %%\n", v.kind, std::max(0.0, render - six),
                written.seconds, written.bytes / 1e3, 100 * extra / color);
  }
  fs::remove_all(dir);
  return 0;
}
