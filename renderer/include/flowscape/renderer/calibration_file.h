#pragma once
// Rigs from calibration files. A calibration knows its cameras' lenses and, for several cameras,
// where each sits relative to the first, but not where the first sits on the vehicle: that mount
// is asked for. Read: OpenCV's cv::FileStorage YAML or XML as its calibration sample and tutorial
// write them (one camera: camera_matrix, distortion_coefficients, image_width, image_height,
// fisheye_model) and Kalibr's camchain YAML (cam0, cam1, ...: camera_model, intrinsics,
// distortion_model, distortion_coeffs, resolution, T_cn_cnm1). docs/cameras.md has the mapping.
#include <filesystem>
#include <optional>

#include "flowscape/renderer/rig.h"

namespace flowscape {

// The first camera's mount in the rig frame, as a rig file gives it.
struct CameraMount {
  Vec3 position = Vec3::Zero();                // metres, x forward, y left, z up
  Vec3 yaw_pitch_roll_degrees = Vec3::Zero();  // rig.h's look()
};

// .yaml, .yml or .xml: a calibration, not a rig file (.json) or a preset.
bool is_calibration_file(const std::filesystem::path& path);

// The rig of a calibration file, named after the file, its cameras cam0, cam1, ... (Kalibr's own
// names); every camera after the first mounted through the calibration's chain of T_cn_cnm1.
// Throws FileError naming the file and what is wrong: no mount given, a model this toolkit does
// not have (Kalibr's omni, eucm, fov), a missing or malformed entry.
Rig rig_from_calibration(const std::filesystem::path& file,
                         const std::optional<CameraMount>& first_camera);

}  // namespace flowscape
