#pragma once
// What a release holds, in numbers (docs/release.md, "Statistics"): per frame of a sequence, from
// the images of its statistics view as the writer writes them (flow magnitudes, class pixels,
// actor pixels, valid pixels) and per sequence from its rig poses (ego speed and yaw rate), in
// meta.json's "statistics"; gathered per map, weather and over the release for manifest.json,
// the dataset card and the explorer.
#include <array>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flowscape/core/image.h"
#include "flowscape/core/types.h"
#include "flowscape/layout/layout.h"
#include "flowscape/layout/meta.h"

namespace flowscape {

// Flow magnitude histogram bins, in pixels of a 1024-wide image (a view's flow is scaled by
// 1024 / its width): [0, 1/16), then eighth-octave bins from 1/16 to 1024, then [1024, inf).
// The edges, 0 first; bin k holds [edges[k], edges[k + 1]), the last one everything above.
const std::vector<double>& flow_bin_edges();
inline constexpr int kSemanticClasses = 30;  // room for every class table's ids (classes.h)
inline constexpr double kTurnDegrees = 45;   // a sequence "turns" when its yaw changes this much

struct FrameStatistics {
  std::vector<std::uint64_t> flow_histogram;       // every pixel with a known flow; empty: no flow
  double flow_sum = 0;                             // of their magnitudes (1024-wide pixels)
  float flow_p50 = 0, flow_p90 = 0, flow_p99 = 0;  // nearest-rank percentiles
  std::array<std::uint64_t, kSemanticClasses> class_pixels{};
  std::uint64_t pixels = 0, actor_pixels = 0, valid_pixels = 0;
};

// One frame of a view: `flow` (2 channels; empty view: the frame has no forward flow) and its
// `valid` mask, semantic ids and instance ids (an actor is any instance > 0).
FrameStatistics frame_statistics(ImageView<const float> flow, ImageView<const std::uint8_t> valid,
                                 ImageView<const std::uint8_t> semantic,
                                 ImageView<const std::uint16_t> instance);
// The same from a frame's files (a frame a resumed run did not render), found by the layout.
FrameStatistics frame_statistics(const std::filesystem::path& sequence_dir,
                                 const ReleaseLayout& layout, const View& view, int frame,
                                 int frames);

// The view statistics are taken of: the ERP, or the first camera of another rig.
View statistics_view(const ReleaseLayout& layout);

// meta.json's "statistics" of a sequence from its frames' statistics and rig poses
// (rig -> world, x forward, z up) at `fps`.
// `classes`: the class table's size (class_pixels holds that many ids).
nlohmann::json sequence_statistics_json(const View& view,
                                        const std::vector<FrameStatistics>& frames,
                                        const std::vector<Pose>& poses, double fps, int classes);

// The same from a sequence's files, for a release from before meta.json recorded them.
nlohmann::json sequence_statistics_from_files(const std::filesystem::path& sequence_dir,
                                              const ReleaseLayout& layout,
                                              const std::vector<Pose>& poses, int frames,
                                              double fps, int classes);

// manifest.json's "statistics": per map, per weather (the paper's four) and over all the
// sequences given (null when there are none).
struct SequenceStatistics {
  std::string map_name, weather;  // weather: the paper's four (SequenceMeta::base_weather)
  int frames = 0;
  nlohmann::json statistics;  // sequence_statistics_json's
};
// Class shares are named by `class_names` (the release's class table).
nlohmann::json release_statistics(const std::vector<SequenceStatistics>& sequences,
                                  const std::vector<std::string>& class_names);
// A sequence's record from its meta.json (read from `sequence_dir`), checked: a record
// release_statistics cannot read is a FileError naming the meta.json.
SequenceStatistics checked_statistics(const std::filesystem::path& sequence_dir,
                                      const SequenceMeta& meta);
// Of the sequences of the release in `out` that have statistics in their meta.json (class
// shares named by the class table its manifest names, or `class_table` before it has one).
nlohmann::json release_statistics(const std::filesystem::path& out,
                                  const std::vector<std::string>& sequences,
                                  const std::string& class_table);
// A few lines per map and over the release: flow percentiles, ego speed, turning sequences.
std::string statistics_summary(const nlohmann::json& statistics);

// The percentile q (0..1) of a histogram over flow_bin_edges(): the bin where the count reaches
// q * total, interpolated geometrically inside it (linearly in the first; the open last bin gives
// its lower edge), so within one eighth octave of the exact value.
double histogram_percentile(const std::vector<std::uint64_t>& histogram, double q);

// The figure of release_statistics (flow magnitudes per weather and per map, ego speed and yaw
// rate, class shares) as a self-contained SVG; a note when `statistics` is null.
std::string statistics_svg(const nlohmann::json& statistics);

}  // namespace flowscape
