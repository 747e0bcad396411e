#include <catch2/catch.hpp>
#include <fstream>

#include "flowscape/core/files.h"
#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/layout/layout.h"
#include "flowscape/layout/meta.h"
#include "flowscape/quality/flow_datasets.h"
#include "flowscape/quality/gt_quality.h"
#include "shifted_pattern.h"
#include "temp_dir.h"

using namespace flowscape;
using namespace shifted;
namespace fs = std::filesystem;

TEST_CASE("each dataset layout is recognised from a tiny fixture") {
  TempDir dir;
  const Image<std::uint8_t> a = to8(image_of(0, 0)), b = to8(image_of(1, 0));
  const Image<float> flow = constant_flow(1, 0);
  Image<std::uint8_t> ones(W, H, 1);
  std::fill(ones.data.begin(), ones.data.end(), 1);
  const auto pair = [&](const fs::path& i1, const fs::path& i2, const fs::path& f) {
    write_image(i1, a), write_image(i2, b), write_flow(f, flow.view(), ones.view());
  };
  // FlowScape release
  const fs::path seq = dir.path / "release" / "sequences" / "map00_seq00";
  SequenceMeta meta;
  meta.scene = "map00_seq00", meta.weather = {{"preset", "fog"}}, meta.frames = 2;
  write_meta(seq, meta);
  pair(seq / "erp/color/000000.png", seq / "erp/color/000001.png", seq / "erp/flow/000000.flo");
  write_image(seq / "erp/valid/000000.png", ones);
  // PanoFlow tree
  const fs::path pano = dir.path / "pano" / "test" / "rain";
  pair(pano / "img/map01_seq07/000000.jpg", pano / "img/map01_seq07/000001.jpg",
       pano / "flow/map01_seq07/000000.flo");
  // Sintel
  const fs::path sintel = dir.path / "sintel" / "training";
  for (const char* pass : {"clean", "final"})
    pair(sintel / pass / "alley_1/frame_0001.png", sintel / pass / "alley_1/frame_0002.png",
         sintel / "flow/alley_1/frame_0001.flo");
  write_image(sintel / "occlusions/alley_1/frame_0001.png", ones);
  // KITTI 2015 and 2012
  for (const auto& [root, images] : {std::pair{"kitti15", "image_2"}, {"kitti12", "colored_0"}}) {
    const fs::path t = dir.path / root / "training";
    pair(t / images / "000000_10.png", t / images / "000000_11.png", t / "flow_occ/000000_10.png");
    write_flow(t / "flow_noc/000000_10.png", flow.view(), ones.view());
  }
  // FlyingChairs
  pair(dir.path / "chairs/data/00001_img1.ppm", dir.path / "chairs/data/00001_img2.ppm",
       dir.path / "chairs/data/00001_flow.flo");
  const std::vector<std::tuple<std::string, std::string, std::size_t, VisibleMask>> expected = {
      {"release", "flowscape", 1, VisibleMask::NonZero},
      {"pano", "panoflow", 1, VisibleMask::None},
      {"sintel", "sintel", 2, VisibleMask::Zero},
      {"kitti15", "kitti2015", 1, VisibleMask::FlowValid},
      {"kitti12", "kitti2012", 1, VisibleMask::FlowValid},
      {"chairs", "flyingchairs", 1, VisibleMask::None}};
  for (const auto& [folder, layout, pairs, mask] : expected) {
    INFO(folder);
    const FlowDataset found = find_flow_dataset(dir.path / folder);
    CHECK(found.layout == layout);
    REQUIRE(found.pairs.size() == pairs);
    CHECK(found.pairs[0].visible_kind == mask);
    const QualityReport report = evaluate_quality(found, {{}, false});
    CHECK(report.rows[0].wpe < 0.3 * report.rows[0].pe);  // integer images of a 1-px shift
  }
  CHECK(find_flow_dataset(dir.path / "release").pairs[0].panorama);
  CHECK(find_flow_dataset(dir.path / "pano").pairs[0].category == "test/rain");
  const FlowDataset globbed = glob_flow_dataset((dir.path / "chairs/data/*_img?.ppm").string(),
                                                (dir.path / "chairs/data/*.flo").string(), false);
  CHECK(globbed.pairs.size() == 1);
  CHECK_THROWS_WITH(find_flow_dataset(dir.path / "nowhere"),
                    Catch::Contains("nowhere: no such folder"));
  fs::create_directories(dir.path / "empty");
  CHECK_THROWS_WITH(find_flow_dataset(dir.path / "empty"),
                    Catch::Contains("not a known flow dataset"));
}

TEST_CASE("corrupt files stop the evaluation with the file named") {
  TempDir dir;
  const fs::path data = dir.path / "data";
  write_image(data / "00001_img1.ppm", to8(image_of(0, 0)));
  write_image(data / "00001_img2.ppm", to8(image_of(1, 0)));
  write_flo(data / "00001_flow.flo", constant_flow(1, 0).view());
  fs::resize_file(data / "00001_flow.flo", 100);
  CHECK_THROWS_WITH(evaluate_quality(find_flow_dataset(dir.path), {{}, false}),
                    Catch::Contains("00001_flow.flo"));
  write_flo(data / "00001_flow.flo", constant_flow(1, 0).view());
  std::ofstream(data / "00001_img2.ppm") << "P6 garbage";
  CHECK_THROWS_WITH(evaluate_quality(find_flow_dataset(dir.path), {{}, false}),
                    Catch::Contains("00001_img2.ppm"));
}

TEST_CASE("a release's manifest says which kinds and conventions gt_quality reads") {
  TempDir dir;
  const Image<std::uint8_t> a = to8(image_of(0, 0)), b = to8(image_of(1, 0));
  Image<std::uint8_t> ones(W, H, 1);
  std::fill(ones.data.begin(), ones.data.end(), 1);
  const fs::path root = dir.path / "release", seq = root / "sequences" / "map00_seq00";
  SequenceMeta meta;
  meta.scene = "map00_seq00", meta.weather = {{"preset", "fog"}}, meta.frames = 2;
  write_meta(seq, meta);
  write_image(seq / "erp/color/000000.png", a), write_image(seq / "erp/color/000001.png", b);
  write_flow(seq / "erp/flow/000000.flo", constant_flow(1, 0).view(), ones.view());
  write_image(seq / "erp/valid/000000.png", ones);
  write_flow(seq / "erp/flow_backward/000001.flo", constant_flow(-1, 0).view(), ones.view());
  write_image(seq / "erp/valid_backward/000001.png", ones);
  nlohmann::json manifest = {
      {"layout", layout_json(ReleaseLayout::of({"flow_backward"}, {1}, false))},
      {"conventions", conventions_json()}};
  write_text(root / "manifest.json", manifest.dump());
  const FlowDataset found = find_flow_dataset(root);
  REQUIRE(found.pairs.size() == 1);
  CHECK(found.pairs[0].backward == seq / "erp/flow_backward/000001.flo");
  const QualityReport report = evaluate_quality(found, {{}, false});
  CHECK(report.rows[0].round_trip_pairs == 1);
  CHECK(report.rows[0].both_ways == long(W) * H);  // a panorama: every target wraps in
  CHECK(report.rows[0].round_trip_share() == 1);
  CHECK(report_table(report).find("100.00%") != std::string::npos);
  // flow a program could not read as gt_quality does is refused, naming the manifest
  manifest["conventions"]["flow"]["value"] = "source - target";
  write_text(root / "manifest.json", manifest.dump());
  CHECK_THROWS_WITH(find_flow_dataset(root),
                    Catch::Contains("manifest.json: conventions: flow is not target - source"));
}
