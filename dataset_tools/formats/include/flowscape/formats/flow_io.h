#pragma once
// Optical-flow files: Middlebury .flo, KITTI 16-bit PNG, float EXR. Every reader checks its input
// and throws FileError naming the file and the problem; every writer writes atomically.
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "flowscape/core/image.h"

namespace flowscape {

struct Flow {
  Image<float> uv;            // 2 channels, pixels, u right, v down; unknown = kUnknownFlow
  Image<std::uint8_t> valid;  // 1 channel, 1 where the flow is known (and, for KITTI, valid)
};

// Middlebury: "PIEH" (202021.25f), int32 width, int32 height, then float32 u,v interleaved,
// little endian. Components above 1e9 mean unknown.
// The header's size is checked against the file's length before anything is allocated.
Flow read_flo(const std::filesystem::path& path);
Flow parse_flo(const std::filesystem::path& path, std::string_view bytes);  // errors name `path`
void write_flo(const std::filesystem::path& path, ImageView<const float> uv);

// KITTI: RGB 16-bit PNG, R = u * 64 + 2^15, G = v * 64 + 2^15, B = 1 where valid.
Flow read_kitti_png(const std::filesystem::path& path);
void write_kitti_png(const std::filesystem::path& path, ImageView<const float> uv,
                     ImageView<const std::uint8_t> valid = {});

// OpenEXR: float32 channels "u", "v".
Flow read_flow_exr(const std::filesystem::path& path);
void write_flow_exr(const std::filesystem::path& path, ImageView<const float> uv);

// By extension: .flo, .png (KITTI), .exr. Only KITTI stores `valid`; the others keep the flow of
// every pixel (unknown ones as kUnknownFlow).
Flow read_flow(const std::filesystem::path& path);
void write_flow(const std::filesystem::path& path, ImageView<const float> uv,
                ImageView<const std::uint8_t> valid = {});

}  // namespace flowscape
