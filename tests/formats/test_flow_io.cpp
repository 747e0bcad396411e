#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/geometry/geometry.h"
#include "temp_dir.h"

using namespace flowscape;
namespace fsys = std::filesystem;

namespace {

constexpr int kWidth = 37, kHeight = 23;  // the field tests/python/flow_files.py writes

float reference_u(int x, int y) { return (x - 2.f * y) / 4; }
float reference_v(int x, int y) { return (3.f * x + y) / 8 - 5; }
bool reference_valid(int x, int y) { return (x + y) % 3 != 0; }

int run_python(const std::string& mode, const fsys::path& folder) {
  const std::string command = std::string(FLOWSCAPE_PYTHON) + " " + FLOWSCAPE_SOURCE_DIR +
                              "/tests/python/flow_files.py " + mode + " " + folder.string();
  return std::system(command.c_str());
}

}  // namespace

TEST_CASE("flow files written by independent numpy code read back identically") {
  TempDir dir;
  REQUIRE(run_python("write", dir.path) == 0);

  const Flow flo = read_flo(dir.path / "numpy.flo");
  REQUIRE(flo.uv.width == kWidth);
  REQUIRE(flo.uv.height == kHeight);
  CHECK(flo.uv.pixel(0, 0)[0] == 1e10f);
  CHECK(*flo.valid.pixel(0, 0) == 0);
  int differences = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (x == 0 && y == 0) continue;
      differences += flo.uv.pixel(x, y)[0] != reference_u(x, y) ||
                     flo.uv.pixel(x, y)[1] != reference_v(x, y) || *flo.valid.pixel(x, y) != 1;
    }
  CHECK(differences == 0);

  const Flow kitti = read_kitti_png(dir.path / "numpy_kitti.png");
  REQUIRE(kitti.uv.width == kWidth);
  differences = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const bool valid = reference_valid(x, y);
      differences += *kitti.valid.pixel(x, y) != valid;
      if (valid)
        differences += kitti.uv.pixel(x, y)[0] != reference_u(x, y) ||
                       kitti.uv.pixel(x, y)[1] != reference_v(x, y);
    }
  CHECK(differences == 0);
}

TEST_CASE("flow files we write are read identically by the independent numpy reader") {
  TempDir dir;
  Image<float> uv(kWidth, kHeight, 2);
  Image<std::uint8_t> valid(kWidth, kHeight, 1);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      uv.pixel(x, y)[0] = reference_u(x, y);
      uv.pixel(x, y)[1] = reference_v(x, y);
      *valid.pixel(x, y) = reference_valid(x, y);
    }
  write_flow(dir.path / "ours.flo", uv.view());
  write_flow(dir.path / "ours_kitti.png", uv.view(), valid.view());
  CHECK(run_python("check", dir.path) == 0);

  write_flow(dir.path / "ours.exr", uv.view());
  const Flow exr = read_flow(dir.path / "ours.exr");
  CHECK(exr.uv.data == uv.data);
  CHECK(fsys::directory_iterator(dir.path) != fsys::directory_iterator());
  for (const auto& entry : fsys::directory_iterator(dir.path))  // no temporary left behind
    CHECK_FALSE(entry.path().filename().string().starts_with("."));
}

TEST_CASE("corrupt, truncated or wrong flow files give an error naming the file and the problem") {
  TempDir dir;
  REQUIRE(run_python("write", dir.path) == 0);
  const auto fails_with = [&](const std::string& name, const std::string& problem) {
    const std::string path = (dir.path / name).string();
    CHECK_THROWS_WITH(read_flow(path), Catch::Contains(path) && Catch::Contains(problem));
  };
  fails_with("truncated.flo", "truncated .flo data");
  fails_with("header_only.flo", "truncated .flo header");
  fails_with("bad_magic.flo", "bad magic");
  fails_with("bad_size.flo", "bad .flo size");
  fails_with("trailing.flo", "trailing bytes");
  fails_with("nan.flo", "NaN");
  fails_with("truncated_kitti.png", "corrupt or truncated");
  fails_with("eight_bit_kitti.png", "8-bit");
  fails_with("not_an_image.png", "cannot read image");
  fails_with("missing.flo", "file not found");
  fails_with("missing.png", "file not found");
  CHECK_THROWS_WITH(read_flow(dir.path / "numpy.txt"), Catch::Contains("unknown flow file type"));
}

TEST_CASE("flow that a format cannot hold is refused and nothing is written") {
  TempDir dir;
  Image<float> uv(4, 3, 2, 1.f);
  uv.pixel(2, 1)[1] = std::nanf("");
  CHECK_THROWS_WITH(write_flow(dir.path / "nan.flo", uv.view()),
                    Catch::Contains("NaN at pixel (2, 1)"));
  uv.pixel(2, 1)[1] = 600;  // KITTI PNG holds +-512 px
  CHECK_THROWS_WITH(write_flow(dir.path / "big.png", uv.view()),
                    Catch::Contains("exceeds the KITTI"));
  CHECK(fsys::is_empty(dir.path));
}

// The values a flow file of each release format keeps, by closed forms: KITTI rounds to 1/64 px
// within [-512, 511.984]; a half float keeps 11 significant bits (1/8 px steps from 128 px, 1/4
// from 256, 1/2 from 512) up to 65504.
TEST_CASE("a release's flow formats keep the flow to their precision and flag what is beyond") {
  TempDir dir;
  const std::vector<float> values = {0.3f,   -7.126f, 130.06f, -250.3f, 300.13f,     -511.9f,
                                     600.2f, -600.7f, 700.3f,  70000.f, kUnknownFlow};
  Image<float> uv(int(values.size()), 1, 2);
  for (std::size_t i = 0; i < values.size(); ++i)
    uv.data[2 * i] = values[i], uv.data[2 * i + 1] = i + 1 == values.size() ? kUnknownFlow : 1.f;
  const auto kept = [](FlowFormat format, float x) -> float {
    if (format == FlowFormat::KittiPng)
      return std::abs(x) < 511.99f ? std::round(x * 64) / 64 : kUnknownFlow;
    if (std::abs(x) > 65504) return kUnknownFlow;
    const double step = std::abs(x) >= 512   ? 0.5
                        : std::abs(x) >= 256 ? 0.25
                        : std::abs(x) >= 128 ? 0.125
                                             : std::ldexp(1.0, std::ilogb(x) - 10);
    return float(std::round(x / step) * step);
  };
  for (const FlowFormat format : {FlowFormat::KittiPng, FlowFormat::HalfExr}) {
    INFO(flow_format_name(format));
    const fsys::path file = dir.path / ("flow" + std::string(flow_format_extension(format)));
    const std::size_t flagged = write_flow_as(file, format, uv.view());
    CHECK(flagged == (format == FlowFormat::KittiPng ? 4 : 1));  // 600.2, -600.7, 700.3, 70000
    const Flow back = read_flow(file);
    const Image<float> expected = stored_flow(format, uv.view());
    CHECK(back.uv.data == expected.data);
    for (std::size_t i = 0; i + 1 < values.size(); ++i) {
      INFO(values[i]);
      const float u = kept(format, values[i]);
      CHECK(back.uv.data[2 * i] == u);
      CHECK(back.uv.data[2 * i + 1] == (u == kUnknownFlow ? kUnknownFlow : 1.f));
      CHECK(*back.valid.pixel(int(i), 0) == (u != kUnknownFlow));
    }
    CHECK(back.uv.data[2 * (values.size() - 1)] == kUnknownFlow);
  }
  // KITTI's flagged values are clamped to the range, not wrapped, and B = 0
  const Image<std::uint16_t> png = read_image<std::uint16_t>(dir.path / "flow.png");
  CHECK((png.pixel(6, 0)[0] == 65535 && png.pixel(6, 0)[2] == 0));
  CHECK((png.pixel(7, 0)[0] == 0 && png.pixel(7, 0)[2] == 0));
  CHECK((png.pixel(5, 0)[0] == 32768 - 32762 && png.pixel(5, 0)[2] == 1));  // -511.9 * 64
  // a half EXR's unknown and beyond-range flow is +infinity
  const Image<float> exr = read_image<float>(dir.path / "flow.exr");
  CHECK(std::isinf(exr.pixel(9, 0)[0]));
  CHECK(std::isinf(exr.pixel(10, 0)[0]));
  CHECK(exr.pixel(4, 0)[0] == 300.25f);
  CHECK_THROWS_WITH(flow_format_from_name("kitti"), Catch::Contains("kitti-png"));
  CHECK(flow_format_from_name("half-exr") == FlowFormat::HalfExr);
}
