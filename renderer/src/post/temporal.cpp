#include "flowscape/renderer/temporal.h"

#include <tbb/parallel_for.h>

#include <array>
#include <cmath>

namespace flowscape {
namespace {

constexpr int kLayers = 4;     // direct, indirect, specular, other
constexpr int kVarianced = 3;  // the first three carry a variance (ColorLayers::variance)
Image<float> ColorLayers::*const kLayer[kLayers] = {&ColorLayers::direct, &ColorLayers::indirect,
                                                    &ColorLayers::specular, &ColorLayers::other};

float luminance(const float* c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; }

bool has_surface(const ColorLayers& layers, std::size_t i) {
  const float* n = &layers.normal.data[3 * i];
  return n[0] != 0 || n[1] != 0 || n[2] != 0;
}

// The stacked tiles (the cube's faces) a row belongs to.
struct Tiles {
  int height;  // the image's when not stacked
  int of(int y) const { return y / height; }
};

// The bilinear taps around a continuous position (pixel centres at +0.5) of a neighbour that show
// the centre pixel's surface, their weights summing to 1 (none: it shows another one there).
struct Taps {
  std::array<std::size_t, 4> index{};
  std::array<float, 4> weight{};
  int count = 0;
};

// What a tap must match: the centre pixel's instance, surface or not, and tile.
struct Surface {
  std::uint16_t instance;
  bool surface;
  int tile;
};

Taps matching_taps(const TemporalNeighbour& n, double px, double py, const Surface& centre,
                   bool wraps, Tiles tiles) {
  const int W = n.instance.width, H = n.instance.height;
  const double u = px - 0.5, v = py - 0.5;
  const int x0 = int(std::floor(u)), y0 = int(std::floor(v));
  const float fx = float(u - x0), fy = float(v - y0);
  Taps taps;
  float total = 0;
  for (int k = 0; k < 4; ++k) {
    int x = x0 + (k & 1);
    const int y = y0 + (k >> 1);
    if (wraps) x = ((x % W) + W) % W;
    if (x < 0 || x >= W || y < 0 || y >= H || tiles.of(y) != centre.tile) continue;
    const std::size_t i = std::size_t(y) * W + x;
    if (n.instance.data[i] != centre.instance || has_surface(*n.layers, i) != centre.surface)
      continue;
    const float w = ((k & 1) ? fx : 1 - fx) * ((k >> 1) ? fy : 1 - fy);
    if (w <= 0) continue;
    taps.index[std::size_t(taps.count)] = i, taps.weight[std::size_t(taps.count)] = w;
    ++taps.count, total += w;
  }
  if (total < 1e-3f) return {};
  for (int k = 0; k < taps.count; ++k) taps.weight[std::size_t(k)] /= total;
  return taps;
}

// The taps' weighted mean of a 3-channel image.
std::array<float, 3> read(const Image<float>& image, const Taps& taps) {
  std::array<float, 3> v{};
  for (int k = 0; k < taps.count; ++k)
    for (int c = 0; c < 3; ++c)
      v[std::size_t(c)] +=
          taps.weight[std::size_t(k)] * image.data[3 * taps.index[std::size_t(k)] + c];
  return v;
}

// A neighbour's layers read where frame t's pixels are seen in it (found: a matching surface
// there): colour, luminance and variance per layer.
struct Reprojected {
  std::array<Image<float>, kLayers> color;  // empty for frame t's own (own_layers)
  std::array<std::vector<float>, kLayers> luminance, variance;
  std::vector<char> found;
};

// The luminance and variance of each layer of frame t's own pixels, in Reprojected's form (their
// colour stays in `layers`).
Reprojected own_layers(const ColorLayers& layers) {
  const std::size_t n = layers.direct.pixel_count();
  Reprojected own;
  own.found.assign(n, 1);
  for (int l = 0; l < kLayers; ++l) {
    own.luminance[l].resize(n), own.variance[l].assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      own.luminance[l][i] = luminance(&(layers.*kLayer[l]).data[3 * i]);
      if (l < kVarianced) own.variance[l][i] = layers.variance.data[3 * i + l];
    }
  }
  return own;
}

Reprojected reprojected(const TemporalNeighbour& n, const ColorLayers& centre,
                        ImageView<const std::uint16_t> instance, const TemporalOptions& options,
                        Tiles tiles) {
  const int W = centre.direct.width, H = centre.direct.height;
  const std::size_t count = centre.direct.pixel_count();
  Reprojected r;
  r.found.assign(count, 0);
  for (int l = 0; l < kLayers; ++l)
    r.color[l] = Image<float>(W, H, 3), r.luminance[l].assign(count, 0),
    r.variance[l].assign(count, 0);
  tbb::parallel_for(0, H, [&](int y) {
    for (int x = 0; x < W; ++x) {
      const std::size_t i = std::size_t(y) * W + x;
      if (!n.valid.data[i]) continue;
      const Surface surface{instance.data[i], has_surface(centre, i), tiles.of(y)};
      const Taps taps =
          matching_taps(n, x + 0.5 + n.flow.data[2 * i], y + 0.5 + n.flow.data[2 * i + 1], surface,
                        options.wraps, tiles);
      if (taps.count == 0) continue;
      r.found[i] = 1;
      const std::array<float, 3> variance = read(n.layers->variance, taps);
      for (int l = 0; l < kLayers; ++l) {
        const std::array<float, 3> color = read(n.layers->*kLayer[l], taps);
        std::copy(color.begin(), color.end(), &r.color[l].data[3 * i]);
        r.luminance[l][i] = luminance(color.data());
        if (l < kVarianced) r.variance[l][i] = variance[std::size_t(l)];
      }
    }
  });
  return r;
}

// Whether `a` and `b` (luminance means with these variances) differ by no more than their noise
// explains; without a variance (the 'other' layer), by no more than the relative tolerance.
bool agree(double a, double b, double variance, const TemporalOptions& options) {
  const double tolerance = variance > 0 ? options.sigmas * std::sqrt(variance)
                                        : options.relative_tolerance * std::max(a, b);
  return std::abs(a - b) <= tolerance;
}

// Whether a neighbour's layer l agrees with the centre's at pixel (x, y): the pixels themselves
// (the centre's variance the 3 x 3 mean around it, a steadier estimate, plus the neighbour's read
// at its taps), and the means over the 3 x 3 pixels where the neighbour was found (a shading change
// too small to see in one noisy pixel shows in nine).
bool agrees(const Reprojected& own, const Reprojected& their, int l, int x, int y, int W, int H,
            const TemporalOptions& options, Tiles tiles) {
  double mine = 0, theirs = 0, variance = 0, spread = 0;
  int found = 0, around = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int ny = y + dy;
      int nx = x + dx;
      if (options.wraps) nx = (nx + W) % W;
      if (nx < 0 || nx >= W || ny < 0 || ny >= H || tiles.of(ny) != tiles.of(y)) continue;
      const std::size_t q = std::size_t(ny) * W + nx;
      spread += own.variance[l][q], ++around;
      if (!their.found[q]) continue;
      mine += own.luminance[l][q], theirs += their.luminance[l][q];
      variance += own.variance[l][q] + their.variance[l][q], ++found;
    }
  const std::size_t i = std::size_t(y) * W + x;
  const double pixel_variance = spread / around + their.variance[l][i];
  return agree(own.luminance[l][i], their.luminance[l][i], pixel_variance, options) &&
         agree(mine / found, theirs / found, variance / (double(found) * found), options);
}

}  // namespace

ColorLayers temporal_layers(const ColorLayers& centre, ImageView<const std::uint16_t> instance,
                            const std::vector<TemporalNeighbour>& neighbours,
                            const TemporalOptions& options) {
  const int W = centre.direct.width, H = centre.direct.height;
  const Tiles tiles{options.tile_height > 0 ? options.tile_height : H};
  const Reprojected own = own_layers(centre);
  std::vector<Reprojected> theirs;
  for (const TemporalNeighbour& n : neighbours)
    theirs.push_back(reprojected(n, centre, instance, options, tiles));
  ColorLayers out = centre;
  tbb::parallel_for(0, H, [&](int y) {
    for (int x = 0; x < W; ++x) {
      const std::size_t i = std::size_t(y) * W + x;
      for (int l = 0; l < kLayers; ++l) {
        std::array<double, 3> color{};
        double variance = own.variance[l][i];
        int frames = 1;
        for (int c = 0; c < 3; ++c) color[std::size_t(c)] = (centre.*kLayer[l]).data[3 * i + c];
        for (const Reprojected& their : theirs) {
          if (!their.found[i] || !agrees(own, their, l, x, y, W, H, options, tiles)) continue;
          for (int c = 0; c < 3; ++c) color[std::size_t(c)] += their.color[l].data[3 * i + c];
          variance += their.variance[l][i], ++frames;
        }
        for (int c = 0; c < 3; ++c)
          (out.*kLayer[l]).data[3 * i + c] = float(color[std::size_t(c)] / frames);
        if (l < kVarianced) out.variance.data[3 * i + l] = float(variance / frames / frames);
      }
    }
  });
  return out;
}

}  // namespace flowscape
