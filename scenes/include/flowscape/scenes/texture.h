#pragma once
// Textures fixed to surfaces. A Pattern is a procedural texture evaluated at a surface point's
// texture coordinates (uv; metres along the surface for the built-in city) or its position in the
// object's own frame, so it moves exactly with the surface and the flow stays exact. Every pattern
// is filtered over the pixel's footprint (its width in uv units): detail finer than the footprint
// fades to its mean instead of aliasing, like a mip-map. The functions below are the library the
// city's materials are made of (after pbrt-v4's textures): band-limited value-noise fBm, Worley
// cells, box-filtered pulse trains for bricks, tiles and stripes, and line coverage for cracks.
#include <Eigen/Core>
#include <cstdint>
#include <functional>

#include "flowscape/core/types.h"

namespace flowscape {

// Where a texture is looked up.
struct TexturePoint {
  Vec2 uv = Vec2::Zero();        // texture coordinates
  Vec3 position = Vec3::Zero();  // in the object's own frame
  double footprint = 0;          // filter width in uv units (0: a point sample)
};

// What a surface looks like at a point.
struct SurfaceLook {
  Eigen::Vector3f albedo{0.6f, 0.6f, 0.6f};  // linear reflectance
  float roughness = 0.1f;                    // of the glossy and metal lobes
  Vec2 slope = Vec2::Zero();                 // bump: gradient of the height field over uv (m / m)
};

// A procedural texture: the look at a point, given the material's own (its albedo and roughness,
// which weather may have changed: wet ground is darker).
using Pattern = std::function<SurfaceLook(const TexturePoint& at, const SurfaceLook& base)>;

namespace tex {

// A hash of a lattice point, uniform in [0, 1).
double hash01(std::int64_t x, std::int64_t y, std::uint64_t seed);
double hash01(std::uint64_t key, std::uint64_t seed);

struct Noise {
  double value = 0;
  Vec2 gradient = Vec2::Zero();  // d value / d p
};
// Value noise in [-1, 1] with a quintic fade (C2), and its exact gradient.
Noise value_noise(const Vec2& p, std::uint64_t seed);
// Fractal sum of value noise: `octaves` octaves from `frequency` (cycles per uv unit) up, each
// twice as fine and `gain` times as strong (the first has amplitude 1). Octaves whose wavelength is
// below two footprints fade out (their mean is 0), so the sum never aliases.
Noise fbm(const Vec2& p, std::uint64_t seed, double frequency, int octaves, double footprint,
          double gain = 0.5);

// How much of a feature of size `size` survives a filter of width `footprint`: 1 while it spans
// two footprints or more, 0 at one footprint or less.
double visible(double size, double footprint);

// Worley cells on a jittered grid of spacing `size`: distances to the nearest and second nearest
// feature points (uv units) and the nearest one's cell.
struct Cells {
  double f1 = 0, f2 = 0;
  std::uint64_t id = 0;
};
Cells cells(const Vec2& p, double size, std::uint64_t seed);

// The share of the box [d - footprint / 2, d + footprint / 2] inside [-half_width, half_width]:
// a line of width 2 half_width seen at signed distance d, box-filtered.
double line_coverage(double d, double half_width, double footprint);
// The share of the box around x inside pulses [0, width) that repeat every `period`.
double pulse_train(double x, double period, double width, double footprint);

// Courses of bricks (or tiles, slabs, panels) of `size` including one joint, every other course
// shifted by `shift` of a length. Mortar: the filtered share of joint under the footprint.
struct Bond {
  double mortar = 0;
  std::uint64_t unit = 0;     // which brick
  Vec2 local = Vec2::Zero();  // position in the brick, [0, 1)^2
};
Bond bond(const Vec2& p, const Vec2& size, double joint, double shift, double footprint);

double smoothstep(double edge0, double edge1, double x);
Eigen::Vector3f mix(const Eigen::Vector3f& a, const Eigen::Vector3f& b, double t);

}  // namespace tex
}  // namespace flowscape
