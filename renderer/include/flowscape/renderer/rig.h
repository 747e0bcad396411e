#pragma once
// A rig: named cameras, each a projection (a lens of lens.h, or the equirectangular panorama) and a
// mount in the rig frame (x forward, y left, z up). The `flowscape` rig is seven cameras too: the
// ERP and the six cube faces at the rig's origin, written as FlowScape's views.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flowscape/renderer/projection.h"
#include "flowscape/renderer/renderer.h"

namespace flowscape {

struct RigCamera {
  std::string name;              // its folder: cameras/<name>
  Projection projection;         // the model and its image; rotation: camera -> rig
  Vec3 position = Vec3::Zero();  // of the optical centre in the rig frame, metres
  Readout readout{};             // a rolling shutter's (global by default)
  Pose mount() const;            // camera -> rig
};

struct Rig {
  std::string name;                // a preset's name or the rig file's
  std::vector<RigCamera> cameras;  // at least one
  // The flowscape rig (flowscape_rig): its ERP's colour is stitched from the cube faces' where it
  // has them, and its views are written as FlowScape's (erp/, cube/<face>/), not as cameras/<name>.
  bool flowscape = false;

  // The flowscape rig's six cube faces (cameras 1 to 6, in geometry.h's kFaces order).
  bool has_cube_faces() const { return flowscape && cameras.size() == 1 + kFaces.size(); }
  // Where its cameras sit (rig frame): each camera's, the flowscape rig's one shared centre.
  std::vector<Vec3> optical_centres() const;
};

inline constexpr const char* kFlowscapeRig = "flowscape";
// The most cameras a rig file or calibration may hold (each writes a folder of every kind).
inline constexpr std::size_t kMaxRigCameras = 16;
// The flowscape rig: the ERP `height` high ("erp") and, with a face_size above 0, the six 90-degree
// cube faces ("front", "back", ... as face_name gives them) that face_size square.
Rig flowscape_rig(int height, int face_size);
// Rig presets besides flowscape: "fisheye", "woodscape", "pal", "dual-fisheye".
std::vector<std::string> rig_presets();
// A preset's cameras, their images scaled to `size` (the release's ERP height): fisheye and pal
// size^2, dual-fisheye size x 2 size, woodscape 1.25 size x 0.94 size (WoodScape's aspect).
// Throws std::invalid_argument for other names.
Rig rig_preset(const std::string& name, int size);

// A rig file: {"name": ..., "cameras": [{"name", "model", "parameters", "mount": {"position":
// [x, y, z], "camera_to_rig": 3x3 rows | "yaw_pitch_roll_degrees": [y, p, r]},
// "rolling_shutter": {"readout_ms": r, "lines": "rows" | "columns"}}]} (no rolling_shutter: a
// global shutter); model "equirectangular" takes parameters {"height"}, a mount without rotation
// and no rolling shutter. Throws std::invalid_argument naming what is wrong (docs/cameras.md).
Rig rig_from_json(const nlohmann::json& json);
// The rig for images `scale` times as large (previews): every camera's image size and
// intrinsics scaled (lens.h's scaled_lens; an equirectangular camera's height rounded), mounts
// unchanged. Throws std::invalid_argument for a scale that leaves an image under 2 pixels.
Rig scaled_rig(const Rig& rig, double scale);
// What meta.json records and rig_from_json reads back.
nlohmann::json to_json(const Rig& rig);

// The camera's rotation for yaw (left, about the rig's z), then pitch (up), then roll (about its
// forward axis, right-handed), starting from looking forward (the front face's frame).
Mat3 look(double yaw_degrees, double pitch_degrees, double roll_degrees);

// The request as the camera sees it: every moment's rig (and the track) moved to the camera's
// optical centre (its position turned with the rig, so a rotation's lever arm moves it too), and
// the camera's readout.
TruthRequest at_camera(const TruthRequest& request, const RigCamera& camera);

}  // namespace flowscape
