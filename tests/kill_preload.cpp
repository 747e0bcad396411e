// LD_PRELOAD shim for tests: a process killed (SIGKILL, nothing runs after it) at one moment of
// writing one file, as a power cut or an out-of-memory kill would. FLOWSCAPE_KILL_FILE names the
// file by the end of its path (e.g. "release/card/sunny.png"); FLOWSCAPE_KILL_AT says when:
//   open    its temporary has just been created, empty
//   write   half of the first write to its temporary has reached the file
//   rename  its temporary is whole, just before it is renamed into place
// A temporary is write_file's ".partial-<pid>-<name>" beside the file (core/files.h).
#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cstdarg>
#include <cstdlib>
#include <string>
#include <string_view>

namespace {

bool kill_at(std::string_view moment) {
  const char* at = std::getenv("FLOWSCAPE_KILL_AT");
  return at && moment == at && std::getenv("FLOWSCAPE_KILL_FILE");
}

// The file a path stands for: itself, or for a temporary the file it will be renamed to.
std::string target_of(std::string path) {
  const std::size_t slash = path.rfind('/') + 1;  // npos + 1 = 0: no folder
  const std::string_view prefix = ".partial-";
  if (path.compare(slash, prefix.size(), prefix) != 0) return path;
  const std::size_t dash = path.find('-', slash + prefix.size());
  return dash == std::string::npos ? path : path.substr(0, slash) + path.substr(dash + 1);
}

bool is_kill_file(const std::string& path, bool temporary) {
  const std::string target = target_of(path);
  if (temporary == (target == path)) return false;
  const std::string_view wanted = std::getenv("FLOWSCAPE_KILL_FILE");
  return target.size() >= wanted.size() &&
         target.compare(target.size() - wanted.size(), wanted.size(), wanted) == 0;
}

std::string path_of(int fd) {
  char link[4096];
  const ssize_t n = readlink(("/proc/self/fd/" + std::to_string(fd)).c_str(), link, sizeof link);
  return n > 0 ? std::string(link, std::size_t(n)) : std::string();
}

[[noreturn]] void die() {
  kill(getpid(), SIGKILL);
  _exit(137);  // not reached
}

template <class Function>
Function real(const char* name) {
  return reinterpret_cast<Function>(dlsym(RTLD_NEXT, name));
}

// The real `symbol` (open or open64), then death if this creates the file's temporary.
int open_then_maybe_die(const char* symbol, const char* path, int flags, va_list args) {
  const mode_t mode = (flags & O_CREAT) ? mode_t(va_arg(args, int)) : 0;
  const int fd = real<int (*)(const char*, int, ...)>(symbol)(path, flags, mode);
  if (fd >= 0 && (flags & O_CREAT) && kill_at("open") && is_kill_file(path, true)) die();
  return fd;
}

}  // namespace

extern "C" int open(const char* path, int flags, ...) {
  va_list args;
  va_start(args, flags);
  const int fd = open_then_maybe_die("open", path, flags, args);
  va_end(args);
  return fd;
}

extern "C" int open64(const char* path, int flags, ...) {
  va_list args;
  va_start(args, flags);
  const int fd = open_then_maybe_die("open64", path, flags, args);
  va_end(args);
  return fd;
}

extern "C" ssize_t write(int fd, const void* data, size_t size) {
  static const auto real_write = real<ssize_t (*)(int, const void*, size_t)>("write");
  if (!kill_at("write") || size < 2 || !is_kill_file(path_of(fd), true))
    return real_write(fd, data, size);
  real_write(fd, data, size / 2);
  die();
}

extern "C" int rename(const char* from, const char* to) {
  static const auto real_rename = real<int (*)(const char*, const char*)>("rename");
  if (kill_at("rename") && is_kill_file(to, false)) die();
  return real_rename(from, to);
}
