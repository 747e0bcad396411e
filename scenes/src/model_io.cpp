// Whole scenes to glTF with their classes, and back.
#include "flowscape/scenes/model_io.h"

#include <strings.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <stdexcept>

#include "flowscape/core/files.h"
#include "flowscape/scenes/skinning.h"
#include "gltf_read.h"

namespace flowscape {
namespace {

using V3 = Eigen::Vector3d;

// Appends the triangles of a glTF mesh (positions only), vertices moved by `transform` (in the
// file's frame).
void append_gltf_mesh(const tinygltf::Model& model, const tinygltf::Mesh& gltf_mesh,
                      const Eigen::Matrix4d& transform, SemanticClass cls, std::uint16_t material,
                      const std::string& path, Mesh& mesh) {
  for (const tinygltf::Primitive& primitive : gltf_mesh.primitives) {
    if (primitive.mode != -1 && primitive.mode != TINYGLTF_MODE_TRIANGLES) continue;
    const auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end()) fail(path, "a primitive has no POSITION");
    const tinygltf::Accessor& positions = accessor_at(model, position->second, path);
    const std::size_t vertices = accessor_count(model, positions, path);
    const int base = int(mesh.vertices.size());
    for (std::size_t v = 0; v < vertices; ++v) {
      const Eigen::Vector4d p(accessor_value(model, positions, v, 0, path),
                              accessor_value(model, positions, v, 1, path),
                              accessor_value(model, positions, v, 2, path), 1);
      mesh.vertices.push_back(from_y_up((transform * p).head<3>()).cast<float>());
    }
    const std::vector<int> indices = triangle_indices(model, primitive, vertices, path);
    for (std::size_t k = 0; k + 2 < indices.size(); k += 3) {
      mesh.triangles.emplace_back(base + indices[k], base + indices[k + 1], base + indices[k + 2]);
      mesh.classes.push_back(cls);
      mesh.materials.push_back(material);
    }
  }
}

}  // namespace

std::string class_name(SemanticClass cls) {
  static const char* const kNames[] = {
      "Unlabeled",    "Building", "Fence",    "Other",      "Pedestrian", "Pole",
      "RoadLine",     "Road",     "SideWalk", "Vegetation", "Vehicles",   "Wall",
      "TrafficSign",  "Sky",      "Ground",   "Bridge",     "RailTrack",  "GuardRail",
      "TrafficLight", "Static",   "Dynamic",  "Water",      "Terrain",    "Rider",
      "Car",          "Truck",    "Bus",      "Motorcycle", "Bicycle",    "EgoVehicle"};
  const int id = int(cls);
  return id < int(std::size(kNames)) ? kNames[id] : "class" + std::to_string(id);
}

SemanticClass class_from_name(const std::string& name) {
  std::string known;
  for (int id = 0; id < kSceneClasses; ++id) {
    const std::string candidate = class_name(SemanticClass(id));
    if (strcasecmp(candidate.c_str(), name.c_str()) == 0) return SemanticClass(id);
    known += (id ? ", " : "") + candidate;
  }
  throw std::invalid_argument("unknown class \"" + name + "\" (one of " + known + ")");
}

void export_gltf(const Scene& scene, double t, const std::string& path) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "flowscape";
  model.buffers.emplace_back();
  std::vector<unsigned char>& bytes = model.buffers[0].data;
  model.scenes.emplace_back();
  const auto append = [&](const void* data, std::size_t size, int target) {
    while (bytes.size() % 4) bytes.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0, view.byteOffset = bytes.size(), view.byteLength = size, view.target = target;
    bytes.insert(bytes.end(), static_cast<const unsigned char*>(data),
                 static_cast<const unsigned char*>(data) + size);
    model.bufferViews.push_back(view);
    return int(model.bufferViews.size()) - 1;
  };
  const auto add_node = [&](const Mesh& mesh, const Pose& pose, std::uint16_t instance) {
    std::map<int, std::vector<std::size_t>> by_class;
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k)
      by_class[int(mesh.classes[k])].push_back(k);
    for (const auto& [cls, triangles] : by_class) {
      std::vector<float> positions;
      std::vector<std::uint32_t> indices;
      Eigen::Vector3d lo = V3::Constant(1e30), hi = -lo;
      for (std::size_t k : triangles)
        for (int c = 0; c < 3; ++c) {
          const V3 p =
              to_y_up((pose * mesh.vertices[mesh.triangles[k][c]].cast<double>()).cast<float>());
          for (int a = 0; a < 3; ++a) positions.push_back(float(p[a]));
          lo = lo.cwiseMin(p.cast<float>().cast<double>()),
          hi = hi.cwiseMax(p.cast<float>().cast<double>());
          indices.push_back(std::uint32_t(indices.size()));
        }
      tinygltf::Accessor position;
      position.bufferView =
          append(positions.data(), positions.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER);
      position.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT, position.type = TINYGLTF_TYPE_VEC3;
      position.count = positions.size() / 3;
      position.minValues = {lo.x(), lo.y(), lo.z()}, position.maxValues = {hi.x(), hi.y(), hi.z()};
      tinygltf::Accessor index;
      index.bufferView =
          append(indices.data(), indices.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
      index.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, index.type = TINYGLTF_TYPE_SCALAR;
      index.count = indices.size();
      model.accessors.push_back(position), model.accessors.push_back(index);
      tinygltf::Primitive primitive;
      primitive.attributes["POSITION"] = int(model.accessors.size()) - 2;
      primitive.indices = int(model.accessors.size()) - 1, primitive.mode = TINYGLTF_MODE_TRIANGLES;
      tinygltf::Mesh gltf_mesh;
      gltf_mesh.primitives.push_back(primitive);
      model.meshes.push_back(gltf_mesh);
      tinygltf::Node node;
      node.mesh = int(model.meshes.size()) - 1;
      node.name = class_name(SemanticClass(cls)) + "_" + std::to_string(instance);
      node.extras = tinygltf::Value(
          tinygltf::Value::Object{{"class_id", tinygltf::Value(cls)},
                                  {"class", tinygltf::Value(class_name(SemanticClass(cls)))},
                                  {"instance", tinygltf::Value(int(instance))}});
      model.nodes.push_back(node);
      model.scenes[0].nodes.push_back(int(model.nodes.size()) - 1);
    }
  };
  add_node(scene.world, Pose::Identity(), 0);
  for (const Actor& actor : scene.actors)
    for (const Part& part : actor.parts)
      add_node(part_mesh_at(part, t), part_pose(actor, part, t), actor.instance);
  model.defaultScene = 0;
  tinygltf::TinyGLTF writer;
  std::ostringstream encoded;
  if (!writer.WriteGltfSceneToStream(&model, encoded, false, false))
    fail(path, "cannot write glTF");
  write_file(path, encoded.str());
}

std::vector<ExportedMesh> import_gltf(const std::string& path) {
  const tinygltf::Model model = read_gltf(path);
  std::vector<ExportedMesh> meshes;
  for_each_node(model, path,
                [&](const tinygltf::Node& node, const Eigen::Matrix4d& transform,
                    const std::vector<std::string>&) {
                  if (node.mesh >= int(model.meshes.size()))
                    fail(path, "node " + node.name + " refers to a mesh the file lacks");
                  if (node.mesh < 0) return;
                  if (!node.extras.Has("class_id") || !node.extras.Has("instance"))
                    fail(path, "node " + node.name + " has no class_id / instance in its extras");
                  const int cls = node.extras.Get("class_id").GetNumberAsInt();
                  const int instance = node.extras.Get("instance").GetNumberAsInt();
                  if (cls < 0 || cls > 255 || instance < 0 || instance > 65535)
                    fail(path, "node " + node.name + " has an out-of-range class or instance");
                  if (meshes.empty() || meshes.back().instance != instance)
                    meshes.push_back({std::uint16_t(instance), {}});
                  append_gltf_mesh(model, model.meshes[node.mesh], transform, SemanticClass(cls), 0,
                                   path, meshes.back().mesh);
                });
  return meshes;
}

}  // namespace flowscape
