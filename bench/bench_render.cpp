// Renderer throughput on a street-like fixture (ground, 300 buildings, 60 driving boxes, sun and
// sky): primary-ray ground truth and path-traced colour in million rays per second per core, and
// seconds per panoramic frame (6 x F^2 faces stitched to H x 2H ERP) next to a primary-rays-only
// frame. Usage: bench_render [face size (0: no cube rig)] [ERP height] [samples per pixel]
// [threads]; then each camera model's cost per pixel against a pinhole face of the same size
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "flowscape/renderer/renderer.h"
#include "flowscape/renderer/rig.h"
#include "flowscape/scenes/test_scenes.h"
#include "flowscape/stitcher/stitch.h"

using namespace flowscape;

namespace {

Scene street_fixture() {
  Scene scene;
  Material facade;
  facade.albedo = {0.7f, 0.6f, 0.5f};
  facade.pattern = checker(1.5, {0.2f / 0.7f, 0.25f / 0.6f, 0.3f / 0.5f});
  Material paint;
  paint.kind = Material::Kind::Glossy, paint.albedo = {0.6f, 0.1f, 0.1f};
  scene.materials = {Material{}, facade, paint};
  add_box(scene.world, Eigen::Vector3f(-200, -200, -1), Eigen::Vector3f(200, 200, 0),
          SemanticClass::Road);
  std::uint32_t state = 12345;
  const auto random = [&state] { return (state = state * 1664525u + 1013904223u) / 4294967296.0f; };
  for (int b = 0; b < 300; ++b) {
    const float x = -180 + 360 * random(), y = -180 + 360 * random();
    if (std::abs(y) < 12) continue;  // keep the road free
    const float w = 6 + 10 * random(), h = 8 + 32 * random();
    add_box(scene.world, Eigen::Vector3f(x, y, 0), Eigen::Vector3f(x + w, y + w, h),
            SemanticClass::Building);
  }
  scene.world.materials.assign(scene.world.triangles.size(), 1);
  scene.world.materials[0] = scene.world.materials[1] = 0;
  for (int c = 0; c < 60; ++c) {
    const double x0 = -150 + 300 * random(), lane = random() < 0.5 ? -4 : 4, speed = lane * 3;
    Actor car{std::uint16_t(c + 1), {}, [x0, lane, speed](double t) {
                return Pose(Eigen::Translation3d(x0 + speed * t, lane, 0.8));
              }};
    Mesh body;
    add_box(body, Eigen::Vector3f(-2.2f, -0.9f, -0.8f), Eigen::Vector3f(2.2f, 0.9f, 0.7f),
            SemanticClass::Vehicles);
    body.materials.assign(body.triangles.size(), 2);
    car.parts.push_back(rigid_part(std::move(body)));
    scene.actors.push_back(std::move(car));
  }
  return scene;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Each camera model's cost per pixel it sees (ground truth, colour), against the pinhole face of
// the same size in the same run; images F wide (the dual fisheye's two halves F / 2 high). The
// views see different parts of the street, so scene content moves the figures too.
void camera_models(Renderer& renderer, const FramePair& frames, const RenderOptions& options,
                   int F) {
  struct Model {
    const char* name;
    Projection projection;
  };
  const Mat3 forward = face_rotation(Face::Front);
  const std::vector<Model> models{
      {"pinhole face (baseline)", Projection::cube_face(Face::Front, F)},
      {"pinhole, OpenCV distortion",
       Projection::of_lens(
           make_lens("pinhole",
                     {{"width", F},
                      {"height", F},
                      {"K", {{F / 2.0, 0, F / 2.0 - 0.5}, {0, F / 2.0, F / 2.0 - 0.5}, {0, 0, 1}}},
                      {"D", {-0.2, 0.05, 0.001, 0.001, 0}}}),
           forward)},
      {"Kannala-Brandt 200", Projection::of_lens(kannala_brandt_200(F), forward)},
      {"double sphere",
       Projection::of_lens(
           make_lens("double_sphere",
                     {{"width", F},
                      {"height", F},
                      {"K", {{F / 4.0, 0, F / 2.0 - 0.5}, {0, F / 4.0, F / 2.0 - 0.5}, {0, 0, 1}}},
                      {"xi", -0.2},
                      {"alpha", 0.6},
                      {"max_angle_degrees", 100}}),
           forward)},
      {"WoodScape 190", Projection::of_lens(woodscape_190(F, F * 3 / 4), forward)},
      {"dual fisheye 190", Projection::of_lens(dual_fisheye_190(F / 2), forward)},
      {"panoramic annular", Projection::of_lens(panoramic_annular(F, 60), look(0, 90, 0))},
  };
  std::printf("  camera models, %d px wide (cost per pixel seen: ground truth, colour)\n", F);
  double base_truth = 0, base_color = 0;
  for (const Model& m : models) {
    const Projection& p = m.projection;
    int seen = 0;
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) seen += p.covers(Vec2(x + 0.5, y + 0.5));
    auto start = std::chrono::steady_clock::now();
    renderer.ground_truth(p, frames);
    const double truth = seconds_since(start) / seen * 1e9;
    start = std::chrono::steady_clock::now();
    renderer.color(p, frames, options);
    const double color = seconds_since(start) / seen * 1e9;
    if (base_truth == 0) base_truth = truth, base_color = color;
    std::printf("    %-28s %5.1f %% seen  truth %7.0f ns/px (%.2fx)  colour %8.0f ns/px (%.2fx)\n",
                m.name, 100.0 * seen / (p.width * p.height), truth, truth / base_truth, color,
                color / base_color);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int F = argc > 1 ? std::atoi(argv[1]) : 512, H = argc > 2 ? std::atoi(argv[2]) : 512;
  const int spp = argc > 3 ? std::atoi(argv[3]) : 16;
  tbb::global_control limit(
      tbb::global_control::max_allowed_parallelism,
      argc > 4 ? std::atoi(argv[4]) : tbb::this_task_arena::max_concurrency());
  const int threads =
      int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  const Scene scene = street_fixture();
  Renderer renderer(scene);
  FramePair frames;
  frames.rig = Pose(Eigen::Translation3d(0, 0, 1.7));
  frames.next_rig = Pose(Eigen::Translation3d(10.0 / kFrameRate, 0, 1.7)) *
                    Pose(Eigen::AngleAxisd(0.01, Vec3::UnitZ()));
  const RenderOptions options{spp, argc > 5 ? std::atoi(argv[5]) : 4, 0};
  std::printf("bench_render: street fixture, %zu actors, %d threads, %d spp\n", scene.actors.size(),
              threads, spp);

  // direct ERP
  const Projection erp = Projection::equirectangular(H);
  auto start = std::chrono::steady_clock::now();
  const GroundTruth gt = renderer.ground_truth(erp, frames);
  const double gt_seconds = seconds_since(start);
  start = std::chrono::steady_clock::now();
  RenderStats stats;
  renderer.color(erp, frames, options, &stats);
  const double color_seconds = seconds_since(start);
  const double pixels = double(erp.width) * erp.height;
  std::printf("  primary rays (ground truth: camera + visibility ray)  %6.2f Mrays/s/core\n",
              2 * pixels / gt_seconds / threads / 1e6);
  std::printf("  path tracing (%d spp, up to 4 bounces, sun rays)       %6.2f Mrays/s/core\n", spp,
              stats.rays / color_seconds / threads / 1e6);
  std::printf(
      "  %d x %d ERP direct: colour %.2f s + flow/semantics %.2f s = %.2f s per frame"
      "   (target < 2 s on 2 cores)\n",
      erp.height, erp.width, color_seconds, gt_seconds, color_seconds + gt_seconds);
  std::printf("  at this speed 2 s per frame allows %d spp\n",
              int(spp * (2 - gt_seconds) / color_seconds));

  if (F <= 0) return 0;  // face size 0: the direct ERP figures only

  // cube rig + stitch
  const CubeToErp map = make_cube_to_erp(F, H);
  start = std::chrono::steady_clock::now();
  render_cube(renderer, F, frames, nullptr);
  const double primary_only = seconds_since(start);
  start = std::chrono::steady_clock::now();
  const CubeFrame cube = render_cube(renderer, F, frames, &options);
  const double render_seconds = seconds_since(start);
  start = std::chrono::steady_clock::now();
  resample_bilinear(map.sampling, raw_color(cube.color));
  cube_to_erp_flow(map, {cube.truth.flow.view(), cube.truth.instance.view()}, FlowMode::Wrap360);
  resample_nearest(map.sampling, cube.truth.semantic);
  const double stitch_seconds = seconds_since(start);
  std::printf(
      "  panoramic frame, 6 x %d^2 faces -> %d x %d: render %.2f s + stitch %.3f s = %.2f s\n", F,
      H, 2 * H, render_seconds, stitch_seconds, render_seconds + stitch_seconds);
  std::printf("  baseline: the same frame with primary rays only (no colour)   %.2f s\n",
              primary_only + stitch_seconds);
  camera_models(renderer, frames, options, F);
  return 0;
}
