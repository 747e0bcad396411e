#include <catch2/catch.hpp>
#include <set>

#include "flowscape/release/layout.h"

using namespace flowscape;
namespace fs = std::filesystem;

TEST_CASE("the layout spells design.md's paths") {
  CHECK(sequence_name(3, 5) == "map03_seq05");
  CHECK(frame_name(42) == "000042");
  CHECK(sequence_dir("out", "map03_seq05") == fs::path("out/sequences/map03_seq05"));
  CHECK(frame_file(output_kind("flow"), std::nullopt, 41) == fs::path("erp/flow/000041.flo"));
  CHECK(frame_file(output_kind("depth"), Face::Left, 2) == fs::path("cube/left/depth/000002.exr"));
  CHECK(frame_file(output_kind("instance"), Face::Down, 0) ==
        fs::path("cube/down/instance/000000.png"));
  CHECK(split_file("out", "test") == fs::path("out/splits/test.txt"));
  CHECK_THROWS_WITH(output_kind("normals"), Catch::Contains("unknown output kind \"normals\""));
}

TEST_CASE("every kind has its own name and folder, and flow and valid end a frame early") {
  std::set<std::string_view> names, folders;
  for (const OutputKind& kind : kOutputKinds) names.insert(kind.name), folders.insert(kind.folder);
  CHECK(names.size() == kOutputKinds.size());
  CHECK(folders.size() == kOutputKinds.size());
  CHECK(output_kind("flow").is_flow());
  CHECK_FALSE(output_kind("depth").is_flow());
  for (const char* kind : {"flow", "valid"}) {
    CHECK(has_frame(output_kind(kind), 98, 100));
    CHECK_FALSE(has_frame(output_kind(kind), 99, 100));
  }
  CHECK(has_frame(output_kind("color"), 99, 100));
  CHECK_FALSE(has_frame(output_kind("color"), 100, 100));
}

TEST_CASE("a frame has 6 files per view, the last frame 4; the cube adds six views") {
  CHECK(frame_files(0, 3, false).size() == 6);
  CHECK(frame_files(2, 3, false).size() == 4);
  CHECK(frame_files(0, 3, true).size() == 6 * 7);
  CHECK(frame_files(2, 3, true).size() == 4 * 7);
  const auto files = frame_files(1, 3, true);
  CHECK(std::count(files.begin(), files.end(), fs::path("cube/up/valid/000001.png")) == 1);
  CHECK(std::count(files.begin(), files.end(), fs::path("erp/color/000001.png")) == 1);
}

TEST_CASE("the layout in manifest.json states the same paths as templates") {
  const nlohmann::json layout = layout_json();
  CHECK(layout["sequence_dir"] == "sequences/{sequence}");
  CHECK(layout["frame_file"] == "{view}/{folder}/{frame:06d}{extension}");
  CHECK(layout["views"]["cube"] == "cube/{face}");
  CHECK(layout["faces"] == nlohmann::json{"front", "right", "back", "left", "up", "down"});
  REQUIRE(layout["kinds"].size() == kOutputKinds.size());
  for (std::size_t k = 0; k < kOutputKinds.size(); ++k) {
    const nlohmann::json& row = layout["kinds"][k];
    CHECK(row["name"] == kOutputKinds[k].name);
    const std::string path = std::string(layout["views"]["erp"]) + "/" +
                             std::string(row["folder"]) + "/000007" + std::string(row["extension"]);
    CHECK(fs::path(path) == frame_file(kOutputKinds[k], std::nullopt, 7));
  }
  CHECK(layout["kinds"][0]["pixel_type"] == "uint8");
  CHECK(layout["kinds"][1]["pairs_only"] == true);
}
