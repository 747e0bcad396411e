#include "flowscape/core/files.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <system_error>
#include <utility>
#include <vector>

namespace flowscape {
namespace fs = std::filesystem;
namespace {

constexpr const char* kTemporaryPrefix = ".partial-";

// `what` and the OS error, when the call that failed set one (streams do not always).
[[noreturn]] void fail(const fs::path& path, const std::string& what) {
  throw FileError(path, errno ? what + ": " + std::strerror(errno) : what);
}

// A descriptor that closes itself if an error leaves it open.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

void write_all(const fs::path& temporary, const fs::path& path, std::string_view bytes) {
  Descriptor file{::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644)};
  if (file.fd < 0) fail(path, "cannot create");
  while (!bytes.empty()) {
    errno = 0;
    const ssize_t written = ::write(file.fd, bytes.data(), bytes.size());
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) fail(path, "cannot write");
    bytes.remove_prefix(std::size_t(written));
  }
  if (::fsync(file.fd) != 0) fail(path, "cannot write (fsync)");
  const int fd = std::exchange(file.fd, -1);
  if (::close(fd) != 0) fail(path, "cannot write (close)");
}

// Flushes what another writer put in `temporary`; errors the page cache held back surface here.
void sync_file(const fs::path& temporary, const fs::path& path) {
  Descriptor file{::open(temporary.c_str(), O_RDONLY | O_CLOEXEC)};
  if (file.fd < 0) fail(path, "cannot reopen the written file");
  if (::fsync(file.fd) != 0) fail(path, "cannot write (fsync)");
}

void sync_folder(const fs::path& path) {
  const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
  Descriptor dir{::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)};
  if (dir.fd < 0 || ::fsync(dir.fd) != 0) fail(path, "cannot sync its folder");
}

void replace_with(const fs::path& temporary, const fs::path& path,
                  const std::function<void()>& write) {
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  try {
    write();
    if (::rename(temporary.c_str(), path.c_str()) != 0) fail(path, "cannot rename into place");
    sync_folder(path);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
}

}  // namespace

std::FILE* diagnostics() {
  static std::FILE* stream = [] {
    std::FILE* copy = fdopen(dup(STDERR_FILENO), "w");
    if (copy) setvbuf(copy, nullptr, _IOLBF, 0);
    return copy ? copy : stderr;
  }();
  return stream;
}

fs::path cache_directory(const char* variable, const std::string& name) {
  if (const char* dir = std::getenv(variable); dir && *dir) return dir;
  const char* cache = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  const fs::path base = cache && *cache ? fs::path(cache)
                        : home && *home ? fs::path(home) / ".cache"
                                        : fs::path("/tmp");
  return base / "flowscape" / name;
}

fs::path temporary_path(const fs::path& path) {
  // the process id keeps processes writing the same file (shards recording config.json) apart
  return path.parent_path() /
         (kTemporaryPrefix + std::to_string(::getpid()) + "-" + path.filename().string());
}

void write_file(const fs::path& path, std::string_view bytes) {
  const fs::path temporary = temporary_path(path);
  replace_with(temporary, path, [&] { write_all(temporary, path, bytes); });
}

void write_atomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  const fs::path temporary = temporary_path(path);
  replace_with(temporary, path, [&] {
    write(temporary);
    sync_file(temporary, path);
  });
}

void write_text(const fs::path& path, const std::string& text) { write_file(path, text); }

std::uintmax_t require_regular_file(const fs::path& path, std::uintmax_t max_bytes) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) throw FileError(path, "file not found");
  if (fs::is_directory(status)) throw FileError(path, "is a folder, expected a file");
  if (!fs::is_regular_file(status)) throw FileError(path, "not a regular file");
  const std::uintmax_t size = fs::file_size(path);
  if (size > max_bytes)
    throw FileError(path, "too large: " + std::to_string(size) + " bytes (at most " +
                              std::to_string(max_bytes) + ")");
  return size;
}

std::string read_file(const fs::path& path, std::uintmax_t max_bytes) {
  const std::uintmax_t size = require_regular_file(path, max_bytes);
  std::ifstream in(path, std::ios::binary);
  std::string bytes(size, '\0');
  errno = 0;
  if (!in.read(bytes.data(), std::streamsize(size))) fail(path, "cannot read");
  return bytes;
}

namespace {

// The name a temporary (".partial-<digits>-<name>") stands for; empty for other names.
std::string target_name(const fs::path& path) {
  const std::string name = path.filename().string();
  const std::size_t digits = std::string_view(kTemporaryPrefix).size();
  if (!name.starts_with(kTemporaryPrefix)) return "";
  const std::size_t dash = name.find_first_not_of("0123456789", digits);
  if (dash == std::string::npos || dash == digits || name[dash] != '-') return "";
  return name.substr(dash + 1);
}

}  // namespace

bool is_temporary_file(const fs::path& path) { return !target_name(path).empty(); }

namespace {

// Removes the regular files `entries` yields that `doomed` picks; collected first, since removing
// while iterating would upset the iterator.
template <class Iterator, class Predicate>
std::size_t remove_files(Iterator entries, Predicate doomed) {
  std::vector<fs::path> found;
  for (const auto& entry : entries)
    if (entry.is_regular_file() && doomed(entry.path())) found.push_back(entry.path());
  for (const auto& path : found) fs::remove(path);
  return found.size();
}

}  // namespace

std::size_t remove_temporary_files(const fs::path& dir) {
  if (!fs::is_directory(dir)) return 0;
  return remove_files(fs::directory_iterator(dir), is_temporary_file);
}

std::size_t remove_temporary_files_under(const fs::path& dir) {
  if (!fs::is_directory(dir)) return 0;
  return remove_files(fs::recursive_directory_iterator(dir), is_temporary_file);
}

std::size_t remove_temporaries_of(const fs::path& path) {
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(dir) || path.filename().empty()) return 0;
  return remove_files(fs::directory_iterator(dir), [&](const fs::path& file) {
    return target_name(file) == path.filename().string();
  });
}

}  // namespace flowscape
