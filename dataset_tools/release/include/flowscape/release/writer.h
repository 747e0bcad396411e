#pragma once
// Rendering and writing the sequences of a release (design.md's layout), resumably.
#include <filesystem>
#include <functional>

#include "flowscape/release/config.h"

namespace flowscape {

struct SequenceProgress {
  std::function<void()> frame_done, frame_skipped;
};
// Renders and writes one sequence: every frame whose files are not all there and complete yet
// (formats/complete_file.h; temporary files a killed run left are removed first), then meta.json.
// Files appear atomically; the same config gives the same bytes whatever the thread count. A
// frame's files are written while the next frame renders (one frame in flight, so the cores stay
// busy while files are encoded). `baseline` (bench_release's only): each frame's files written
// before the next renders, traced as it says; the ground-truth bytes are the same, the colour
// within its noise (docs/release.md, "Speed").
void write_sequence(const ReleaseConfig& config, const SequencePlan& plan,
                    const std::filesystem::path& out, const SequenceProgress& progress,
                    const TracingBaseline* baseline = nullptr);

// Records the config in <out>/config.json before anything else. If `out` already holds a release
// made with another config (config.json, or manifest.json's), refuses with a FileError naming the
// differing keys, or with `force` deletes that release's files (sequences/, manifests, card,
// config.json, manifest.json; nothing else) and starts over.
void claim_release(const ReleaseConfig& config, const std::filesystem::path& out, bool force);

// claim_release, this shard's sequences (all of them for one shard), then the dataset card and
// manifest.json, or for one of several shards its shard manifest (manifest.h). Progress:
// done/total, rate, ETA on stderr.
struct ReleaseWritten {
  std::filesystem::path manifest;                    // manifest.json or this shard's manifest
  std::size_t sequences = 0, frames = 0, files = 0;  // of this shard
};
ReleaseWritten write_release(const ReleaseConfig& config, const std::filesystem::path& out,
                             bool force = false);

}  // namespace flowscape
