#pragma once
// Seeded hashing and random numbers (splitmix64), the same numbers on every platform.
#include <cstdint>

namespace flowscape {

// The splitmix64 step: a well-mixed 64-bit hash of x.
constexpr std::uint64_t mix_bits(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  std::uint64_t bits() {
    const std::uint64_t x = state_;
    state_ += 0x9e3779b97f4a7c15ull;
    return mix_bits(x);
  }
  double uniform(double lo = 0, double hi = 1) {
    return lo + (hi - lo) * double(bits() >> 11) * 0x1.0p-53;
  }
  int below(int n) { return int(bits() % std::uint64_t(n)); }  // 0 .. n - 1
  bool chance(double p) { return uniform() < p; }

 private:
  std::uint64_t state_;
};

// A seed derived from `seed` and two small numbers (a map and a sequence, a frame and a purpose).
inline std::uint64_t derived_seed(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
  return Random(seed ^ (a << 32) ^ (b << 8) ^ 0x632be59bd9b4e019ull).bits();
}

}  // namespace flowscape
