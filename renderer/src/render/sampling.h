#pragma once
// Internal: the path tracer's random numbers and the directions and reflectances it samples.
#include <array>
#include <cmath>
#include <cstdint>

#include "flowscape/core/random.h"
#include "flowscape/geometry/geometry.h"

namespace flowscape {

// Owen-scrambled Sobol points (Burley 2020, "Practical Hash-based Owen Scrambling"), padded pair
// by pair as pbrt-v4's PaddedSobolSampler does: each pair of dimensions is a (0,2)-sequence over
// the samples of a pixel, and each pair takes the samples in its own random order (a permutation
// of the power-of-two block they fill), so the pairs of one sample are independent of each other
// (a sample's sun direction does not follow from its position in the pixel).
namespace sobol {

inline std::uint32_t reverse_bits(std::uint32_t x) {
  x = (x << 16) | (x >> 16);
  x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
  x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
  x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
  return ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
}

// Laine and Karras's hash, a random permutation of the bits below each bit.
inline std::uint32_t laine_karras(std::uint32_t x, std::uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

inline std::uint32_t owen_scramble(std::uint32_t x, std::uint32_t seed) {
  return reverse_bits(laine_karras(reverse_bits(x), seed));
}

// The second dimension of the Sobol sequence (the first is reverse_bits of the index) for the
// bits of an index from bit `shift` on (a byte of it): the XOR of the direction numbers it has.
constexpr std::array<std::uint32_t, 256> second_dimension_table(int shift) {
  std::array<std::uint32_t, 256> table{};
  std::uint32_t directions[32] = {};
  for (std::uint32_t v = 1u << 31, k = 0; k < 32; ++k, v ^= v >> 1) directions[k] = v;
  for (std::uint32_t byte = 0; byte < 256; ++byte)
    for (int k = 0; k < 8; ++k)
      if (byte >> k & 1) table[byte] ^= directions[shift + k];
  return table;
}

inline std::uint32_t second_dimension(std::uint32_t index) {  // index < 2^16
  static constexpr std::array<std::uint32_t, 256> kLow = second_dimension_table(0),
                                                  kHigh = second_dimension_table(8);
  return kLow[index & 0xffu] ^ kHigh[index >> 8 & 0xffu];
}

// A random permutation of 0 .. 2^bits - 1 chosen by `key`: Kensler's hash ("Correlated
// Multi-Jittered Sampling", 2013), a bijection on the low bits.
inline std::uint32_t permute(std::uint32_t i, int bits, std::uint32_t key) {
  const std::uint32_t w = (1u << bits) - 1;
  i ^= key, i *= 0xe170893du, i ^= key >> 16, i ^= (i & w) >> 4;
  i ^= key >> 8, i *= 0x0929eb3fu, i ^= key >> 23, i ^= (i & w) >> 1;
  i *= 1 | key >> 27, i *= 0x6935fa69u, i ^= (i & w) >> 11, i *= 0x74dcb303u;
  i ^= (i & w) >> 2, i *= 0x9e501cc3u, i ^= (i & w) >> 2, i *= 0xc860a3dfu;
  i &= w, i ^= i >> 5;
  return (i + key) & w;
}

// Point `index` of a block of 2^bits (bits <= 16), in the order chosen by the bits of `order` and
// with the scrambles in the bits of `scrambles`. The order is two rounds of the hash: one leaves
// small blocks' orders visibly related (pairs' correlation over 16 samples: E[r^2] 0.085 where a
// random order gives 1/15). An index beyond the block takes the Sobol points after it in order, so
// that extra samples of a pixel (its edge samples) fill the gaps between its block's.
inline Vec2 point(std::uint32_t index, int bits, std::uint64_t order, std::uint64_t scrambles) {
  const std::uint32_t shuffled = index >> bits ? index
                                               : permute(permute(index, bits, std::uint32_t(order)),
                                                         bits, std::uint32_t(order >> 32));
  return {owen_scramble(reverse_bits(shuffled), std::uint32_t(scrambles)) * 0x1.0p-32,
          owen_scramble(second_dimension(shuffled), std::uint32_t(scrambles >> 32)) * 0x1.0p-32};
}

}  // namespace sobol

// The random numbers of sample `index` of the `count` of one pixel: pairs of dimensions. The first
// kStratifiedPairs (the pixel jitter and the first surface's light, lobe and choice: where
// stratification pays) are Owen-scrambled Sobol points, each pair with its own scrambles and
// sample order (from the pixel's key and the pair); the pairs after them, deeper in the path where
// the paths of a pixel have spread apart, are plain hashed uniforms at a tenth of the cost.
// Counts above 2^16 repeat the first 2^16 Sobol points.
class Sampler {
 public:
  static constexpr int kStratifiedPairs = 4;
  // The orders and scrambles of a pixel's stratified pairs, shared by its samples.
  struct PixelKeys {
    explicit PixelKeys(std::uint64_t pixel_key) : pixel(pixel_key) {
      for (int p = 0; p < kStratifiedPairs; ++p)
        order[p] = pair_key(pixel_key, p + 1), scrambles[p] = mix_bits(order[p]);
    }
    std::uint64_t pixel, order[kStratifiedPairs], scrambles[kStratifiedPairs];
  };

  Sampler() = default;
  Sampler(const PixelKeys& keys, int index, int count)
      : keys_(&keys), index_(std::uint32_t(index) & 0xffffu), bits_(block_bits(count)) {}
  Vec2 next() {
    if (++pair_ <= kStratifiedPairs)
      return sobol::point(index_, bits_, keys_->order[pair_ - 1], keys_->scrambles[pair_ - 1]);
    const std::uint64_t bits = mix_bits(pair_key(keys_->pixel, pair_) ^ index_);
    return {double(bits >> 40) * 0x1.0p-24, double(bits >> 8 & 0xffffffu) * 0x1.0p-24};
  }
  // The sample's time over a shutter (motion blur) in [0, 1): stratified over the pixel's samples
  // in an order of its own, so that it follows neither the jitter nor the light's pairs.
  double time() const {
    const std::uint64_t key = pair_key(keys_->pixel, 0);
    return sobol::point(index_, bits_, key, mix_bits(key)).x();
  }

 private:
  static std::uint64_t pair_key(std::uint64_t pixel_key, int pair) {
    return mix_bits(pixel_key + 0x9e3779b97f4a7c15ull * std::uint64_t(pair));
  }
  static int block_bits(int count) {  // of the power of two that holds `count` samples
    int bits = 0;
    while (bits < 16 && (1 << bits) < count) ++bits;
    return bits;
  }
  const PixelKeys* keys_ = nullptr;
  std::uint32_t index_ = 0;
  int pair_ = 0, bits_ = 0;
};

// Orthonormal frame around n (Duff et al. 2017).
inline Mat3 frame_around(const Vec3& n) {
  const double sign = std::copysign(1.0, n.z()), a = -1 / (sign + n.z()), b = n.x() * n.y() * a;
  Mat3 m;
  m.col(0) = Vec3(1 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  m.col(1) = Vec3(b, sign + n.y() * n.y() * a, -n.y());
  m.col(2) = n;
  return m;
}

inline Vec3 cosine_direction(const Vec3& n, Vec2 u) {
  const double r = std::sqrt(u.x());
  const SinCos phi = sin_cos(2 * kPi * u.y());
  return frame_around(n) * Vec3(r * phi.cos, r * phi.sin, std::sqrt(std::max(0.0, 1 - u.x())));
}

inline Vec3 reflect(const Vec3& d, const Vec3& n) { return d - 2 * d.dot(n) * n; }

inline double schlick(double cos_i, double f0) {
  const double m = 1 - cos_i, m2 = m * m;
  return f0 + (1 - f0) * m2 * m2 * m;
}

// Fresnel reflectance of a smooth dielectric; 1 for total internal reflection.
inline double dielectric_fresnel(double cos_i, double eta) {  // eta = n_incident / n_transmitted
  const double sin2_t = eta * eta * (1 - cos_i * cos_i);
  if (sin2_t >= 1) return 1;
  const double cos_t = std::sqrt(1 - sin2_t);
  const double rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const double rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return (rs * rs + rp * rp) / 2;
}

}  // namespace flowscape
