#include <catch2/catch.hpp>
#include <fstream>

#include "flowscape/layout/meta.h"
#include "temp_dir.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

SequenceMeta example() {
  SequenceMeta m;
  m.scene = "map02_seq06", m.map = 2, m.sequence = 6, m.map_name = "highway";
  m.seed = 18446744073709551557ull;  // above 2^63: must survive JSON
  m.weather = {{"preset", "fog"}, {"fog_density", 0.05}};
  m.frames = 3, m.erp_height = 16, m.camera_height = 1.7, m.face_size = 8;
  for (int f = 0; f < 3; ++f)
    m.poses.push_back(Pose(Eigen::Translation3d(f * 0.1, 0.2, 1.7) *
                           Eigen::AngleAxisd(0.3 + f * 0.01, Vec3::UnitZ())));
  return m;
}

}  // namespace

TEST_CASE("meta.json holds design.md's keys and reads back exactly") {
  TempDir dir;
  const SequenceMeta m = example();
  write_meta(dir.path, m);
  nlohmann::json raw;
  std::ifstream(dir.path / "meta.json") >> raw;
  CHECK(raw["scene"] == "map02_seq06");
  CHECK(raw["weather"]["preset"] == "fog");
  CHECK(raw["fps"] == 30.0);
  CHECK(raw["erp"]["width"] == 32);
  CHECK(raw["cube"]["focal"] == 4.0);
  CHECK(raw["poses"][1][3] == Approx(0.1));  // row-major 3x4: translation x
  const SequenceMeta back = read_meta(dir.path);
  CHECK(back.seed == m.seed);
  CHECK(back.weather_preset() == "fog");
  REQUIRE(back.poses.size() == 3);
  for (int f = 0; f < 3; ++f) CHECK(back.poses[f].matrix() == m.poses[f].matrix());
  CHECK(to_json(back) == to_json(m));
}

TEST_CASE("a release without cube faces writes no cube entry") {
  SequenceMeta m = example();
  m.face_size = 0;
  CHECK_FALSE(to_json(m).contains("cube"));
  CHECK(meta_from_json(to_json(m)).face_size == 0);
}

TEST_CASE("meta.json's schema 2: views hold view records only, no ERP record without an ERP") {
  // issue 35, point 10: a rig without an ERP recorded a 512 x 1024 ERP, and "views" mixed strings
  SequenceMeta m = example();
  m.views = views_json(m.erp_height, m.face_size);
  const nlohmann::json j = to_json(m);
  CHECK(j["schema"] == kMetaSchema);
  CHECK(j["frames_of_reference"]["camera"].get<std::string>().starts_with("x right, y down"));
  for (const auto& [name, view] : j["views"].items()) {
    INFO(name);
    CHECK(view.is_object());
  }
  m.erp_height = 0, m.face_size = 0;  // another rig's sequence
  CHECK_FALSE(to_json(m).contains("erp"));
  CHECK(meta_from_json(to_json(m)).erp_height == 0);
  // schema 1 (flowscape 0.9): the frames' descriptions among the views, read without them
  nlohmann::json old = j;
  old.erase("schema"), old.erase("frames_of_reference");
  old["views"]["camera_frame"] = "x right, y down, z forward";
  old["views"]["rig_frame"] = "x forward, y left, z up";
  const SequenceMeta back = meta_from_json(old);
  CHECK_FALSE(back.views.contains("camera_frame"));
  CHECK(back.views.contains("erp"));
  CHECK(back.erp_height == 16);
}

TEST_CASE("a missing or broken meta.json is named") {
  TempDir dir;
  CHECK_THROWS_WITH(read_meta(dir.path), Catch::Contains("meta.json: missing"));
  std::ofstream(dir.path / "meta.json") << R"({"scene": "x"})";
  CHECK_THROWS_WITH(read_meta(dir.path), Catch::Contains("meta.json: bad meta.json"));
  nlohmann::json bad = to_json(example());
  bad["poses"][0] = {1, 2, 3};
  CHECK_THROWS_WITH(meta_from_json(bad), Catch::Contains("12 numbers"));
}

TEST_CASE("2-D boxes span each instance's pixels; on a panorama the short way round the seam") {
  Image<std::uint16_t> ids(16, 4, 1);
  const auto paint = [&](std::uint16_t id, int x0, int x1, int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) *ids.pixel(x % 16, y) = id;
  };
  paint(3, 2, 5, 1, 3);    // columns 2..4, rows 1..2
  paint(9, 14, 18, 0, 1);  // columns 14, 15, 0, 1: across the seam
  paint(5, 7, 8, 3, 4);
  paint(5, 12, 13, 0, 1);  // one instance in two places
  std::vector<InstanceBox> boxes = instance_boxes(ids.view(), true);
  REQUIRE(boxes.size() == 3);
  const auto same = [](const InstanceBox& b, int id, int x0, int y0, int x1, int y1) {
    return b.instance == id && b.x0 == x0 && b.y0 == y0 && b.x1 == x1 && b.y1 == y1;
  };
  CHECK(same(boxes[0], 3, 2, 1, 5, 3));
  CHECK(same(boxes[1], 5, 7, 0, 13, 4));
  CHECK(same(boxes[2], 9, 14, 0, 2, 1));      // x1 <= x0: wraps
  boxes = instance_boxes(ids.view(), false);  // a pinhole image does not wrap
  CHECK(same(boxes[2], 9, 0, 0, 16, 1));
  paint(9, 0, 16, 2, 3);  // all the way round
  CHECK(same(instance_boxes(ids.view(), true)[2], 9, 0, 0, 16, 3));
}

TEST_CASE("views record each camera's K and pose in the rig") {
  const nlohmann::json views = views_json(16, 8);
  CHECK(views["erp"]["width"] == 32);
  CHECK(views["erp"]["model"] == "equirectangular");
  const nlohmann::json& front = views["cube/front"];
  CHECK(front["K"] == nlohmann::json{{4.0, 0, 3.5}, {0, 4.0, 3.5}, {0, 0, 1}});
  // the front camera's z (forward) is the rig's x, its x (right) the rig's -y
  CHECK(front["camera_to_rig"] ==
        nlohmann::json{{0.0, 0.0, 1.0}, {-1.0, 0.0, 0.0}, {0.0, -1.0, 0.0}});
  CHECK(views["cube/up"]["camera_to_rig"][2][2] == 1.0);  // looks along the rig's z
  CHECK_FALSE(views_json(16, 0).contains("cube/front"));
}
