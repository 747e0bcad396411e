#pragma once
// The files of a FlowScape release (design.md, "Release layout"), written down once. Every kind of
// output a frame can have is one row of kOutputKinds; the writer, resume, manifest, dataset card,
// splits, previews, merge, stitch_erp, gt_quality and the Python plugin (through the "layout" that
// manifest.json carries) find files through it. A new output kind is a row here plus the code that
// produces its image in release/src/writer.cpp (docs/architecture.md).
#include <array>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "flowscape/stitcher/geometry.h"

namespace flowscape {

enum class PixelType : std::uint8_t { UInt8, UInt16, Float32 };
// How stitching takes the kind from the cube faces to the ERP (stitcher/stitch.h).
enum class Resampling : std::uint8_t {
  Bilinear,  // smooth quantities
  Nearest,   // ids, depth, masks: never blended
  Flow,      // flow vectors, re-projected per pixel; the file is a flow file (formats/flow_io.h)
};

struct OutputKind {
  std::string_view name;       // in code, configs and manifest.json
  std::string_view folder;     // <view>/<folder>/<frame><extension>
  std::string_view extension;  // ".png", ".flo", ".exr"
  PixelType pixel;
  int channels;
  Resampling resampling;
  bool erp, cube;                // written for the ERP view, for every cube face
  bool pairs_only;               // only frames with a next frame (forward flow F -> F + 1)
  std::string_view description;  // for the dataset card

  constexpr bool is_flow() const { return resampling == Resampling::Flow; }
};

inline constexpr std::array<OutputKind, 6> kOutputKinds{{
    {"color", "color", ".png", PixelType::UInt8, 3, Resampling::Bilinear, true, true, false,
     "8-bit sRGB PNG, path traced"},
    {"flow", "flow", ".flo", PixelType::Float32, 2, Resampling::Flow, true, true, true,
     "forward flow to the next frame in pixels, Middlebury .flo (360-degree on the ERP)"},
    {"semantic", "semantic", ".png", PixelType::UInt8, 1, Resampling::Nearest, true, true, false,
     "8-bit CARLA class ids"},
    {"instance", "instance", ".png", PixelType::UInt16, 1, Resampling::Nearest, true, true, false,
     "16-bit instance ids (0 = static world and sky)"},
    {"depth", "depth", ".exr", PixelType::Float32, 1, Resampling::Nearest, true, true, false,
     "float EXR, metres along the ray (+inf for the sky)"},
    {"valid", "valid", ".png", PixelType::UInt8, 1, Resampling::Nearest, true, true, true,
     "8-bit, 1 where the flow target is visible in the next frame"},
}};

// The row named `name`; throws std::invalid_argument for other names.
const OutputKind& output_kind(std::string_view name);
// Whether a sequence of `frames` frames has this kind at `frame` (pairs_only kinds end one early).
bool has_frame(const OutputKind& kind, int frame, int frames);

std::string sequence_name(int map, int sequence);  // "map03_seq05"
std::string frame_name(int frame);                 // "000042"
std::filesystem::path sequence_dir(const std::filesystem::path& release, const std::string& name);
inline constexpr const char* kSequencesDir = "sequences";  // <release>/sequences/<name>
inline constexpr const char* kMetaFile = "meta.json";
inline constexpr const char* kManifestFile = "manifest.json";
// The config a release is being made with, written before its first frame (writer.h).
inline constexpr const char* kConfigFile = "config.json";
// Where the shards of a release put their manifests until flowscape_merge joins them (manifest.h).
inline constexpr const char* kShardDir = "manifests";
// The dataset card's example images (dataset_card.h), beside its README.md.
inline constexpr const char* kCardDir = "card";

// A view of a sequence: the ERP panorama (no face) or one cube face.
using View = std::optional<Face>;
inline constexpr const char* kErpDir = "erp";    // the ERP view's folder
inline constexpr const char* kCubeDir = "cube";  // the faces' folders are cube/<face>
std::filesystem::path view_dir(View view);       // "erp" or "cube/<face>"
// <view>/<folder>/<frame><extension>, relative to the sequence folder.
std::filesystem::path frame_file(const OutputKind& kind, View view, int frame);
// The ERP file of output kind `kind` ("flow", "depth", ...) of a frame in a sequence folder.
std::filesystem::path erp_file(const std::filesystem::path& sequence, std::string_view kind,
                               int frame);
// Every file of one frame, relative to the sequence folder.
std::vector<std::filesystem::path> frame_files(int frame, int frames, bool cube);
// Every file of a sequence of `frames` frames (meta.json and each frame's), relative to its folder.
std::vector<std::filesystem::path> sequence_files(int frames, bool cube);

// splits/<side>.txt of a release.
std::filesystem::path split_file(const std::filesystem::path& release, const std::string& side);

// The layout as manifest.json states it: path templates (Python str.format fields) and the kinds.
nlohmann::json layout_json();

}  // namespace flowscape
