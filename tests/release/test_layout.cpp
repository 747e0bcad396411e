#include <catch2/catch.hpp>
#include <set>

#include "flowscape/layout/layout.h"

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

TEST_CASE("every kind has its own name and folder; pair kinds end a frame early or start late") {
  std::set<std::string_view> names, folders;
  for (const OutputKind& kind : kOutputKinds) names.insert(kind.name), folders.insert(kind.folder);
  CHECK(names.size() == kOutputKinds.size());
  CHECK(folders.size() == kOutputKinds.size());
  CHECK(output_kind("flow").is_flow());
  CHECK(output_kind("flow_backward").is_flow());
  CHECK_FALSE(output_kind("depth").is_flow());
  for (const char* kind : {"flow", "valid", "scene_flow"}) {
    CHECK(has_frame(output_kind(kind), 98, 100));
    CHECK_FALSE(has_frame(output_kind(kind), 99, 100));
  }
  for (const char* kind : {"flow_backward", "valid_backward"}) {
    CHECK_FALSE(has_frame(output_kind(kind), 0, 100));
    CHECK(has_frame(output_kind(kind), 99, 100));
  }
  CHECK(has_frame(output_kind("color"), 99, 100));
  CHECK_FALSE(has_frame(output_kind("color"), 100, 100));
  const ReleaseKind gap4(output_kind("flow_backward"), 4);
  CHECK(gap4.name() == "flow_backward_gap4");
  CHECK(gap4.step() == -4);
  CHECK_FALSE(gap4.has_frame(3, 100));
  CHECK(gap4.has_frame(4, 100));
  CHECK(gap4.valid_kind().name() == "valid_backward_gap4");
  CHECK(ReleaseKind(output_kind("flow"), 2).valid_kind().name() == "valid_gap2");
  CHECK(flow_kind_of_step(-4) == gap4);
  CHECK(flow_kind_of_step(3) == ReleaseKind(output_kind("flow"), 3));
}

TEST_CASE("kind names and folders spell their gaps; other spellings are no kind") {
  CHECK(release_kind("flow_gap2") == ReleaseKind(output_kind("flow"), 2));
  CHECK(release_kind("valid_backward_gap16") == ReleaseKind(output_kind("valid_backward"), 16));
  CHECK(release_kind("normal") == ReleaseKind(output_kind("normal")));
  for (const char* other : {"flow_gap1", "flow_gap02", "flow_gap", "flow_gapx", "normal_gap2",
                            "depth_gap3", "flows", ""})
    CHECK_FALSE(release_kind(other));
  CHECK(frame_file(ReleaseKind(output_kind("valid"), 4), Face::Up, 7) ==
        fs::path("cube/up/valid_gap4/000007.png"));
}

TEST_CASE("a frame has 6 files per view, the last frame 4; the cube adds six views") {
  const ReleaseLayout six = flowscape_layout(false), cube = flowscape_layout(true);
  CHECK(six.frame_files(0, 3).size() == 6);
  CHECK(six.frame_files(2, 3).size() == 4);
  CHECK(cube.frame_files(0, 3).size() == 6 * 7);
  CHECK(cube.frame_files(2, 3).size() == 4 * 7);
  const auto files = cube.frame_files(1, 3);
  CHECK(std::count(files.begin(), files.end(), fs::path("cube/up/valid/000001.png")) == 1);
  CHECK(std::count(files.begin(), files.end(), fs::path("erp/color/000001.png")) == 1);
  CHECK(six.sequence_files(3).size() == 1 + 6 + 6 + 4);
}

TEST_CASE("a layout holds the six, the picked kinds and each per-gap kind at every gap") {
  const ReleaseLayout layout = ReleaseLayout::of({"flow_backward", "normal"}, {4, 1, 2}, false);
  std::vector<std::string> names;
  for (const ReleaseKind& kind : layout.kinds) names.push_back(kind.name());
  CHECK(names == std::vector<std::string>{"color", "flow", "flow_gap2", "flow_gap4", "semantic",
                                          "instance", "depth", "valid", "valid_gap2", "valid_gap4",
                                          "flow_backward", "flow_backward_gap2",
                                          "flow_backward_gap4", "valid_backward",
                                          "valid_backward_gap2", "valid_backward_gap4", "normal"});
  // frame 0 of 10: color, semantic, instance, depth, normal + forward flow and valid at 1, 2, 4
  CHECK(layout.frame_files(0, 10).size() == 5 + 6);
  CHECK(layout.frame_files(9, 10).size() == 5 + 6);  // backward at 1, 2, 4
  CHECK(layout.frame_files(3, 10).size() == 5 + 6 + 4);
  CHECK(layout.flow_steps(3, 10) == std::vector<int>{1, 2, 4, -1, -2});
  CHECK(layout.flow_steps(9, 10) == std::vector<int>{-1, -2, -4});
  CHECK(ReleaseLayout::of({"all"}, {1}, true).kinds.size() == kOutputKinds.size());
  CHECK_THROWS_WITH(ReleaseLayout::of({"color"}, {1}, true),
                    Catch::Contains("unknown output kind \"color\""));
  CHECK_THROWS_WITH(ReleaseLayout::of({"normals"}, {1}, true),
                    Catch::Contains("pick from: all, flow_backward, valid_backward"));
  CHECK_THROWS_WITH(ReleaseLayout::of({}, {2}, true), Catch::Contains("flow gaps must include 1"));
  CHECK_THROWS_WITH(ReleaseLayout::of({}, {1, 0}, true),
                    Catch::Contains("flow gap 0 is out of range"));
}

TEST_CASE("the layout in manifest.json states the same paths as templates") {
  const ReleaseLayout release = ReleaseLayout::of({"all"}, {1, 3}, true);
  const nlohmann::json layout = layout_json(release);
  CHECK(layout["sequence_dir"] == "sequences/{sequence}");
  CHECK(layout["frame_file"] == "{view}/{folder}/{frame:06d}{extension}");
  CHECK(layout["views"]["cube"] == "cube/{face}");
  CHECK(layout["faces"] == nlohmann::json{"front", "right", "back", "left", "up", "down"});
  REQUIRE(layout["kinds"].size() == release.kinds.size());
  for (std::size_t k = 0; k < release.kinds.size(); ++k) {
    const nlohmann::json& row = layout["kinds"][k];
    CHECK(row["name"] == release.kinds[k].name());
    CHECK(row["step"] == release.kinds[k].step());
    const std::string path = std::string(layout["views"]["erp"]) + "/" +
                             std::string(row["folder"]) + "/000007" + std::string(row["extension"]);
    CHECK(fs::path(path) == frame_file(release.kinds[k], std::nullopt, 7));
  }
  CHECK(layout["kinds"][0]["pixel_type"] == "uint8");
  CHECK(layout["kinds"][1]["pairs_only"] == true);
  const ReleaseLayout back = layout_from_json(layout);
  CHECK(back.kinds == release.kinds);
  CHECK(back.cube);
  CHECK(layout_from_json(nlohmann::json()).kinds == flowscape_layout(true).kinds);  // before 0.8
}
