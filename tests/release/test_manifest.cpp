#include <catch2/catch.hpp>
#include <fstream>
#include <functional>
#include <sstream>

#include "flowscape/core/files.h"
#include "flowscape/core/sha256.h"
#include "flowscape/layout/layout.h"
#include "flowscape/layout/meta.h"
#include "flowscape/release/manifest.h"
#include "flowscape/release/writer.h"
#include "temp_dir.h"
#include "tiny_release.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

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
  // per sequence: meta.json, 7 views x (frame 0: the six, scene flow, normal; the last frame: the
  // four of every frame, backward flow and valid, normal)
  CHECK((written.sequences == 2 && written.frames == 4 &&
         written.files == 2 * (1 + 7 * ((6 + 2) + (4 + 2 + 1)))));
  CHECK(file_bytes(sharded / "manifest.json") == file_bytes(single / "manifest.json"));

  const nlohmann::json manifest = read_json(single / "manifest.json");
  CHECK(manifest["generator"] == kGeneratorVersion);
  CHECK(manifest["layout"] == layout_json(release_layout(config)));
  CHECK(manifest["conventions"]["flow"]["value"] == "target - source");
  CHECK(manifest["counts"]["flow_pairs"] == 2);
  const std::string color = "sequences/map00_seq01/erp/color/000001.png";
  CHECK(manifest["files"][color]["sha256"] == sha256_file(single / color));
  CHECK(manifest["files"][color]["bytes"] == fs::file_size(single / color));
  CHECK(manifest["files"].contains("README.md"));
  // every file of every frame is listed
  for (const SequencePlan& plan : plan_sequences(config))
    for (int f = 0; f < 2; ++f)
      for (const fs::path& file : release_layout(config).frame_files(f, 2))
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
  // a shard rerun with another config is refused before it renders anything
  config.spp = 2, config.shard = 1, config.shards = 2;
  CHECK_THROWS_WITH(write_release(config, dir.path),
                    Catch::Contains("config.json: this release was made with another config "
                                    "(spp: 1 recorded, 2 now)"));
  // a shard manifest stating another config (edited, or from another release) is named
  const fs::path shard1 = dir.path / "manifests" / "shard-1-of-2.json";
  nlohmann::json edited = read_json(shard1);
  edited["config"]["spp"] = 2;
  write_text(shard1, edited.dump());
  CHECK_THROWS_WITH(merge_shards(dir.path, false),
                    Catch::Contains("shard-1-of-2.json: made with another config than "
                                    "shard-0-of-2.json (spp: 1 there, 2 here)"));
}

TEST_CASE("merge names the config keys of a shard that was refused") {
  TempDir dir;
  ReleaseConfig config = tiny_release_config(2, 2);
  make_shard(config, 0, 2, dir.path);
  ReleaseConfig other = config;
  other.spp = 2, other.seed = 9, other.shard = 1, other.shards = 2;
  CHECK_THROWS(write_release(other, dir.path));
  CHECK_THROWS_WITH(merge_shards(dir.path, false),
                    Catch::Contains("manifests: no manifest from shard(s) 1 of 2: rerun them; "
                                    "shard 1 was refused: its config differs (seed: 11 in "
                                    "shard-0-of-2.json, 9 in shard 1; spp: 1 in "
                                    "shard-0-of-2.json, 2 in shard 1)"));
  make_shard(config, 1, 2, dir.path);  // rerun with the release's config: the refusal is gone
  CHECK_FALSE(fs::exists(dir.path / "manifests" / "refused-shard-1-of-2.json"));
  CHECK_NOTHROW(merge_shards(dir.path, true));
}

TEST_CASE("the manifest lists the layout's files only; --check and merge name the others") {
  TempDir dir;
  ReleaseConfig config = tiny_release_config(2, 2);
  make_shard(config, 0, 2, dir.path);
  make_shard(config, 1, 2, dir.path);
  const fs::path seq = sequence_dir(dir.path, "map00_seq01");
  const fs::path stray = seq / "erp" / "color" / "notes.txt";
  const fs::path stale = seq / "cube" / "up" / "depth" / ".partial-31337-000001.exr";
  write_text(stray, "a user's file");
  write_text(stale, "half");
  const fs::path stale_shard = dir.path / "manifests" / ".partial-8-shard-0-of-2.json";
  write_text(stale_shard, "{");
  ReleaseConfig whole = config;
  whole.shards = 1;
  std::vector<ReleaseProblem> problems = release_problems(dir.path, whole);
  REQUIRE(problems.size() == 3);
  CHECK(
      (problems[0].path == stale_shard && problems[1].path == stale && problems[2].path == stray));
  CHECK(problems[0].problem == "temporary file of an interrupted run");
  CHECK(problems[2].problem == "not part of the release");
  CHECK_THROWS_WITH(merge_shards(dir.path, true),
                    Catch::Contains("notes.txt: not part of the release"));
  fs::remove(stray);
  merge_shards(dir.path, true);
  CHECK_FALSE(fs::exists(stale));
  const nlohmann::json manifest = read_json(dir.path / "manifest.json");
  for (const auto& [name, entry] : manifest["files"].items()) CHECK_FALSE(is_temporary_file(name));
  CHECK(release_problems(dir.path, whole).empty());
  write_text(dir.path / "card" / ".partial-3-sunny.png", "half");
  fs::resize_file(seq / kMetaFile, 3);
  fs::remove(seq / frame_file(output_kind("flow"), std::nullopt, 0));
  problems = release_problems(dir.path, whole);
  REQUIRE(problems.size() == 3);
  CHECK(problems[0].problem == "temporary file of an interrupted run");
  CHECK(problems[1].problem == "listed in manifest.json but missing");
  CHECK(problems[2].problem == "size differs from manifest.json");
}

TEST_CASE("hostile shard manifests are refused with the file named") {
  TempDir dir;
  const ReleaseConfig config = tiny_release_config(2, 2);
  make_shard(config, 0, 2, dir.path);
  const fs::path shard = dir.path / "manifests" / "shard-0-of-2.json";
  const nlohmann::json good = read_json(shard);
  const auto refused_with = [&](const std::function<void(nlohmann::json&)>& change,
                                const std::string& message) {
    nlohmann::json hostile = good;
    change(hostile);
    write_text(shard, hostile.dump());
    CHECK_THROWS_WITH(
        merge_shards(dir.path, false),
        Catch::Contains("shard-0-of-2.json: bad shard manifest: ") && Catch::Contains(message));
  };
  refused_with([](auto& j) { j["shards"] = 0; }, "\"shards\" 0 is out of range (1..1048576)");
  refused_with([](auto& j) { j["shard"] = 7; }, "\"shard\" 7 is out of range (0..1)");
  refused_with([](auto& j) { j["shards"] = 1.5; }, "(got 1.5)");
  refused_with([](auto& j) { j.erase("config"); }, "key 'config' not found");
  refused_with([](auto& j) { j["config"]["maps"] = 4294967297; }, "out of range");
  refused_with(
      [](auto& j) {
        j["files"]["../../etc/passwd"] = {{"bytes", 1}, {"sha256", ""}};
      },
      "is not a path under sequences/");
  write_text(shard, "{\"shards\": ");
  CHECK_THROWS_WITH(merge_shards(dir.path, false), Catch::Contains("shard-0-of-2.json: not JSON"));
}
