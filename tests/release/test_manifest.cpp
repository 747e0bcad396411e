#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>

#include "flowscape/release/layout.h"
#include "flowscape/release/manifest.h"
#include "flowscape/release/sha256.h"
#include "flowscape/release/writer.h"
#include "temp_dir.h"
#include "tiny_release.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

nlohmann::json read_json(const fs::path& path) {
  nlohmann::json j;
  std::ifstream(path) >> j;
  return j;
}

// Shard `shard` of `shards` of `config` into `out`, with its shard manifest.
void make_shard(ReleaseConfig config, int shard, int shards, const fs::path& out) {
  config.shard = shard, config.shards = shards;
  CHECK(write_release(config, out).manifest == shard_manifest_path(out, config));
}

}  // namespace

TEST_CASE("merged shards give the manifest one process writes, with every file's sha256") {
  TempDir dir;
  const ReleaseConfig config = tiny_release_config(2, 2);
  const fs::path sharded = dir.path / "sharded", single = dir.path / "single";
  make_shard(config, 1, 2, sharded);
  CHECK(fs::exists(sharded / "manifests" / "shard-1-of-2.json"));
  CHECK_THROWS_WITH(merge_shards(sharded, false),
                    Catch::Contains("no manifest from shard(s) 0 of 2: rerun them"));
  make_shard(config, 0, 2, sharded);
  merge_shards(sharded, true);
  CHECK_FALSE(fs::exists(sharded / "manifests"));
  // one process: it finds every frame made (the same bytes: rendering is deterministic) and
  // writes its own card and manifest
  fs::create_directories(single);
  fs::copy(sharded / "sequences", single / "sequences", fs::copy_options::recursive);
  const ReleaseWritten written = write_release(config, single);
  CHECK(written.manifest == single / "manifest.json");
  // per sequence: meta.json, 7 views x (6 kinds of frame 0 + 4 of the last frame)
  CHECK((written.sequences == 2 && written.frames == 4 && written.files == 2 * (1 + 7 * (6 + 4))));
  CHECK(file_bytes(sharded / "manifest.json") == file_bytes(single / "manifest.json"));

  const nlohmann::json manifest = read_json(single / "manifest.json");
  CHECK(manifest["generator"] == kGeneratorVersion);
  CHECK(manifest["layout"] == layout_json());
  CHECK(manifest["counts"]["flow_pairs"] == 2);
  const std::string color = "sequences/map00_seq01/erp/color/000001.png";
  CHECK(manifest["files"][color]["sha256"] == sha256_file(single / color));
  CHECK(manifest["files"][color]["bytes"] == fs::file_size(single / color));
  CHECK(manifest["files"].contains("README.md"));
  // every file of every frame is listed
  for (const SequencePlan& plan : plan_sequences(config))
    for (int f = 0; f < 2; ++f)
      for (const fs::path& file : frame_files(f, 2, true))
        REQUIRE(manifest["files"].contains(
            fs::relative(sequence_dir(single, plan.name) / file, single).generic_string()));
}

TEST_CASE("merge names what is missing or made otherwise") {
  TempDir dir;
  ReleaseConfig config = tiny_release_config(2, 2);
  make_shard(config, 0, 2, dir.path);
  make_shard(config, 1, 2, dir.path);
  fs::remove(sequence_dir(dir.path, "map00_seq01") /
             frame_file(output_kind("valid"), Face::Back, 0));
  CHECK_THROWS_WITH(merge_shards(dir.path, false),
                    Catch::Contains("cube/back/valid/000000.png: missing (rerun shard 1)"));
  config.spp = 2;
  make_shard(config, 1, 2, dir.path);  // its manifest now states another config
  CHECK_THROWS_WITH(merge_shards(dir.path, false),
                    Catch::Contains("shards made with different configs"));
}
