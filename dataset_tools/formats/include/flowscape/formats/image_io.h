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

// How a written image is compressed, losslessly either way: PNG's zlib level (0-9; 6 is libpng's
// and OpenImageIO's default) and an EXR's compression by OpenEXR's name ("zip", "zips", "piz",
// "rle", "none"; "zip" is OpenImageIO's default); lossy only with exr_half.
struct Compression {
  int png_level = 6;
  std::string exr = "zip";
  bool exr_half = false;  // float pixels stored as 16-bit half floats (11 significant bits)
};

// The bytes of the file `path` names (the file type from its extension: .png, .jpg, .exr, ...),
// encoded in memory in T's format. Channel names are optional (formats like EXR store them).
template <class T>
std::vector<unsigned char> encode_image(const std::filesystem::path& path, ImageView<const T> image,
                                        const std::vector<std::string>& channel_names = {},
                                        const Compression& compression = {});

// Writes encode_image's bytes atomically.
template <class T>
void write_image(const std::filesystem::path& path, ImageView<const T> image,
                 const std::vector<std::string>& channel_names = {},
                 const Compression& compression = {});
template <class T>
void write_image(const std::filesystem::path& path, const Image<T>& image) {
  write_image(path, image.view());
}

}  // namespace flowscape
