// OIDN's U-Net on rendered frames (its own published weights, fetched by scripts/install_deps.sh):
// a lit wall gets cleaner, an edge between two instances and a high-contrast albedo pattern
// survive, against references of many samples; the same bytes for any thread count.
#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cmath>

#include "flowscape/renderer/neural_denoise.h"
#include "flowscape/scenes/test_scenes.h"

using namespace flowscape;

namespace {

// Like the pytest tests, these skip (with a warning) where install_deps.sh could not fetch the
// weights (no npm); the suite's U-Net-equals-PyTorch tests use weights written on the spot.
bool weights_fetched() {
  try {
    oidn_weights_file("default");
    return true;
  } catch (const std::exception& missing) {
    WARN("skipped: " << missing.what());
    return false;
  }
}

const UNet& unet() {
  static const UNet net(read_unet_weights(oidn_weights_file("default")));
  return net;
}

Image<float> denoised(const ColorLayers& layers, bool wrap = false) {
  const NeuralFeatures f = neural_features(layers);
  return neural_denoise(unet(), {f.color.view(), f.albedo.view(), f.normal.view(),
                                 autoexposure(f.color.view()), wrap});
}

double rms(const Image<float>& a, const Image<float>& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i) sum += std::pow(a.data[i] - b.data[i], 2);
  return std::sqrt(sum / double(a.data.size()));
}

// A wall 6 m ahead under sky light only (no sun: all of its light is noisy indirect), on the
// left a darker box of another instance (1 m nearer), and on the wall a checker of albedo 0.8 /
// 0.08 in cells of 1.5 m (8 pixels).
Scene wall_scene(bool checkered) {
  Scene scene = textured_plane(6, 40);
  scene.environment.sun_irradiance = Eigen::Vector3f::Zero();
  scene.environment.sun_disc_visibility = 0;
  scene.materials[0].albedo = {0.8f, 0.8f, 0.8f};
  if (checkered) scene.materials[0].pattern = checker(1.5, Eigen::Vector3f::Constant(0.1f));
  Material dark;
  dark.albedo = {0.2f, 0.2f, 0.2f};
  scene.materials.push_back(dark);
  Actor box = sliding_box({4.5, 1.2, 0}, Vec3::Zero(), 1);
  scene.actors.push_back(std::move(box));
  return scene;
}

}  // namespace

TEST_CASE("the U-Net cleans a wall and keeps its edges and its albedo pattern") {
  if (!weights_fetched()) return;
  for (const bool checkered : {false, true}) {
    INFO((checkered ? "checker" : "plain"));
    const Scene scene = wall_scene(checkered);
    Renderer renderer(scene);
    const Projection camera = Projection::cube_face(Face::Front, 64);
    const ColorLayers noisy = renderer.color_layers(camera, FramePair{}, {4, 4, 3});
    const Image<float> reference = renderer.color(camera, FramePair{}, {512, 4, 7});
    const Image<float> raw = raw_color(noisy), clean = denoised(noisy);
    // cleaner: the plain wall at least three times closer to the reference than the raw 4
    // samples; the checker, whose cells' edges are a coverage the samples leave noisy, closer
    CHECK(rms(clean, reference) < rms(raw, reference) / (checkered ? 1.5 : 3));
    // the box's edge (columns 0..31 box, 32.. wall, rows about the centre): the step in brightness
    // between two columns either side stays within 15 % of the reference's
    const GroundTruth truth = renderer.ground_truth(camera, FramePair{});
    int edge = -1;
    for (int x = 1; x < 64 && edge < 0; ++x)
      if (*truth.instance.pixel(x - 1, 32) != *truth.instance.pixel(x, 32)) edge = x;
    REQUIRE(edge > 4);
    const auto column_mean = [&](const Image<float>& image, int x) {
      double sum = 0;
      for (int y = 20; y < 44; ++y) sum += image.pixel(x, y)[1];
      return sum / 24;
    };
    const double step_ref = column_mean(reference, edge + 1) - column_mean(reference, edge - 2);
    const double step = column_mean(clean, edge + 1) - column_mean(clean, edge - 2);
    CHECK(std::abs(step - step_ref) < 0.15 * std::abs(step_ref) + 1e-3);
    if (checkered) {  // the pattern's contrast: the spread of the wall's pixels, within 15 %
      const auto spread = [&](const Image<float>& image) {
        double sum = 0, squares = 0;
        int n = 0;
        for (int y = 0; y < 64; ++y)
          for (int x = edge + 2; x < 64; ++x) {
            const double v = image.pixel(x, y)[1];
            sum += v, squares += v * v, ++n;
          }
        return std::sqrt(squares / n - std::pow(sum / n, 2));
      };
      CHECK(spread(clean) == Approx(spread(reference)).epsilon(0.15));
    }
  }
}

TEST_CASE("the U-Net gives the same bytes with 1 and 2 threads, tiles and all") {
  if (!weights_fetched()) return;
  const Scene scene = wall_scene(true);
  Renderer renderer(scene);
  const Projection erp = Projection::equirectangular(224);  // 448 + 64 wide: two tiles
  const ColorLayers layers = renderer.color_layers(erp, FramePair{}, {1, 1, 5});
  Image<float> one;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = denoised(layers, true);
  }
  CHECK(denoised(layers, true).data == one.data);
}
