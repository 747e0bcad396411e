#pragma once
// Train/test splits of a release by whole sequences, the test side stratified by weather
// (FlowScape: 14 of 64 sequences, 8 sunny + 2 cloud + 2 fog + 2 rain), and the folder tree the
// public PanoFlow code reads: panoflow/<split>/<weather>/img/<scene>/<frame>.jpg and
// .../flow/<scene>/<frame>.flo.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "flowscape/geometry/geometry.h"

namespace flowscape {

struct SequenceInfo {
  std::string name, weather;  // weather: the preset (splits are stratified by it)
  std::string base_weather;   // the PanoFlow folder it goes to (SequenceMeta::base_weather)
  int frames;
};
// Every sequence of a release, from sequences/*/meta.json (sorted by name).
std::vector<SequenceInfo> read_release_sequences(const std::filesystem::path& release);

struct Split {
  std::vector<SequenceInfo> train, test, val;  // val: only from split_by_hash
};
// Per weather, round(n * share) sequences go to test (share 0.2 for sunny, 0.25 for the others),
// at least one and never all when there are two or more; which ones is decided by the seed. When
// every weather has a single sequence, one of them (by the seed) is the test split, so neither
// side is ever empty; fewer than 2 sequences is an error.
Split split_sequences(const std::vector<SequenceInfo>& sequences, std::uint64_t seed);

// A split that stays as it is when a release grows: each sequence's side comes from a stable hash
// of its name and the seed alone (u in [0, 1): test below test_share, val below test_share +
// val_share, else train), and every sequence of a held-out map (0-7) is test. Not stratified: the
// shares hold on average.
struct HashSplitOptions {
  double test_share = 0.2, val_share = 0;
  std::vector<int> held_out_maps{};
};
Split split_by_hash(const std::vector<SequenceInfo>& sequences, std::uint64_t seed,
                    const HashSplitOptions& options);
// The hash's value for a sequence name in [0, 1) (FNV-1a of the name, mixed with the seed).
double split_hash(const std::string& name, std::uint64_t seed);

// splits/train.txt and splits/test.txt (and val.txt when the split has one; a stale one is
// removed): one flow pair per line, "<scene> <frame>".
void write_split_files(const std::filesystem::path& release, const Split& split);
// splits/all.txt: every pair of every sequence (a release of one sequence has only this split).
void write_all_split(const std::filesystem::path& release,
                     const std::vector<SequenceInfo>& sequences);
// How the tree stores flow. The defaults are the public FlowScape's conventions (docs/release.md):
// classic ERP flow, and the sky marked unknown so the public loader's |u|, |v| < 1000 mask drops
// it.
struct PanoflowOptions {
  FlowMode flow = FlowMode::Classic;
  bool sky_invalid = true;
  bool occluded_invalid = false;  // also pixels whose target is hidden in the next frame
  bool final_pass = false;        // the images of the final pass (output kind "final"), not clean
};
// The PanoFlow tree: panoflow/{train,test}/{cloud,fog,rain,sunny} always all there (sequences of
// other presets filed under their base weather), JPEG images, flow in `options`' conventions, and
// panoflow/flowscape.json recording them. A tree with other conventions is rewritten; whole files
// of a tree with the same ones are kept. Returns the "<split>/<weather>" folders left empty.
std::vector<std::string> write_panoflow_tree(const std::filesystem::path& release,
                                             const Split& split,
                                             const PanoflowOptions& options = {});

}  // namespace flowscape
