#include "flowscape/scenes/model_io.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <tiny_gltf.h>

#include <assimp/Importer.hpp>
#include <cstring>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "flowscape/scenes/shapes.h"

namespace flowscape {
namespace {

using V3 = Eigen::Vector3d;

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw std::runtime_error(path + ": " + problem);
}

// glTF and assimp: y up, z forward, x = y_up x z_forward (left); ours: x forward, y left, z up.
Eigen::Vector3f from_y_up(const V3& p) {
  return Eigen::Vector3f(float(p.z()), float(p.x()), float(p.y()));
}
V3 to_y_up(const Eigen::Vector3f& p) { return {p.y(), p.z(), p.x()}; }

Eigen::Matrix4d node_matrix(const tinygltf::Node& node) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  if (node.matrix.size() == 16) return Eigen::Map<const Eigen::Matrix4d>(node.matrix.data());
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  if (node.translation.size() == 3)
    a.translate(V3(node.translation[0], node.translation[1], node.translation[2]));
  if (node.rotation.size() == 4)
    a.rotate(
        Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]));
  if (node.scale.size() == 3) a.scale(V3(node.scale[0], node.scale[1], node.scale[2]));
  m = a.matrix();
  return m;
}

// Element `i` of an accessor as doubles, checked against its buffer.
double accessor_value(const tinygltf::Model& model, const tinygltf::Accessor& accessor,
                      std::size_t i, int component, const std::string& path) {
  if (accessor.bufferView < 0 || accessor.bufferView >= int(model.bufferViews.size()))
    fail(path, "accessor without a valid buffer view");
  const tinygltf::BufferView& view = model.bufferViews[accessor.bufferView];
  const tinygltf::Buffer& buffer = model.buffers.at(view.buffer);
  const int size = tinygltf::GetComponentSizeInBytes(accessor.componentType);
  const int count = tinygltf::GetNumComponentsInType(accessor.type);
  const std::size_t stride = view.byteStride ? view.byteStride : std::size_t(size * count);
  const std::size_t offset = view.byteOffset + accessor.byteOffset + i * stride + component * size;
  if (size <= 0 || offset + size > buffer.data.size()) fail(path, "accessor reads past its buffer");
  const unsigned char* p = buffer.data.data() + offset;
  switch (accessor.componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return *p;
    default:
      fail(path, "unsupported accessor component type");
  }
}

// Appends the triangles of a glTF mesh, vertices moved by `transform` (in the file's frame).
void append_gltf_mesh(const tinygltf::Model& model, const tinygltf::Mesh& gltf_mesh,
                      const Eigen::Matrix4d& transform, SemanticClass cls, std::uint16_t material,
                      const std::string& path, Mesh& mesh) {
  for (const tinygltf::Primitive& primitive : gltf_mesh.primitives) {
    if (primitive.mode != -1 && primitive.mode != TINYGLTF_MODE_TRIANGLES) continue;
    const auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end()) fail(path, "a primitive has no POSITION");
    const tinygltf::Accessor& positions = model.accessors.at(position->second);
    const int base = int(mesh.vertices.size());
    for (std::size_t v = 0; v < positions.count; ++v) {
      const Eigen::Vector4d p(accessor_value(model, positions, v, 0, path),
                              accessor_value(model, positions, v, 1, path),
                              accessor_value(model, positions, v, 2, path), 1);
      mesh.vertices.push_back(from_y_up((transform * p).head<3>()));
    }
    std::vector<int> indices;
    if (primitive.indices >= 0) {
      const tinygltf::Accessor& accessor = model.accessors.at(primitive.indices);
      for (std::size_t k = 0; k < accessor.count; ++k)
        indices.push_back(int(accessor_value(model, accessor, k, 0, path)));
    } else {
      for (std::size_t k = 0; k < positions.count; ++k) indices.push_back(int(k));
    }
    for (std::size_t k = 0; k + 2 < indices.size(); k += 3) {
      for (int c = 0; c < 3; ++c)
        if (indices[k + c] < 0 || std::size_t(indices[k + c]) >= positions.count)
          fail(path, "triangle index out of range");
      mesh.triangles.emplace_back(base + indices[k], base + indices[k + 1], base + indices[k + 2]);
      mesh.classes.push_back(cls);
      mesh.materials.push_back(material);
    }
  }
}

tinygltf::Model read_gltf(const std::string& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  const bool binary = std::filesystem::path(path).extension() == ".glb";
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &error, &warning, path)
                         : loader.LoadASCIIFromFile(&model, &error, &warning, path);
  if (!ok) fail(path, error.empty() ? "cannot read glTF" : error.substr(0, error.find('\n')));
  return model;
}

void walk_nodes(const tinygltf::Model& model, int index, const Eigen::Matrix4d& parent,
                const std::function<void(const tinygltf::Node&, const Eigen::Matrix4d&)>& visit,
                int depth = 0) {
  if (index < 0 || index >= int(model.nodes.size()) || depth > 64) return;
  const tinygltf::Node& node = model.nodes[index];
  const Eigen::Matrix4d transform = parent * node_matrix(node);
  visit(node, transform);
  for (int child : node.children) walk_nodes(model, child, transform, visit, depth + 1);
}

void for_each_node(
    const tinygltf::Model& model,
    const std::function<void(const tinygltf::Node&, const Eigen::Matrix4d&)>& visit) {
  if (model.scenes.empty()) {
    for (int n = 0; n < int(model.nodes.size()); ++n)
      walk_nodes(model, n, Eigen::Matrix4d::Identity(), visit);
    return;
  }
  const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
  for (int n : model.scenes[scene].nodes) walk_nodes(model, n, Eigen::Matrix4d::Identity(), visit);
}

Mesh load_gltf(const std::string& path, SemanticClass cls, std::uint16_t material) {
  const tinygltf::Model model = read_gltf(path);
  Mesh mesh;
  for_each_node(model, [&](const tinygltf::Node& node, const Eigen::Matrix4d& transform) {
    if (node.mesh >= int(model.meshes.size()))
      fail(path, "node " + node.name + " refers to a mesh the file lacks");
    if (node.mesh >= 0)
      append_gltf_mesh(model, model.meshes[node.mesh], transform, cls, material, path, mesh);
  });
  return mesh;
}

Mesh load_with_assimp(const std::string& path, SemanticClass cls, std::uint16_t material) {
  Assimp::Importer importer;
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_PreTransformVertices);
  if (!scene || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    fail(path, std::string("assimp cannot read it: ") + importer.GetErrorString());
  Mesh mesh;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* source = scene->mMeshes[m];
    const int base = int(mesh.vertices.size());
    for (unsigned v = 0; v < source->mNumVertices; ++v) {
      const aiVector3D& p = source->mVertices[v];
      mesh.vertices.push_back(from_y_up(V3(p.x, p.y, p.z)));
    }
    for (unsigned f = 0; f < source->mNumFaces; ++f) {
      const aiFace& face = source->mFaces[f];
      if (face.mNumIndices != 3) continue;
      mesh.triangles.emplace_back(base + int(face.mIndices[0]), base + int(face.mIndices[1]),
                                  base + int(face.mIndices[2]));
      mesh.classes.push_back(cls);
      mesh.materials.push_back(material);
    }
  }
  return mesh;
}

}  // namespace

std::string class_name(SemanticClass cls) {
  static const char* const kNames[] = {
      "Unlabeled",    "Building", "Fence",    "Other",      "Pedestrian", "Pole",
      "RoadLine",     "Road",     "SideWalk", "Vegetation", "Vehicles",   "Wall",
      "TrafficSign",  "Sky",      "Ground",   "Bridge",     "RailTrack",  "GuardRail",
      "TrafficLight", "Static",   "Dynamic",  "Water",      "Terrain"};
  const int id = int(cls);
  return id < int(std::size(kNames)) ? kNames[id] : "class" + std::to_string(id);
}

Mesh load_model(const std::string& path, SemanticClass cls, double length, std::uint16_t material) {
  if (!std::filesystem::is_regular_file(path)) fail(path, "no such model file");
  if (!(length > 0)) fail(path, "model length must be positive");
  const std::string extension = std::filesystem::path(path).extension().string();
  Mesh mesh = extension == ".gltf" || extension == ".glb" ? load_gltf(path, cls, material)
                                                          : load_with_assimp(path, cls, material);
  if (mesh.triangles.empty()) fail(path, "the model has no triangles");
  Eigen::Vector3f lo = mesh.vertices[0], hi = mesh.vertices[0];
  for (const Eigen::Vector3f& v : mesh.vertices) {
    if (!v.allFinite()) fail(path, "a vertex is not finite");
    lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  }
  if (!(hi.x() > lo.x())) fail(path, "the model has no extent along its forward axis");
  const float scale = float(length / (hi.x() - lo.x()));
  const Eigen::Vector3f centre((lo.x() + hi.x()) / 2, (lo.y() + hi.y()) / 2, lo.z());
  for (Eigen::Vector3f& v : mesh.vertices) v = (v - centre) * scale;
  return mesh;
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
      add_node(part.mesh, part_pose(actor, part, t), actor.instance);
  model.defaultScene = 0;
  tinygltf::TinyGLTF writer;
  const std::string partial = path + ".partial";
  if (!writer.WriteGltfSceneToFile(&model, partial, true, true, false, false))
    fail(path, "cannot write glTF");
  std::filesystem::rename(partial, path);
}

std::vector<ExportedMesh> import_gltf(const std::string& path) {
  const tinygltf::Model model = read_gltf(path);
  std::vector<ExportedMesh> meshes;
  for_each_node(model, [&](const tinygltf::Node& node, const Eigen::Matrix4d& transform) {
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
    append_gltf_mesh(model, model.meshes[node.mesh], transform, SemanticClass(cls), 0, path,
                     meshes.back().mesh);
  });
  return meshes;
}

}  // namespace flowscape
