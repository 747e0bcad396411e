// flowscape_split: train/test splits of a release by whole sequences (test stratified by weather)
// in splits/, and the panoflow/ tree the public PanoFlow code reads.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <map>

#include "cli.h"
#include "flowscape/core/files.h"
#include "flowscape/release/meta.h"
#include "flowscape/release/split.h"

using namespace flowscape;

int main(int argc, char** argv) {
  CLI::App app{
      "Split a FlowScape release into train and test by whole sequences, the test side "
      "stratified by weather, and lay it out for the PanoFlow code."};
  std::string release;
  std::uint64_t seed = 0;
  bool no_panoflow = false;
  PanoflowOptions panoflow;
  std::string flow = "classic", sky = "invalid", occluded = "kept", pass = "clean";
  app.add_option("release", release, "release folder (made by gen_flowscape)")->required();
  app.add_option("--seed", seed, "which sequences of each weather go to test");
  app.add_flag("--no-panoflow", no_panoflow, "only splits/, no panoflow/ tree");
  app.add_option("--flow", flow, "panoflow/ flow: classic (the public FlowScape's) or 360")
      ->check(CLI::IsMember({"classic", "360"}));
  app.add_option("--sky", sky,
                 "panoflow/ sky pixels: invalid (stored as unknown, 1e10, which the public "
                 "loader's |u|,|v| < 1000 mask drops) or kept (their finite flow)")
      ->check(CLI::IsMember({"invalid", "kept"}));
  app.add_option("--occluded", occluded,
                 "panoflow/ pixels whose target is hidden in the next frame: kept, or invalid")
      ->check(CLI::IsMember({"invalid", "kept"}));
  app.add_option("--pass", pass,
                 "panoflow/ images: clean (color) or final (the final pass; the release must "
                 "have it)")
      ->check(CLI::IsMember({"clean", "final"}))
      ->capture_default_str();
  finish_options(app, "flowscape_split");
  if (const auto status = parse_options(app, argc, argv)) return *status;
  try {
    const Split split = split_sequences(read_release_sequences(release), seed);
    write_split_files(release, split);
    panoflow = {flow == "classic" ? FlowMode::Classic : FlowMode::Wrap360, sky == "invalid",
                occluded == "invalid", pass == "final"};
    if (!no_panoflow && !read_release_layout(release).has_erp()) {
      no_panoflow = true;
      std::fprintf(diagnostics(),
                   "flowscape_split: warning: %s: its rig has no ERP view, so no panoflow/ tree "
                   "(the PanoFlow code reads ERP images); splits/ only\n",
                   release.c_str());
    }
    if (!no_panoflow)
      for (const std::string& folder : write_panoflow_tree(release, split, panoflow))
        std::fprintf(diagnostics(),
                     "flowscape_split: warning: panoflow/%s is empty (no sequence of that weather "
                     "in that split); the folder is there for the PanoFlow code\n",
                     folder.c_str());
    for (const auto& [label, side] : {std::pair{"train", &split.train}, {"test", &split.test}}) {
      std::map<std::string, int> per_weather;
      int pairs = 0;
      for (const SequenceInfo& s : *side) ++per_weather[s.weather], pairs += s.frames - 1;
      std::printf("%-5s %3zu sequences, %6d pairs:", label, side->size(), pairs);
      for (const auto& [weather, n] : per_weather)
        std::printf("  %s %d (%.1f %%)", weather.c_str(), n, 100.0 * n / side->size());
      std::printf("\n");
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(diagnostics(), "flowscape_split: error: %s\n", e.what());
    return 1;
  }
}
