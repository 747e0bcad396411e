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

// Where the stacked tiles are: a pixel's tile, and whether a row lies in it.
struct Tiles {
  int height;  // the image's when not stacked
  int of(int y) const { return y / height; }
};

// The variance channels, each the mean of the 3 x 3 pixels around (within the tile): the
// estimate from a few samples is itself noisy.
Image<float> smoothed_variance(const Image<float>& variance, bool wraps, Tiles tiles) {
  const int W = variance.width, H = variance.height;
  Image<float> out(W, H, 3);
  tbb::parallel_for(0, H, [&](int y) {
    for (int x = 0; x < W; ++x) {
      std::array<float, 3> sum{};
      int n = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int ny = y + dy;
          int nx = x + dx;
          if (wraps) nx = (nx + W) % W;
          if (nx < 0 || nx >= W || ny < 0 || ny >= H || tiles.of(ny) != tiles.of(y)) continue;
          for (int c = 0; c < 3; ++c) sum[std::size_t(c)] += variance.pixel(nx, ny)[c];
          ++n;
        }
      for (int c = 0; c < 3; ++c) out.pixel(x, y)[c] = sum[std::size_t(c)] / float(n);
    }
  });
  return out;
}

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

// One pixel's running sums: each layer's colour, how many frames it took, its summed variance.
struct Accumulated {
  std::array<std::array<float, 3>, kLayers> color{};
  std::array<int, kLayers> frames{};
  std::array<float, kVarianced> variance{};
};

}  // namespace

ColorLayers temporal_layers(const ColorLayers& centre, ImageView<const std::uint16_t> instance,
                            const std::vector<TemporalNeighbour>& neighbours,
                            const TemporalOptions& options) {
  const int W = centre.direct.width, H = centre.direct.height;
  const Tiles tiles{options.tile_height > 0 ? options.tile_height : H};
  const Image<float> centre_spread = smoothed_variance(centre.variance, options.wraps, tiles);
  std::vector<Image<float>> spread;
  for (const TemporalNeighbour& n : neighbours)
    spread.push_back(smoothed_variance(n.layers->variance, options.wraps, tiles));
  ColorLayers out = centre;
  tbb::parallel_for(0, H, [&](int y) {
    for (int x = 0; x < W; ++x) {
      const std::size_t i = std::size_t(y) * W + x;
      Accumulated sum;
      for (int l = 0; l < kLayers; ++l) {
        for (int c = 0; c < 3; ++c) sum.color[l][c] = (centre.*kLayer[l]).data[3 * i + c];
        sum.frames[l] = 1;
      }
      for (int l = 0; l < kVarianced; ++l) sum.variance[l] = centre.variance.data[3 * i + l];
      const Surface surface{instance.data[i], has_surface(centre, i), tiles.of(y)};
      for (std::size_t k = 0; k < neighbours.size(); ++k) {
        const TemporalNeighbour& n = neighbours[k];
        if (!n.valid.data[i]) continue;
        const Taps taps =
            matching_taps(n, x + 0.5 + n.flow.data[2 * i], y + 0.5 + n.flow.data[2 * i + 1],
                          surface, options.wraps, tiles);
        if (taps.count == 0) continue;
        const std::array<float, 3> their_spread = read(spread[k], taps);
        const std::array<float, 3> their_variance = read(n.layers->variance, taps);
        for (int l = 0; l < kLayers; ++l) {
          const std::array<float, 3> theirs = read(n.layers->*kLayer[l], taps);
          const float mine = luminance(&(centre.*kLayer[l]).data[3 * i]);
          const float other = luminance(theirs.data());
          const float noise =
              l < kVarianced
                  ? std::sqrt(centre_spread.data[3 * i + l] + their_spread[std::size_t(l)])
                  : 0.0f;
          const float tolerance =
              options.sigmas * noise + options.relative_tolerance * std::max(mine, other);
          if (!(std::abs(other - mine) <= tolerance)) continue;
          for (int c = 0; c < 3; ++c) sum.color[l][c] += theirs[std::size_t(c)];
          ++sum.frames[l];
          if (l < kVarianced) sum.variance[l] += their_variance[std::size_t(l)];
        }
      }
      for (int l = 0; l < kLayers; ++l)
        for (int c = 0; c < 3; ++c)
          (out.*kLayer[l]).data[3 * i + c] = sum.color[l][c] / float(sum.frames[l]);
      for (int l = 0; l < kVarianced; ++l)
        out.variance.data[3 * i + l] =
            sum.variance[l] / float(sum.frames[l]) / float(sum.frames[l]);
    }
  });
  return out;
}

}  // namespace flowscape
