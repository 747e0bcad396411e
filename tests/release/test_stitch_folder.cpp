#include <catch2/catch.hpp>
#include <set>

#include "flowscape/formats/cubemap_io.h"
#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/layout/stitch_folder.h"
#include "flowscape/renderer/renderer.h"
#include "flowscape/scenes/test_scenes.h"
#include "temp_dir.h"

using namespace flowscape;
namespace fs = std::filesystem;

TEST_CASE("the yaw demo stitches to the exact flow u = yaw / 360 W") {
  TempDir dir;
  const YawDemo demo = run_yaw_demo(dir.path, 32, 32, 3);
  CHECK((demo.erp_width == 64 && demo.erp_height == 32));
  CHECK(demo.expected_u == Approx(64 * 3 / 360.0));
  CHECK(demo.largest_error < 0.01);
  for (const char* file :
       {"color/000000.png", "color/000001.png", "flow/000000.flo", "semantic/000000.png",
        "instance/000000.png", "depth/000000.exr", "valid/000000.png"})
    CHECK(fs::exists(dir.path / "erp" / file));
}

TEST_CASE("stitching a folder resumes, redoes what is missing, and samples ids nearest") {
  TempDir dir;
  run_yaw_demo(dir.path, 16, 16, 3);
  StitchFolderOptions o{dir.path / "cube", dir.path / "out", 16};
  o.progress = false;
  CHECK(stitch_cube_folder(o) == 7);  // 2 colour, flow (+ its valid), semantic, instance, depth
  CHECK(stitch_cube_folder(o) == 0);
  fs::remove(o.out_dir / "valid" / "000000.png");
  CHECK(stitch_cube_folder(o) == 2);  // the flow stitch that writes it, and its flow
  CHECK(fs::exists(o.out_dir / "valid" / "000000.png"));
  o.force = true;
  CHECK(stitch_cube_folder(o) == 7);
  // ids are never blended: every ERP id is one of the cube's
  const Image<std::uint16_t> erp = read_image<std::uint16_t>(o.out_dir / "instance" / "000000.png");
  CHECK(std::set<std::uint16_t>(erp.data.begin(), erp.data.end()) == std::set<std::uint16_t>{1, 2});
}

TEST_CASE("a missing cubemap folder is named") {
  TempDir dir;
  CHECK_THROWS_WITH(stitch_cube_folder({dir.path / "nope", dir.path / "out"}),
                    Catch::Contains("nope: cubemap folder not found"));
}

TEST_CASE("stitch_erp stitches backward and gap flows with their masks, and turns vectors") {
  // a cube of a room seen by a turning, moving rig, rendered with every kind, stitched, and set
  // against the ERP ray cast directly: normals of walls are constant, so nearest sampling is exact
  // away from the room's edges; backward flow is re-projected as forward flow is
  TempDir dir;
  Scene scene = box_room(10);
  Renderer renderer(scene);
  const auto rig = [](double t) {
    return Pose(Eigen::Translation3d(t, 0.5 * t, 0) * Eigen::AngleAxisd(0.4 * t, Vec3::UnitZ()));
  };
  const double t = 1, dt = 1 / kFrameRate;
  TruthRequest request{{t, t + dt, rig(t), rig(t + dt)}, {{t - dt, rig(t - dt)}}};
  request.normal = true;
  const CubeFrame cube = render_cube(renderer, 32, request, nullptr);
  const fs::path cube_dir = dir.path / "cube";
  write_cube_image(cube_dir, "normal", "000001.exr", cube.truth.normal.view());
  write_cube_flow(cube_dir, "flow_backward", "000001.flo", cube.truth.more[0].flow.view());
  write_cube_image(cube_dir, "valid_backward", "000001.png", cube.truth.more[0].valid.view());
  write_cube_image(cube_dir, "instance", "000001.png", cube.truth.instance.view());
  write_cube_flow(cube_dir, "flow_gap3", "000001.flo", cube.truth.flow.view());
  StitchFolderOptions o{cube_dir, dir.path / "erp", 32};
  o.progress = false;
  CHECK(stitch_cube_folder(o) == 5);  // normal, instance, two flows, the backward flow's mask
  CHECK(fs::exists(o.out_dir / "valid_backward" / "000001.png"));
  CHECK(fs::exists(o.out_dir / "flow_gap3" / "000001.flo"));
  CHECK_FALSE(fs::exists(o.out_dir / "valid_gap3"));  // the cube has none to stitch
  const GroundTruth direct = renderer.ground_truth(Projection::equirectangular(32), request);
  const Image<float> normal = read_image<float>(o.out_dir / "normal" / "000001.exr");
  const Flow back = read_flo(o.out_dir / "flow_backward" / "000001.flo");
  int compared = 0;
  for (int y = 2; y < 30; ++y)
    for (int x = 0; x < 64; ++x) {
      const float* n = normal.pixel(x, y);
      const float* d = direct.normal.pixel(x, y);
      if (Vec3(n[0] - d[0], n[1] - d[1], n[2] - d[2]).norm() > 1e-6) continue;  // at an edge
      ++compared;
      const float* b = back.uv.pixel(x, y);
      const float* e = direct.more[0].flow.pixel(x, y);
      CHECK(b[0] == Approx(e[0]).margin(0.02));
      CHECK(b[1] == Approx(e[1]).margin(0.02));
    }
  CHECK(compared > 64 * 28 * 8 / 10);
}
