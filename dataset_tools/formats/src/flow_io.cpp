#include "flowscape/formats/flow_io.h"

#include <Imath/half.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

#include "flowscape/formats/image_io.h"
#include "flowscape/geometry/geometry.h"

namespace flowscape {
namespace {

static_assert(std::endian::native == std::endian::little, "flow files are little endian");

constexpr float kFloMagic = 202021.25f;
constexpr int kMaxSide = 1 << 16;
constexpr std::uintmax_t kMaxFloBytes = 12 + 8 * kMaxImagePixels;
constexpr double kKittiScale = 64.0, kKittiOffset = 32768.0;

struct FlowFormatNames {
  FlowFormat format;
  std::string_view name, extension;
};
// In FlowFormat's order.
constexpr FlowFormatNames kFlowFormats[] = {{FlowFormat::Flo, "flo", ".flo"},
                                            {FlowFormat::KittiPng, "kitti-png", ".png"},
                                            {FlowFormat::HalfExr, "half-exr", ".exr"}};

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
      *flow.valid.pixel(x, y) = p[2] != 0;
      for (int c = 0; c < 2; ++c)
        f[c] = p[2] != 0 ? float((p[c] - kKittiOffset) / kKittiScale) : kUnknownFlow;
    }
  return flow;
}

namespace {

double kitti_stored(float f) { return std::round(f * kKittiScale + kKittiOffset); }
bool in_kitti_range(double stored) { return stored >= 0 && stored <= 65535; }

// KITTI's pixels of the flow: beyond the range refused (`flag` false) or clamped and flagged B = 0
// (counted in `flagged`).
Image<std::uint16_t> kitti_pixels(const std::filesystem::path& path, ImageView<const float> uv,
                                  ImageView<const std::uint8_t> valid, bool flag,
                                  std::size_t& flagged) {
  require_flow_image(path, uv);
  require_valid_image(path, uv, valid);
  Image<std::uint16_t> png(uv.width, uv.height, 3);
  for (int y = 0; y < uv.height; ++y)
    for (int x = 0; x < uv.width; ++x) {
      const float* f = uv.pixel(x, y);
      const bool known = is_known_flow(f[0], f[1]) && (!valid.data || *valid.pixel(x, y));
      if (!known) continue;
      std::uint16_t* p = png.pixel(x, y);
      bool in_range = true;
      for (int c = 0; c < 2; ++c) {
        const double stored = kitti_stored(f[c]);
        if (!in_kitti_range(stored) && !flag)
          throw FileError(path, "flow " + std::to_string(f[c]) + at(x, y) +
                                    " exceeds the KITTI PNG range of +-512 px");
        in_range = in_range && in_kitti_range(stored);
        p[c] = std::uint16_t(std::clamp(stored, 0.0, 65535.0));
      }
      p[2] = in_range;
      flagged += !in_range;
    }
  return png;
}

// Half-float flow: unknown and beyond +-65504 px as +infinity (counted in `flagged`).
Image<float> half_exr_flow(ImageView<const float> uv, std::size_t& flagged) {
  Image<float> stored = stored_flow(FlowFormat::HalfExr, uv);
  for (std::size_t i = 0; i < stored.pixel_count(); ++i) {
    float* f = &stored.data[2 * i];
    if (is_known_flow(f[0], f[1])) continue;
    flagged += is_known_flow(uv.data[2 * i], uv.data[2 * i + 1]);
    f[0] = f[1] = std::numeric_limits<float>::infinity();
  }
  return stored;
}

}  // namespace

void write_kitti_png(const std::filesystem::path& path, ImageView<const float> uv,
                     ImageView<const std::uint8_t> valid) {
  std::size_t flagged = 0;
  write_image(path, kitti_pixels(path, uv, valid, false, flagged));
}

Flow read_flow_exr(const std::filesystem::path& path) {
  Image<float> exr = read_image<float>(path);
  if (exr.channels < 2)
    throw FileError(path, "flow EXR needs 2 channels (u, v), has " + std::to_string(exr.channels));
  Image<float> uv(exr.width, exr.height, 2);
  for (std::size_t i = 0; i < uv.pixel_count(); ++i)
    for (int c = 0; c < 2; ++c) {
      const float f = exr.data[i * exr.channels + c];
      uv.data[2 * i + c] = std::isinf(f) ? kUnknownFlow : f;
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

FlowFormat flow_format_from_name(std::string_view name) {
  for (const FlowFormatNames& row : kFlowFormats)
    if (row.name == name) return row.format;
  throw std::invalid_argument("flow format must be flo, kitti-png or half-exr, not \"" +
                              std::string(name) + "\"");
}

std::string_view flow_format_name(FlowFormat format) { return kFlowFormats[int(format)].name; }

std::string_view flow_format_extension(FlowFormat format) {
  return kFlowFormats[int(format)].extension;
}

Image<float> stored_flow(FlowFormat format, ImageView<const float> uv) {
  Image<float> stored(uv.width, uv.height, 2);
  std::copy_n(uv.data, stored.data.size(), stored.data.begin());
  if (format == FlowFormat::Flo) return stored;
  for (std::size_t i = 0; i < stored.pixel_count(); ++i) {
    float* f = &stored.data[2 * i];
    bool known = is_known_flow(f[0], f[1]);
    for (int c = 0; c < 2 && known; ++c) {
      if (format == FlowFormat::KittiPng) {
        const double kept = kitti_stored(f[c]);  // read back as read_kitti_png does
        known = in_kitti_range(kept);
        f[c] = float((kept - kKittiOffset) / kKittiScale);
      } else {
        const Imath::half kept(f[c]);  // round to nearest even, as OpenEXR writes it
        known = !kept.isInfinity();
        f[c] = float(kept);
      }
    }
    if (!known) f[0] = f[1] = kUnknownFlow;
  }
  return stored;
}

std::size_t write_flow_as(const std::filesystem::path& path, FlowFormat format,
                          ImageView<const float> uv) {
  std::size_t flagged = 0;
  if (format == FlowFormat::KittiPng)  // zlib level 2 (bench_encoding): half level 6's time
    write_image<std::uint16_t>(path, kitti_pixels(path, uv, {}, true, flagged).view(), {}, {2});
  else if (format == FlowFormat::HalfExr)
    require_flow_image(path, uv),
        write_image<float>(path, half_exr_flow(uv, flagged).view(), {"u", "v"}, {6, "zip", true});
  else
    write_flo(path, uv);
  return flagged;
}

}  // namespace flowscape
