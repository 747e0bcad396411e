// Renderer throughput on a street-like fixture (ground, 300 buildings, 60 driving boxes, sun and
// sky): primary-ray ground truth and path-traced colour in million rays per second per core, and
// seconds per panoramic frame (6 x F^2 faces stitched to H x 2H ERP) next to a primary-rays-only
// frame. Usage: bench_render [face size (0: no cube rig)] [ERP height] [samples per pixel]
// [threads]
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "flowscape/renderer/renderer.h"
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
    Part body{{}, fixed_pose()};
    add_box(body.mesh, Eigen::Vector3f(-2.2f, -0.9f, -0.8f), Eigen::Vector3f(2.2f, 0.9f, 0.7f),
            SemanticClass::Vehicles);
    body.mesh.materials.assign(body.mesh.triangles.size(), 2);
    car.parts.push_back(std::move(body));
    scene.actors.push_back(std::move(car));
  }
  return scene;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
  return 0;
}
