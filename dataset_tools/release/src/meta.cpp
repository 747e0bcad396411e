#include "flowscape/release/meta.h"

#include <fstream>

#include "flowscape/core/files.h"
#include "flowscape/release/layout.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

constexpr const char* kRigFrame = "x forward, y left, z up; rig pose = rig -> world, 3x4 row-major";

nlohmann::json pose_row_major(const Pose& pose) {
  std::vector<double> values;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) values.push_back(pose.matrix()(r, c));
  return values;
}

Pose pose_from_row_major(const nlohmann::json& values) {
  const auto v = values.get<std::vector<double>>();
  if (v.size() != 12) throw std::invalid_argument("a pose needs 12 numbers (3x4 row-major)");
  Pose pose = Pose::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) pose.matrix()(r, c) = v[std::size_t(4 * r + c)];
  return pose;
}

}  // namespace

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
  nlohmann::json j = {
      {"scene", m.scene},
      {"map", m.map},
      {"map_name", m.map_name},
      {"sequence", m.sequence},
      {"seed", m.seed},
      {"weather", m.weather},
      {"frames", m.frames},
      {"fps", m.fps},
      {"erp", {{"width", 2 * m.erp_height}, {"height", m.erp_height}, {"flow", "360-degree"}}},
      {"camera",
       {{"height_above_ego", m.camera_height},
        {"pitch_sway_degrees", m.camera_pitch_sway},
        {"roll_sway_degrees", m.camera_roll_sway},
        {"frame", kRigFrame}}},
      {"poses", poses},
      {"city", m.city}};
  if (m.face_size > 0) {
    nlohmann::json faces = nlohmann::json::array();
    for (Face face : kFaces) faces.push_back(face_name(face));
    j["cube"] = {{"face_size", m.face_size}, {"focal", m.face_size / 2.0}, {"faces", faces}};
  }
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
    m.erp_height = j.at("erp").at("height").get<int>();
    m.camera_height = j.at("camera").at("height_above_ego").get<double>();
    m.camera_pitch_sway = j.at("camera").value("pitch_sway_degrees", 0.0);
    m.camera_roll_sway = j.at("camera").value("roll_sway_degrees", 0.0);
    for (const nlohmann::json& pose : j.at("poses")) m.poses.push_back(pose_from_row_major(pose));
    m.city = j.value("city", nlohmann::json());
    if (j.contains("cube")) m.face_size = j.at("cube").at("face_size").get<int>();
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
  write_text(sequence_dir / kMetaFile, to_json(meta).dump(1) + "\n");
}

}  // namespace flowscape
