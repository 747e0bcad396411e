// flowscape_explore: writes the explorer page of an existing release (release/explorer.h):
// open <out>/index.html in a browser, no server needed.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli.h"
#include "flowscape/core/files.h"
#include "flowscape/release/explorer.h"
#include "flowscape/release/statistics.h"

using namespace flowscape;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  CLI::App app{
      "The release explorer: a static page (index.html, data.js, previews) of a FlowScape "
      "release's sequences, frames, kinds, calibration, statistics and gt_quality scores "
      "(<release>/quality.json where gt_quality --json wrote it)."};
  std::string release, out;
  ExplorerOptions options;
  options.progress = true;
  app.add_option("release", release, "release folder")->required();
  app.add_option("-o,--out", out, "output folder (default: <release>/explorer)");
  app.add_option("--frames", options.frames, "frames per sequence, spread evenly")
      ->check(CLI::Range(1, 100000));
  app.add_option("--width", options.width, "width of the ERP's previews (other views: half)")
      ->check(CLI::Range(16, 4096));
  app.add_flag("--faces", options.faces, "also the cube faces");
  finish_options(app, "flowscape_explore");
  if (const auto status = parse_options(app, argc, argv)) return *status;
  if (out.empty()) out = (fs::path(release) / kExplorerDir).string();
  try {
    const nlohmann::json statistics = write_explorer(release, out, options);
    std::fputs(statistics_summary(statistics).c_str(), stdout);
    std::printf("%s\n", (fs::path(out) / "index.html").c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(diagnostics(), "flowscape_explore: error: %s\n", e.what());
    return 1;
  }
}
