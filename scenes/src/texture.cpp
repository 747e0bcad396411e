#include "flowscape/scenes/texture.h"

#include <algorithm>
#include <cmath>

#include "flowscape/core/random.h"

namespace flowscape::tex {
namespace {

double to_unit(std::uint64_t bits) { return double(bits >> 11) * 0x1.0p-53; }

// The fade of value noise and its derivative: 6t^5 - 15t^4 + 10t^3.
double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
double fade_derivative(double t) { return 30 * t * t * (t - 1) * (t - 1); }

// Integral over [0, x] of pulses [0, width) repeating every period.
double pulse_integral(double x, double period, double width) {
  const double n = std::floor(x / period), r = x - n * period;
  return n * width + std::min(r, width);
}

}  // namespace

double hash01(std::int64_t x, std::int64_t y, std::uint64_t seed) {
  return to_unit(mix_bits(seed ^ mix_bits(std::uint64_t(x) * 0x9e3779b97f4a7c15ull ^
                                          std::uint64_t(y) * 0xc2b2ae3d27d4eb4full)));
}

double hash01(std::uint64_t key, std::uint64_t seed) {
  return to_unit(mix_bits(seed ^ mix_bits(key)));
}

Noise value_noise(const Vec2& p, std::uint64_t seed) {
  const double fx = std::floor(p.x()), fy = std::floor(p.y());
  const auto ix = std::int64_t(fx), iy = std::int64_t(fy);
  const double tx = p.x() - fx, ty = p.y() - fy, u = fade(tx), v = fade(ty);
  const auto corner = [&](int dx, int dy) { return 2 * hash01(ix + dx, iy + dy, seed) - 1; };
  const double a = corner(0, 0), b = corner(1, 0), c = corner(0, 1), d = corner(1, 1);
  const double k1 = b - a, k2 = c - a, k3 = a - b - c + d;
  return {a + k1 * u + k2 * v + k3 * u * v,
          {fade_derivative(tx) * (k1 + k3 * v), fade_derivative(ty) * (k2 + k3 * u)}};
}

double visible(double size, double footprint) {
  if (footprint <= 0) return 1;
  return std::clamp(size / footprint - 1, 0.0, 1.0);
}

Noise fbm(const Vec2& p, std::uint64_t seed, double frequency, int octaves, double footprint,
          double gain) {
  // each octave turned by about 37 degrees against the last, so the lattices do not line up
  constexpr double kCos = 0.8, kSin = 0.6;
  Noise sum;
  double amplitude = 1;
  Vec2 q = p;
  Eigen::Matrix2d turned = Eigen::Matrix2d::Identity();  // q = turned * p
  for (int k = 0; k < octaves; ++k, frequency *= 2, amplitude *= gain) {
    const double weight = amplitude * visible(1 / frequency, footprint);
    if (weight <= 0) break;
    const Noise n = value_noise(q * frequency + Vec2(17.3 * k, 5.9 * k), seed + std::uint64_t(k));
    sum.value += weight * n.value;
    sum.gradient += weight * frequency * (turned.transpose() * n.gradient);
    q = Vec2(kCos * q.x() - kSin * q.y(), kSin * q.x() + kCos * q.y());
    turned = Eigen::Matrix2d{{kCos, -kSin}, {kSin, kCos}} * turned;
  }
  return sum;
}

Cells cells(const Vec2& p, double size, std::uint64_t seed) {
  const Vec2 s = p / size;
  const auto ix = std::int64_t(std::floor(s.x())), iy = std::int64_t(std::floor(s.y()));
  Cells out{1e30, 1e30, 0};
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const std::int64_t cx = ix + dx, cy = iy + dy;
      const Vec2 feature(double(cx) + 0.1 + 0.8 * hash01(cx, cy, seed),
                         double(cy) + 0.1 + 0.8 * hash01(cx, cy, seed + 1));
      const double d = (feature - s).norm() * size;
      if (d < out.f1) {
        out.f2 = out.f1, out.f1 = d;
        out.id = mix_bits(std::uint64_t(cx) * 0x9e3779b97f4a7c15ull ^ std::uint64_t(cy));
      } else if (d < out.f2) {
        out.f2 = d;
      }
    }
  return out;
}

double line_coverage(double d, double half_width, double footprint) {
  if (footprint <= 0) return std::abs(d) < half_width ? 1 : 0;
  const double overlap =
      std::min(d + footprint / 2, half_width) - std::max(d - footprint / 2, -half_width);
  return std::clamp(overlap / footprint, 0.0, 1.0);
}

double pulse_train(double x, double period, double width, double footprint) {
  if (footprint <= 0) {
    const double r = x - period * std::floor(x / period);
    return r < width ? 1 : 0;
  }
  return (pulse_integral(x + footprint / 2, period, width) -
          pulse_integral(x - footprint / 2, period, width)) /
         footprint;
}

Bond bond(const Vec2& p, const Vec2& size, double joint, double shift, double footprint) {
  const double row = std::floor(p.y() / size.y());
  const double x = p.x() + (std::fmod(row, 2.0) != 0 ? shift * size.x() : 0);
  const double column = std::floor(x / size.x());
  // joints centred on the brick boundaries
  const double mortar_x = pulse_train(x + joint / 2, size.x(), joint, footprint);
  const double mortar_y = pulse_train(p.y() + joint / 2, size.y(), joint, footprint);
  return {1 - (1 - mortar_x) * (1 - mortar_y),
          mix_bits(std::uint64_t(std::int64_t(column)) * 0x9e3779b97f4a7c15ull ^
                   std::uint64_t(std::int64_t(row))),
          {x / size.x() - column, p.y() / size.y() - row}};
}

double smoothstep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

Eigen::Vector3f mix(const Eigen::Vector3f& a, const Eigen::Vector3f& b, double t) {
  return a + (b - a) * float(t);
}

}  // namespace flowscape::tex
