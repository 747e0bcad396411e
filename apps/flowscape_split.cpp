// flowscape_split: train/test splits of a release by whole sequences (test stratified by weather)
// in splits/, and the panoflow/ tree the public PanoFlow code reads.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <map>

#include "cli.h"
#include "flowscape/core/files.h"
#include "flowscape/release/split.h"

using namespace flowscape;

int main(int argc, char** argv) {
  CLI::App app{
      "Split a FlowScape release into train and test by whole sequences, the test side "
      "stratified by weather, and lay it out for the PanoFlow code."};
  std::string release;
  std::uint64_t seed = 0;
  bool no_panoflow = false;
  app.add_option("release", release, "release folder (made by gen_flowscape)")->required();
  app.add_option("--seed", seed, "which sequences of each weather go to test");
  app.add_flag("--no-panoflow", no_panoflow, "only splits/, no panoflow/ tree");
  one_line_errors(app, "flowscape_split");
  CLI11_PARSE(app, argc, argv);
  try {
    const Split split = split_sequences(read_release_sequences(release), seed);
    write_split_files(release, split);
    if (!no_panoflow) write_panoflow_tree(release, split);
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
