#include "flowscape/core/files.h"

#include <unistd.h>

#include <fstream>
#include <system_error>
#include <vector>

namespace flowscape {
namespace {

constexpr const char* kTemporaryPrefix = ".partial-";

}  // namespace

std::FILE* diagnostics() {
  static std::FILE* stream = [] {
    std::FILE* copy = fdopen(dup(STDERR_FILENO), "w");
    if (copy) setvbuf(copy, nullptr, _IOLBF, 0);
    return copy ? copy : stderr;
  }();
  return stream;
}

std::filesystem::path temporary_path(const std::filesystem::path& path) {
  return path.parent_path() / (kTemporaryPrefix + path.filename().string());
}

void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path&)>& write) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  const std::filesystem::path temporary = temporary_path(path);
  try {
    write(temporary);
    std::filesystem::rename(temporary, path);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out << text;
    if (!out.flush()) throw FileError(path, "cannot write");
  });
}

void remove_temporary_files(const std::filesystem::path& dir) {
  if (!std::filesystem::exists(dir)) return;
  std::vector<std::filesystem::path> found;  // removing while iterating would upset the iterator
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().filename().string().starts_with(kTemporaryPrefix))
      found.push_back(entry.path());
  for (const auto& path : found) std::filesystem::remove(path);
}

}  // namespace flowscape
