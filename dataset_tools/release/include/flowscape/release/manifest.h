#pragma once
// manifest.json of a release: generator, config, counts, the layout (layout.h) and the sha256 and
// size of every file; the shard manifests of a release made in pieces, and their merge.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "flowscape/release/config.h"

namespace flowscape {

inline constexpr const char* kGeneratorVersion = "flowscape 0.7";

// Paths (relative to `out`, sorted) with the sha256 and size of every file of the given sequences.
nlohmann::json file_hashes(const std::filesystem::path& out,
                           const std::vector<SequencePlan>& plans);
// manifest.json: the files given plus the dataset card's.
void write_manifest(const std::filesystem::path& out, const ReleaseConfig& config,
                    const nlohmann::json& files);

// manifests/shard-K-of-N.json: what one shard (config.shard of config.shards) wrote.
std::filesystem::path shard_manifest_path(const std::filesystem::path& out,
                                          const ReleaseConfig& config);
void write_shard_manifest(const std::filesystem::path& out, const ReleaseConfig& config,
                          const nlohmann::json& files);
// Joins what the shards of a release wrote: checks that every shard reported, that they share one
// config and that every planned sequence is complete (and, with `verify`, every file's sha256),
// then writes the dataset card and manifest.json as one process would have, and removes
// manifests/. Returns the config; throws naming what is missing.
ReleaseConfig merge_shards(const std::filesystem::path& out, bool verify);

}  // namespace flowscape
