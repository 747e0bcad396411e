#include <catch2/catch.hpp>

#include "flowscape/renderer/renderer.h"
#include "flowscape/scenes/city.h"
#include "flowscape/scenes/shapes.h"
#include "flowscape/scenes/test_scenes.h"
#include "warp_errors.h"

using namespace flowscape;
using V3 = Eigen::Vector3d;

namespace {

// Bricks with toned units and fine fBm, in uv: detail at every scale the camera sees.
std::shared_ptr<const Pattern> brickwork() {
  return std::make_shared<const Pattern>([](const TexturePoint& at, const SurfaceLook& base) {
    const tex::Bond b = tex::bond(at.uv, {0.4, 0.15}, 0.02, 0.5, at.footprint);
    const double tone = 1 + 0.5 * (tex::hash01(b.unit, 3) - 0.5) * tex::visible(0.4, at.footprint);
    const tex::Noise grain = tex::fbm(at.uv, 4, 6, 4, at.footprint);
    SurfaceLook look = base;
    look.albedo = base.albedo * float(tone * (1 - 0.6 * b.mortar) * (1 + 0.2 * grain.value));
    look.slope = 0.01 * grain.gradient;
    return look;
  });
}

// A lit, brick-textured wall 8 m ahead of the camera and a textured box (its pattern in its own
// uv) in front of it, its front face 6 m ahead, sliding sideways at `box_speed` m/s.
Scene textured_wall(double box_speed) {
  Scene scene;
  Material wall, paint;
  wall.albedo = {0.6f, 0.35f, 0.25f}, wall.pattern = brickwork();
  paint.albedo = {0.2f, 0.5f, 0.3f}, paint.pattern = brickwork();
  scene.materials = {wall, paint};
  add_quad(scene.world, {8, 30, -5}, {8, -30, -5}, {8, -30, 15}, {8, 30, 15},
           {SemanticClass::Wall, 0});
  scene.actors.push_back(sliding_box({7, 0.5, -0.5}, {0, -box_speed, 0}, 1));
  scene.environment.sun_direction = V3(-0.6, 0.3, 0.6).normalized();
  return scene;
}

}  // namespace

// With a focal length of 80 px, a surface D m ahead moving sideways by 3 D / 80 m moves 3 px: the
// flow is a whole number of pixels, warping needs no interpolation, and frame t+1 at x + V shows
// the very surface points frame t shows at x. If the texture sticks to its surface, what is left
// is the render noise; a texture that slid would leave its pattern's contrast.
TEST_CASE("textures move exactly with the flow: camera and object motion of whole pixels") {
  const Projection camera = Projection::pinhole(160, 120, 90);  // focal 80 px
  for (const bool object : {false, true}) {
    INFO((object ? "the box slides" : "the camera slides past the wall"));
    // the wall: the camera moves 3 * 8 / 80 m to its left (+y); the box (front face 6 m ahead)
    // moves 3 * 6 / 80 m per frame to the camera's right while the camera stands
    const double box_speed = object ? 3 * 6.0 / 80 * kFrameRate : 0;
    const Scene scene = textured_wall(box_speed);
    Renderer renderer(scene);
    FramePair frames;
    if (!object) frames.next_rig = Pose(Eigen::Translation3d(0, 3 * 8.0 / 80, 0));
    const FramePair next{frames.next_time, 2 * frames.next_time, frames.next_rig, frames.next_rig};
    const Image<float> first = renderer.color(camera, frames, {64, 3, 1});
    const Image<float> again = renderer.color(camera, frames, {64, 3, 2});
    const Image<float> second = renderer.color(camera, next, {64, 3, 1});
    GroundTruth truth = renderer.ground_truth(camera, frames);
    // only the surface that moved 3 px, the wall or the box's front face, away from its border (a
    // border pixel's samples also meet the box's sides, seen from another angle after the move)
    const auto moving = [&](int x, int y) {
      const float* f = truth.flow.pixel(x, y);
      return std::abs(f[0] - 3) < 1e-3 && std::abs(f[1]) < 1e-3 &&
             (!object || *truth.instance.pixel(x, y) == 7);
    };
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 160; ++x) {
        bool inside = true;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            inside = inside && x + dx >= 0 && x + dx < 160 && y + dy >= 0 && y + dy < 120 &&
                     moving(x + dx, y + dy);
        if (!inside) *truth.valid.pixel(x, y) = 0;
      }
    const WarpErrors e = warp_errors(first, again, second, truth);
    REQUIRE(e.pixels > (object ? 400 : 10000));
    INFO("PE " << e.pe << ", WPE " << e.wpe << ", noise " << e.noise << ", 1 px off " << e.wpe_off
               << " over " << e.pixels << " pixels");
    CHECK(e.pe > 5 * e.noise);  // the texture, not the noise, makes the frames differ
    CHECK(e.wpe < 1.3 * e.noise);
    CHECK(e.wpe_off > 3 * e.wpe);
  }
}

TEST_CASE("the ground truth is the same bytes with and without textures") {
  CityConfig config;
  config.map = 0, config.vehicles = 10, config.pedestrians = 10, config.duration = 1;
  const City city = make_city(config);
  Scene plain = city.scene;
  for (Material& m : plain.materials) m.pattern.reset(), m.images = {};
  Renderer textured_renderer(city.scene), plain_renderer(plain);
  const FramePair frames{0.5, 0.5 + 1 / kFrameRate, city.rig(0.5), city.rig(0.5 + 1 / kFrameRate)};
  const Projection erp = Projection::equirectangular(48);
  const GroundTruth a = textured_renderer.ground_truth(erp, frames),
                    b = plain_renderer.ground_truth(erp, frames);
  CHECK(a.flow.data == b.flow.data);
  CHECK(a.semantic.data == b.semantic.data);
  CHECK(a.instance.data == b.instance.data);
  CHECK(a.depth.data == b.depth.data);
  CHECK(a.valid.data == b.valid.data);
  // and the colour does change: the city is textured
  RenderOptions options{4, 2, 1};
  const Image<float> with = textured_renderer.color(erp, frames, options);
  options.textures = false;
  CHECK(with.data != textured_renderer.color(erp, frames, options).data);
}

TEST_CASE("without textures a surface shows its material's plain albedo") {
  Scene scene;
  Material m;
  m.albedo = {0.3f, 0.5f, 0.7f}, m.pattern = brickwork();
  scene.materials = {m};
  add_quad(scene.world, {4, 10, -10}, {4, -10, -10}, {4, -10, 10}, {4, 10, 10},
           {SemanticClass::Wall, 0});
  Environment& e = scene.environment;  // a sky of radiance 1 all round and no sun
  e.sun_irradiance.setZero(), e.sky_zenith.setOnes(), e.sky_horizon.setOnes(), e.ground.setOnes();
  Renderer renderer(scene);
  RenderOptions options{8, 2, 1};
  options.textures = false;
  const Image<float> image = renderer.color(Projection::pinhole(16, 16, 60), {}, options);
  for (std::size_t i = 0; i < image.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) REQUIRE(image.data[3 * i + c] == Approx(m.albedo[c]).epsilon(1e-5));
}
