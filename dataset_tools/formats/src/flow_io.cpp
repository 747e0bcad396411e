#include "flowscape/formats/flow_io.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>

#include "flowscape/formats/image_io.h"
#include "flowscape/stitcher/geometry.h"

namespace flowscape {
namespace {

static_assert(std::endian::native == std::endian::little, "flow files are little endian");

constexpr float kFloMagic = 202021.25f;
constexpr int kMaxSide = 1 << 16;
constexpr std::uintmax_t kMaxFloBytes = 12 + 8 * kMaxImagePixels;
constexpr double kKittiScale = 64.0, kKittiOffset = 32768.0;

std::string at(int x, int y) {
  return " at pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")";
}

void require_flow_image(const std::filesystem::path& path, ImageView<const float> uv) {
  if (uv.width <= 0 || uv.height <= 0 || uv.channels != 2 || !uv.data)
    throw FileError(path, "flow to write must be a non-empty 2-channel image");
  for (int y = 0; y < uv.height; ++y)
    for (int x = 0; x < uv.width; ++x)
      for (int c = 0; c < 2; ++c)
        if (std::isnan(uv.pixel(x, y)[c]))
          throw FileError(path, "flow to write holds NaN" + at(x, y));
}

void require_valid_image(const std::filesystem::path& path, ImageView<const float> uv,
                         ImageView<const std::uint8_t> valid) {
  if (valid.data && (valid.width != uv.width || valid.height != uv.height || valid.channels != 1))
    throw FileError(path, "valid mask size does not match the flow");
}

// Marks known flow valid; rejects NaN and infinity, which no format uses for "unknown".
Flow with_known_mask(const std::filesystem::path& path, Image<float> uv) {
  const int width = uv.width, height = uv.height;
  Flow flow{std::move(uv), Image<std::uint8_t>(width, height, 1)};
  for (int y = 0; y < flow.uv.height; ++y)
    for (int x = 0; x < flow.uv.width; ++x) {
      const float* f = flow.uv.pixel(x, y);
      if (!std::isfinite(f[0]) || !std::isfinite(f[1]))
        throw FileError(path, "flow holds NaN or infinity" + at(x, y));
      *flow.valid.pixel(x, y) = is_known_flow(f[0], f[1]);
    }
  return flow;
}

}  // namespace

Flow read_flo(const std::filesystem::path& path) {
  return parse_flo(path, read_file(path, kMaxFloBytes));
}

Flow parse_flo(const std::filesystem::path& path, std::string_view bytes) {
  if (bytes.size() < 12) throw FileError(path, "truncated .flo header (needs 12 bytes)");
  float magic = 0;
  std::int32_t size[2] = {0, 0};
  std::memcpy(&magic, bytes.data(), 4);
  std::memcpy(size, bytes.data() + 4, 8);
  if (magic != kFloMagic) throw FileError(path, "not a Middlebury .flo file (bad magic number)");
  const int width = size[0], height = size[1];
  if (width <= 0 || height <= 0 || width > kMaxSide || height > kMaxSide)
    throw FileError(path, "bad .flo size " + std::to_string(width) + "x" + std::to_string(height));
  // the header's size is checked against the file's before anything is allocated
  const std::size_t data = std::size_t(width) * std::size_t(height) * 8;
  if (bytes.size() - 12 < data)
    throw FileError(path, "truncated .flo data: the header's " + std::to_string(width) + "x" +
                              std::to_string(height) + " needs " + std::to_string(data) +
                              " bytes, the file has " + std::to_string(bytes.size() - 12));
  if (bytes.size() - 12 > data) throw FileError(path, "trailing bytes after the .flo data");
  Image<float> uv(width, height, 2);
  std::memcpy(uv.data.data(), bytes.data() + 12, data);
  return with_known_mask(path, std::move(uv));
}

void write_flo(const std::filesystem::path& path, ImageView<const float> uv) {
  require_flow_image(path, uv);
  std::string bytes(12 + uv.pixel_count() * 8, '\0');
  const std::int32_t size[2] = {uv.width, uv.height};
  std::memcpy(bytes.data(), &kFloMagic, 4);
  std::memcpy(bytes.data() + 4, size, 8);
  std::memcpy(bytes.data() + 12, uv.data, uv.pixel_count() * 8);
  write_file(path, bytes);
}

Flow read_kitti_png(const std::filesystem::path& path) {
  const Image<std::uint16_t> png = read_image<std::uint16_t>(path);
  if (png.channels != 3)
    throw FileError(path, "KITTI flow PNG needs 3 channels, has " + std::to_string(png.channels));
  Flow flow{Image<float>(png.width, png.height, 2), Image<std::uint8_t>(png.width, png.height, 1)};
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) {
      const std::uint16_t* p = png.pixel(x, y);
      float* f = flow.uv.pixel(x, y);
      f[0] = float((p[0] - kKittiOffset) / kKittiScale);
      f[1] = float((p[1] - kKittiOffset) / kKittiScale);
      *flow.valid.pixel(x, y) = p[2] != 0;
    }
  return flow;
}

void write_kitti_png(const std::filesystem::path& path, ImageView<const float> uv,
                     ImageView<const std::uint8_t> valid) {
  require_flow_image(path, uv);
  require_valid_image(path, uv, valid);
  Image<std::uint16_t> png(uv.width, uv.height, 3);
  for (int y = 0; y < uv.height; ++y)
    for (int x = 0; x < uv.width; ++x) {
      const float* f = uv.pixel(x, y);
      const bool known = is_known_flow(f[0], f[1]) && (!valid.data || *valid.pixel(x, y));
      if (!known) continue;
      std::uint16_t* p = png.pixel(x, y);
      for (int c = 0; c < 2; ++c) {
        const double stored = std::round(f[c] * kKittiScale + kKittiOffset);
        if (stored < 0 || stored > 65535)
          throw FileError(path, "flow " + std::to_string(f[c]) + at(x, y) +
                                    " exceeds the KITTI PNG range of +-512 px");
        p[c] = std::uint16_t(stored);
      }
      p[2] = 1;
    }
  write_image(path, png);
}

Flow read_flow_exr(const std::filesystem::path& path) {
  Image<float> exr = read_image<float>(path);
  if (exr.channels < 2)
    throw FileError(path, "flow EXR needs 2 channels (u, v), has " + std::to_string(exr.channels));
  Image<float> uv(exr.width, exr.height, 2);
  for (std::size_t i = 0; i < uv.pixel_count(); ++i) {
    uv.data[2 * i] = exr.data[i * exr.channels];
    uv.data[2 * i + 1] = exr.data[i * exr.channels + 1];
  }
  return with_known_mask(path, std::move(uv));
}

void write_flow_exr(const std::filesystem::path& path, ImageView<const float> uv) {
  require_flow_image(path, uv);
  write_image(path, uv, {"u", "v"});
}

Flow read_flow(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".flo") return read_flo(path);
  if (ext == ".png") return read_kitti_png(path);
  if (ext == ".exr") return read_flow_exr(path);
  throw FileError(path, "unknown flow file type '" + ext + "' (use .flo, .png or .exr)");
}

void write_flow(const std::filesystem::path& path, ImageView<const float> uv,
                ImageView<const std::uint8_t> valid) {
  const std::string ext = path.extension().string();
  if (ext == ".flo") return write_flo(path, uv);
  if (ext == ".png") return write_kitti_png(path, uv, valid);
  if (ext == ".exr") return write_flow_exr(path, uv);
  throw FileError(path, "unknown flow file type '" + ext + "' (use .flo, .png or .exr)");
}

}  // namespace flowscape
