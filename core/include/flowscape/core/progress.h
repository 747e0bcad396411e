#pragma once
// Progress of a long job on stderr: "label done/total (rate/s, ETA)". On a terminal the line
// is redrawn in place; otherwise a line is printed every few seconds. Thread-safe.
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace flowscape {

class Progress {
 public:
  Progress(std::string label, std::size_t total, std::string unit = "items");
  void advance(std::size_t count = 1);
  void skip(std::size_t count = 1);  // done earlier (a resumed job): counted, not in the rate
  void finish();                     // prints the final line

 private:
  void print(bool final);

  std::string label_, unit_;
  std::size_t total_, done_ = 0, skipped_ = 0;
  std::chrono::steady_clock::time_point start_, last_print_;
  bool terminal_;
  std::mutex mutex_;
};

}  // namespace flowscape
