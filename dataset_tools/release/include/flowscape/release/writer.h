#pragma once
// Rendering and writing the sequences of a release (design.md's layout), resumably.
#include <filesystem>
#include <functional>

#include "flowscape/release/config.h"

namespace flowscape {

struct SequenceProgress {
  std::function<void()> frame_done, frame_skipped;
};
// Renders and writes one sequence: meta.json, then every frame whose files are not all there yet
// (temporary files a killed run left are removed first). Files appear atomically; the same config
// gives the same bytes whatever the thread count.
void write_sequence(const ReleaseConfig& config, const SequencePlan& plan,
                    const std::filesystem::path& out, const SequenceProgress& progress);

// This shard's sequences (all of them for one shard), then the dataset card and manifest.json, or
// for one of several shards its shard manifest (manifest.h). Progress: done/total, rate, ETA on
// stderr.
struct ReleaseWritten {
  std::filesystem::path manifest;                    // manifest.json or this shard's manifest
  std::size_t sequences = 0, frames = 0, files = 0;  // of this shard
};
ReleaseWritten write_release(const ReleaseConfig& config, const std::filesystem::path& out);

}  // namespace flowscape
