#pragma once
// Files written whole or not at all, and the one error type whose message names the file.
#include <cstdio>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>

namespace flowscape {

// "<path>: <problem>", for one-line error reports.
struct FileError : std::runtime_error {
  FileError(const std::filesystem::path& path, const std::string& problem)
      : std::runtime_error(path.string() + ": " + problem) {}
};

// Where FlowScape's own messages go: the process's original stderr, even while a library's own
// chatter on fd 2 is muted (see formats/image_io.cpp).
std::FILE* diagnostics();

// Writes through a temporary file beside `path` (same extension) and renames it into place, so a
// crash never leaves a half-written `path`. The temporary is removed when `write` throws.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& temporary)>& write);
// A text file (JSON, Markdown, lists), written atomically.
void write_text(const std::filesystem::path& path, const std::string& text);

// The temporary name write_atomically uses for `path` (hidden, same folder, same extension).
std::filesystem::path temporary_path(const std::filesystem::path& path);
// Removes the temporary files a killed run left anywhere under `dir`.
void remove_temporary_files(const std::filesystem::path& dir);

}  // namespace flowscape
