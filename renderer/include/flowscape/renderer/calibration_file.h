#pragma once
// Rigs from calibration files, as the tools that made them write them. A calibration knows its
// cameras' lenses and, for several cameras, where each sits relative to the first, but not where
// the first sits on the vehicle: that mount is asked for. Read (docs/cameras.md has the mapping):
// - Kalibr's camchain and camchain-imucam YAML (cam0, cam1, ...: camera_model, intrinsics,
//   distortion_model, distortion_coeffs, resolution, and T_cn_cnm1 or T_cam_imu);
// - OpenCV's calibration sample and tutorial output, YAML (%YAML:1.0, !!opencv-matrix) or XML
//   (camera_matrix, distortion_coefficients, image_width, image_height, fisheye_model, in any
//   case: the tutorial writes Camera_Matrix and image_Width);
// - ROS's camera_info, as a YAML file (camera_matrix, distortion_model, distortion_coefficients)
//   or a message (K, D, width, height, distortion_model);
// - COLMAP's cameras.txt (one camera; its pixel centres moved to OpenCV's convention);
// - a glTF file's perspective cameras (.gltf, .glb), 512 pixels high.
// YAML is read by yaml-cpp as any YAML tool reads it, XML by OpenCV's FileStorage; both refused
// when nested more than 64 levels deep, before a parser sees them.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "flowscape/renderer/rig.h"

namespace flowscape {

// The first camera's mount in the rig frame, as a rig file gives it.
struct CameraMount {
  Vec3 position = Vec3::Zero();                // metres, x forward, y left, z up
  Vec3 yaw_pitch_roll_degrees = Vec3::Zero();  // rig.h's look()
};

// .yaml, .yml, .xml, .txt (COLMAP), .gltf or .glb: a calibration, not a rig file (.json) or a
// preset.
bool is_calibration_file(const std::filesystem::path& path);

// The rig of a calibration file, named after the file, its cameras cam0, cam1, ... (Kalibr's own
// names; COLMAP's cam<CAMERA_ID>; a glTF camera's node name); every camera after the first
// mounted through the calibration's chain. Throws FileError naming the file, the key and what is
// wrong: no mount given, a model this toolkit does not have (Kalibr's omni, eucm, fov), a
// missing or malformed entry, more than 16 cameras.
Rig rig_from_calibration(const std::filesystem::path& file,
                         const std::optional<CameraMount>& first_camera);

// One line per camera whose image sees less than half its pixels (a wide-angle calibration whose
// distortion polynomial stops being invertible within the image): the share seen and the angle
// off the axis where its model stops.
std::vector<std::string> calibration_warnings(const Rig& rig);

}  // namespace flowscape
