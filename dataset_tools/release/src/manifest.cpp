#include "flowscape/release/manifest.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <stdexcept>

#include "flowscape/core/files.h"
#include "flowscape/core/sha256.h"
#include "flowscape/layout/layout.h"
#include "flowscape/layout/meta.h"
#include "flowscape/release/dataset_card.h"
#include "flowscape/release/explorer.h"
#include "flowscape/release/scenario.h"
#include "flowscape/release/statistics.h"
#include "flowscape/scenes/city.h"
#include "json_integer.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

nlohmann::json file_entry(const fs::path& file) {
  return {{"sha256", sha256_file(file)}, {"bytes", fs::file_size(file)}};
}

// The files of the given sequences of a release made with `config`, relative to the release.
std::vector<fs::path> release_sequence_files(const ReleaseConfig& config,
                                             const std::vector<SequencePlan>& plans) {
  const std::vector<fs::path> in_sequence = release_layout(config).sequence_files(config.frames);
  std::vector<fs::path> files;
  for (const SequencePlan& plan : plans)
    for (const fs::path& file : in_sequence) files.push_back(sequence_dir("", plan.name) / file);
  return files;
}

nlohmann::json counts(const ReleaseConfig& config) {
  std::map<std::string, int> per_weather, per_time, per_sky, per_map;
  int sequences = 0;
  for (const SequencePlan& plan : plan_sequences(config))
    ++per_weather[plan.weather], ++per_time[plan.time_of_day], ++per_sky[plan.sky],
        ++per_map[map_name(plan.map)], ++sequences;
  return {{"sequences", sequences},
          {"frames", sequences * config.frames},
          {"flow_pairs", sequences * (config.frames - 1)},
          {"sequences_per_weather", per_weather},
          {"sequences_per_time_of_day", per_time},
          {"sequences_per_sky", per_sky},
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

constexpr const char* kRefusedPrefix = "refused-";

// The shard manifests in manifests/ (sorted by name); what refused shards recorded is not one.
std::vector<ShardManifest> read_shard_manifests(const fs::path& out) {
  const fs::path dir = out / kShardDir;
  if (!fs::is_directory(dir)) throw FileError(dir, "no shard manifests (did the shards run?)");
  std::vector<ShardManifest> shards;
  for (const auto& entry : fs::directory_iterator(dir))
    if (!entry.path().filename().string().starts_with(kRefusedPrefix))
      shards.push_back(read_shard_manifest(entry.path()));
  if (shards.empty()) throw FileError(dir, "no shard manifests (did the shards run?)");
  std::sort(shards.begin(), shards.end(),
            [](const ShardManifest& a, const ShardManifest& b) { return a.path < b.path; });
  return shards;
}

fs::path refused_shard_path(const fs::path& out, int shard, int shards) {
  ReleaseConfig config;
  config.shard = shard, config.shards = shards;
  const fs::path manifest = shard_manifest_path(out, config);
  return manifest.parent_path() / (kRefusedPrefix + manifest.filename().string());
}

// "shard 1 was refused: its config differs (spp: 1 in shard-0-of-2.json, 2 in shard 1)" for each
// missing shard that recorded a refusal.
std::string refusals(const fs::path& out, const ShardManifest& reported,
                     const std::vector<int>& missing) {
  std::string text;
  for (int k : missing) {
    const fs::path refused = refused_shard_path(out, k, reported.shards);
    if (!fs::exists(refused)) continue;
    const nlohmann::json attempt = read_json(refused).value("config", nlohmann::json());
    text += "; shard " + std::to_string(k) + " was refused: its config differs (" +
            config_differences(reported.config, "in " + reported.path.filename().string(), attempt,
                               "in shard " + std::to_string(k)) +
            ")";
  }
  return text;
}

std::string number_list(const std::vector<int>& numbers) {
  std::string text;
  for (int k : numbers) text += (text.empty() ? "" : ", ") + std::to_string(k);
  return text;
}

void check_sequence_complete(const fs::path& out, const ReleaseConfig& config,
                             const SequencePlan& plan) {
  const fs::path dir = sequence_dir(out, plan.name);
  const int shard = plan.number % config.shards;
  const std::string rerun = " (rerun shard " + std::to_string(shard) + ")";
  if (!fs::exists(dir / kMetaFile)) throw FileError(dir, "sequence missing" + rerun);
  for (const fs::path& file : release_layout(config).sequence_files(config.frames))
    if (!fs::exists(dir / file)) throw FileError(dir / file, "missing" + rerun);
}

}  // namespace

nlohmann::json file_hashes(const fs::path& out, const ReleaseConfig& config,
                           const std::vector<SequencePlan>& plans) {
  std::vector<fs::path> files = release_sequence_files(config, plans);
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files)
    if (!fs::is_regular_file(out / file)) throw FileError(out / file, "missing");
  std::vector<nlohmann::json> entries(files.size());
  tbb::parallel_for(std::size_t(0), files.size(),
                    [&](std::size_t k) { entries[k] = file_entry(out / files[k]); });
  nlohmann::json hashes = nlohmann::json::object();
  for (std::size_t k = 0; k < files.size(); ++k) hashes[files[k].generic_string()] = entries[k];
  return hashes;
}

void write_manifest(const fs::path& out, const ReleaseConfig& config, const nlohmann::json& files,
                    const nlohmann::json& statistics) {
  nlohmann::json all = files;
  for (const fs::path& card : dataset_card_files(config))
    all[card.generic_string()] = file_entry(out / card);
  if (fs::exists(out / kConfigFile)) all[kConfigFile] = file_entry(out / kConfigFile);
  nlohmann::json manifest = {
      {"generator", kGeneratorVersion},
      {"config", to_json(config)},
      {"counts", counts(config)},
      {"layout", layout_json(release_layout(config))},
      {"conventions", conventions_json(config.classes, release_frame_rates(config),
                                       flow_format_from_name(config.flow_format))},
      {"files", all}};
  if (!statistics.is_null()) manifest["statistics"] = statistics;
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
  const fs::path path = shard_manifest_path(out, config);
  remove_temporaries_of(path);
  write_text(path, shard.dump(1) + "\n");
  fs::remove(refused_shard_path(out, config.shard, config.shards));
}

void write_refused_shard(const fs::path& out, const ReleaseConfig& config) {
  const nlohmann::json attempt = {
      {"config", to_json(config)}, {"shard", config.shard}, {"shards", config.shards}};
  write_text(refused_shard_path(out, config.shard, config.shards), attempt.dump(1) + "\n");
}

namespace {

// Every shard reported, with one config and shard count.
void check_shards_agree(const fs::path& out, const std::vector<ShardManifest>& shards) {
  const ShardManifest& first = shards.front();
  std::vector<bool> seen(std::size_t(first.shards), false);
  for (const ShardManifest& shard : shards) {
    if (shard.config != first.config)
      throw FileError(shard.path,
                      "made with another config than " + first.path.filename().string() + " (" +
                          config_differences(first.config, "there", shard.config, "here") + ")");
    if (shard.shards != first.shards)
      throw FileError(shard.path, "one of " + std::to_string(shard.shards) + " shards, " +
                                      first.path.filename().string() + " one of " +
                                      std::to_string(first.shards));
    seen[std::size_t(shard.shard)] = true;
  }
  std::vector<int> missing;
  for (int k = 0; k < first.shards; ++k)
    if (!seen[std::size_t(k)]) missing.push_back(k);
  if (!missing.empty())
    throw FileError(out / kShardDir, "no manifest from shard(s) " + number_list(missing) + " of " +
                                         std::to_string(first.shards) + ": rerun them" +
                                         refusals(out, first, missing));
}

// The union of the shards' file lists; each must name a file of the release.
nlohmann::json shard_files(const ReleaseConfig& config, const std::vector<ShardManifest>& shards) {
  std::set<std::string> release;
  for (const fs::path& file : release_sequence_files(config, plan_sequences(config)))
    release.insert(file.generic_string());
  nlohmann::json files = nlohmann::json::object();
  for (const ShardManifest& shard : shards) {
    for (const auto& [name, entry] : shard.files.items())
      if (!release.contains(name))
        throw FileError(shard.path, "lists \"" + name + "\", which is not part of the release");
    files.update(shard.files);
  }
  return files;
}

}  // namespace

ReleaseConfig merge_shards(const fs::path& out, bool verify) {
  remove_temporary_files(out / kShardDir);
  const std::vector<ShardManifest> shards = read_shard_manifests(out);
  check_shards_agree(out, shards);
  ReleaseConfig config = release_config_from_json(shards.front().config);
  config.shards = shards.front().shards;
  const nlohmann::json files = shard_files(config, shards);
  const std::vector<SequencePlan> plans = plan_sequences(config);
  for (const SequencePlan& plan : plans) check_sequence_complete(out, config, plan);
  // every shard has finished: what their killed runs left anywhere is stale
  remove_temporary_files(out);
  remove_temporary_files_under(sequence_dir(out, ""));
  const nlohmann::json on_disk = verify ? file_hashes(out, config, plans) : nlohmann::json();
  for (const auto& [path, entry] : files.items()) {
    if (!fs::exists(out / path)) throw FileError(out / path, "listed by a shard but missing");
    if (fs::file_size(out / path) != entry.at("bytes").get<std::uintmax_t>())
      throw FileError(out / path, "size differs from its shard manifest");
    if (verify && on_disk.value(path, nlohmann::json()) != entry)
      throw FileError(out / path, "sha256 differs from its shard manifest");
  }
  config.shard = 0, config.shards = 1;
  if (verify) throw_first_problem(release_problems(out, config));
  warn_of_mixed_kernels(out, sequence_names(config));
  const nlohmann::json statistics = release_statistics(out, sequence_names(config), config.classes);
  write_dataset_card(out, config, statistics);
  write_manifest(out, config, files, statistics);
  write_explorer(out, out / kExplorerDir, {.progress = true});
  fs::remove_all(out / kShardDir);
  return config;
}

std::map<std::string, int> kernel_families(const fs::path& out,
                                           const std::vector<std::string>& sequences) {
  std::map<std::string, int> families;
  for (const std::string& name : sequences) {
    const nlohmann::json generator = read_meta(sequence_dir(out, name)).generator;
    if (generator.is_object() && generator.contains("kernels"))
      ++families[generator.at("kernels").get<std::string>()];
  }
  return families;
}

void warn_of_mixed_kernels(const fs::path& out, const std::vector<std::string>& sequences) {
  const std::map<std::string, int> families = kernel_families(out, sequences);
  if (families.size() < 2) return;
  std::string counts;
  for (const auto& [family, count] : families)
    counts += (counts.empty() ? "" : ", ") + family + " " + std::to_string(count);
  std::fprintf(diagnostics(),
               "%s: the sequences were rendered with different Embree kernel families (%s "
               "sequences): their float ground truth in the last bits and a few colour "
               "pixels may differ (docs/release.md, \"Determinism\"; FLOWSCAPE_EMBREE_CONFIG)\n",
               out.string().c_str(), counts.c_str());
}

std::vector<ReleaseProblem> release_problems(const fs::path& out, const ReleaseConfig& config) {
  std::set<fs::path> release;
  for (const fs::path& file : release_sequence_files(config, plan_sequences(config)))
    release.insert(file);
  for (const fs::path& file : dataset_card_files(config)) release.insert(file);
  std::vector<ReleaseProblem> problems;
  if (fs::exists(out) && !fs::is_directory(out))
    throw FileError(out, "is a file, not a folder: a release needs a folder");
  if (!fs::is_directory(out)) return problems;
  for (const auto& entry : fs::recursive_directory_iterator(out)) {
    if (!entry.is_regular_file()) continue;
    const fs::path relative = fs::relative(entry.path(), out);
    const fs::path top = *relative.begin();
    if (is_temporary_file(relative))
      problems.push_back({entry.path(), "temporary file of an interrupted run"});
    else if ((top == kSequencesDir || top == kCardDir) && !release.contains(relative))
      problems.push_back({entry.path(), "not part of the release"});
  }
  if (fs::exists(out / kManifestFile)) {
    const nlohmann::json manifest = read_json(out / kManifestFile);
    const nlohmann::json listed =
        manifest.is_object() ? manifest.value("files", nlohmann::json()) : nlohmann::json();
    if (!listed.is_object()) problems.push_back({out / kManifestFile, "has no \"files\" object"});
    for (const auto& [name, entry] : listed.items()) {
      if (!fs::is_regular_file(out / name))
        problems.push_back({out / name, "listed in manifest.json but missing"});
      else if (!entry.is_object() ||
               entry.value("bytes", nlohmann::json()) != fs::file_size(out / name))
        problems.push_back({out / name, "size differs from manifest.json"});
    }
  }
  std::sort(problems.begin(), problems.end(),
            [](const ReleaseProblem& a, const ReleaseProblem& b) { return a.path < b.path; });
  return problems;
}

void throw_first_problem(const std::vector<ReleaseProblem>& problems) {
  if (problems.empty()) return;
  const std::size_t more = problems.size() - 1;
  throw FileError(
      problems.front().path,
      problems.front().problem +
          (more ? " (and " + std::to_string(more) + " more: gen_flowscape --check)" : ""));
}

}  // namespace flowscape
