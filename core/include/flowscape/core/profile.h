#pragma once
// Where a process's time goes, by stage: wall seconds per named phase, summed over every thread
// and call, and how busy the cores were (CPU seconds over wall seconds). bench_release prints them;
// a phase costs two clock reads and a lock, so phases are stages of a frame, never inner loops.
#include <string>
#include <vector>

namespace flowscape {

struct PhaseTime {
  std::string name;
  double seconds = 0;  // wall time inside the phase, summed over threads and calls
  long calls = 0;
};

// Times the enclosing scope as phase `name` (a string literal). Phases may nest: each counts
// its own wall time, nested phases included.
class ScopedPhase {
 public:
  explicit ScopedPhase(const char* name);
  ~ScopedPhase();
  ScopedPhase(const ScopedPhase&) = delete;
  ScopedPhase& operator=(const ScopedPhase&) = delete;

 private:
  const char* name_;
  double start_;
};

std::vector<PhaseTime> phase_times();  // in the order phases were first used
void reset_phase_times();

// User + system CPU seconds the process has used (getrusage); over a stretch of wall time, their
// difference is how many cores were busy on average.
double process_cpu_seconds();
double wall_seconds();  // a steady clock

}  // namespace flowscape
