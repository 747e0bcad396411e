#pragma once
// The release explorer (docs/release.md, "Explorer"): a static page that works from the folder
// with no server: <out>/index.html, data.js (what the release holds: config, counts, conventions,
// statistics, calibration of every view, per-frame statistics of every sequence, quality.json's
// scores where gt_quality wrote them), statistics.svg and previews/<sequence>/<view>/<kind>/
// <frame>.png, downscaled views of every kind of a sample of frames.
#include <filesystem>
#include <nlohmann/json.hpp>

namespace flowscape {

struct ExplorerOptions {
  int frames = 24;     // frames per sequence, spread evenly (all of a shorter sequence)
  int width = 512;     // of the ERP's previews (other views: half)
  bool faces = false;  // also the cube faces
  bool progress = false;
};

// Reads the release in `release` (its manifest.json where there is one, every sequence's
// meta.json and the sampled frames' files; every frame's for a sequence whose meta.json has no
// statistics, from before they were recorded) and writes the page into `out` (replacing an earlier
// page there: its previews folder is removed first). Returns the release's statistics (as
// manifest.json holds them; null without sequences). Errors are FileErrors naming the file.
nlohmann::json write_explorer(const std::filesystem::path& release,
                              const std::filesystem::path& out,
                              const ExplorerOptions& options = {});

// Where a release keeps its page, and the file gt_quality's scores are read from.
inline constexpr const char* kExplorerDir = "explorer";
inline constexpr const char* kQualityFile = "quality.json";

}  // namespace flowscape
