#pragma once
// Image files through OpenImageIO, written atomically; one error type whose message names the file.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "flowscape/image.h"

namespace flowscape {

// "<path>: <problem>", for one-line error reports.
struct FileError : std::runtime_error {
  FileError(const std::filesystem::path& path, const std::string& problem)
      : std::runtime_error(path.string() + ": " + problem) {}
};

// Where FlowScape's own messages go: the process's original stderr. While images decode, fd 2 is
// pointed at /dev/null, because libpng (inside OpenImageIO) prints its own "libpng error" line
// for a corrupt file before OpenImageIO hands the same error to us; we report it in one line.
std::FILE* diagnostics();

// Writes through a temporary file beside `path` (same extension) and renames it into place, so a
// crash never leaves a half-written `path`. The temporary is removed when `write` throws.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& temporary)>& write);
// A text file (JSON, Markdown, lists), written atomically.
void write_text(const std::filesystem::path& path, const std::string& text);

// The temporary name write_atomically uses for `path` (hidden, same folder, same extension).
std::filesystem::path temporary_path(const std::filesystem::path& path);

// An image in the pixel type stored in its file (8-bit, 16-bit, or float for everything else).
using AnyImage = std::variant<Image<std::uint8_t>, Image<std::uint16_t>, Image<float>>;
AnyImage read_any_image(const std::filesystem::path& path);

// Reads an image whose file stores exactly T (uint8_t, uint16_t or float); other types are an
// error.
template <class T>
Image<T> read_image(const std::filesystem::path& path);

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
