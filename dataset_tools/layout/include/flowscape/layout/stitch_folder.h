#pragma once
// Stitching a cubemap folder as a release lays it out (<cube dir>/<face>/<kind>/<frame>) into ERP
// files (<out>/<kind>/<frame>), every output kind of layout.h with the resampling its row names.
#include <cstddef>
#include <filesystem>

#include "flowscape/geometry/geometry.h"

namespace flowscape {

struct StitchFolderOptions {
  std::filesystem::path cube_dir, out_dir;
  int height = 512;  // ERP height; width 2 x height
  FlowMode flow_mode = FlowMode::Wrap360;
  bool force = false;  // redo outputs that exist (otherwise they are skipped: reruns resume)
  bool progress = true;
};

// Stitches every frame found; the valid mask of a frame with flow comes out of its flow stitch (the
// flow's own instance and valid masks guide it). Returns the number of files written (0 when
// everything existed). Throws FileError naming the file for missing or corrupt input.
std::size_t stitch_cube_folder(const StitchFolderOptions& options);

// The built-in analytic panorama (stitcher/synthetic.h, a yaw of `yaw_degrees` between frame 0 and
// 1) written as a cubemap folder to <dir>/cube and stitched into <dir>/erp, with a flow image.
struct YawDemo {
  int erp_width = 0, erp_height = 0;
  double expected_u = 0;     // the exact flow: u = yaw / 360 * W, v = 0 everywhere
  double largest_error = 0;  // of the stitched flow, pixels
};
YawDemo run_yaw_demo(const std::filesystem::path& dir, int face_size, int erp_height,
                     double yaw_degrees);

}  // namespace flowscape
