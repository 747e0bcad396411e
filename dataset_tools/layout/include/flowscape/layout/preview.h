#pragma once
// Preview tiles of a sequence of a release, read back from its files.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "flowscape/core/image.h"
#include "flowscape/layout/layout.h"

namespace flowscape {

// Colour | flow (PanoFlow wheel) | semantics (in the colours of the release's class table) of one
// frame of a view (the ERP by default), each at most `width` wide (the last frame has no flow:
// black). The flow is read as the release stores it (`flow_format`).
std::vector<Image<std::uint8_t>> frame_preview_row(const std::filesystem::path& sequence_dir,
                                                   int frame, int width, const View& view = {},
                                                   const std::string& class_table = "carla-0.9.13",
                                                   FlowFormat flow_format = FlowFormat::Flo);

}  // namespace flowscape
