#pragma once
// The dataset card of a release: README.md with counts, sizes, classes, layout, how to reproduce
// and the licence, and an example frame per weather under card/.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "flowscape/release/config.h"

namespace flowscape {

// Removes temporaries an interrupted card left in card/, then writes the card's files, with the
// release's statistics (statistics.h's release_statistics; null: none recorded).
void write_dataset_card(const std::filesystem::path& out, const ReleaseConfig& config,
                        const nlohmann::json& statistics);
// The files the card of a release made with `config` has, relative to the release (sorted):
// README.md and one example per weather under card/.
std::vector<std::filesystem::path> dataset_card_files(const ReleaseConfig& config);
// What --force deletes of a card made with any config.
void remove_dataset_card(const std::filesystem::path& out);

}  // namespace flowscape
