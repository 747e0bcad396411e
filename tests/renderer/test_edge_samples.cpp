// Edge samples (RenderOptions::edge_samples): at the edges of what a camera ray meets before any
// surface (an emitter, the sky) the pixel's coverage is sampled by extra camera rays; checked
// against the closed-form coverage of a board's vertical edge, glowing against a black sky and
// diffuse against a uniform sky (where the surface's light is scaled by the finer coverage: the
// ratio estimator).
#include <catch2/catch.hpp>
#include <cmath>

#include "flowscape/renderer/renderer.h"
#include "flowscape/scenes/shapes.h"
#include "independent_math.h"

using namespace flowscape;

namespace {

constexpr double kFront = 9.95;  // metres from the camera to the board's face
constexpr int kWidth = 64, kHeight = 16;
const double kFocal = kWidth / 2.0 / std::tan(30 * indep::pi / 180);  // a 60-degree pinhole

// The board's left edge in image columns when it reaches `left` metres left of the axis (between
// 1.3 and 1.36 m: all in column 12).
double edge_column(double left) { return kWidth / 2.0 - kFocal * left / kFront; }

// A still board facing a camera at the origin looking along +x, from `left` metres left of the
// axis to far right of the image, past its top and bottom, made of `board_material`, under a sky
// of radiance `sky` everywhere (below the horizon too) and no sun.
Scene board_scene(const Material& board_material, float sky, double left) {
  Scene scene;
  Environment& e = scene.environment;
  e.sky_zenith = e.sky_horizon = e.ground = Eigen::Vector3f::Constant(sky);
  e.sun_irradiance = Eigen::Vector3f::Zero();
  scene.materials = {board_material};
  add_box(scene.world, Eigen::Vector3f(9.95f, -30, -8), Eigen::Vector3f(10.05f, float(left), 8),
          SemanticClass::Vehicles);
  return scene;
}

// The largest difference over the rows of column `x` between the raw colour's first channel and
// `expected`; adds the squared differences to `squares`.
double worst_in_column(const Image<float>& color, int x, double expected, double& squares) {
  double worst = 0;
  for (int y = 0; y < kHeight; ++y) {
    const double difference = std::abs(color.pixel(x, y)[0] - expected);
    worst = std::max(worst, difference), squares += difference * difference;
  }
  return worst;
}

Image<float> render(const Scene& scene, int edge_samples, std::uint64_t seed) {
  RenderOptions options{8, 1, seed};
  options.edge_samples = edge_samples;
  Renderer renderer(scene);
  return renderer.color(Projection::pinhole(kWidth, kHeight, 60),
                        FramePair{0, 0, Pose::Identity(), Pose::Identity()}, options);
}

// Renders the board with its edge at six places across a column, each with its own seed, with
// edge samples and without, and checks the edge's column against `expected(c)` for its coverage
// c: every pixel within `light` / 32 with them (32 samples stratified across the pixel's width:
// each of 32 columns of it holds one) and `light` / 8 without, and their mean squared error
// smaller than a quarter of the one without. Returns the image with edge samples of the last.
template <class Expected>
Image<float> check_edges(const Material& board, float sky, double light, const Expected& expected,
                         std::uint64_t seed) {
  double fine_squares = 0, coarse_squares = 0;
  Image<float> color;
  for (int k = 0; k < 6; ++k) {
    const double left = 1.3 + 0.01 * k, edge = edge_column(left);
    const int column = int(edge);
    const double value = expected(column + 1 - edge);
    const Scene scene = board_scene(board, sky, left);
    color = render(scene, 32, seed + k);
    const double fine = worst_in_column(color, column, value, fine_squares);
    const double coarse =
        worst_in_column(render(scene, 0, seed + k), column, value, coarse_squares);
    INFO("coverage " << column + 1 - edge << ": worst " << fine << " with edge samples, " << coarse
                     << " without");
    CHECK(fine <= light / 32 + 1e-3 * light);
    CHECK(coarse <= light / 8 + 1e-3 * light);
  }
  INFO("mean squared error " << fine_squares / 96 << " with edge samples, " << coarse_squares / 96
                             << " without");
  CHECK(fine_squares < coarse_squares / 4);
  return color;
}

}  // namespace

TEST_CASE("edge samples bring a glowing edge's pixels to their coverage within 1/32") {
  Material glow;
  glow.kind = Material::Kind::Emissive, glow.emission = {1, 1, 1};
  const Image<float> color = check_edges(
      glow, 0, 1, [](double c) { return c; }, 1);
  // away from the edge nothing changes: the board glows 1, the sky is black
  const int column = int(edge_column(1.35));
  CHECK(color.pixel(column + 2, 5)[0] == Approx(1));
  CHECK(color.pixel(column - 2, 5)[0] == 0);
}

TEST_CASE("at a diffuse board's edge against the sky the surface's light follows the coverage") {
  // A board of albedo 0.5 under a uniform sky of radiance 1 reflects 0.5 (its hemisphere is all
  // sky; one cosine-sampled bounce finds exactly that), so a pixel covering c of it is
  // 0.5 c + (1 - c): the surface layers scaled to the edge samples' coverage keep that within
  // 0.5 / 32; taken from the pixel's own 8 samples they would err by up to 0.5 / 8.
  Material diffuse;
  diffuse.albedo = {0.5f, 0.5f, 0.5f};
  const Image<float> color = check_edges(
      diffuse, 1, 0.5, [](double c) { return 0.5 * c + (1 - c); }, 11);
  CHECK(color.pixel(int(edge_column(1.35)) + 2, 5)[0] == Approx(0.5).epsilon(1e-3));
}
