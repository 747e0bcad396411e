// Test fixture for the Python plugin: a one-pair release in FlowScape's layout, rendered while
// the rig turns left by 3 degrees in place, so every pixel's flow is u = W * 3 / 360, v = 0.
// Usage: yaw_release OUT_DIR
#include <cstdio>

#include "flowscape/color.h"
#include "flowscape/flow_io.h"
#include "flowscape/io.h"
#include "flowscape/renderer.h"
#include "flowscape/test_scenes.h"

using namespace flowscape;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: yaw_release OUT_DIR\n");
    return 2;
  }
  const std::filesystem::path out = argv[1], erp_dir = out / "sequences" / "yaw00_seq00" / "erp";
  Scene scene = textured_plane(8, 60);
  scene.materials[0].checker_size = 0.7f;
  add_box(scene.world, {-30, -30, -3}, {30, 30, -2}, SemanticClass::Road);
  scene.world.materials.resize(scene.world.triangles.size(), 0);
  Renderer renderer(scene);
  FramePair frames;
  frames.next_rig = Pose(Eigen::AngleAxisd(3 * kPi / 180, Vec3::UnitZ()));
  const FramePair next{frames.next_time, 2 * frames.next_time, frames.next_rig, frames.next_rig};
  const Projection erp = Projection::equirectangular(32);
  const GroundTruth gt = renderer.ground_truth(erp, frames),
                    gt_next = renderer.ground_truth(erp, next);
  write_image(erp_dir / "color" / "000000.png",
              linear_to_srgb8(renderer.color(erp, frames, {4, 2, 1}).view()));
  write_image(erp_dir / "color" / "000001.png",
              linear_to_srgb8(renderer.color(erp, next, {4, 2, 2}).view()));
  write_flo(erp_dir / "flow" / "000000.flo", gt.flow.view());
  write_image(erp_dir / "valid" / "000000.png", gt.valid);
  write_image(erp_dir / "semantic" / "000000.png", gt.semantic);
  write_image(erp_dir / "semantic" / "000001.png", gt_next.semantic);
  write_text(
      out / "sequences" / "yaw00_seq00" / "meta.json",
      R"({"scene": "yaw00_seq00", "map_name": "yaw", "frames": 2, "weather": {"preset": "sunny"}})"
      "\n");
  for (const char* split : {"train.txt", "test.txt"})
    write_text(out / "splits" / split, "yaw00_seq00 000000\n");
  std::printf("%s\n", out.c_str());
  return 0;
}
