#pragma once
// Files written whole or not at all, and the one error type whose message names the file.
#include <cstdio>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace flowscape {

// "<path>: <problem>", for one-line error reports.
struct FileError : std::runtime_error {
  FileError(const std::filesystem::path& path, const std::string& problem)
      : std::runtime_error(path.string() + ": " + problem) {}
};

// Where FlowScape's own messages go: the process's original stderr, even while a library's own
// chatter on fd 2 is muted (see formats/image_io.cpp).
std::FILE* diagnostics();

// Where fetched data (trained weights, sky maps) lives: the folder `variable` names when set, else
// $XDG_CACHE_HOME (or ~/.cache, or /tmp without a home) / flowscape / `name`.
std::filesystem::path cache_directory(const char* variable, const std::string& name);

// Every output goes through here. Writes through a temporary file beside `path` (same extension),
// checking each write, fsync and close, and renames it into place only when all succeeded, then
// syncs the folder: a crash or a full disk never leaves a half-written file under `path`. The first
// failure throws a FileError naming `path` and the OS error; the temporary is removed.
void write_file(const std::filesystem::path& path, std::string_view bytes);
// A text file (JSON, Markdown, lists): write_file.
void write_text(const std::filesystem::path& path, const std::string& text);
// For writers that must name a file themselves (a hard link, a video encoder): `write` fills the
// temporary; it is then synced (errors checked) and renamed like write_file's.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& temporary)>& write);

// The bytes of a regular file, refusing folders, missing files and files over `max_bytes`, each
// with a FileError naming it.
std::string read_file(const std::filesystem::path& path, std::uintmax_t max_bytes = 1u << 30);
// The same checks without reading it (for a reader that streams the file); returns its size.
std::uintmax_t require_regular_file(const std::filesystem::path& path, std::uintmax_t max_bytes);

// The temporary name write_file uses for `path`: hidden, same folder, same extension, with the
// process id (".partial-<pid>-name.ext").
std::filesystem::path temporary_path(const std::filesystem::path& path);
// Whether a file's name is one temporary_path makes (".partial-<digits>-<name>"), whoever made it.
bool is_temporary_file(const std::filesystem::path& path);
// Removes the temporary files a killed run left in `dir` itself (not in its subfolders); files of
// other names are never touched, and a missing `dir` is nothing to do. Returns how many went.
std::size_t remove_temporary_files(const std::filesystem::path& dir);
// The same in `dir` and every folder below it.
std::size_t remove_temporary_files_under(const std::filesystem::path& dir);
// The temporaries of `path` alone, whichever process wrote them (a file only one writer makes).
std::size_t remove_temporaries_of(const std::filesystem::path& path);

}  // namespace flowscape
