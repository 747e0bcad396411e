#include <algorithm>
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

namespace {

// A 2 x 2 WebP image (oiiotool --pattern constant:color=0.2,0.6,0.9 2x2 3 -d uint8 -o t.webp),
// its bytes and as base64.
const unsigned char kWebpBytes[72] = {
    0x52, 0x49, 0x46, 0x46, 0x40, 0x00, 0x00, 0x00, 0x57, 0x45, 0x42, 0x50, 0x56, 0x50, 0x38,
    0x20, 0x34, 0x00, 0x00, 0x00, 0x50, 0x02, 0x00, 0x9d, 0x01, 0x2a, 0x02, 0x00, 0x02, 0x00,
    0x00, 0x00, 0x00, 0x25, 0xa0, 0x02, 0x74, 0xba, 0x01, 0xf8, 0x01, 0xfa, 0x01, 0xfc, 0x00,
    0x0c, 0x3c, 0x00, 0x9b, 0xff, 0xf6, 0xf4, 0x9f, 0xa0, 0x91, 0x36, 0xff, 0xdb, 0xd2, 0xff,
    0xfd, 0xe4, 0xd1, 0xbf, 0x1d, 0x5d, 0x7f, 0xfb, 0xc4, 0xa0, 0x00, 0x00};
const char* kWebp =
    "UklGRkAAAABXRUJQVlA4IDQAAABQAgCdASoCAAIAAAAAJaACdLoB+AH6AfwADDwAm//29J+gkTb/29L//eTRvx1df/"
    "vEoAAA";

}  // namespace

TEST_CASE("glTF files that require EXT_texture_webp load; other required extensions are named") {
  TempDir dir, cache;
  setenv("FLOWSCAPE_TEXTURE_CACHE", cache.path.c_str(), 1);
  nlohmann::json gltf = triangle_gltf();
  // as Godot 4 exports it: the texture's only source is the extension's
  gltf["extensionsUsed"] = gltf["extensionsRequired"] = {"EXT_texture_webp"};
  gltf["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  gltf["textures"] = {{{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}}};
  // a file beside the model
  std::ofstream(dir.path / "t.webp", std::ios::binary)
      .write(reinterpret_cast<const char*>(kWebpBytes), sizeof kWebpBytes);
  gltf["images"] = {{{"uri", "t.webp"}}};
  CHECK(load_error(dir.path, gltf) == "loaded");
  Scene scene;
  load_model((dir.path / "hostile.gltf").string(), SemanticClass::Vehicles, 4, scene);
  const Material& m = textured_material(scene);
  CHECK(m.images.base_color == (dir.path / "t.webp").string());
  // as a .glb holds it: in a buffer view, its MIME type given
  nlohmann::json in_buffer = gltf;
  in_buffer["buffers"].push_back(
      {{"byteLength", 72}, {"uri", std::string("data:application/octet-stream;base64,") + kWebp}});
  in_buffer["bufferViews"].push_back({{"buffer", 1}, {"byteLength", 72}});
  in_buffer["images"] = {{{"bufferView", 3}, {"mimeType", "image/webp"}}};
  CHECK(load_error(dir.path, in_buffer) == "loaded");
  Scene buffered;
  load_model((dir.path / "hostile.gltf").string(), SemanticClass::Vehicles, 4, buffered);
  const std::string cached = textured_material(buffered).images.base_color;
  CHECK(fs::path(cached).extension() == ".webp");
  CHECK(file_bytes(cached) == file_bytes(dir.path / "t.webp"));
  // a data: uri of WebP, which tinygltf cannot decode, is named
  nlohmann::json in_uri = gltf;
  in_uri["images"] = {{{"uri", std::string("data:image/webp;base64,") + kWebp}}};
  CHECK_THAT(load_error(dir.path, in_uri), Catch::Contains("image 0 is WebP in a data: uri"));
  unsetenv("FLOWSCAPE_TEXTURE_CACHE");
  for (const char* extension :
       {"KHR_draco_mesh_compression", "KHR_texture_basisu", "EXT_meshopt_compression"}) {
    gltf["extensionsRequired"] = {"EXT_texture_webp", extension};
    CHECK_THAT(load_error(dir.path, gltf),
               Catch::Contains(std::string("hostile.gltf: requires the glTF extension ") +
                               extension + ", which this reader does not support"));
  }
  gltf["extensionsRequired"] = {"EXT_texture_webp"};
  gltf["textures"][0]["extensions"]["EXT_texture_webp"]["source"] = 4;
  CHECK_THAT(load_error(dir.path, gltf),
             Catch::Contains("texture 0 names a missing image (4 of 1)"));
}

TEST_CASE("a glTF node chain 20,000 deep is refused, not walked off the stack") {
  TempDir dir;
  nlohmann::json gltf = triangle_gltf();
  gltf["nodes"] = nlohmann::json::array();
  for (int n = 0; n < 20000; ++n)
    gltf["nodes"].push_back(n + 1 < 20000 ? nlohmann::json{{"children", {n + 1}}}
                                          : nlohmann::json{{"mesh", 0}});
  CHECK_THAT(load_error(dir.path, gltf),
             Catch::Contains("hostile.gltf: nodes nest more than 256 levels deep"));
  Scene scene;
  CHECK_THROWS_WITH(
      load_world({(dir.path / "hostile.gltf").string(), 1, false, {{"*", SemanticClass::Road}}},
                 scene),
      Catch::Contains("nest more than 256 levels deep"));
}

TEST_CASE("a world's class patterns match a part's ancestors, as Sketchfab names them") {
  TempDir dir;
  nlohmann::json gltf = triangle_gltf();
  // Sketchfab: a root, a named object, and the mesh's node "Object_4" beneath it
  gltf["nodes"] = {{{"name", "Sketchfab_model"}, {"children", {1, 3}}},
                   {{"name", "Car_body"}, {"children", {2}}},
                   {{"name", "Object_4"}, {"mesh", 0}},
                   {{"name", "Object_7"}, {"mesh", 0}, {"translation", {5, 0, 0}}}};
  const fs::path file = dir.path / "sketchfab.gltf";
  std::ofstream(file) << gltf.dump();
  Scene scene;
  const auto counts = class_counts(
      load_world({file.string(),
                  1,
                  false,
                  {{"car*", SemanticClass::Vehicles}, {"object_*", SemanticClass::Static}}},
                 scene));
  CHECK(counts.at(SemanticClass::Vehicles).triangles == 1);  // Object_4, under Car_body
  CHECK(counts.at(SemanticClass::Static).triangles == 1);    // Object_7, under the root only
  CHECK_THROWS_WITH(
      load_world({file.string(), 1, false, {{"wheel*", SemanticClass::Vehicles}}}, scene),
      Catch::Contains("its part \"Object_4\" (in Car_body < Sketchfab_model) "
                      "matches no class pattern (wheel*)"));
}

TEST_CASE("an OBJ whose group lines follow their faces is read as its authors meant") {
  TempDir dir;
  // the classic Cornell box's way: each "g" names the faces before it; the last names none after
  const fs::path obj = dir.path / "cornell.obj";
  std::ofstream(obj) << "# faces first, then their group's name\nmtllib cornell.mtl\n"
                        "v 0 0 0\nv 10 0 0\nv 10 0 10\nv 0 0 10\n"
                        "usemtl white\nf 1 2 3\nf 1 3 4\ng floor\n"
                        "v 0 5 0\nv 1 5 0\nv 1 6 0\nf 5 6 7\ng light\n";
  std::ofstream(dir.path / "cornell.mtl") << "newmtl white\nKd 0.7 0.7 0.7\n";
  Scene scene;
  const auto counts = class_counts(load_world(
      {obj.string(), 1, false, {{"floor", SemanticClass::Road}, {"light", SemanticClass::Pole}}},
      scene));
  CHECK(counts.at(SemanticClass::Road).triangles == 2);
  CHECK(counts.at(SemanticClass::Pole).triangles == 1);
  CHECK(counts.at(SemanticClass::Pole).lo.z() == Approx(5));  // the light: y (up) 5-6
  CHECK(counts.at(SemanticClass::Road).hi.z() == Approx(0));  // the floor at y 0
  // the material library is still found
  CHECK(std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) {
    return m.albedo.isApprox(Eigen::Vector3f::Constant(0.7f));
  }));
}

TEST_CASE("PLY files whose header promises more than the file holds are refused before assimp") {
  TempDir dir;
  const auto refused = [&](const std::string& name, const std::string& bytes,
                           const std::string& says) {
    std::ofstream(dir.path / name, std::ios::binary) << bytes;
    Scene scene;
    CHECK_THROWS_WITH(load_model((dir.path / name).string(), SemanticClass::Vehicles, 4, scene),
                      Catch::Contains(name) && Catch::Contains(says));
  };
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float "
      "y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  std::string body(3 * 12, '\0');
  body += std::string(1, char(3)) + std::string(12, '\0');
  refused("cut.ply", header + body.substr(0, 20), "the file holds 20 after it (truncated?)");
  refused("huge.ply",
          "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty "
          "float y\nproperty float z\nelement face 10000000\nproperty list uchar int "
          "vertex_indices\nend_header\n" +
              body,
          "declares 10000000 face elements, more than a model may hold");
  // enough bytes for the rows' counts, not for the faces' indices: 2 of 3 faces there
  std::string two_faces = std::string(3 * 12, '\0');
  for (int f = 0; f < 2; ++f) two_faces += std::string(1, char(3)) + std::string(12, '\0');
  refused("fewer.ply",
          "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty "
          "float y\nproperty float z\nelement face 3\nproperty list uchar int "
          "vertex_indices\nend_header\n" +
              two_faces,
          "declares 3 face elements, the file holds 2 (truncated?)");
  refused("short.ply",
          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty "
          "float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
          "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
          "declares 5 rows of elements, the file holds 4");
  // the whole file loads
  std::ofstream(dir.path / "whole.ply", std::ios::binary)
      << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty "
         "float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
         "0 0 0\n1 0 0\n0 0 1\n3 0 1 2\n";
  Scene scene;
  CHECK(load_model((dir.path / "whole.ply").string(), SemanticClass::Vehicles, 4, scene)
            .triangles.size() == 1);
}
