#include "flowscape/layout/layout.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "flowscape/layout/classes.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

// The layout's names and templates; layout_json() states the same as str.format templates.
constexpr const char* kSplitsDir = "splits";

std::string numbered(const char* format, int value) {
  char text[32];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

const char* pixel_type_name(PixelType type) {
  switch (type) {
    case PixelType::UInt8:
      return "uint8";
    case PixelType::UInt16:
      return "uint16";
    case PixelType::Float32:
      return "float32";
  }
  return "";
}

const char* resampling_name(Resampling resampling) {
  switch (resampling) {
    case Resampling::Bilinear:
      return "bilinear";
    case Resampling::Nearest:
      return "nearest";
    case Resampling::Flow:
      return "flow";
    case Resampling::Vector:
      return "vector";
  }
  return "";
}

}  // namespace

const OutputKind& output_kind(std::string_view name) {
  for (const OutputKind& kind : kOutputKinds)
    if (kind.name == name) return kind;
  throw std::invalid_argument("unknown output kind \"" + std::string(name) + "\"");
}

namespace {

constexpr std::string_view kGapSuffix = "_gap";

const char* direction_name(Direction direction) {
  switch (direction) {
    case Direction::Forward:
      return "forward";
    case Direction::Backward:
      return "backward";
    case Direction::None:
      return "none";
  }
  return "";
}

}  // namespace

std::string ReleaseKind::name() const {
  return std::string(row->name) + (gap > 1 ? std::string(kGapSuffix) + std::to_string(gap) : "");
}

std::string_view ReleaseKind::extension() const {
  return row->is_flow() ? flow_format_extension(flow_format) : row->extension;
}

std::string ReleaseKind::folder() const {
  return std::string(row->folder) + (gap > 1 ? std::string(kGapSuffix) + std::to_string(gap) : "");
}

bool ReleaseKind::has_frame(int frame, int frames) const {
  return frame >= 0 && frame < frames && frame + step() >= 0 && frame + step() < frames;
}

ReleaseKind ReleaseKind::valid_kind() const {
  if (!row->is_flow()) throw std::logic_error(name() + " is not a flow kind");
  return {output_kind(row->direction == Direction::Backward ? "valid_backward" : "valid"), gap};
}

ReleaseKind flow_kind_of_step(int step) {
  if (step == 0) throw std::logic_error("a flow needs a step other than 0");
  return {output_kind(step > 0 ? "flow" : "flow_backward"), std::abs(step)};
}

std::optional<ReleaseKind> release_kind(std::string_view name) {
  for (const OutputKind& kind : kOutputKinds) {
    if (name == kind.name) return ReleaseKind(kind);
    if (!kind.per_gap || !name.starts_with(std::string(kind.name) + std::string(kGapSuffix)))
      continue;
    const std::string_view digits = name.substr(kind.name.size() + kGapSuffix.size());
    if (digits.empty() || digits.size() > 4 || digits[0] == '0' ||
        digits.find_first_not_of("0123456789") != std::string_view::npos)
      continue;
    const int gap = std::stoi(std::string(digits));
    if (gap > 1) return ReleaseKind(kind, gap);
  }
  return std::nullopt;
}

bool has_frame(const ReleaseKind& kind, int frame, int frames) {
  return kind.has_frame(frame, frames);
}

namespace {

// A picked name must be a row that is not in every release, at gap 1, or "all".
void check_picked(const std::vector<std::string>& picked) {
  for (const std::string& name : picked) {
    const std::optional<ReleaseKind> kind = release_kind(name);
    if (name == "all" || (kind && kind->gap == 1 && !kind->row->always)) continue;
    std::string choices = "all";
    for (const std::string& k : pickable_kinds()) choices += ", " + k;
    throw std::invalid_argument("unknown output kind \"" + name + "\" (pick from: " + choices +
                                ")");
  }
}

}  // namespace

namespace {

void set_flow_format(ReleaseLayout& layout, FlowFormat format) {
  layout.flow_format = format;
  for (ReleaseKind& kind : layout.kinds) kind.flow_format = format;
}

}  // namespace

ReleaseLayout ReleaseLayout::of(const std::vector<std::string>& picked,
                                const std::vector<int>& gaps, bool cube, FlowFormat flow_format) {
  if (std::find(gaps.begin(), gaps.end(), 1) == gaps.end())
    throw std::invalid_argument("flow gaps must include 1 (the flow every tool reads)");
  for (int gap : gaps)
    if (gap < 1 || gap > kMaxFlowGap)
      throw std::invalid_argument("flow gap " + std::to_string(gap) + " is out of range (1.." +
                                  std::to_string(kMaxFlowGap) + ")");
  check_picked(picked);
  const bool all = std::find(picked.begin(), picked.end(), "all") != picked.end();
  std::vector<int> sorted = gaps;
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  if (sorted.size() > std::size_t(kMaxFlowGaps))
    throw std::invalid_argument("at most " + std::to_string(kMaxFlowGaps) + " flow gaps");
  ReleaseLayout layout;
  layout.cube = cube;
  const auto is_picked = [&](std::string_view name) {
    return std::find(picked.begin(), picked.end(), name) != picked.end();
  };
  for (const OutputKind& kind : kOutputKinds) {
    // a flow brings the mask of its targets
    const bool wanted = kind.always || all || is_picked(kind.name) ||
                        (kind.name == "valid_backward" && is_picked("flow_backward"));
    if (!wanted) continue;
    for (int gap : kind.per_gap ? sorted : std::vector<int>{1})
      layout.kinds.emplace_back(kind, gap);
  }
  set_flow_format(layout, flow_format);
  return layout;
}

const ReleaseKind* ReleaseLayout::find(std::string_view name) const {
  for (const ReleaseKind& kind : kinds)
    if (kind.name() == name) return &kind;
  return nullptr;
}

View View::of_camera(std::string name) {
  View view;
  view.camera = std::move(name);
  return view;
}

std::vector<View> ReleaseLayout::views() const {
  std::vector<View> views;
  if (has_erp()) views.emplace_back();
  if (has_erp() && cube) views.insert(views.end(), kFaces.begin(), kFaces.end());
  for (const LayoutCamera& camera : cameras) views.push_back(View::of_camera(camera.name));
  return views;
}

std::vector<fs::path> ReleaseLayout::frame_files(int frame, int frames) const {
  std::vector<fs::path> files;
  for (const View& view : views())
    for (const ReleaseKind& kind : kinds)
      if (in_view(kind, view) && kind.has_frame(frame, frames))
        files.push_back(frame_file(kind, view, frame));
  return files;
}

std::vector<fs::path> ReleaseLayout::sequence_files(int frames) const {
  std::vector<fs::path> files{kMetaFile};
  for (int f = 0; f < frames; ++f) {
    const std::vector<fs::path> frame = frame_files(f, frames);
    files.insert(files.end(), frame.begin(), frame.end());
  }
  return files;
}

std::vector<int> ReleaseLayout::flow_steps(int frame, int frames) const {
  std::vector<int> steps;
  if (frame + 1 < frames) steps.push_back(1);
  for (const ReleaseKind& kind : kinds)
    if (kind.row->is_flow() && kind.has_frame(frame, frames) &&
        std::find(steps.begin(), steps.end(), kind.step()) == steps.end())
      steps.push_back(kind.step());
  return steps;
}

ReleaseLayout flowscape_layout(bool cube) { return ReleaseLayout::of({}, {1}, cube); }

std::vector<std::string> pickable_kinds() {
  std::vector<std::string> names;
  for (const OutputKind& kind : kOutputKinds)
    if (!kind.always) names.emplace_back(kind.name);
  return names;
}

std::string sequence_name(int map, int sequence) {
  return numbered("map%02d", map) + numbered("_seq%02d", sequence);
}

std::string frame_name(int frame) { return numbered("%06d", frame); }

fs::path sequence_dir(const fs::path& release, const std::string& name) {
  return release / kSequencesDir / name;
}

fs::path view_dir(const View& view) {
  if (!view.camera.empty()) return fs::path(kCamerasDir) / view.camera;
  return view.face ? fs::path(kCubeDir) / std::string(face_name(*view.face)) : fs::path(kErpDir);
}

fs::path frame_file(const ReleaseKind& kind, const View& view, int frame) {
  return view_dir(view) / kind.folder() / (frame_name(frame) + std::string(kind.extension()));
}

fs::path erp_file(const fs::path& sequence, std::string_view kind, int frame) {
  const std::optional<ReleaseKind> known = release_kind(kind);
  if (!known) throw std::invalid_argument("unknown output kind \"" + std::string(kind) + "\"");
  return sequence / frame_file(*known, std::nullopt, frame);
}

fs::path split_file(const fs::path& release, const std::string& side) {
  return release / kSplitsDir / (side + ".txt");
}

nlohmann::json layout_json(const ReleaseLayout& layout) {
  nlohmann::json kinds = nlohmann::json::array();
  for (const ReleaseKind& kind : layout.kinds) {
    const OutputKind& k = *kind.row;
    kinds.push_back({{"name", kind.name()},
                     {"folder", kind.folder()},
                     {"extension", kind.extension()},
                     {"pixel_type", pixel_type_name(k.pixel)},
                     {"channels", k.channels},
                     {"resampling", resampling_name(k.resampling)},
                     {"erp", k.erp},
                     {"cube", k.cube},
                     {"direction", direction_name(k.direction)},
                     {"gap", kind.gap},
                     {"step", kind.step()},
                     {"pairs_only", k.direction == Direction::Forward},
                     {"description", k.description}});
  }
  nlohmann::json faces = nlohmann::json::array();
  for (Face face : kFaces) faces.push_back(face_name(face));
  nlohmann::json cameras = nlohmann::json::array();
  for (const LayoutCamera& c : layout.cameras)
    cameras.push_back({{"name", c.name}, {"panorama", c.panorama}});
  return {{"sequence_dir", std::string(kSequencesDir) + "/{sequence}"},
          {"meta", kMetaFile},
          {"views",
           {{"erp", kErpDir},
            {"cube", std::string(kCubeDir) + "/{face}"},
            {"camera", std::string(kCamerasDir) + "/{camera}"}}},
          {"cameras", cameras},
          {"faces", faces},
          {"frame_file", "{view}/{folder}/{frame:06d}{extension}"},
          {"split_file", std::string(kSplitsDir) + "/{split}.txt"},
          {"cube_faces", layout.cube},
          {"flow_format", flow_format_name(layout.flow_format)},
          {"kinds", kinds}};
}

namespace {

// The flow conventions' keys of its file, by format (flow_io.h's FlowFormat): what it holds, its
// precision and range, and how flow beyond the range is marked.
void add_flow_file(FlowFormat format, nlohmann::json& flow) {
  if (format == FlowFormat::KittiPng) {
    flow["file"] = "KITTI 16-bit PNG: R = u * 64 + 2^15, G = v * 64 + 2^15, B = 1 where known";
    flow["file_precision"] = "1/64 px steps (rounded to nearest)";
    flow["file_range"] = "[-512, 511.984] px";
    flow["file_out_of_range"] = "B = 0 (unknown), the value clamped to the range, never wrapped";
  } else if (format == FlowFormat::HalfExr) {
    flow["file"] = "OpenEXR, half-float channels u, v; unknown flow +inf";
    flow["file_precision"] =
        "11 significant bits (nearest even): 1/8 px steps from 128 px, 1/4 px from 256 px, 1/2 "
        "px from 512 px";
    flow["file_range"] = "+-65504 px";
    flow["file_out_of_range"] = "+inf: unknown";
  } else {
    flow["file"] = "Middlebury .flo: float32 little-endian, tag 202021.25, width, height, u v";
    flow["file_precision"] = "float32";
  }
}

}  // namespace

nlohmann::json conventions_json(const std::string& class_table_name,
                                const std::vector<double>& frame_rates, FlowFormat flow_format) {
  const ClassTable& table = class_table(class_table_name);
  nlohmann::json conventions = {
      {"frame_rate", frame_rates.size() == 1 ? nlohmann::json(frame_rates[0])
                                             : nlohmann::json{{"per_sequence", "meta.json fps"},
                                                              {"rates", frame_rates}}},
      {"time", "frame F is at F / frame_rate seconds"},
      {"world_frame", "right-handed, z up, metres"},
      {"rig_frame", "x forward, y left, z up"},
      {"camera_frame", "x right, y down, z forward (meta.json views: camera_to_rig)"},
      {"pixel_centre", "pixel (i, j) is at (i + 0.5, j + 0.5); K in meta.json: OpenCV's (0, 0)"},
      {"flow",
       {{"value", "target - source"},
        {"source", "the pixel of frame F"},
        {"target",
         "where its surface point (fixed on its object) is seen in frame F + step, "
         "step = the kind's step in layout.kinds (forward > 0, backward < 0)"},
        {"units", "pixels"},
        {"channels", {"u", "v"}},
        {"u", "right"},
        {"v", "down"},
        {"erp_seam", "360"},
        {"erp_u_range", "(-W/2, W/2]: the shortest way round (paper Eq. 3)"},
        {"sky", "finite: the rig's rotation only (points at infinity)"},
        {"occluded", "kept: exact flow, the valid mask is 0"},
        {"unknown_value", kUnknownFlow},
        {"unknown_where", "the target is behind a pinhole camera"}}},
      {"valid",
       {{"1", "the flow target is in front of the camera and visible in the target frame"},
        {"0", "occluded, behind the camera, or unknown"}}},
      {"depth",
       {{"value", "euclidean distance along the pixel-centre ray from the optical centre"},
        {"units", "metres"},
        {"sky", "inf"}}},
      {"scene_flow",
       {{"value", "the surface point's position at F + 1 minus at F"},
        {"frame", "camera frame at F"},
        {"units", "metres"},
        {"sky", "nan"}}},
      {"normal",
       {{"value", "unit normal of the first opaque surface, facing the camera"},
        {"frame", "camera frame"},
        {"sky", "nan"}}},
      {"semantic",
       {{"classes", table.name == "carla-0.9.13" ? "CARLA 0.9.10-0.9.13 (design.md)"
                                                 : "CARLA 0.9.14 and the ego vehicle (29)"},
        {"table", table.name},
        {"names", table.names},
        {"sky", table.sky}}},
      {"instance", {{"static_world_and_sky", 0}}},
      {"boxes_2d",
       {{"value", "[instance, x0, y0, x1, y1] in pixel edges, x1 and y1 exclusive"},
        {"erp_wrap", "x1 <= x0: the box crosses the seam (columns x0..W-1, then 0..x1-1)"}}}};
  add_flow_file(flow_format, conventions["flow"]);
  return conventions;
}

ReleaseLayout layout_from_json(const nlohmann::json& json) {
  if (!json.is_object() || !json.contains("kinds")) return flowscape_layout(true);
  ReleaseLayout layout;
  layout.cube = json.value("cube_faces", true);
  for (const nlohmann::json& c : json.value("cameras", nlohmann::json::array()))
    layout.cameras.push_back({c.at("name").get<std::string>(), c.value("panorama", false)});
  for (const nlohmann::json& row : json.at("kinds")) {
    const std::string name = row.is_object() ? row.value("name", "") : "";
    const std::optional<ReleaseKind> kind = release_kind(name);
    if (!kind) throw std::invalid_argument("unknown output kind \"" + name + "\"");
    layout.kinds.push_back(*kind);
  }
  set_flow_format(layout, flow_format_from_name(json.value("flow_format", "flo")));
  return layout;
}

}  // namespace flowscape
