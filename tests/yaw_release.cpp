// Test fixture for the Python plugin: a one-pair release in FlowScape's layout, rendered while
// the rig turns left by 3 degrees in place, so every pixel's flow is u = W * 3 / 360, v = 0.
// Usage: yaw_release OUT_DIR
#include <cstdio>

#include "flowscape/core/files.h"
#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/formats/srgb.h"
#include "flowscape/layout/layout.h"
#include "flowscape/layout/meta.h"
#include "flowscape/release/dataset_card.h"
#include "flowscape/release/manifest.h"
#include "flowscape/renderer/renderer.h"
#include "flowscape/scenes/test_scenes.h"

using namespace flowscape;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: yaw_release OUT_DIR\n");
    return 2;
  }
  ReleaseConfig config;
  config.maps = 1, config.sequences_per_map = 1, config.frames = 2, config.height = 32;
  config.cube = false, config.outputs = {};  // the six kinds of FlowScape
  const fs::path out = argv[1];
  const SequencePlan plan = plan_sequences(config).front();
  const fs::path seq = sequence_dir(out, plan.name);
  Scene scene = textured_plane(8, 60);
  scene.materials[0].pattern = checker(0.7, Eigen::Vector3f::Constant(1 / 3.0f));
  add_box(scene.world, {-30, -30, -3}, {30, 30, -2}, SemanticClass::Road);
  scene.world.materials.resize(scene.world.triangles.size(), 0);
  Renderer renderer(scene);
  FramePair frames;
  frames.next_rig = Pose(Eigen::AngleAxisd(3 * kPi / 180, Vec3::UnitZ()));
  const FramePair next{frames.next_time, 2 * frames.next_time, frames.next_rig, frames.next_rig};
  const Projection erp = Projection::equirectangular(config.height);
  const GroundTruth gt = renderer.ground_truth(erp, frames),
                    gt_next = renderer.ground_truth(erp, next);
  const auto file = [&](const char* kind, int frame) { return erp_file(seq, kind, frame); };
  write_image(file("color", 0), linear_to_srgb8(renderer.color(erp, frames, {4, 2, 1}).view()));
  write_image(file("color", 1), linear_to_srgb8(renderer.color(erp, next, {4, 2, 2}).view()));
  write_flo(file("flow", 0), gt.flow.view());
  write_image(file("valid", 0), gt.valid);
  for (const auto& [frame, truth] : {std::pair{0, &gt}, {1, &gt_next}}) {
    write_image(file("semantic", frame), truth->semantic);
    write_image(file("instance", frame), truth->instance);
    write_image(file("depth", frame), truth->depth);
  }
  SequenceMeta meta;
  meta.scene = plan.name, meta.map_name = "yaw", meta.weather = {{"preset", "sunny"}};
  meta.frames = 2, meta.erp_height = config.height, meta.poses = {frames.rig, frames.next_rig};
  write_meta(seq, meta);
  for (const char* side : {"train", "test"})
    write_text(split_file(out, side), plan.name + " " + frame_name(0) + "\n");
  write_dataset_card(out, config, nullptr);  // its meta.json records no statistics
  write_manifest(out, config, file_hashes(out, config, {plan}), nullptr);
  std::printf("%s\n", out.c_str());
  return 0;
}
