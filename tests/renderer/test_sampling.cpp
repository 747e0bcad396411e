// The path tracer's sampler (renderer/src/render/sampling.h, internal): Owen-scrambled Sobol pairs.
#include <catch2/catch.hpp>
#include <set>

#include "render/sampling.h"

using namespace flowscape;

TEST_CASE("the second Sobol dimension follows from its direction numbers 1, 3, 5, 15") {
  // v_k = m_k / 2^k = 1/2, 3/4, 5/8, 15/16; point i is the XOR of the v_k of i's set bits
  const double expected[16] = {0,      0.5,    0.75,   0.25,   0.625,  0.125,  0.375,  0.875,
                               0.9375, 0.4375, 0.1875, 0.6875, 0.3125, 0.8125, 0.5625, 0.0625};
  for (std::uint32_t i = 0; i < 16; ++i)
    CHECK(sobol::second_dimension(i) * 0x1.0p-32 == expected[i]);
  // and the bits from 8 on: v_9 = 0b1'1101'1101 / 2^9 (the recurrence v ^= v >> 1 from v_1)
  std::uint32_t v = 1u << 31;
  for (int k = 1; k < 9; ++k) v ^= v >> 1;
  CHECK(sobol::second_dimension(256) == v);
}

TEST_CASE("the first 16 samples of a pixel's pair are a (0,4,2)-net: one in every elementary box") {
  for (std::uint64_t key : {1ull, 77ull, 123456789ull})
    for (int pair = 0; pair < 4; ++pair) {
      Vec2 points[16];
      for (int i = 0; i < 16; ++i) {
        const Sampler::PixelKeys keys(key);
        Sampler sampler(keys, i, 16);
        for (int p = 0; p < pair; ++p) sampler.next();
        points[i] = sampler.next();
      }
      for (int columns : {1, 2, 4, 8, 16}) {  // boxes of 1/columns x columns/16
        std::set<std::pair<int, int>> boxes;
        for (const Vec2& p : points) {
          REQUIRE((p.x() >= 0 && p.x() < 1 && p.y() >= 0 && p.y() < 1));
          boxes.insert({int(p.x() * columns), int(p.y() * (16 / columns))});
        }
        INFO("key " << key << ", pair " << pair << ", " << columns << " columns");
        CHECK(boxes.size() == 16);
      }
    }
}

TEST_CASE("a pixel's samples after its block (edge samples) fill it out to a (0,5,2)-net") {
  // 8 samples of a pixel and the 24 edge samples after them: the first 32 points of the same
  // scrambled Sobol sequence, one in every elementary box of area 1/32
  for (std::uint64_t key : {3ull, 99ull, 987654321ull}) {
    const Sampler::PixelKeys keys(key);
    Vec2 points[32];
    for (int i = 0; i < 32; ++i) points[i] = Sampler(keys, i, 8).next();
    for (int columns : {1, 2, 4, 8, 16, 32}) {
      std::set<std::pair<int, int>> boxes;
      for (const Vec2& p : points)
        boxes.insert({int(p.x() * columns), int(p.y() * (32 / columns))});
      INFO("key " << key << ", " << columns << " columns");
      CHECK(boxes.size() == 32);
    }
  }
}

namespace {

double correlation(const double* a, const double* b, int n) {
  double mean_a = 0, mean_b = 0, ab = 0, aa = 0, bb = 0;
  for (int i = 0; i < n; ++i) mean_a += a[i] / n, mean_b += b[i] / n;
  for (int i = 0; i < n; ++i)
    ab += (a[i] - mean_a) * (b[i] - mean_b), aa += (a[i] - mean_a) * (a[i] - mean_a),
        bb += (b[i] - mean_b) * (b[i] - mean_b);
  return ab / std::sqrt(aa * bb);
}

}  // namespace

TEST_CASE("the pairs of one sample are independent: the sun sample does not follow the jitter") {
  // Within a pixel, 16 samples of two independent stratified coordinates are paired at random:
  // their correlation r has E[r^2] = 1 / (n - 1) = 1/15. A second pair that followed from the
  // first (a shifted copy, b = a + c mod 1, as shifted R2 pairs were) has E[r^2] = 1/5 over c.
  double squared = 0, mean_first = 0;
  const int pixels = 4096;
  for (int pixel = 0; pixel < pixels; ++pixel) {
    double a[16], b[16];
    for (int i = 0; i < 16; ++i) {
      const Sampler::PixelKeys keys(mix_bits(pixel));
      Sampler sampler(keys, i, 16);
      a[i] = sampler.next().x(), b[i] = sampler.next().x();
      mean_first += a[i] / (16 * pixels);
    }
    const double r = correlation(a, b, 16);
    squared += r * r / pixels;
  }
  CHECK(squared == Approx(1.0 / 15).margin(0.01));
  CHECK(mean_first == Approx(0.5).margin(1e-3));  // stratified: far closer than 1 / sqrt(n)
}
