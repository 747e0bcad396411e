#include "flowscape/core/progress.h"

#include <unistd.h>

#include <cstdio>

#include "flowscape/core/files.h"

namespace flowscape {

Progress::Progress(std::string label, std::size_t total, std::string unit)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      total_(total),
      start_(std::chrono::steady_clock::now()),
      last_print_(start_),
      terminal_(isatty(fileno(diagnostics()))) {}

void Progress::advance(std::size_t count) {
  std::lock_guard lock(mutex_);
  done_ += count;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_print_ >= std::chrono::milliseconds(terminal_ ? 200 : 5000)) {
    last_print_ = now;
    print(false);
  }
}

void Progress::skip(std::size_t count) {
  std::lock_guard lock(mutex_);
  done_ += count, skipped_ += count;
}

void Progress::finish() {
  std::lock_guard lock(mutex_);
  print(true);
}

void Progress::print(bool final) {
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = seconds > 0 ? (done_ - skipped_) / seconds : 0;
  const double eta = rate > 0 ? (total_ - done_) / rate : 0;
  const bool slow = rate < 1;  // a few items a minute read better per minute
  std::fprintf(diagnostics(), "%s%s %zu/%zu %s (%.2f/%s, %s %.0fs)%s", terminal_ ? "\r" : "",
               label_.c_str(), done_, total_, unit_.c_str(), slow ? rate * 60 : rate,
               slow ? "min" : "s", final ? "took" : "ETA", final ? seconds : eta,
               terminal_ && !final ? "" : "\n");
  std::fflush(diagnostics());
}

}  // namespace flowscape
