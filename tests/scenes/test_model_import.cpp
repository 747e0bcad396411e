#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
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

namespace {

// Triangles per class and the extent of each class's vertices.
struct ClassCount {
  int triangles = 0;
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e9f), hi = -lo;
};
std::map<SemanticClass, ClassCount> class_counts(const Mesh& mesh) {
  std::map<SemanticClass, ClassCount> counts;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    ClassCount& c = counts[mesh.classes[t]];
    ++c.triangles;
    for (int k = 0; k < 3; ++k) {
      c.lo = c.lo.cwiseMin(mesh.vertices[mesh.triangles[t][k]]);
      c.hi = c.hi.cwiseMax(mesh.vertices[mesh.triangles[t][k]]);
    }
  }
  return counts;
}

const std::vector<WorldClass> kSquareClasses = {
    {"road*", SemanticClass::Road},       {"SIDEWALK*", SemanticClass::SideWalk},
    {"lawn*", SemanticClass::Terrain},    {"building*", SemanticClass::Building},
    {"tree*", SemanticClass::Vegetation}, {"pole*", SemanticClass::Pole},
    {"ground*", SemanticClass::Terrain}};

}  // namespace

TEST_CASE("a user's glTF world gets its classes from name patterns, in metres, z up") {
  const std::string square = fs::path(FLOWSCAPE_SOURCE_DIR) / "examples/worlds/square.gltf";
  Scene scene;
  const Mesh world = load_world({square, 1, false, kSquareClasses}, scene);
  // what make_square.py builds: a road quad, two sidewalks of top and kerb, a lawn and the ground,
  // 9 boxes of houses, 6 trees (a 12-sided cone and a box trunk), 6 lamp poles
  auto counts = class_counts(world);
  CHECK(counts[SemanticClass::Road].triangles == 2);
  CHECK(counts[SemanticClass::SideWalk].triangles == 8);
  CHECK(counts[SemanticClass::Terrain].triangles == 4);
  CHECK(counts[SemanticClass::Building].triangles == 9 * 12);
  CHECK(counts[SemanticClass::Vegetation].triangles == 6 * (24 + 12));
  CHECK(counts[SemanticClass::Pole].triangles == 6 * 12);
  CHECK(counts.size() == 6);
  // the road from (-40, -4, 0) to (40, 4, 0) in our frame (the file has y up)
  CHECK(counts[SemanticClass::Road].lo.isApprox(Eigen::Vector3f(-40, -4, 0)));
  CHECK(counts[SemanticClass::Road].hi.isApprox(Eigen::Vector3f(40, 4, 0)));
  CHECK(counts[SemanticClass::Building].hi.z() == Approx(18));  // the tallest house
  // the same file said to be in centimetres
  Scene small_scene;
  counts = class_counts(load_world({square, 0.01, false, kSquareClasses}, small_scene));
  CHECK(counts[SemanticClass::Road].hi.isApprox(Eigen::Vector3f(0.4f, 0.04f, 0)));
}

TEST_CASE("an OBJ world with z up; unmatched names, animations and skins refused by name") {
  TempDir dir;
  const fs::path obj = dir.path / "yard.obj";
  std::ofstream(obj) << "o road_a\nv 0 0 0\nv 10 0 0\nv 10 5 0\nf 1 2 3\n"
                        "o shed_b\nv 0 0 0\nv 1 0 0\nv 1 0 7\nf 4 5 6\n";
  const std::vector<WorldClass> classes = {{"road*", SemanticClass::Road},
                                           {"*", SemanticClass::Building}};
  Scene scene;
  const auto counts = class_counts(load_world({obj.string(), 1, true, classes}, scene));
  REQUIRE(counts.size() == 2);
  CHECK(counts.at(SemanticClass::Road).hi.isApprox(Eigen::Vector3f(10, 5, 0)));  // flat, z up
  CHECK(counts.at(SemanticClass::Building).hi.z() == Approx(7));
  // read as y up, the shed lies along x and stands 0 high... and its 7 m go forward
  Scene y_up;
  const auto lying = class_counts(load_world({obj.string(), 1, false, classes}, y_up));
  CHECK(lying.at(SemanticClass::Building).hi.x() == Approx(7));

  CHECK_THROWS_WITH(load_world({obj.string(), 1, true, {{"road*", SemanticClass::Road}}}, scene),
                    Catch::Contains("yard.obj: its part \"shed_b\" matches no class pattern "
                                    "(road*)"));
  CHECK_THROWS_WITH(load_world({obj.string(), 1, true, {}}, scene),
                    Catch::Contains("yard.obj: a world needs classes"));
  CHECK_THROWS_WITH(load_world({obj.string(), 0, true, classes}, scene),
                    Catch::Contains("metres per unit must be positive"));
  CHECK_THROWS_WITH(load_world({(dir.path / "none.glb").string(), 1, false, classes}, scene),
                    Catch::Contains("none.glb: no such world file"));
  const auto gltf_error = [&](const std::function<void(nlohmann::json&)>& change) {
    nlohmann::json gltf = triangle_gltf();
    change(gltf);
    const fs::path file = dir.path / "moving.gltf";
    std::ofstream(file) << gltf.dump();
    try {
      load_world({file.string(), 1, false, classes}, scene);
    } catch (const FileError& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  CHECK(gltf_error([](auto&) {}) == "loaded");
  CHECK_THAT(gltf_error([](auto& j) {
               j["animations"] = {
                   {{"channels", nlohmann::json::array()}, {"samplers", nlohmann::json::array()}}};
             }),
             Catch::Contains("moving.gltf: holds animations: a world model is static"));
  CHECK_THAT(gltf_error([](auto& j) {
               j["skins"] = {{{"joints", {1}}}};
               j["nodes"][0]["skin"] = 0;
             }),
             Catch::Contains("moving.gltf: holds skins"));
}
