// flowscape_split: train/test splits of a release by whole sequences (test stratified by weather)
// in splits/, and the panoflow/ tree the public PanoFlow code reads.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <map>

#include "cli.h"
#include "flowscape/core/files.h"
#include "flowscape/layout/meta.h"
#include "flowscape/layout/split.h"

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
  std::string method = "stratified";
  HashSplitOptions by_hash;
  app.add_option("release", release, "release folder (made by gen_flowscape)")->required();
  app.add_option("--seed", seed, "which sequences of each weather go to test");
  app.add_flag("--no-panoflow", no_panoflow, "only splits/, no panoflow/ tree");
  app.add_option("--method", method,
                 "stratified: the paper's test split, per weather (FlowScape: 14 of 64 sequences); "
                 "hash: each sequence's side from a stable hash of its name and --seed, so a "
                 "release that grows keeps every sequence where it was (--test-share, "
                 "--val-share, --held-out-maps)")
      ->check(CLI::IsMember({"stratified", "hash"}))
      ->capture_default_str();
  auto* test_share = app.add_option("--test-share", by_hash.test_share,
                                    "hash: the share of sequences in test (on average)")
                         ->check(CLI::Range(0.0, 1.0))
                         ->capture_default_str();
  auto* val_share = app.add_option("--val-share", by_hash.val_share,
                                   "hash: the share in splits/val.txt (on average)")
                        ->check(CLI::Range(0.0, 1.0))
                        ->capture_default_str();
  auto* held_out = app.add_option("--held-out-maps", by_hash.held_out_maps,
                                  "hash: maps (0-7) whose sequences are all test")
                       ->check(CLI::Range(0, 7));
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
  if (method != "hash" && (test_share->count() || val_share->count() || held_out->count())) {
    std::fprintf(diagnostics(),
                 "flowscape_split: error: --test-share, --val-share and "
                 "--held-out-maps belong to --method hash (see --help)\n");
    return kUsageError;
  }
  if (by_hash.test_share + by_hash.val_share > 1) {
    std::fprintf(diagnostics(),
                 "flowscape_split: error: --test-share + --val-share is above 1 (see --help)\n");
    return kUsageError;
  }
  try {
    const std::vector<SequenceInfo> sequences = read_release_sequences(release);
    write_all_split(release, sequences);
    if (sequences.size() < 2) {
      std::fprintf(diagnostics(),
                   "flowscape_split: warning: %s: one sequence, so splits/all.txt only (train and "
                   "test take whole sequences: they need two); FlowScape(root, \"all\") reads it\n",
                   release.c_str());
      return 0;
    }
    const Split split = method == "hash" ? split_by_hash(sequences, seed, by_hash)
                                         : split_sequences(sequences, seed);
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
    for (const auto& [label, side] :
         {std::pair{"train", &split.train}, {"test", &split.test}, {"val", &split.val}}) {
      if (side->empty() && std::string(label) == "val") continue;
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
