#include "flowscape/renderer/denoise.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "camera/cube_faces.h"

namespace flowscape {
namespace {

constexpr int kFiltered = 3;  // direct, indirect (both divided by the albedo), specular

// What the filter's geometric weights compare, per pixel.
struct Features {
  std::vector<Eigen::Vector3f> normal, position;  // unit normal; point relative to the camera
  std::vector<float> footprint;                   // the pixel's width at that point (metres)
  std::vector<std::uint16_t> instance;
  std::vector<char> surface;  // an opaque first surface: its light is filtered
};

Features features(const ColorLayers& layers, const DenoiseGuide& guide) {
  const Projection& camera = *guide.projection;
  const int W = camera.width, H = camera.height;
  const std::size_t n = std::size_t(W) * H;
  Features f{std::vector<Eigen::Vector3f>(n), std::vector<Eigen::Vector3f>(n),
             std::vector<float>(n), std::vector<std::uint16_t>(n), std::vector<char>(n)};
  tbb::parallel_for(0, H, [&](int y) {
    for (int x = 0; x < W; ++x) {
      const std::size_t i = std::size_t(y) * W + x;
      const float* normal = layers.normal.pixel(x, y);
      const double depth = *guide.depth.pixel(x, y);
      const Eigen::Vector3f sum(normal[0], normal[1], normal[2]);
      f.surface[i] = std::isfinite(depth) && sum.norm() > 0;
      if (!f.surface[i]) continue;
      f.normal[i] = sum.normalized();
      f.position[i] = (camera.ray(Vec2(x + 0.5, y + 0.5)).normalized() * depth).cast<float>();
      f.footprint[i] = float(depth * camera.pixel_spread(Vec2(x + 0.5, y + 0.5)));
      f.instance[i] = *guide.instance.pixel(x, y);
    }
  });
  return f;
}

float sharpened(float cosine, int sharpness) {
  float w = cosine > 0 ? cosine : 0;
  for (int k = 0; k < sharpness; ++k) w *= w;
  return w;
}

float luminance(const Eigen::Vector3f& c) {
  return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
}

// A filtered layer: its colour and the variance of its luminance, per pixel.
struct Signal {
  std::vector<Eigen::Vector3f> color;
  std::vector<float> variance;
};

// The light of a layer arriving at the surface: the layer divided by the albedo (0 where there is
// none), its variance likewise.
Signal arriving(const Image<float>& layer, const ColorLayers& layers, int channel, bool divide) {
  const std::size_t n = layer.pixel_count();
  Signal s{std::vector<Eigen::Vector3f>(n), std::vector<float>(n)};
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f albedo(layers.albedo.data[3 * i], layers.albedo.data[3 * i + 1],
                                 layers.albedo.data[3 * i + 2]);
    const float a = divide ? luminance(albedo) : 1;
    for (int c = 0; c < 3; ++c) {
      const float by = divide ? albedo[c] : 1;
      s.color[i][c] = by > 1e-6f ? layer.data[3 * i + c] / by : 0;
    }
    s.variance[i] = a > 1e-6f ? layers.variance.data[3 * i + channel] / (a * a) : 0;
  }
  return s;
}

// One a-trous level over the layers that have it (DenoiseOptions::levels; the others pass
// through): each pixel the weighted mean of its 3 x 3 neighbours 2^level apart. Weights: the
// B-spline taps, the plane (depth) and normal agreement and the same instance, shared by the
// layers, times each layer's luminance agreement within its noise (Schied et al. 2017); the
// variances follow as sum w^2 var / (sum w)^2.
void filter_level(const Features& f, int W, int H, bool wraps, int level,
                  const DenoiseOptions& options, const std::array<Signal, kFiltered>& in,
                  std::array<Signal, kFiltered>& out) {
  static constexpr float kTaps[3] = {0.25f, 0.5f, 0.25f};
  const int step = 1 << level;
  std::array<bool, kFiltered> filtered;
  for (int l = 0; l < kFiltered; ++l) {
    filtered[l] = level < options.levels[l];
    if (!filtered[l]) out[l] = in[l];
  }
  tbb::parallel_for(0, H, [&](int y) {
    for (int x = 0; x < W; ++x) {
      const std::size_t p = std::size_t(y) * W + x;
      if (!f.surface[p]) {
        for (int l = 0; l < kFiltered; ++l)
          out[l].color[p] = in[l].color[p], out[l].variance[p] = in[l].variance[p];
        continue;
      }
      const float tolerance = options.plane_tolerance * f.footprint[p] * float(step);
      std::array<float, kFiltered> scale, centre, total{}, variance{};
      std::array<Eigen::Vector3f, kFiltered> sum;
      for (int l = 0; l < kFiltered; ++l) {
        scale[l] = options.luminance_tolerance[l] * std::sqrt(in[l].variance[p]) + 1e-6f;
        centre[l] = luminance(in[l].color[p]);
        sum[l].setZero();
      }
      for (int dy = -1; dy <= 1; ++dy) {
        const int qy = y + dy * step;
        if (qy < 0 || qy >= H) continue;
        for (int dx = -1; dx <= 1; ++dx) {
          int qx = x + dx * step;
          if (wraps) qx = ((qx % W) + W) % W;
          if (qx < 0 || qx >= W) continue;
          const std::size_t q = std::size_t(qy) * W + qx;
          if (!f.surface[q] || f.instance[q] != f.instance[p]) continue;
          const float off_plane = std::abs(f.normal[p].dot(f.position[q] - f.position[p]));
          if (off_plane >= tolerance) continue;
          const float geometric = kTaps[dx + 1] * kTaps[dy + 1] * (1 - off_plane / tolerance) *
                                  sharpened(f.normal[p].dot(f.normal[q]), options.normal_sharpness);
          for (int l = 0; l < kFiltered; ++l) {
            if (!filtered[l]) continue;
            const float w =
                options.luminance_tolerance[l] > 0
                    ? geometric *
                          std::exp(-std::abs(luminance(in[l].color[q]) - centre[l]) / scale[l])
                    : geometric;
            sum[l] += w * in[l].color[q], total[l] += w, variance[l] += w * w * in[l].variance[q];
          }
        }
      }
      for (int l = 0; l < kFiltered; ++l) {
        if (!filtered[l]) continue;
        out[l].color[p] = sum[l] / total[l];  // the centre's own weight is positive
        out[l].variance[p] = variance[l] / (total[l] * total[l]);
      }
    }
  });
}

}  // namespace

Image<float> denoise(const ColorLayers& layers, const DenoiseGuide& guide,
                     const DenoiseOptions& options) {
  const Projection& camera = *guide.projection;
  const int W = camera.width, H = camera.height;
  if (layers.indirect.width != W || layers.indirect.height != H || guide.depth.width != W ||
      guide.depth.height != H || guide.instance.width != W || guide.instance.height != H)
    throw std::invalid_argument("denoise: layers, guide and camera differ in size");
  const Features f = features(layers, guide);
  const std::size_t n = std::size_t(W) * H;
  std::array<Signal, kFiltered> light{arriving(layers.direct, layers, 0, true),
                                      arriving(layers.indirect, layers, 1, true),
                                      arriving(layers.specular, layers, 2, false)},
      next = light;
  const bool wraps = camera.wraps_around();
  const int levels = *std::max_element(options.levels, options.levels + kFiltered);
  for (int level = 0; level < levels; ++level) {
    filter_level(f, W, H, wraps, level, options, light, next);
    light.swap(next);
  }
  Image<float> color = layers.other;
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const float albedo = layers.albedo.data[3 * i + c];
      color.data[3 * i + c] +=
          f.surface[i]
              ? albedo * (light[0].color[i][c] + light[1].color[i][c]) + light[2].color[i][c]
              : layers.direct.data[3 * i + c] + layers.indirect.data[3 * i + c] +
                    layers.specular.data[3 * i + c];
    }
  return color;
}

Image<float> denoise_cube(const ColorLayers& c, const GroundTruth& truth,
                          const DenoiseOptions& options) {
  const int N = c.direct.width;
  Image<float> out(N, 6 * N, 3);
  for (Face face : kFaces) {
    const ColorLayers layers = face_of(c, face);
    const Image<float> depth = face_of(truth.depth, face);
    const Image<std::uint16_t> instance = face_of(truth.instance, face);
    const Projection camera = Projection::cube_face(face, N);
    const Image<float> color = denoise(layers, {&camera, depth.view(), instance.view()}, options);
    std::copy(color.data.begin(), color.data.end(), face_view(out.view(), face).data);
  }
  return out;
}

}  // namespace flowscape
