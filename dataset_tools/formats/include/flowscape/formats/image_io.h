#pragma once
// Image files through OpenImageIO, written atomically; errors are FileErrors naming the file.
// While images decode, fd 2 is pointed at /dev/null, because libpng (inside OpenImageIO) prints its
// own "libpng error" line for a corrupt file before OpenImageIO hands the same error to us; we
// report it in one line on diagnostics().
#include <cstdint>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "flowscape/core/files.h"
#include "flowscape/core/image.h"

namespace flowscape {

// The most any image read may hold; larger headers are refused before decoding, as are headers
// claiming more pixels than their file can hold (image_io.cpp: check_header).
inline constexpr std::uintmax_t kMaxImagePixels = std::uintmax_t(1) << 28;
inline constexpr std::uintmax_t kMaxImageBytes = std::uintmax_t(1) << 31;

// An image in the pixel type stored in its file (8-bit, 16-bit, or float for everything else).
using AnyImage = std::variant<Image<std::uint8_t>, Image<std::uint16_t>, Image<float>>;
AnyImage read_any_image(const std::filesystem::path& path);

// Reads an image whose file stores exactly T (uint8_t, uint16_t or float); other types are an
// error.
template <class T>
Image<T> read_image(const std::filesystem::path& path);

// An 8-bit RGB image after JPEG compression at `quality` (1-100, libjpeg's scale through OpenCV,
// 4:2:0 chroma) and decompression: the artefacts a camera's encoder leaves.
Image<std::uint8_t> jpeg_round_trip(ImageView<const std::uint8_t> rgb, int quality);

// Writes in T's format (the file type from the extension: .png, .jpg, .exr, ...), atomically.
// Channel names are optional (formats like EXR store them).
template <class T>
void write_image(const std::filesystem::path& path, ImageView<const T> image,
                 const std::vector<std::string>& channel_names = {});
template <class T>
void write_image(const std::filesystem::path& path, const Image<T>& image) {
  write_image(path, image.view());
}

}  // namespace flowscape
