#pragma once
// Train/test splits of a release by whole sequences, the test side stratified by weather
// (FlowScape: 14 of 64 sequences, 8 sunny + 2 cloud + 2 fog + 2 rain), and the folder tree the
// public PanoFlow code reads: panoflow/<split>/<weather>/img/<scene>/<frame>.jpg and
// .../flow/<scene>/<frame>.flo.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace flowscape {

struct SequenceInfo {
  std::string name, weather;
  int frames;
};
// Every sequence of a release, from sequences/*/meta.json (sorted by name).
std::vector<SequenceInfo> read_release_sequences(const std::filesystem::path& release);

struct Split {
  std::vector<SequenceInfo> train, test;
};
// Per weather, round(n * share) sequences go to test (share 0.2 for sunny, 0.25 for the others),
// at least one and never all when there are two or more; which ones is decided by the seed.
Split split_sequences(const std::vector<SequenceInfo>& sequences, std::uint64_t seed);

// splits/train.txt and splits/test.txt: one flow pair per line, "<scene> <frame>".
void write_split_files(const std::filesystem::path& release, const Split& split);
// The PanoFlow tree (JPEG images, the .flo files hard-linked or copied); existing files are kept.
void write_panoflow_tree(const std::filesystem::path& release, const Split& split);

}  // namespace flowscape
