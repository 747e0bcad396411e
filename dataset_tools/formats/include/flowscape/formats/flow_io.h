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

// KITTI: RGB 16-bit PNG, R = u * 64 + 2^15, G = v * 64 + 2^15, B = 1 where valid (read back as
// unknown flow where B = 0).
Flow read_kitti_png(const std::filesystem::path& path);
void write_kitti_png(const std::filesystem::path& path, ImageView<const float> uv,
                     ImageView<const std::uint8_t> valid = {});

// OpenEXR: float32 channels "u", "v" (read: half too, and infinity as unknown flow, which a half
// cannot hold as 1e10).
Flow read_flow_exr(const std::filesystem::path& path);
void write_flow_exr(const std::filesystem::path& path, ImageView<const float> uv);

// By extension: .flo, .png (KITTI), .exr. Only KITTI stores `valid`; the others keep the flow of
// every pixel (unknown ones as kUnknownFlow).
Flow read_flow(const std::filesystem::path& path);
void write_flow(const std::filesystem::path& path, ImageView<const float> uv,
                ImageView<const std::uint8_t> valid = {});

// How a release stores its flow (--flow-format): Middlebury .flo, float32 (the default: the
// PanoFlow tree reads it); KITTI's 16-bit PNG, 1/64 px steps within +-512 px; half-float EXR
// ("u", "v"), 11 significant bits (0.25 px steps from 256 to 512 px) within +-65504 px.
enum class FlowFormat : std::uint8_t { Flo, KittiPng, HalfExr };
// "flo", "kitti-png", "half-exr"; other names throw std::invalid_argument listing these.
FlowFormat flow_format_from_name(std::string_view name);
std::string_view flow_format_name(FlowFormat format);
std::string_view flow_format_extension(FlowFormat format);  // ".flo", ".png", ".exr"

// The flow a file of `format` gives back: rounded to the format's steps, and unknown
// (kUnknownFlow) where it is unknown or beyond the format's range.
Image<float> stored_flow(FlowFormat format, ImageView<const float> uv);

// Writes flow in `format`. Flow beyond the format's range is flagged unknown, never wrapped:
// KITTI's B = 0 (the value clamped to the range), an EXR's infinity. Returns how many pixels were.
std::size_t write_flow_as(const std::filesystem::path& path, FlowFormat format,
                          ImageView<const float> uv);

}  // namespace flowscape
