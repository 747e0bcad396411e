#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>

#include "flowscape/formats/image_io.h"
#include "flowscape/formats/srgb.h"

using namespace flowscape;

TEST_CASE("JPEG compression leaves its artefacts, fewer at a higher quality, the same every time") {
  Image<std::uint8_t> image(64, 64, 3);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      std::uint8_t* p = image.pixel(x, y);
      p[0] = std::uint8_t(4 * x), p[1] = std::uint8_t(4 * y),
      p[2] = std::uint8_t(128 + 60 * std::sin(x / 5.0) * std::cos(y / 7.0));
    }
  const auto error = [&](int quality) {
    const Image<std::uint8_t> seen = jpeg_round_trip(image.view(), quality);
    double sum = 0;
    for (std::size_t i = 0; i < seen.data.size(); ++i)
      sum += std::abs(int(seen.data[i]) - int(image.data[i]));
    return sum / seen.data.size();
  };
  CHECK(error(95) < 3);
  CHECK(error(10) > 2 * error(95));
  CHECK(jpeg_round_trip(image.view(), 30).data == jpeg_round_trip(image.view(), 30).data);
  // red stays red: the channel order survives OpenCV's BGR
  Image<std::uint8_t> red(16, 16, 3);
  for (int i = 0; i < 256; ++i) red.data[3 * i] = 200;
  const Image<std::uint8_t> seen = jpeg_round_trip(red.view(), 90);
  CHECK(seen.pixel(8, 8)[0] > 180);
  CHECK(seen.pixel(8, 8)[2] < 20);
  CHECK_THROWS(jpeg_round_trip(red.view(), 0));
}

TEST_CASE("8-bit sRGB decodes to linear and encodes back to the same byte") {
  for (int v = 0; v < 256; ++v) CHECK(linear_to_srgb8(srgb8_to_linear(std::uint8_t(v))) == v);
  CHECK(srgb8_to_linear(0) == 0);
  CHECK(srgb8_to_linear(255) == Approx(1));
  CHECK(srgb8_to_linear(10) == Approx(10 / 255.0 / 12.92));  // the linear segment
  CHECK(srgb8_to_linear(188) == Approx(std::pow((188 / 255.0 + 0.055) / 1.055, 2.4)));
}

TEST_CASE("every PNG level and EXR compression gives back the same pixels; bad levels refused") {
  Image<std::uint8_t> bytes(37, 11, 3);
  Image<std::uint16_t> words(37, 11, 1);
  Image<float> floats(37, 11, 3);
  for (std::size_t i = 0; i < bytes.data.size(); ++i) bytes.data[i] = std::uint8_t(i * 7919 % 251);
  for (std::size_t i = 0; i < words.data.size(); ++i) words.data[i] = std::uint16_t(i * 40503);
  for (std::size_t i = 0; i < floats.data.size(); ++i) floats.data[i] = std::sin(double(i)) * 1e3f;
  floats.data[5] = std::numeric_limits<float>::quiet_NaN();
  floats.data[6] = std::numeric_limits<float>::infinity();
  const auto temp = std::filesystem::temp_directory_path() / "flowscape-compression-test";
  std::filesystem::create_directories(temp);
  std::vector<std::uintmax_t> sizes;  // of the 8-bit PNG, by level
  for (int level = 0; level <= 9; ++level) {
    write_image<std::uint8_t>(temp / "b.png", bytes.view(), {}, {level, "zip"});
    write_image<std::uint16_t>(temp / "w.png", words.view(), {}, {level, "zip"});
    CHECK(read_image<std::uint8_t>(temp / "b.png").data == bytes.data);
    CHECK(read_image<std::uint16_t>(temp / "w.png").data == words.data);
    sizes.push_back(std::filesystem::file_size(temp / "b.png"));
  }
  CHECK(sizes[9] < sizes[0]);  // deflated against stored: the level reached libpng
  for (const char* exr : {"zip", "zips", "piz", "rle", "none"}) {
    INFO(exr);
    write_image<float>(temp / "f.exr", floats.view(), {}, {6, exr});
    const Image<float> back = read_image<float>(temp / "f.exr");
    CHECK(std::memcmp(back.data.data(), floats.data.data(), floats.data.size() * 4) == 0);
  }
  CHECK_THROWS_WITH(encode_image<std::uint8_t>(temp / "b.png", bytes.view(), {}, {10, "zip"}),
                    Catch::Contains("b.png") && Catch::Contains("PNG compression level 10"));
  std::filesystem::remove_all(temp);
}
