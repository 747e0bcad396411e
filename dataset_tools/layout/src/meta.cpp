#include "flowscape/layout/meta.h"

#include <algorithm>
#include <fstream>
#include <limits>
#include <map>

#include "flowscape/core/files.h"
#include "flowscape/layout/classes.h"
#include "flowscape/layout/layout.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

constexpr const char* kRigFrame = "x forward, y left, z up; rig pose = rig -> world, 3x4 row-major";
constexpr const char* kCameraFrame =
    "x right, y down, z forward; a view's camera_to_rig maps it to the rig frame";

Pose pose_from_row_major(const nlohmann::json& values) {
  const auto v = values.get<std::vector<double>>();
  if (v.size() != 12) throw std::invalid_argument("a pose needs 12 numbers (3x4 row-major)");
  Pose pose = Pose::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) pose.matrix()(r, c) = v[std::size_t(4 * r + c)];
  return pose;
}

nlohmann::json matrix_rows(const Mat3& m) {
  return {{m(0, 0), m(0, 1), m(0, 2)}, {m(1, 0), m(1, 1), m(1, 2)}, {m(2, 0), m(2, 1), m(2, 2)}};
}

}  // namespace

nlohmann::json pose_row_major(const Pose& pose) {
  std::vector<double> values;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) values.push_back(pose.matrix()(r, c));
  return values;
}

nlohmann::json views_json(int erp_height, int face_size) {
  const int W = 2 * erp_height;
  nlohmann::json views = {
      {kErpDir,
       {{"model", "equirectangular"},
        {"width", W},
        {"height", erp_height},
        {"longitude",
         "phi = 2 pi x / W - pi, x the continuous column (pixel i's centre at i + "
         "0.5); phi = 0 looks forward (rig x), phi grows to the right"},
        {"latitude", "theta = pi y / H - pi / 2, growing downwards"},
        {"ray_in_rig", "(cos theta cos phi, -cos theta sin phi, -sin theta)"},
        {"camera_to_rig", matrix_rows(face_rotation(Face::Front))},
        {"translation_in_rig", {0, 0, 0}}}}};
  if (face_size <= 0) return views;
  const double f = face_size / 2.0, c = face_size / 2.0 - 0.5;
  for (Face face : kFaces)
    views[std::string(view_dir(face).generic_string())] = {
        {"model", "pinhole"},
        {"width", face_size},
        {"height", face_size},
        {"K", {{f, 0, c}, {0, f, c}, {0, 0, 1}}},
        {"K_pixel_origin", "the centre of the top-left pixel is (0, 0) (OpenCV)"},
        {"field_of_view_degrees", 90},
        {"camera_to_rig", matrix_rows(face_rotation(face))},
        {"translation_in_rig", {0, 0, 0}}};
  return views;
}

namespace {

// The columns an instance covers, [x0, x1): from its first to its last column; on a panorama the
// complement of the longest run of empty columns round the circle (x1 <= x0: across the seam).
std::pair<int, int> column_span(const std::vector<bool>& columns, bool panorama) {
  const int W = int(columns.size());
  const int first = int(std::find(columns.begin(), columns.end(), true) - columns.begin());
  if (!panorama) {
    const int last =
        W - 1 - int(std::find(columns.rbegin(), columns.rend(), true) - columns.rbegin());
    return {first, last + 1};
  }
  int gap_start = 0, gap = 0, run_start = 0, run = 0;
  for (int i = 1; i <= W; ++i) {  // from a covered column, so no run is cut by the seam
    const int x = (first + i) % W;
    if (columns[std::size_t(x)]) {
      run = 0;
      continue;
    }
    if (run++ == 0) run_start = x;
    if (run > gap) gap = run, gap_start = run_start;
  }
  if (gap == 0) return {0, W};
  return {(gap_start + gap) % W, gap_start == 0 ? W : gap_start};
}

}  // namespace

std::vector<InstanceBox> instance_boxes(ImageView<const std::uint16_t> ids, bool panorama) {
  struct Extent {
    int y0, y1;
    std::vector<bool> columns;
  };
  std::map<std::uint16_t, Extent> found;
  for (int y = 0; y < ids.height; ++y)
    for (int x = 0; x < ids.width; ++x) {
      const std::uint16_t id = *ids.pixel(x, y);
      if (id == 0) continue;
      auto [entry, fresh] = found.try_emplace(id, Extent{y, y + 1, {}});
      Extent& e = entry->second;
      if (fresh) e.columns.assign(std::size_t(ids.width), false);
      e.columns[std::size_t(x)] = true;
      e.y1 = y + 1;
    }
  std::vector<InstanceBox> boxes;
  for (const auto& [id, e] : found) {
    const auto [x0, x1] = column_span(e.columns, panorama);
    boxes.push_back({id, x0, e.y0, x1, e.y1});
  }
  return boxes;
}

std::string SequenceMeta::weather_preset() const { return weather.at("preset").get<std::string>(); }

std::string SequenceMeta::base_weather() const {
  const auto number = [&](const char* key) { return weather.value(key, 0.0); };
  if (number("precipitation") > 0) return "rain";
  if (number("fog_density") >= 0.01) return "fog";
  return number("cloudiness") >= 0.5 ? "cloud" : "sunny";
}

nlohmann::json to_json(const SequenceMeta& m) {
  nlohmann::json poses = nlohmann::json::array();
  for (const Pose& pose : m.poses) poses.push_back(pose_row_major(pose));
  nlohmann::json j = {{"schema", kMetaSchema},
                      {"frames_of_reference", {{"rig", kRigFrame}, {"camera", kCameraFrame}}},
                      {"scene", m.scene},
                      {"map", m.map},
                      {"map_name", m.map_name},
                      {"sequence", m.sequence},
                      {"seed", m.seed},
                      {"weather", m.weather},
                      {"frames", m.frames},
                      {"fps", m.fps},
                      {"camera",
                       {{"height_above_ego", m.camera_height},
                        {"pitch_sway_degrees", m.camera_pitch_sway},
                        {"roll_sway_degrees", m.camera_roll_sway},
                        {"frame", kRigFrame}}},
                      {"poses", poses},
                      {"city", m.city}};
  if (m.erp_height > 0)
    j["erp"] = {{"width", 2 * m.erp_height}, {"height", m.erp_height}, {"flow", "360-degree"}};
  if (m.face_size > 0) {
    nlohmann::json faces = nlohmann::json::array();
    for (Face face : kFaces) faces.push_back(face_name(face));
    j["cube"] = {{"face_size", m.face_size}, {"focal", m.face_size / 2.0}, {"faces", faces}};
  }
  for (const auto& [key, record] : {std::pair{"views", &m.views},
                                    {"actors", &m.actors},
                                    {"boxes_2d", &m.boxes},
                                    {"rig", &m.rig},
                                    {"statistics", &m.statistics},
                                    {"final", &m.final},
                                    {"scenario", &m.scenario},
                                    {"generator", &m.generator}})
    if (!record->is_null()) j[key] = *record;
  return j;
}

SequenceMeta meta_from_json(const nlohmann::json& j) {
  SequenceMeta m;
  try {
    m.scene = j.at("scene").get<std::string>();
    m.map = j.at("map").get<int>();
    m.map_name = j.at("map_name").get<std::string>();
    m.sequence = j.at("sequence").get<int>();
    m.seed = j.at("seed").get<std::uint64_t>();
    m.weather = j.at("weather");
    m.frames = j.at("frames").get<int>();
    m.fps = j.at("fps").get<double>();
    if (j.contains("erp")) m.erp_height = j.at("erp").at("height").get<int>();
    m.camera_height = j.at("camera").at("height_above_ego").get<double>();
    m.camera_pitch_sway = j.at("camera").value("pitch_sway_degrees", 0.0);
    m.camera_roll_sway = j.at("camera").value("roll_sway_degrees", 0.0);
    for (const nlohmann::json& pose : j.at("poses")) m.poses.push_back(pose_from_row_major(pose));
    m.city = j.value("city", nlohmann::json());
    if (j.contains("cube")) m.face_size = j.at("cube").at("face_size").get<int>();
    m.views = j.value("views", nlohmann::json());
    if (m.views.is_object())  // schema 1 held the frames' descriptions among the views
      for (const char* text : {"camera_frame", "rig_frame"}) m.views.erase(text);
    m.actors = j.value("actors", nlohmann::json());
    m.boxes = j.value("boxes_2d", nlohmann::json());
    m.rig = j.value("rig", nlohmann::json());
    m.statistics = j.value("statistics", nlohmann::json());
    m.final = j.value("final", nlohmann::json());
    m.scenario = j.value("scenario", nlohmann::json());
    m.generator = j.value("generator", nlohmann::json());
    m.weather_preset();
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(e.what());
  }
  if (m.frames < 1) throw std::invalid_argument("frames must be at least 1");
  return m;
}

nlohmann::json read_json(const fs::path& path) {
  const std::string text = read_file(path, std::uintmax_t(1) << 28);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw FileError(path, std::string("not JSON: ") + e.what());
  }
}

ReleaseLayout read_release_layout(const fs::path& release) {
  const fs::path manifest = release / kManifestFile;
  if (!fs::exists(manifest)) return flowscape_layout(true);
  const nlohmann::json json = read_json(manifest);
  try {
    return layout_from_json(json.is_object() ? json.value("layout", nlohmann::json())
                                             : nlohmann::json());
  } catch (const std::exception& e) {  // unknown kinds, and json's type errors
    throw FileError(manifest, std::string("layout: ") + e.what());
  }
}

std::string read_release_class_table(const fs::path& release) {
  const fs::path manifest = release / kManifestFile;
  if (!fs::exists(manifest)) return "carla-0.9.13";
  const nlohmann::json json = read_json(manifest);
  try {
    const nlohmann::json semantic = json.value("conventions", nlohmann::json::object())
                                        .value("semantic", nlohmann::json::object());
    const std::string name = semantic.value("table", "carla-0.9.13");
    class_table(name);
    return name;
  } catch (const std::exception& e) {
    throw FileError(manifest, std::string("conventions: ") + e.what());
  }
}

SequenceMeta read_meta(const fs::path& sequence_dir) {
  const fs::path path = sequence_dir / kMetaFile;
  if (!fs::exists(path)) throw FileError(path, "missing (an unfinished sequence?)");
  const nlohmann::json json = read_json(path);
  try {
    return meta_from_json(json);
  } catch (const std::exception& e) {
    throw FileError(path, std::string("bad meta.json: ") + e.what());
  }
}

void write_meta(const fs::path& sequence_dir, const SequenceMeta& meta) {
  // compact: the actors' and boxes' columns would be mostly indentation
  write_text(sequence_dir / kMetaFile, to_json(meta).dump() + "\n");
}

}  // namespace flowscape
