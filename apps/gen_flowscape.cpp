// gen_flowscape: renders a FlowScape release (design.md's layout): per map its sequences in their
// weathers, every modality in ERP and on the six cube faces, meta.json per sequence, manifest.json
// with sha256 of every file and a dataset card. Killed at any moment, the same command resumes and
// finishes with the same bytes.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "flowscape/io.h"
#include "flowscape/progress.h"
#include "flowscape/release.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

ReleaseConfig read_config_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw FileError(path, "cannot open the config file");
  try {
    return release_config_from_json(nlohmann::json::parse(in));
  } catch (const nlohmann::json::exception& e) {
    throw FileError(path, std::string("not JSON: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw FileError(path, e.what());
  }
}

void parse_shard(const std::string& text, ReleaseConfig& config) {
  int k = -1, n = -1;
  char slash = 0;
  if (std::sscanf(text.c_str(), "%d%c%d", &k, &slash, &n) != 3 || slash != '/')
    throw std::invalid_argument("--shard wants K/N, e.g. 0/4 (got \"" + text + "\")");
  config.shard = k, config.shards = n;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Render a FlowScape release: ERP and cube-face colour, 360-degree flow, semantics, "
      "instances, depth and validity for every frame of every sequence, with a manifest. "
      "Rerun the same command to resume an interrupted run."};
  ReleaseConfig c;  // the defaults make the paper's FlowScape
  std::string out = "dataset", config_file, shard, weathers;
  int threads = 0;
  auto* out_option = app.add_option("-o,--out", out, "release folder");
  app.add_option("--config", config_file, "JSON with any of the options below (command line wins)");
  auto* maps = app.add_option("--maps", c.maps, "city maps (1-8)");
  auto* seqs = app.add_option("--sequences-per-map", c.sequences_per_map, "sequences per map");
  auto* frames = app.add_option("--frames", c.frames, "frames per sequence (30 Hz)");
  auto* res = app.add_option("--resolution", c.height, "ERP height (width = 2 x height)");
  auto* face = app.add_option("--face-size", c.face_size, "cube face size in pixels");
  auto* spp = app.add_option("--spp", c.spp, "path-traced samples per pixel");
  auto* weather = app.add_option("--weather", weathers,
                                 "comma-separated weather presets cycled over each map's "
                                 "sequences (default sunny x5,cloud,fog,rain)");
  auto* vehicles = app.add_option("--vehicles", c.vehicles, "vehicles per map");
  auto* pedestrians = app.add_option("--pedestrians", c.pedestrians, "pedestrians per map");
  auto* seed = app.add_option("--seed", c.seed, "release seed");
  bool no_cube = false;
  app.add_flag("--no-cube", no_cube, "ERP only: no cube faces (ERP colour rendered directly)");
  app.add_option("--shard", shard, "K/N: make only the sequences k with k % N == K");
  app.add_option("--threads", threads, "threads (0: all cores)")->check(CLI::NonNegativeNumber);
  bool check = false, demo = false;
  app.add_flag("--demo", demo,
               "a small release in demo/ (1 map, 2 sequences of 4 frames, 128 x 256, 8 spp) unless "
               "options say otherwise");
  app.add_flag("--check", check, "only check the options and print the plan; write nothing");
  CLI11_PARSE(app, argc, argv);
  try {
    if (!config_file.empty()) {
      const ReleaseConfig given = c;
      const ReleaseConfig file = read_config_file(config_file);
      c = file;
      if (maps->count()) c.maps = given.maps;
      if (seqs->count()) c.sequences_per_map = given.sequences_per_map;
      if (frames->count()) c.frames = given.frames;
      if (res->count()) c.height = given.height;
      if (face->count()) c.face_size = given.face_size;
      if (spp->count()) c.spp = given.spp;
      if (vehicles->count()) c.vehicles = given.vehicles;
      if (pedestrians->count()) c.pedestrians = given.pedestrians;
      if (seed->count()) c.seed = given.seed;
    }
    if (demo) {
      if (!maps->count()) c.maps = 1;
      if (!seqs->count()) c.sequences_per_map = 2;
      if (!frames->count()) c.frames = 4;
      if (!res->count()) c.height = 128;
      if (!face->count()) c.face_size = 64;
      if (!spp->count()) c.spp = 8;
      if (!weather->count()) c.weathers = {"sunny", "rain"};
      if (!out_option->count()) out = "demo";
    }
    if (weather->count()) {
      c.weathers.clear();
      std::stringstream list(weathers);
      for (std::string name; std::getline(list, name, ',');) c.weathers.push_back(name);
    }
    if (no_cube) c.cube = false;
    if (!shard.empty()) parse_shard(shard, c);
    validate(c);
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              threads > 0 ? threads : tbb::this_task_arena::max_concurrency());
    std::vector<SequencePlan> mine;
    for (const SequencePlan& plan : plan_sequences(c))
      if (in_shard(plan, c)) mine.push_back(plan);
    if (check) {
      std::printf("%zu sequences of %d frames; shard %d/%d makes %zu of them\n",
                  plan_sequences(c).size(), c.frames, c.shard, c.shards, mine.size());
      return 0;
    }
    Progress progress("gen_flowscape", mine.size() * std::size_t(c.frames), "frames");
    for (const SequencePlan& plan : mine)
      write_sequence(c, plan, out, {[&] { progress.advance(); }, [&] { progress.skip(); }});
    progress.finish();
    const nlohmann::json files = file_hashes(out, mine);
    if (c.shards == 1) {
      write_dataset_card(out, c);
      write_manifest(out, c, files);
      std::printf("%s: %zu sequences, %zu frames, %zu files\n",
                  (fs::path(out) / "manifest.json").c_str(), mine.size(),
                  mine.size() * std::size_t(c.frames), files.size());
    } else {
      const fs::path part =
          fs::path(out) / "manifests" /
          ("shard-" + std::to_string(c.shard) + "-of-" + std::to_string(c.shards) + ".json");
      write_text(
          part,
          nlohmann::json{
              {"config", to_json(c)}, {"shard", c.shard}, {"shards", c.shards}, {"files", files}}
                  .dump(1) +
              "\n");
      std::printf("%s: shard %d/%d, %zu sequences\n", part.c_str(), c.shard, c.shards, mine.size());
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(diagnostics(), "gen_flowscape: error: %s\n", e.what());
    return 1;
  }
}
