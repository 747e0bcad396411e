#include "flowscape/core/profile.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <mutex>

namespace flowscape {
namespace {

std::mutex phases_mutex;
std::vector<PhaseTime>& phases() {
  static std::vector<PhaseTime> all;
  return all;
}

}  // namespace

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double process_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

ScopedPhase::ScopedPhase(const char* name) : name_(name), start_(wall_seconds()) {}

ScopedPhase::~ScopedPhase() {
  const double elapsed = wall_seconds() - start_;
  const std::lock_guard<std::mutex> lock(phases_mutex);
  std::vector<PhaseTime>& all = phases();
  auto found = std::find_if(all.begin(), all.end(), [&](const PhaseTime& p) {
    return std::strcmp(p.name.c_str(), name_) == 0;
  });
  if (found == all.end()) found = all.insert(all.end(), PhaseTime{name_});
  found->seconds += elapsed;
  ++found->calls;
}

std::vector<PhaseTime> phase_times() {
  const std::lock_guard<std::mutex> lock(phases_mutex);
  return phases();
}

void reset_phase_times() {
  const std::lock_guard<std::mutex> lock(phases_mutex);
  phases().clear();
}

}  // namespace flowscape
