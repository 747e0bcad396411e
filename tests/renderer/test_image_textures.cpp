#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "flowscape/formats/image_io.h"
#include "flowscape/renderer/renderer.h"
#include "flowscape/scenes/model_io.h"
#include "temp_dir.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

// A 2 x 2 m quad standing in the plane y = 0 (x from -1 to 1, z from 0 to 2), written as glTF
// (y up, z forward: our (x, y, z) is glTF (y, z, x)) with uv (0, 0) at its top left seen from -y
// and its texture `png`; rough and not metallic, so it is Lambertian.
fs::path write_quad(const fs::path& dir, const std::string& png, bool mask) {
  const float positions[4][3] = {{0, 2, -1}, {0, 2, 1}, {0, 0, -1}, {0, 0, 1}};  // TL TR BL BR
  const float normals[4][3] = {{-1, 0, 0}, {-1, 0, 0}, {-1, 0, 0}, {-1, 0, 0}};  // towards -y
  const float uvs[4][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  const std::uint16_t indices[6] = {0, 2, 3, 0, 3, 1};
  std::ofstream bin(dir / "quad.bin", std::ios::binary);
  bin.write(reinterpret_cast<const char*>(positions), 48);
  bin.write(reinterpret_cast<const char*>(normals), 48);
  bin.write(reinterpret_cast<const char*>(uvs), 32);
  bin.write(reinterpret_cast<const char*>(indices), 12);
  bin.close();
  const auto view = [](int offset, int length) {
    return nlohmann::json{{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}};
  };
  const auto accessor = [](int view, int count, int type, const char* kind) {
    return nlohmann::json{
        {"bufferView", view}, {"componentType", type}, {"count", count}, {"type", kind}};
  };
  nlohmann::json material = {
      {"pbrMetallicRoughness",
       {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}};
  if (mask) material["alphaMode"] = "MASK", material["alphaCutoff"] = 0.5;
  nlohmann::json accessors = {accessor(0, 4, 5126, "VEC3"), accessor(1, 4, 5126, "VEC3"),
                              accessor(2, 4, 5126, "VEC2"), accessor(3, 6, 5123, "SCALAR")};
  accessors[0]["min"] = {0, 0, -1}, accessors[0]["max"] = {0, 2, 1};
  const nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
            {"indices", 3},
            {"material", 0}}}}}}},
      {"materials", {material}},
      {"textures", {{{"source", 0}, {"sampler", 0}}}},
      {"samplers", {{{"magFilter", 9729}}}},
      {"images", {{{"uri", png}}}},
      {"buffers", {{{"uri", "quad.bin"}, {"byteLength", 140}}}},
      {"bufferViews", {view(0, 48), view(48, 48), view(96, 32), view(128, 12)}},
      {"accessors", accessors}};
  std::ofstream(dir / "quad.gltf") << gltf.dump(1);
  return dir / "quad.gltf";
}

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// The quad as the whole world, under a sky of radiance 1 in every direction and no sun: a
// Lambertian surface then sends back exactly its albedo.
Scene quad_scene(const fs::path& gltf) {
  Scene scene;
  scene.materials.clear();
  scene.world = load_model(gltf.string(), SemanticClass::Wall, 2, scene);
  scene.environment.sun_irradiance.setZero();
  scene.environment.sky_zenith.setOnes(), scene.environment.sky_horizon.setOnes();
  scene.environment.ground.setOnes();
  return scene;
}

// The camera 3 m in front of the quad (at y = -3, 1 m up) looking at it along +y.
FramePair facing_quad() {
  FramePair frames;
  frames.rig = frames.next_rig =
      Pose(Eigen::Translation3d(0, -3, 1) * Eigen::AngleAxisd(kPi / 2, Vec3::UnitZ()));
  return frames;
}

// Where the centre of pixel (x, y) of a W x W pinhole of 60 degrees looks on the quad, as uv:
// the ray (1, -a, -b) in the rig (x forward, y left, z up) turned by the rig's 90 degree yaw to
// (a, 1, -b) in the world, from (0, -3, 1) to the plane y = 0, and u = (x + 1) / 2, v = (2 - z)
// / 2.
Vec2 quad_uv(int x, int y, int W) {
  const double f = W / 2.0 / std::tan(kPi / 6);
  const double a = (x + 0.5 - W / 2.0) / f, b = (y + 0.5 - W / 2.0) / f;
  const double t = 3;  // the ray (a, 1, -b) reaches y = 0 after 3 units of its y
  return {(t * a + 1) / 2, (2 - (1 - t * b)) / 2};
}

// Bilinear interpolation of 2 x 2 sRGB texels (texel centres at uv 0.25 and 0.75, wrapping).
double bilinear(const std::uint8_t (&texels)[4][3], const Vec2& uv, int c) {
  const double s = uv.x() * 2 - 0.5, t = uv.y() * 2 - 0.5;
  const int s0 = int(std::floor(s)), t0 = int(std::floor(t));
  const double fs = s - s0, ft = t - t0;
  double sum = 0;
  for (int k = 0; k < 4; ++k) {
    const int si = ((s0 + k % 2) % 2 + 2) % 2, ti = ((t0 + k / 2) % 2 + 2) % 2;
    sum += (k % 2 ? fs : 1 - fs) * (k / 2 ? ft : 1 - ft) * texels[2 * ti + si][c];
  }
  return sum / 255;
}

// The pixel whose centre looks at world point p.
std::array<int, 2> pixel_of(const Projection& camera, const FramePair& frames, const Vec3& p) {
  const auto xy = camera.project(frames.rig.inverse() * p);
  REQUIRE(xy.has_value());
  return {int(std::floor(xy->x())), int(std::floor(xy->y()))};
}

}  // namespace

TEST_CASE("a glTF's texture shows its texels' colours where the uvs put them") {
  TempDir dir;
  // top left red, top right green, bottom left blue, bottom right grey (sRGB)
  Image<std::uint8_t> texels(2, 2, 3);
  const std::uint8_t colours[4][3] = {{200, 30, 20}, {40, 180, 60}, {20, 50, 210}, {128, 128, 128}};
  for (int k = 0; k < 4; ++k)
    for (int c = 0; c < 3; ++c) texels.pixel(k % 2, k / 2)[c] = colours[k][c];
  write_image(dir.path / "texels.png", texels);
  const Scene scene = quad_scene(write_quad(dir.path, "texels.png", false));
  Renderer renderer(scene);
  const Projection camera = Projection::pinhole(96, 96, 60);
  const FramePair frames = facing_quad();
  const Image<float> image = renderer.color(camera, frames, {16, 2, 1});
  // texel centres: uv (0.25, 0.25) is x = -0.5, z = 1.5 on the quad, and so on
  const Vec3 centres[4] = {{-0.5, 0, 1.5}, {0.5, 0, 1.5}, {-0.5, 0, 0.5}, {0.5, 0, 0.5}};
  for (int k = 0; k < 4; ++k) {
    INFO("texel " << k);
    const auto [x, y] = pixel_of(camera, frames, centres[k]);
    const Vec2 uv = quad_uv(x, y, 96);
    CHECK((uv - Vec2(0.25 + 0.5 * (k % 2), 0.25 + 0.5 * (k / 2))).norm() < 0.02);
    for (int c = 0; c < 3; ++c)
      CHECK(image.pixel(x, y)[c] == Approx(srgb_to_linear(bilinear(colours, uv, c))).epsilon(1e-3));
  }
}

TEST_CASE("an alpha mask cuts holes that the ground truth and the colour both see") {
  TempDir dir;
  // left column opaque white, right column transparent
  Image<std::uint8_t> texels(2, 2, 4);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      std::uint8_t* p = texels.pixel(x, y);
      p[0] = p[1] = p[2] = 100, p[3] = x == 0 ? 255 : 0;
    }
  write_image(dir.path / "cutout.png", texels);
  const Scene scene = quad_scene(write_quad(dir.path, "cutout.png", true));
  Renderer renderer(scene);
  const Projection camera = Projection::pinhole(96, 96, 60);
  const FramePair frames = facing_quad();
  const GroundTruth truth = renderer.ground_truth(camera, frames);
  const Image<float> image = renderer.color(camera, frames, {4, 2, 1});
  const auto [sx, sy] = pixel_of(camera, frames, {-0.5, 0, 1.0});  // the opaque half
  const auto [hx, hy] = pixel_of(camera, frames, {0.5, 0, 1.0});   // the hole
  CHECK(*truth.semantic.pixel(sx, sy) == std::uint8_t(SemanticClass::Wall));
  const Vec3 camera_at = frames.rig.translation();
  CHECK(*truth.depth.pixel(sx, sy) == Approx((Vec3(-0.5, 0, 1) - camera_at).norm()).epsilon(0.01));
  CHECK(*truth.semantic.pixel(hx, hy) == std::uint8_t(SemanticClass::Sky));
  CHECK(std::isinf(*truth.depth.pixel(hx, hy)));
  CHECK(image.pixel(sx, sy)[0] == Approx(srgb_to_linear(100 / 255.0)).epsilon(0.04));
  CHECK(image.pixel(hx, hy)[0] == Approx(1).epsilon(0.01));  // the sky behind
}

TEST_CASE("a missing texture file is named") {
  TempDir dir;
  const Scene scene = quad_scene(write_quad(dir.path, "gone.png", false));
  CHECK_THROWS_WITH(Renderer(scene), Catch::Contains("gone.png: texture file not found"));
}
