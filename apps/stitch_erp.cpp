// stitch_erp: a cubemap folder (<face>/<modality>/<frame>) -> ERP files (<modality>/<frame>).
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>

#include "flowscape/cubemap_io.h"
#include "flowscape/flow_viz.h"
#include "flowscape/progress.h"
#include "flowscape/stitch.h"
#include "flowscape/synthetic.h"

namespace fsys = std::filesystem;
using namespace flowscape;

namespace {

struct Options {
  fsys::path cube_dir, out_dir, demo_dir;
  int height = 512, face_size = 256, threads = 0;
  std::string flow_mode = "360";
  bool force = false;
};

struct Job {
  std::string modality, file;
};

bool has_cube_file(const fsys::path& cube_dir, const std::string& modality,
                   const std::string& file) {
  return fsys::exists(cube_file(cube_dir, Face::Front, modality, file));
}

std::string stem(const std::string& file) { return fsys::path(file).stem().string(); }

void stitch_flow(const Options& o, const CubeToErp& map, const std::string& file) {
  const Flow flow = read_cube_flow(o.cube_dir, file);
  const std::string mask_file = stem(file) + ".png";
  std::optional<Image<std::uint16_t>> instance;
  std::optional<Image<std::uint8_t>> valid;
  if (has_cube_file(o.cube_dir, "instance", mask_file))
    instance = read_cube_image_as<std::uint16_t>(o.cube_dir, "instance", mask_file);
  if (has_cube_file(o.cube_dir, "valid", mask_file))
    valid = read_cube_image_as<std::uint8_t>(o.cube_dir, "valid", mask_file);
  FlowInput input{flow.uv.view()};
  if (instance) input.instance = instance->view();
  input.valid = valid ? valid->view() : flow.valid.view();
  const FlowMode mode = o.flow_mode == "classic" ? FlowMode::Classic : FlowMode::Wrap360;
  const FlowOutput erp = cube_to_erp_flow(map, input, mode);
  write_flow(o.out_dir / "flow" / file, erp.flow.view(), erp.valid.view());
  if (valid) write_image(o.out_dir / "valid" / mask_file, erp.valid);
}

void stitch_image(const Options& o, const CubeToErp& map, const Job& job) {
  const AnyImage cube = read_cube_image(o.cube_dir, job.modality, job.file);
  std::visit(
      [&](const auto& stack) {
        const bool smooth = job.modality == "color";
        const auto erp = smooth ? resample_bilinear(map.sampling, stack.view())
                                : resample_nearest(map.sampling, stack.view());
        write_image(o.out_dir / job.modality / job.file, erp);
      },
      cube);
}

// The files a job writes; it is done when they all exist.
std::vector<fsys::path> outputs(const Options& o, const Job& job) {
  std::vector<fsys::path> files{o.out_dir / job.modality / job.file};
  const std::string mask_file = stem(job.file) + ".png";
  if (job.modality == "flow" && has_cube_file(o.cube_dir, "valid", mask_file))
    files.push_back(o.out_dir / "valid" / mask_file);
  return files;
}

std::vector<Job> list_jobs(const Options& o) {
  std::set<std::string> flow_frames;
  for (const std::string& file : cube_frame_files(o.cube_dir, "flow"))
    flow_frames.insert(stem(file));
  std::vector<Job> jobs;
  for (const std::string modality : {"color", "flow", "semantic", "instance", "depth", "valid"})
    for (const std::string& file : cube_frame_files(o.cube_dir, modality)) {
      // the valid mask of a frame with flow comes out of the flow stitch
      if (modality == "valid" && flow_frames.contains(stem(file))) continue;
      const Job job{modality, file};
      const auto files = outputs(o, job);
      const bool done = std::all_of(files.begin(), files.end(),
                                    [](const fsys::path& f) { return fsys::exists(f); });
      if (o.force || !done) jobs.push_back(job);
    }
  return jobs;
}

int face_size_of(const fsys::path& cube_dir) {
  for (const char* modality : {"color", "semantic", "depth", "flow"})
    for (const std::string& file : cube_frame_files(cube_dir, modality)) {
      if (std::string(modality) == "flow")
        return read_flow(cube_file(cube_dir, Face::Front, modality, file)).uv.width;
      return std::visit([](const auto& image) { return image.width; },
                        read_any_image(cube_file(cube_dir, Face::Front, modality, file)));
    }
  throw FileError(cube_dir, "no cubemap frames found (expected <face>/<modality>/<frame> files)");
}

int stitch_folder(const Options& o) {
  if (!fsys::is_directory(o.cube_dir)) throw FileError(o.cube_dir, "cubemap folder not found");
  const std::vector<Job> jobs = list_jobs(o);
  if (jobs.empty()) {
    std::fprintf(diagnostics(),
                 "stitch_erp: nothing to do, every output in %s exists (--force redoes it)\n",
                 o.out_dir.c_str());
    return 0;
  }
  const CubeToErp map = make_cube_to_erp(face_size_of(o.cube_dir), o.height);
  Progress progress("stitch_erp", jobs.size(), "files");
  for (const Job& job : jobs) {
    if (job.modality == "flow")
      stitch_flow(o, map, job.file);
    else
      stitch_image(o, map, job);
    progress.advance();
  }
  progress.finish();
  return 0;
}

// Writes the analytic yaw cubemap, stitches it, and reports the stitched flow against the exact
// answer u = yaw / 360 * W, v = 0.
int run_demo(Options o) {
  const double yaw_degrees = 3;
  const SyntheticCubemap cube = make_yaw_cubemap(o.face_size, yaw_degrees);
  o.cube_dir = o.demo_dir / "cube";
  o.out_dir = o.demo_dir / "erp";
  write_cube_image(o.cube_dir, "color", "000000.png", cube.color0.view());
  write_cube_image(o.cube_dir, "color", "000001.png", cube.color1.view());
  write_cube_flow(o.cube_dir, "000000.flo", cube.flow.view());
  write_cube_image(o.cube_dir, "semantic", "000000.png", cube.semantic.view());
  write_cube_image(o.cube_dir, "instance", "000000.png", cube.instance.view());
  write_cube_image(o.cube_dir, "depth", "000000.exr", cube.depth.view());
  write_cube_image(o.cube_dir, "valid", "000000.png", cube.valid.view());
  o.force = true;
  stitch_folder(o);
  const Flow erp = read_flo(o.out_dir / "flow" / "000000.flo");
  write_image(o.out_dir / "flow_viz" / "000000.png",
              flow_to_color(erp.uv.view(), erp.valid.view(), {FlowWheel::PanoFlow, 0}));
  double worst = 0;
  const double expected = yaw_degrees / 360 * erp.uv.width;
  for (std::size_t i = 0; i < erp.uv.pixel_count(); ++i)
    worst = std::max(
        {worst, std::abs(erp.uv.data[2 * i] - expected), std::abs(double(erp.uv.data[2 * i + 1]))});
  std::printf("demo: %s holds a %dx%d cubemap and its %dx%d ERP stitch\n", o.demo_dir.c_str(),
              o.face_size, o.face_size, erp.uv.width, erp.uv.height);
  std::printf(
      "demo: a %.0f deg yaw must give u = %.4f px, v = 0 everywhere; largest error %.2e px\n",
      yaw_degrees, expected, worst);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Stitch a cubemap folder (<face>/<modality>/<frame>, faces front right back left up "
      "down) into equirectangular files (<out>/<modality>/<frame>). Colour is bilinear, ids "
      "and depth nearest, flow is re-projected per pixel."};
  Options o;
  app.add_option("cube_dir", o.cube_dir, "cubemap folder, e.g. sequences/map00_seq00/cube");
  app.add_option("-o,--out", o.out_dir, "output folder, e.g. sequences/map00_seq00/erp");
  app.add_option("--height", o.height, "ERP height H (width is 2H)")->check(CLI::Range(2, 1 << 14));
  app.add_option("--flow-mode", o.flow_mode, "360 (shortest way round, paper Eq. 3) or classic")
      ->check(CLI::IsMember({"360", "classic"}));
  app.add_flag("--force", o.force,
               "redo outputs that exist (default: skip them, so reruns resume)");
  app.add_option("--threads", o.threads, "worker threads (0: all cores)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--demo", o.demo_dir,
                 "write the built-in analytic cubemap to DIR/cube and stitch it to DIR/erp");
  app.add_option("--face-size", o.face_size, "face size of the --demo cubemap")
      ->check(CLI::Range(2, 8192));
  CLI11_PARSE(app, argc, argv);
  std::optional<tbb::global_control> threads;
  if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
  try {
    if (!o.demo_dir.empty()) return run_demo(o);
    if (o.cube_dir.empty() || o.out_dir.empty()) {
      std::fprintf(diagnostics(),
                   "stitch_erp: give a cubemap folder and --out (or --demo DIR); see --help\n");
      return 2;
    }
    return stitch_folder(o);
  } catch (const std::exception& e) {
    std::fprintf(diagnostics(), "stitch_erp: error: %s\n", e.what());
    return 1;
  }
}
