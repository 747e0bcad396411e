#include <catch2/catch.hpp>
#include <fstream>

#include "flowscape/release/meta.h"
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

TEST_CASE("a missing or broken meta.json is named") {
  TempDir dir;
  CHECK_THROWS_WITH(read_meta(dir.path), Catch::Contains("meta.json: missing"));
  std::ofstream(dir.path / "meta.json") << R"({"scene": "x"})";
  CHECK_THROWS_WITH(read_meta(dir.path), Catch::Contains("meta.json: bad meta.json"));
  nlohmann::json bad = to_json(example());
  bad["poses"][0] = {1, 2, 3};
  CHECK_THROWS_WITH(meta_from_json(bad), Catch::Contains("12 numbers"));
}
