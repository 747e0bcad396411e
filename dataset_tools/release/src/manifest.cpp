#include "flowscape/release/manifest.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <map>
#include <stdexcept>

#include "flowscape/core/files.h"
#include "flowscape/release/dataset_card.h"
#include "flowscape/release/layout.h"
#include "flowscape/release/meta.h"
#include "flowscape/release/sha256.h"
#include "flowscape/scenes/city.h"
#include "json_integer.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

nlohmann::json file_entry(const fs::path& file) {
  return {{"sha256", sha256_file(file)}, {"bytes", fs::file_size(file)}};
}

std::vector<fs::path> files_under(const fs::path& root, const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(root / dir))
    if (entry.is_regular_file()) files.push_back(fs::relative(entry.path(), root));
  return files;
}

nlohmann::json counts(const ReleaseConfig& config) {
  std::map<std::string, int> per_weather, per_map;
  int sequences = 0;
  for (const SequencePlan& plan : plan_sequences(config))
    ++per_weather[plan.weather], ++per_map[map_name(plan.map)], ++sequences;
  return {{"sequences", sequences},
          {"frames", sequences * config.frames},
          {"flow_pairs", sequences * (config.frames - 1)},
          {"sequences_per_weather", per_weather},
          {"sequences_per_map", per_map}};
}

struct ShardManifest {
  fs::path path;
  nlohmann::json config;  // as written, to compare shards
  int shard = 0, shards = 1;
  nlohmann::json files;
};

// A file entry names a file under sequences/ and its size and hash.
void check_file_entry(const std::string& name, const nlohmann::json& entry) {
  const fs::path path(name);
  const bool inside = path.is_relative() && !name.empty() &&
                      std::none_of(path.begin(), path.end(), [](const fs::path& part) {
                        return part == ".." || part == ".";
                      });
  if (!inside || !name.starts_with(sequence_dir("", "").generic_string()))
    throw std::invalid_argument("file \"" + name + "\" is not a path under sequences/");
  if (!entry.is_object() || !entry.value("bytes", nlohmann::json()).is_number_unsigned() ||
      !entry.value("sha256", nlohmann::json()).is_string())
    throw std::invalid_argument("file \"" + name + "\" lacks its bytes or sha256");
}

ShardManifest read_shard_manifest(const fs::path& path) {
  const nlohmann::json j = read_json(path);
  try {
    ShardManifest m{path, j.at("config"), 0, 1, {}};
    release_config_from_json(m.config);  // validates
    m.shards = json_integer(j.at("shards"), "shards", 1, 1 << 20);
    m.shard = json_integer(j.at("shard"), "shard", 0, m.shards - 1);
    m.files = j.at("files");
    if (!m.files.is_object()) throw std::invalid_argument("\"files\" must be an object");
    for (const auto& [name, entry] : m.files.items()) check_file_entry(name, entry);
    return m;
  } catch (const std::exception& e) {
    throw FileError(path, std::string("bad shard manifest: ") + e.what());
  }
}

std::vector<ShardManifest> read_shard_manifests(const fs::path& out) {
  const fs::path dir = out / kShardDir;
  if (!fs::is_directory(dir)) throw FileError(dir, "no shard manifests (did the shards run?)");
  std::vector<ShardManifest> shards;
  for (const auto& entry : fs::directory_iterator(dir))
    shards.push_back(read_shard_manifest(entry.path()));
  if (shards.empty()) throw FileError(dir, "no shard manifests (did the shards run?)");
  std::sort(shards.begin(), shards.end(),
            [](const ShardManifest& a, const ShardManifest& b) { return a.path < b.path; });
  return shards;
}

void check_sequence_complete(const fs::path& out, const ReleaseConfig& config,
                             const SequencePlan& plan) {
  const fs::path dir = sequence_dir(out, plan.name);
  const int shard = plan.number % config.shards;
  const std::string rerun = " (rerun shard " + std::to_string(shard) + ")";
  if (!fs::exists(dir / kMetaFile)) throw FileError(dir, "sequence missing" + rerun);
  for (int f = 0; f < config.frames; ++f)
    for (const fs::path& file : frame_files(f, config.frames, config.cube))
      if (!fs::exists(dir / file)) throw FileError(dir / file, "missing" + rerun);
}

}  // namespace

nlohmann::json file_hashes(const fs::path& out, const std::vector<SequencePlan>& plans) {
  std::vector<fs::path> files;
  for (const SequencePlan& plan : plans) {
    const fs::path dir = sequence_dir(out, plan.name);
    if (!fs::exists(dir)) throw FileError(dir, "sequence folder missing");
    const std::vector<fs::path> found = files_under(out, fs::relative(dir, out));
    files.insert(files.end(), found.begin(), found.end());
  }
  std::sort(files.begin(), files.end());
  std::vector<nlohmann::json> entries(files.size());
  tbb::parallel_for(std::size_t(0), files.size(),
                    [&](std::size_t k) { entries[k] = file_entry(out / files[k]); });
  nlohmann::json hashes = nlohmann::json::object();
  for (std::size_t k = 0; k < files.size(); ++k) hashes[files[k].generic_string()] = entries[k];
  return hashes;
}

void write_manifest(const fs::path& out, const ReleaseConfig& config, const nlohmann::json& files) {
  nlohmann::json all = files;
  for (const fs::path& card : dataset_card_files(out))
    all[card.generic_string()] = file_entry(out / card);
  if (fs::exists(out / kConfigFile)) all[kConfigFile] = file_entry(out / kConfigFile);
  const nlohmann::json manifest = {{"generator", kGeneratorVersion},
                                   {"config", to_json(config)},
                                   {"counts", counts(config)},
                                   {"layout", layout_json()},
                                   {"files", all}};
  write_text(out / kManifestFile, manifest.dump(1) + "\n");
}

fs::path shard_manifest_path(const fs::path& out, const ReleaseConfig& config) {
  return out / kShardDir /
         ("shard-" + std::to_string(config.shard) + "-of-" + std::to_string(config.shards) +
          ".json");
}

void write_shard_manifest(const fs::path& out, const ReleaseConfig& config,
                          const nlohmann::json& files) {
  const nlohmann::json shard = {{"config", to_json(config)},
                                {"shard", config.shard},
                                {"shards", config.shards},
                                {"files", files}};
  write_text(shard_manifest_path(out, config), shard.dump(1) + "\n");
}

ReleaseConfig merge_shards(const fs::path& out, bool verify) {
  const std::vector<ShardManifest> shards = read_shard_manifests(out);
  ReleaseConfig config = release_config_from_json(shards.front().config);
  config.shards = shards.front().shards;
  std::vector<bool> seen(std::size_t(config.shards), false);
  nlohmann::json files = nlohmann::json::object();
  for (const ShardManifest& shard : shards) {
    if (shard.config != shards.front().config || shard.shards != config.shards)
      throw FileError(shard.path, "made with another config or shard count than " +
                                      shards.front().path.filename().string());
    seen[std::size_t(shard.shard)] = true;
    files.update(shard.files);
  }
  std::string missing;
  for (std::size_t k = 0; k < seen.size(); ++k)
    if (!seen[k]) missing += (missing.empty() ? "" : ", ") + std::to_string(k);
  if (!missing.empty())
    throw FileError(out / kShardDir, "no manifest from shard(s) " + missing + " of " +
                                         std::to_string(config.shards) + ": rerun them");
  const std::vector<SequencePlan> plans = plan_sequences(config);
  for (const SequencePlan& plan : plans) check_sequence_complete(out, config, plan);
  const nlohmann::json on_disk = verify ? file_hashes(out, plans) : nlohmann::json();
  for (const auto& [path, entry] : files.items()) {
    if (!fs::exists(out / path)) throw FileError(out / path, "listed by a shard but missing");
    if (fs::file_size(out / path) != entry.at("bytes").get<std::uintmax_t>())
      throw FileError(out / path, "size differs from its shard manifest");
    if (verify && on_disk.value(path, nlohmann::json()) != entry)
      throw FileError(out / path, "sha256 differs from its shard manifest");
  }
  config.shard = 0, config.shards = 1;
  write_dataset_card(out, config);
  write_manifest(out, config, files);
  fs::remove_all(out / kShardDir);
  return config;
}

}  // namespace flowscape
