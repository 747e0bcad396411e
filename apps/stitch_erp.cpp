// stitch_erp: a cubemap folder (<face>/<kind>/<frame>) -> ERP files (<kind>/<frame>).
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <optional>

#include "cli.h"
#include "flowscape/core/files.h"
#include "flowscape/layout/stitch_folder.h"

using namespace flowscape;

int main(int argc, char** argv) {
  CLI::App app{
      "Stitch a cubemap folder (<face>/<kind>/<frame>, faces front right back left up "
      "down) into equirectangular files (<out>/<kind>/<frame>). Colour is bilinear, ids "
      "and depth nearest, flow is re-projected per pixel."};
  StitchFolderOptions o;
  std::filesystem::path demo_dir;
  std::string flow_mode = "360";
  int threads = 0, face_size = 256;
  app.add_option("cube_dir", o.cube_dir, "cubemap folder, e.g. sequences/map00_seq00/cube");
  app.add_option("-o,--out", o.out_dir, "output folder, e.g. sequences/map00_seq00/erp");
  app.add_option("--height", o.height, "ERP height H (width is 2H)")->check(CLI::Range(2, 1 << 14));
  app.add_option("--flow-mode", flow_mode, "360 (shortest way round, paper Eq. 3) or classic")
      ->check(CLI::IsMember({"360", "classic"}));
  app.add_flag("--force", o.force,
               "redo outputs that exist (default: skip them, so reruns resume)");
  app.add_option("--threads", threads, "worker threads (0: all cores)")->check(CLI::Range(0, 1024));
  app.add_option("--demo", demo_dir,
                 "write the built-in analytic cubemap to DIR/cube and stitch it to DIR/erp");
  app.add_option("--face-size", face_size, "face size of the --demo cubemap")
      ->check(CLI::Range(2, 8192));
  finish_options(app, "stitch_erp");
  if (const auto status = parse_options(app, argc, argv)) return *status;
  std::optional<tbb::global_control> limit;
  if (threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, threads);
  o.flow_mode = flow_mode == "classic" ? FlowMode::Classic : FlowMode::Wrap360;
  try {
    if (!demo_dir.empty()) {
      const double yaw = 3;
      const YawDemo demo = run_yaw_demo(demo_dir, face_size, o.height, yaw);
      std::printf("demo: %s holds a %dx%d cubemap and its %dx%d ERP stitch\n", demo_dir.c_str(),
                  face_size, face_size, demo.erp_width, demo.erp_height);
      std::printf(
          "demo: a %.0f deg yaw must give u = %.4f px, v = 0 everywhere; largest error %.2e px\n",
          yaw, demo.expected_u, demo.largest_error);
      return 0;
    }
    if (o.cube_dir.empty() || o.out_dir.empty()) {
      std::fprintf(diagnostics(),
                   "stitch_erp: give a cubemap folder and --out (or --demo DIR); see --help\n");
      return 2;
    }
    if (stitch_cube_folder(o) == 0)
      std::fprintf(diagnostics(),
                   "stitch_erp: nothing to do, every output in %s exists (--force redoes it)\n",
                   o.out_dir.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(diagnostics(), "stitch_erp: error: %s\n", e.what());
    return 1;
  }
}
