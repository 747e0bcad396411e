#pragma once
// manifest.json of a release: generator, config, counts, the layout (layout.h) and the sha256 and
// size of every file; the shard manifests of a release made in pieces, and their merge.
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flowscape/release/config.h"

namespace flowscape {

inline constexpr const char* kGeneratorVersion = "flowscape 0.15";

// Paths (relative to `out`, sorted) with the sha256 and size of every file the layout gives the
// sequences `plans` of a release made with `config` (whatever else their folders hold); a missing
// file is a FileError.
nlohmann::json file_hashes(const std::filesystem::path& out, const ReleaseConfig& config,
                           const std::vector<SequencePlan>& plans);
// manifest.json: the files given plus the dataset card's and config.json, and the release's
// statistics (left out when null).
void write_manifest(const std::filesystem::path& out, const ReleaseConfig& config,
                    const nlohmann::json& files, const nlohmann::json& statistics);

// manifests/shard-K-of-N.json: what one shard (config.shard of config.shards) wrote.
std::filesystem::path shard_manifest_path(const std::filesystem::path& out,
                                          const ReleaseConfig& config);
void write_shard_manifest(const std::filesystem::path& out, const ReleaseConfig& config,
                          const nlohmann::json& files);
// manifests/refused-shard-K-of-N.json: the config a shard was refused with (another than the
// release's), so that the merge can name the keys that differ; its shard manifest removes it.
void write_refused_shard(const std::filesystem::path& out, const ReleaseConfig& config);
// Joins what the shards of a release wrote: checks that every shard reported, that they share one
// config (else names the keys that differ) and list only files of the release, and that every
// planned sequence is complete; removes the temporaries their killed runs left (all stale now);
// with `verify` also checks every file's sha256 and that no file under sequences/ is foreign.
// Then writes the dataset card and manifest.json as one process would have, and removes
// manifests/. Returns the config; throws naming what is missing.
ReleaseConfig merge_shards(const std::filesystem::path& out, bool verify);

// The Embree kernel families the sequences' meta.json record, with how many sequences each
// rendered (releases before flowscape 0.15 record none). When there are several, one line on
// stderr says so: their float ground truth differs in the last bits and some colour pixels
// (docs/release.md, "Determinism").
std::map<std::string, int> kernel_families(const std::filesystem::path& out,
                                           const std::vector<std::string>& sequences);
void warn_of_mixed_kernels(const std::filesystem::path& out,
                           const std::vector<std::string>& sequences);

// What a folder holds that a release made with `config` should not: temporary files anywhere,
// files under sequences/ and card/ that are not the layout's, and, once manifest.json is there,
// files it lists that are missing or have another size. Sorted by path; empty when clean.
struct ReleaseProblem {
  std::filesystem::path path;
  std::string problem;
};
std::vector<ReleaseProblem> release_problems(const std::filesystem::path& out,
                                             const ReleaseConfig& config);
// A FileError for the first problem (and how many more), if there is one.
void throw_first_problem(const std::vector<ReleaseProblem>& problems);

}  // namespace flowscape
