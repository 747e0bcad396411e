#pragma once
// A FlowScape release on disk (design.md, "Release layout"): what to make (ReleaseConfig), which
// sequences that is (plan_sequences), rendering and writing them resumably (write_sequence), and
// the manifest and dataset card over the files.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flowscape/image.h"

namespace flowscape {

struct ReleaseConfig {
  int maps = 8, sequences_per_map = 8, frames = 100;
  int height = 512;     // ERP height; width = 2 x height
  int face_size = 256;  // cube faces: 256 matches a 512 x 1024 ERP at the equator
  int spp = 16, max_bounces = 4;
  // Weather presets, cycled over the sequences of a map (FlowScape: 5 sunny, cloud, fog, rain).
  std::vector<std::string> weathers{"sunny", "sunny", "sunny", "sunny",
                                    "sunny", "cloud", "fog",   "rain"};
  int vehicles = 100, pedestrians = 60;
  std::uint64_t seed = 0;
  bool cube = true;           // also write the six faces (the ERP colour is stitched from them)
  int shard = 0, shards = 1;  // this process makes the sequences k with k % shards == shard
};
void validate(const ReleaseConfig& config);  // throws std::invalid_argument naming the value
nlohmann::json to_json(const ReleaseConfig& config);
// `base` with the values the JSON gives; unknown keys are an error (a typo would go unnoticed).
ReleaseConfig release_config_from_json(const nlohmann::json& json, ReleaseConfig base = {});

struct SequencePlan {
  std::string name;        // map<MM>_seq<SS>
  int map, index, number;  // number: position in the whole release
  std::string weather;
  std::uint64_t seed;
};
std::vector<SequencePlan> plan_sequences(const ReleaseConfig& config);  // every shard's
bool in_shard(const SequencePlan& plan, const ReleaseConfig& config);

std::filesystem::path sequence_dir(const std::filesystem::path& out, const SequencePlan& plan);
// Files of one frame, relative to the sequence folder (flow and valid only before the last frame).
std::vector<std::string> frame_files(const ReleaseConfig& config, int frame);
std::string frame_name(int frame);  // "000042"

struct SequenceProgress {
  std::function<void()> frame_done, frame_skipped;
};
// Renders and writes one sequence: meta.json, then every frame whose files are not all there yet.
// Files appear atomically; the same config gives the same bytes whatever the thread count.
void write_sequence(const ReleaseConfig& config, const SequencePlan& plan,
                    const std::filesystem::path& out, const SequenceProgress& progress);
// Removes the temporary files a killed run left in a sequence folder.
void remove_partial_files(const std::filesystem::path& dir);

// Paths (relative to `out`, sorted) and sha256 of every file of the given sequences.
nlohmann::json file_hashes(const std::filesystem::path& out,
                           const std::vector<SequencePlan>& plans);
// manifest.json: generator, config, counts per map and weather, files with sha256 and size.
void write_manifest(const std::filesystem::path& out, const ReleaseConfig& config,
                    const nlohmann::json& files);
// Joins what the shards of a release wrote (manifests/shard-K-of-N.json): checks that every
// shard reported, that they share one config and that every planned sequence is complete (and,
// with `verify`, every file's sha256), then writes the dataset card and manifest.json as one
// process would have, and removes manifests/. Returns the config; throws naming what is missing.
ReleaseConfig merge_shards(const std::filesystem::path& out, bool verify);

// README.md: the dataset card, with example images under card/.
void write_dataset_card(const std::filesystem::path& out, const ReleaseConfig& config);

// Colour | flow (PanoFlow wheel) | semantics of one ERP frame, read back from a sequence folder,
// each at most `width` wide (the last frame has no flow: black).
std::vector<Image<std::uint8_t>> frame_preview_row(const std::filesystem::path& sequence_dir,
                                                   int frame, int width);

inline constexpr const char* kGeneratorVersion = "flowscape 0.6";

}  // namespace flowscape
