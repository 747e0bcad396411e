#pragma once
// meta.json, one per sequence (design.md): what the sequence is (map, weather, seed), its cameras
// and the rig pose of every frame. Read and written here only.
#include <array>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flowscape/core/image.h"
#include "flowscape/core/types.h"
#include "flowscape/layout/layout.h"

namespace flowscape {

// meta.json's schema: 2 (flowscape 0.10) keeps only view records in "views" (their frames'
// descriptions in "frames_of_reference") and has an "erp" record only where the release has the
// ERP view; 1 (no "schema" key) is read too.
inline constexpr int kMetaSchema = 2;

struct SequenceMeta {
  std::string scene;  // map<MM>_seq<SS>
  int map = 0, sequence = 0;
  std::string map_name;
  std::uint64_t seed = 0;
  nlohmann::json weather;  // weather/'s record; its "preset" names the base preset
  int frames = 0;
  double fps = kFrameRate;
  int erp_height = 0;        // width 2 x height; ERP flow is 360-degree; 0: no ERP (another rig)
  double camera_height = 0;  // of the rig above the ego vehicle's origin
  double camera_pitch_sway = 0, camera_roll_sway = 0;  // amplitudes in degrees (RigMount)
  std::vector<Pose> poses;  // per frame: rig (x forward, y left, z up) -> world
  nlohmann::json city;      // scenes/' scene record (null when there is none)
  int face_size = 0;        // cube faces (focal face_size / 2); 0 = no faces
  // Calibration of every view (views_json), every actor per frame (box and velocities), and the
  // 2-D box of each instance per view and frame (instance_boxes); null when not recorded.
  nlohmann::json views, actors, boxes;
  nlohmann::json rig;         // the rig's record (renderer/rig.h) for other rigs than flowscape
  nlohmann::json statistics;  // statistics.h's record of the sequence (null when not recorded)
  nlohmann::json final;       // the final pass's shutter, sensor and exposures (final_pass.h)
  nlohmann::json scenario;    // the scenario it renders (scenario.h; null in older releases)
  // What rendered it: flowscape's version, Embree's, the kernel family Embree ran and
  // FLOWSCAPE_EMBREE_CONFIG (null in releases before 0.15).
  nlohmann::json generator;

  std::string weather_preset() const;
  // Which of the paper's four weathers (the PanoFlow code's folders) the sequence counts as, from
  // its recorded weather: "rain" with any precipitation, else "fog" from a fog density of 0.01 /m,
  // else "cloud" from half cover, else "sunny" (hard_rain -> rain, clear_sunset -> sunny, ...).
  std::string base_weather() const;
};

inline constexpr std::array<const char*, 4> kBaseWeathers{"cloud", "fog", "rain", "sunny"};

// Each view's camera model, size, intrinsics and pose in the rig: the ERP's angular conventions
// and, with faces (face_size > 0), each face's 3x3 K (OpenCV's pixel convention: the centre of the
// top-left pixel at (0, 0)); every camera frame is x right, y down, z forward (docs/release.md).
nlohmann::json views_json(int erp_height, int face_size);

// The 2-D box of each instance an instance image shows (0, the static world and the sky, is left
// out), in pixel edges: columns x0..x1-1, rows y0..y1-1, sorted by instance. On a panorama a box
// spans the fewest columns round the circle: x1 <= x0 then means it wraps the seam (columns
// x0..W-1 and 0..x1-1); a box all the way round is x0 = 0, x1 = W.
struct InstanceBox {
  std::uint16_t instance;
  int x0, y0, x1, y1;
};
std::vector<InstanceBox> instance_boxes(ImageView<const std::uint16_t> ids, bool panorama);

// A pose as meta.json writes it: 3x4 row-major.
nlohmann::json pose_row_major(const Pose& pose);

nlohmann::json to_json(const SequenceMeta& meta);
SequenceMeta meta_from_json(const nlohmann::json& json);  // throws std::invalid_argument

// Any JSON file of a release (meta.json, manifests, configs), at most 256 MiB; a missing file, a
// folder or bad JSON is a FileError naming it.
nlohmann::json read_json(const std::filesystem::path& path);

// The kinds and views <release>/manifest.json states (a release without one, or from before the
// kinds were listed: FlowScape's six, ERP and faces); a layout it cannot read is a FileError.
ReleaseLayout read_release_layout(const std::filesystem::path& release);
// The class table its manifest's conventions name (carla-0.9.13 where they name none).
std::string read_release_class_table(const std::filesystem::path& release);

// <sequence dir>/meta.json; errors are FileErrors naming the file.
SequenceMeta read_meta(const std::filesystem::path& sequence_dir);
void write_meta(const std::filesystem::path& sequence_dir, const SequenceMeta& meta);

}  // namespace flowscape
