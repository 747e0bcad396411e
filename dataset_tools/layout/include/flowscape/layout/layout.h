#pragma once
// The files of a FlowScape release (design.md, "Release layout"), written down once. Every kind of
// output a frame can have is one row of kOutputKinds, and a release's ReleaseLayout says which rows
// (and flow gaps) it holds; the writer, resume, manifest, dataset card, splits, previews, merge,
// stitch_erp, gt_quality and the Python plugin (through the "layout" that manifest.json carries)
// find files through it. A new output kind is a row here plus the code that produces its image in
// release/src/writer.cpp (docs/architecture.md).
#include <array>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "flowscape/formats/flow_io.h"
#include "flowscape/geometry/geometry.h"

namespace flowscape {

enum class PixelType : std::uint8_t { UInt8, UInt16, Float32 };
// How stitching takes the kind from the cube faces to the ERP (stitcher/stitch.h).
enum class Resampling : std::uint8_t {
  Bilinear,  // smooth quantities
  Nearest,   // ids, depth, masks: never blended
  Flow,      // flow vectors, re-projected per pixel; the file is a flow file (formats/flow_io.h)
  Vector,    // 3-vectors in the view's camera frame: nearest, turned from each face's frame to the
             // ERP's (normals, scene flow)
};
// Which frames a kind connects: frame F alone, or F with F + gap (forward) or F - gap (backward).
enum class Direction : std::int8_t { None = 0, Forward = 1, Backward = -1 };

struct OutputKind {
  std::string_view name;       // in code, configs and manifest.json
  std::string_view folder;     // <view>/<folder>/<frame><extension>
  std::string_view extension;  // ".png", ".flo", ".exr"
  PixelType pixel;
  int channels;
  Resampling resampling;
  bool erp, cube;  // written for the ERP view, for every cube face
  Direction direction;
  bool per_gap;  // one kind per gap of the release's flow gaps (ReleaseKind)
  bool always;   // in every release (the FlowScape six); the others are picked (--outputs)
  std::string_view description;  // for the dataset card and docs
  // A PNG kind's zlib level: 6 (libpng's default) but where bench_encoding found a lower one
  // pays (colour: a quarter of the time for 8 % more bytes; ids and masks compress fast at 6).
  int png_level = 6;

  constexpr bool is_flow() const { return resampling == Resampling::Flow; }
};

// Every kind a release can hold (docs/release.md, "Output kinds", has each one's definition).
inline constexpr std::array<OutputKind, 14> kOutputKinds{{
    {"color", "color", ".png", PixelType::UInt8, 3, Resampling::Bilinear, true, true,
     Direction::None, false, true, "8-bit sRGB PNG, path traced", 2},
    {"flow", "flow", ".flo", PixelType::Float32, 2, Resampling::Flow, true, true,
     Direction::Forward, true, true,
     "flow from frame F to F + gap in pixels (u right, v down), Middlebury .flo (360-degree on "
     "the ERP)"},
    {"semantic", "semantic", ".png", PixelType::UInt8, 1, Resampling::Nearest, true, true,
     Direction::None, false, true, "8-bit CARLA class ids"},
    {"instance", "instance", ".png", PixelType::UInt16, 1, Resampling::Nearest, true, true,
     Direction::None, false, true, "16-bit instance ids (0 = static world and sky)"},
    {"depth", "depth", ".exr", PixelType::Float32, 1, Resampling::Nearest, true, true,
     Direction::None, false, true, "float EXR, metres along the ray (+inf for the sky)"},
    {"valid", "valid", ".png", PixelType::UInt8, 1, Resampling::Nearest, true, true,
     Direction::Forward, true, true,
     "8-bit, 1 where the flow target is in view and visible in frame F + gap"},
    {"flow_backward", "flow_backward", ".flo", PixelType::Float32, 2, Resampling::Flow, true, true,
     Direction::Backward, true, false,
     "flow from frame F to F - gap in pixels, Middlebury .flo (360-degree on the ERP)"},
    {"valid_backward", "valid_backward", ".png", PixelType::UInt8, 1, Resampling::Nearest, true,
     true, Direction::Backward, true, false,
     "8-bit, 1 where the backward flow target is in view and visible in frame F - gap"},
    {"scene_flow", "scene_flow", ".exr", PixelType::Float32, 3, Resampling::Vector, true, true,
     Direction::Forward, false, false,
     "float EXR, metres: the surface point's 3-D motion from F to F + 1 in the camera frame of F "
     "(NaN for the sky)"},
    {"normal", "normal", ".exr", PixelType::Float32, 3, Resampling::Vector, true, true,
     Direction::None, false, false,
     "float EXR: the first opaque surface's unit geometric normal in the camera frame, facing "
     "the camera (NaN for the sky)"},
    {"normal_shading", "normal_shading", ".exr", PixelType::Float32, 3, Resampling::Vector, true,
     true, Direction::None, false, false,
     "float EXR: the shading normal there (smoothed, bumped and normal-mapped by the textures), "
     "camera frame (NaN for the sky)"},
    {"final", "final", ".png", PixelType::UInt8, 3, Resampling::Bilinear, true, true,
     Direction::None, false, false,
     "8-bit sRGB PNG, the final pass: motion blur traced over the shutter, auto-exposure, lens "
     "glare and vignetting, shot and read noise, a filmic tone curve (meta.json `final`); the "
     "ground truth is the frame time's; opt-in (--outputs final): a second path trace, about "
     "2.5x the clean release's time",
     2},
    {"time", "time", ".exr", PixelType::Float32, 1, Resampling::Nearest, true, true,
     Direction::None, false, false,
     "float EXR, seconds since the sequence's start at which the pixel was captured: the frame's "
     "time, plus its line's offset for a rolling-shutter camera (NaN outside a lens's image)"},
    {"lens_mask", "lens_mask", ".png", PixelType::UInt8, 1, Resampling::Nearest, true, true,
     Direction::None, false, false,
     "8-bit, 1 where water drops or dirt on the lens hide the scene in the final pass (real "
     "lenses; 0 on the ERP and cube faces); the ground truth stays the scene's"},
}};

// The row named `name`; throws std::invalid_argument for other names.
const OutputKind& output_kind(std::string_view name);

// A kind as a release holds it: a row of kOutputKinds and, for a per-gap row, its gap. Gap 1 keeps
// the row's name and folder ("flow", "flow_backward"), gap k > 1 appends "_gap<k>" to both
// ("flow_gap2", "valid_backward_gap4").
struct ReleaseKind {
  const OutputKind* row;
  int gap = 1;
  FlowFormat flow_format = FlowFormat::Flo;  // a flow kind's file: the release's --flow-format
  ReleaseKind(const OutputKind& kind, int gap = 1) : row(&kind), gap(gap) {}  // NOLINT: implicit

  std::string name() const;
  std::string folder() const;
  std::string_view extension() const;                     // the row's, or a flow kind's format's
  int step() const { return int(row->direction) * gap; }  // frame F connects to F + step
  // Whether a sequence of `frames` frames has this kind at `frame` (both ends inside it).
  bool has_frame(int frame, int frames) const;
  // For a flow kind, the mask of its targets (flow -> valid, flow_backward_gap2 ->
  // valid_backward_gap2).
  ReleaseKind valid_kind() const;
  bool operator==(const ReleaseKind& other) const { return row == other.row && gap == other.gap; }
};
// The flow kind of a frame step: +k forward at gap k, -k backward at gap k.
ReleaseKind flow_kind_of_step(int step);
// The release kind a name (or folder) spells: "flow_gap2" -> flow at gap 2; nullopt for others.
std::optional<ReleaseKind> release_kind(std::string_view name);
bool has_frame(const ReleaseKind& kind, int frame, int frames);

// Flow over a gap of k frames: k at most kMaxFlowGap, at most kMaxFlowGaps gaps.
inline constexpr int kMaxFlowGap = 999, kMaxFlowGaps = 8;

// A view of a sequence: the ERP panorama, one cube face (the flowscape rig), or one camera of
// another rig (renderer/rig.h).
struct View {
  std::optional<Face> face;
  std::string camera;  // its name; empty for the ERP and the faces
  View() = default;    // the ERP
  View(std::nullopt_t) {}
  View(Face face) : face(face) {}  // NOLINT: implicit, a face is a view
  static View of_camera(std::string name);
  bool is_erp() const { return !face && camera.empty(); }
};
// Whether a view holds a kind: the ERP its `erp` rows, faces and rig cameras its `cube` rows.
inline bool in_view(const ReleaseKind& kind, const View& view) {
  return view.is_erp() ? kind.row->erp : kind.row->cube;
}
inline constexpr const char* kErpDir = "erp";          // the ERP view's folder
inline constexpr const char* kCubeDir = "cube";        // the faces' folders are cube/<face>
inline constexpr const char* kCamerasDir = "cameras";  // a rig's cameras are cameras/<name>

// A camera of a rig as the layout knows it: its folder's name, and whether its image wraps
// round horizontally (an equirectangular camera).
struct LayoutCamera {
  std::string name;
  bool panorama = false;
  bool operator==(const LayoutCamera&) const = default;
};

// What a release holds: the kinds every release has, the ones picked, each per-gap row at every
// gap (in kOutputKinds order, gaps ascending), and its views: the flowscape rig's ERP and, with
// `cube`, its six faces; or another rig's cameras.
struct ReleaseLayout {
  std::vector<ReleaseKind> kinds;
  bool cube = true;
  // Another rig's cameras, each in cameras/<name>/; none: the flowscape rig's views (erp/ and,
  // with `cube`, cube/<face>/).
  std::vector<LayoutCamera> cameras;
  FlowFormat flow_format = FlowFormat::Flo;  // every flow kind's (ReleaseKind::flow_format)

  bool has_erp() const { return cameras.empty(); }
  std::vector<View> views() const;  // the ERP, the faces, or the cameras

  // `picked`: rows that are not `always` (or "all"); `gaps` must hold 1, each at least 1.
  // Throws std::invalid_argument naming what is wrong.
  static ReleaseLayout of(const std::vector<std::string>& picked, const std::vector<int>& gaps,
                          bool cube, FlowFormat flow_format = FlowFormat::Flo);
  const ReleaseKind* find(std::string_view name) const;  // null when the release lacks it
  bool has(std::string_view name) const { return find(name) != nullptr; }
  // Every file of one frame, relative to the sequence folder.
  std::vector<std::filesystem::path> frame_files(int frame, int frames) const;
  // Every file of a sequence (meta.json and each frame's), relative to its folder.
  std::vector<std::filesystem::path> sequence_files(int frames) const;
  // The frame steps of the flow kinds the frame has, +1 first (the forward flow every frame but
  // the last has), each once.
  std::vector<int> flow_steps(int frame, int frames) const;
};
// The kinds of FlowScape (the six every release has) at gap 1.
ReleaseLayout flowscape_layout(bool cube);
// The rows --outputs may pick, in table order.
std::vector<std::string> pickable_kinds();

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

std::filesystem::path view_dir(const View& view);  // "erp", "cube/<face>", "cameras/<name>"
// <view>/<folder>/<frame><extension>, relative to the sequence folder.
std::filesystem::path frame_file(const ReleaseKind& kind, const View& view, int frame);
// The ERP file of output kind `kind` ("flow", "depth", "flow_gap2", ...) of a frame in a sequence
// folder.
std::filesystem::path erp_file(const std::filesystem::path& sequence, std::string_view kind,
                               int frame);

// splits/<side>.txt of a release.
std::filesystem::path split_file(const std::filesystem::path& release, const std::string& side);

// The layout as manifest.json states it: path templates (Python str.format fields) and the kinds.
nlohmann::json layout_json(const ReleaseLayout& layout);
// The conventions of a release's data, as manifest.json and the dataset card state them for
// programs to read (docs/release.md, "Conventions"): flow direction, units, axes, the ERP seam,
// sky and invalid values, depth, frames and time, the semantic class table (classes.h).
// `frame_rates`: the release's (scenario.h's release_frame_rates); several are listed with
// "per sequence" (meta.json's fps). The flow's file as `flow_format` stores it, with its precision
// and range.
nlohmann::json conventions_json(const std::string& class_table_name = "carla-0.9.13",
                                const std::vector<double>& frame_rates = {kFrameRate},
                                FlowFormat flow_format = FlowFormat::Flo);
// The kinds a manifest's layout lists (a release from before they were listed: FlowScape's six);
// throws std::invalid_argument for kinds it does not know.
ReleaseLayout layout_from_json(const nlohmann::json& layout);

}  // namespace flowscape
