// flowscape_merge: after the shards of a release (gen_flowscape --shard K/N, on one machine or
// many, into one folder) have run, checks the release is complete and writes its manifest and
// dataset card, the same bytes one process would have written.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli.h"
#include "flowscape/core/files.h"
#include "flowscape/release/manifest.h"

using namespace flowscape;

int main(int argc, char** argv) {
  CLI::App app{
      "Merge the shard manifests of a FlowScape release into manifest.json, after checking "
      "that every shard reported and every sequence is complete."};
  std::string out;
  bool verify = false;
  app.add_option("release", out, "release folder the shards wrote into")->required();
  app.add_flag("--verify", verify, "recompute every file's sha256 and compare with the shards'");
  finish_options(app, "flowscape_merge");
  if (const auto status = parse_options(app, argc, argv)) return *status;
  try {
    const ReleaseConfig config = merge_shards(out, verify);
    const int sequences = int(plan_sequences(config).size());
    std::printf("%s/manifest.json: %d sequences, %d frames\n", out.c_str(), sequences,
                sequences * config.frames);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(diagnostics(), "flowscape_merge: error: %s\n", e.what());
    return 1;
  }
}
