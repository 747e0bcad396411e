#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>

#include "flowscape/core/files.h"
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

namespace {

// One triangle (positions, 16-bit indices) in a data: uri, instanced by two nodes: the fuzz seed
// tests/fuzz/corpus/model/triangle.gltf without its format byte.
nlohmann::json triangle_gltf() {
  const std::string seed =
      file_bytes(fs::path(FLOWSCAPE_SOURCE_DIR) / "tests/fuzz/corpus/model/triangle.gltf");
  return nlohmann::json::parse(seed.substr(1));
}

std::string load_error(const fs::path& dir, const nlohmann::json& gltf) {
  const fs::path file = dir / "hostile.gltf";
  std::ofstream(file) << gltf.dump();
  Scene scene;
  try {
    load_model(file.string(), SemanticClass::Vehicles, 4, scene);
  } catch (const FileError& e) {
    return e.what();
  }
  return "loaded";
}

}  // namespace

TEST_CASE("hostile glTF files are refused with the file named, never walked forever") {
  TempDir dir;
  const auto refused = [&](const std::function<void(nlohmann::json&)>& change) {
    nlohmann::json gltf = triangle_gltf();
    change(gltf);
    return load_error(dir.path, gltf);
  };
  CHECK(refused([](auto&) {}) == "loaded");
  CHECK_THAT(refused([](auto& j) { j["scene"] = 5; }),
             Catch::Contains("hostile.gltf: \"scene\": 5 names a scene the file lacks (it has 1)"));
  // a node listing itself as a child twice (the walk was exponential), or once (65 copies)
  CHECK_THAT(refused([](auto& j) {
               j["nodes"][1]["children"] = {1, 1};
             }),
             Catch::Contains("hostile.gltf: node 1 is reached twice"));
  CHECK_THAT(refused([](auto& j) { j["nodes"][0]["children"] = {0}; }),
             Catch::Contains("node 0 is reached twice"));
  CHECK_THAT(refused([](auto& j) {
               j["scenes"][0]["nodes"] = {0, 1};
             }),  // 1 also a child of 0
             Catch::Contains("node 1 is reached twice"));
  CHECK_THAT(refused([](auto& j) { j["nodes"][0]["children"] = {7}; }),
             Catch::Contains("node 7 does not exist"));
  CHECK_THAT(refused([](auto& j) { j["accessors"][0]["count"] = 1000000000; }),
             Catch::Contains("an accessor of 1000000000 elements reads past its"));
  CHECK_THAT(refused([](auto& j) { j["meshes"][0]["primitives"][0]["indices"] = 9; }),
             Catch::Contains("hostile.gltf: ") && Catch::Contains("accessor out of bounds"));
  CHECK_THAT(refused([](auto& j) { j["bufferViews"][1]["buffer"] = 3; }),
             Catch::Contains("a buffer view names a missing buffer"));
  // an index past the vertices: the index view moved onto the float 1.0's upper half, 0x3f80
  CHECK_THAT(refused([](auto& j) { j["bufferViews"][1]["byteOffset"] = 14; }),
             Catch::Contains("out of range (the primitive has 3 vertices)"));
  // 9e6 triangles by instancing a mesh of 100 one-triangle primitives 90,000 times: refused at 2^23
  CHECK_THAT(refused([](auto& j) {
               const nlohmann::json primitive = j["meshes"][0]["primitives"][0];
               for (int p = 1; p < 100; ++p) j["meshes"][0]["primitives"].push_back(primitive);
               j["nodes"] = nlohmann::json::array();
               j["scenes"][0]["nodes"] = nlohmann::json::array();
               for (int n = 0; n < 90000; ++n) {
                 j["nodes"].push_back({{"mesh", 0}});
                 j["scenes"][0]["nodes"].push_back(n);
               }
             }),
             Catch::Contains("too large for an actor model"));
}
