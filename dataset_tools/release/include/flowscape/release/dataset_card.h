#pragma once
// The dataset card of a release: README.md with counts, sizes, classes, layout, how to reproduce
// and the licence, and an example frame per weather under card/.
#include <filesystem>
#include <vector>

#include "flowscape/release/config.h"

namespace flowscape {

void write_dataset_card(const std::filesystem::path& out, const ReleaseConfig& config);
// The card's files that exist under `out` (relative to it, sorted).
std::vector<std::filesystem::path> dataset_card_files(const std::filesystem::path& out);

}  // namespace flowscape
