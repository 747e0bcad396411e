#include <catch2/catch.hpp>
#include <set>

#include "flowscape/formats/image_io.h"
#include "flowscape/release/stitch_folder.h"
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
