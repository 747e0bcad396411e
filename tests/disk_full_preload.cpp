// LD_PRELOAD shim for tests: a disk that fills up. Writes to regular files succeed until
// FLOWSCAPE_DISK_BYTES bytes have been written in all, then come short and fail with ENOSPC, as
// write(2) does on a full file system. Other descriptors (pipes, terminals) are untouched.
#include <dlfcn.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>

namespace {

using WriteFunction = ssize_t (*)(int, const void*, size_t);

std::atomic<long long> room{-1};  // bytes left; -1: not read from the environment yet

long long bytes_left() {
  long long left = room.load();
  if (left >= 0) return left;
  const char* limit = std::getenv("FLOWSCAPE_DISK_BYTES");
  long long expected = -1;
  room.compare_exchange_strong(expected, limit ? std::atoll(limit) : (1LL << 62));
  return room.load();
}

}  // namespace

extern "C" ssize_t write(int fd, const void* data, size_t size) {
  static const auto real_write = reinterpret_cast<WriteFunction>(dlsym(RTLD_NEXT, "write"));
  struct stat status;
  if (fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) return real_write(fd, data, size);
  long long left = bytes_left();
  long long granted;
  do {
    granted = left < (long long)size ? left : (long long)size;
  } while (!room.compare_exchange_weak(left, left - granted));
  if (size > 0 && granted == 0) {
    errno = ENOSPC;
    return -1;
  }
  return real_write(fd, data, size_t(granted));
}
