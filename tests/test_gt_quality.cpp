#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

#include "flowscape/flow_datasets.h"
#include "flowscape/flow_io.h"
#include "flowscape/geometry.h"
#include "flowscape/gt_quality.h"
#include "flowscape/io.h"
#include "flowscape/photoconsistency.h"
#include "temp_dir.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

constexpr int W = 64, H = 48;
constexpr double kTwoPi = 6.283185307179586;

// A smooth pattern, periodic over the image width (so it also wraps like a panorama), 0-255.
double pattern(double x, double y, int c) {
  return 128 + 60 * std::sin(kTwoPi * 3 * x / W + c) * std::cos(0.21 * y) +
         40 * std::cos(kTwoPi * 5 * x / W + 0.13 * y + 2 * c);
}

Image<float> image_of(double dx, double dy) {  // the pattern moved by (dx, dy)
  Image<float> image(W, H, 3);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      for (int c = 0; c < 3; ++c) image.pixel(x, y)[c] = float(pattern(x - dx, y - dy, c));
  return image;
}

Image<float> constant_flow(double u, double v) {
  Image<float> flow(W, H, 2);
  for (std::size_t i = 0; i < flow.pixel_count(); ++i)
    flow.data[2 * i] = float(u), flow.data[2 * i + 1] = float(v);
  return flow;
}

Image<std::uint8_t> to8(const Image<float>& image) {
  Image<std::uint8_t> out(image.width, image.height, image.channels);
  for (std::size_t i = 0; i < image.data.size(); ++i)
    out.data[i] = std::uint8_t(std::lround(std::clamp(image.data[i], 0.0f, 255.0f)));
  return out;
}

}  // namespace

TEST_CASE("a known shift gives WPE near 0 and a large PE while a wrong flow does not") {
  const Image<std::uint8_t> first = to8(image_of(0, 0)), second = to8(image_of(3.4, -1.7));
  const Image<float> right = constant_flow(3.4, -1.7), wrong = constant_flow(-3.4, 1.7);
  const PairErrors good = photo_errors({first.view(), second.view(), right.view()});
  const PairErrors bad = photo_errors({first.view(), second.view(), wrong.view()});
  INFO("good: PE " << good.pe << " WPE " << good.wpe << "; wrong: WPE " << bad.wpe);
  CHECK(good.pe > 20);
  CHECK(good.wpe < 0.05 * good.pe);  // bilinear sampling of a smooth pattern
  CHECK(bad.wpe > 0.8 * bad.pe);
  CHECK(diff_percent(good.pe, good.wpe) > 90);
  CHECK(std::string(quality_label(diff_percent(good.pe, good.wpe))) == "high");
  CHECK(std::string(quality_label(diff_percent(bad.pe, bad.wpe))) == "medium/low");
  // pixels whose target leaves the image are not counted: 4 columns (x + 3.4 > 63) and 2 rows
  CHECK(good.pixels == (W - 4) * (H - 2));
}

TEST_CASE("a panorama turned across its seam is warped back through the wrap") {
  const Image<std::uint8_t> first = to8(image_of(0, 0)), turned = to8(image_of(5.5, 0));
  const Image<float> flow = constant_flow(5.5, 0);
  PairImages pair{first.view(), turned.view(), flow.view()};
  pair.panorama = true;
  const PairErrors wrapped = photo_errors(pair);
  CHECK(wrapped.pixels == W * H);  // every target is inside after wrapping
  CHECK(wrapped.wpe < 0.05 * wrapped.pe);
  pair.panorama = false;
  CHECK(photo_errors(pair).pixels == (W - 6) * H);
}

TEST_CASE("unknown flow and masks decide which pixels count") {
  const Image<std::uint8_t> first = to8(image_of(0, 0)), second = to8(image_of(2, 0));
  Image<float> flow = constant_flow(2, 0);
  Image<std::uint8_t> known(W, H, 1), visible(W, H, 1);
  std::fill(known.data.begin(), known.data.end(), 1);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < 10; ++x) *known.pixel(x, y) = 0, flow.pixel(x, y)[0] = 40;  // junk, invalid
  flow.pixel(20, 20)[0] = kUnknownFlow;
  for (int y = 0; y < H / 2; ++y)
    for (int x = 0; x < W; ++x) *visible.pixel(x, y) = 1;
  const PairErrors e =
      photo_errors({first.view(), second.view(), flow.view(), known.view(), visible.view()});
  CHECK(e.pixels == (W - 10 - 2) * H - 1);
  CHECK(e.visible_pixels == (W - 10 - 2) * H / 2 - 1);
  CHECK(e.wpe < 0.05 * e.pe);
}

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
  fs::create_directories(seq);
  std::ofstream(seq / "meta.json") << R"({"weather": {"preset": "fog"}})";
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
