#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "flowscape/scenes/model_io.h"
#include "temp_dir.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

const fs::path kModels = "/usr/share/assimp/models";  // Debian's assimp-testmodels

// The one material of a model that has a base colour image.
const Material& textured_material(const Scene& scene) {
  for (const Material& m : scene.materials)
    if (!m.images.base_color.empty()) return m;
  FAIL("no material with a base colour image");
  return scene.materials.front();
}

}  // namespace

TEST_CASE("a glTF box keeps its uvs, normals and textured material, wherever the image is") {
  TempDir cache;
  setenv("FLOWSCAPE_TEXTURE_CACHE", cache.path.c_str(), 1);
  const fs::path logo = kModels / "glTF2/BoxTextured-glTF/CesiumLogoFlat.png";
  REQUIRE(fs::exists(logo));
  for (const char* file : {"BoxTextured-glTF/BoxTextured.gltf",        // an image file beside it
                           "BoxTextured-glTF-Binary/BoxTextured.glb",  // in the binary buffer
                           "BoxTextured-glTF-Embedded/BoxTextured.gltf"})  // a data: uri
  {
    INFO(file);
    Scene scene;
    const Mesh box =
        load_model((kModels / "glTF2" / file).string(), SemanticClass::Vehicles, 2, scene);
    CHECK(box.triangles.size() == 12);
    CHECK(box.vertices.size() == 24);  // glTF stores four corners per side, for their uvs
    REQUIRE((box.uvs.size() == 24 && box.normals.size() == 24));
    CHECK((box.uvs[0] - box.uvs[1]).norm() > 0);
    for (std::size_t v = 0; v < 24; ++v) {
      REQUIRE(box.normals[v].norm() == Approx(1));
      REQUIRE(box.uvs[v].allFinite());
    }
    const Material& m = textured_material(scene);
    CHECK(m.kind == Material::Kind::Diffuse);  // metallic 0, roughness 1 in the file
    REQUIRE(fs::exists(m.images.base_color));
    CHECK(file_bytes(m.images.base_color) == file_bytes(logo));
    for (std::uint16_t material : box.materials) CHECK(&scene.materials[material] == &m);
  }
  unsetenv("FLOWSCAPE_TEXTURE_CACHE");
}

TEST_CASE("an OBJ through assimp keeps its uvs, normals and per-part textures") {
  Scene scene;
  const Mesh spider =
      load_model((kModels / "OBJ/spider.obj").string(), SemanticClass::Pedestrian, 0.5, scene);
  CHECK(spider.uvs.size() == spider.vertices.size());
  CHECK(spider.normals.size() == spider.vertices.size());
  std::set<std::string> images;
  for (std::uint16_t m : spider.materials) images.insert(scene.materials[m].images.base_color);
  CHECK(images.size() >= 4);
  for (const std::string& image : images)
    if (!image.empty()) CHECK(fs::exists(image));
}
