#include <catch2/catch.hpp>
#include <fstream>

#include "flowscape/formats/cubemap_io.h"
#include "temp_dir.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

// A stack of six N x N faces whose pixels hold (10 face + the pixel's row, column, 7).
Image<std::uint16_t> labelled_stack(int n) {
  Image<std::uint16_t> stack(n, 6 * n, 3);
  for (int y = 0; y < 6 * n; ++y)
    for (int x = 0; x < n; ++x)
      stack.pixel(x, y)[0] = std::uint16_t(10 * (y / n) + y % n), stack.pixel(x, y)[1] = x,
                     stack.pixel(x, y)[2] = 7;
  return stack;
}

}  // namespace

TEST_CASE("a stacked cubemap is one file per face, in the order front right back left up down") {
  TempDir dir;
  const int n = 4;
  const Image<std::uint16_t> stack = labelled_stack(n);
  write_cube_image(dir.path, "instance", "000003.png", stack.view());
  const char* names[6] = {"front", "right", "back", "left", "up", "down"};
  for (int f = 0; f < 6; ++f) {
    const Image<std::uint16_t> face =
        read_image<std::uint16_t>(dir.path / names[f] / "instance" / "000003.png");
    REQUIRE((face.width == n && face.height == n && face.channels == 3));
    CHECK(face.pixel(0, 0)[0] == 10 * f);
    CHECK(face.pixel(3, 2)[0] == 10 * f + 2);
    CHECK(face.pixel(3, 2)[1] == 3);
  }
  CHECK(read_cube_image_as<std::uint16_t>(dir.path, "instance", "000003.png").data == stack.data);
  const AnyImage any = read_cube_image(dir.path, "instance", "000003.png");
  CHECK(std::get<Image<std::uint16_t>>(any).data == stack.data);
}

TEST_CASE("cube flow files round-trip and frames are listed in order without temporaries") {
  TempDir dir;
  Image<float> flow(3, 18, 2);
  for (std::size_t i = 0; i < flow.data.size(); ++i) flow.data[i] = 0.25f * float(i) - 7;
  for (const char* name : {"000002.flo", "000000.flo", "000001.flo"})
    write_cube_flow(dir.path, "flow", name, flow.view());
  std::ofstream(dir.path / "front" / "flow" / ".partial-000003.flo") << "half";
  CHECK(read_cube_flow(dir.path, "flow", "000001.flo").uv.data == flow.data);
  CHECK(cube_frame_files(dir.path, "flow") ==
        std::vector<std::string>{"000000.flo", "000001.flo", "000002.flo"});
  CHECK(cube_frame_files(dir.path, "color").empty());
}

TEST_CASE("a face of another size is refused naming its file") {
  TempDir dir;
  const Image<std::uint16_t> stack = labelled_stack(4);
  write_cube_image(dir.path, "instance", "000000.png", stack.view());
  write_image(dir.path / "up" / "instance" / "000000.png", Image<std::uint16_t>(5, 5, 3));
  CHECK_THROWS_WITH(read_cube_image(dir.path, "instance", "000000.png"),
                    Catch::Contains("up/instance/000000.png: face size or channels differ"));
  fs::remove(dir.path / "left" / "instance" / "000000.png");
  CHECK_THROWS_WITH(read_cube_image_as<std::uint16_t>(dir.path, "instance", "000000.png"),
                    Catch::Contains("left/instance/000000.png: file not found"));
}
