#pragma once
// A small deterministic random source (splitmix64), the same numbers on every platform.
#include <cstdint>

namespace flowscape {

class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  std::uint64_t bits() {
    std::uint64_t x = (state_ += 0x9e3779b97f4a7c15ull);
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
  }
  double uniform(double lo = 0, double hi = 1) {
    return lo + (hi - lo) * double(bits() >> 11) * 0x1.0p-53;
  }
  int below(int n) { return int(bits() % std::uint64_t(n)); }  // 0 .. n - 1
  bool chance(double p) { return uniform() < p; }

 private:
  std::uint64_t state_;
};

}  // namespace flowscape
