#include "gltf_read.h"

#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace flowscape {

void fail(const std::string& path, const std::string& problem) {
  throw std::runtime_error(path + ": " + problem);
}

namespace {

using V3 = Vec3;

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

}  // namespace

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
      return accessor.normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return accessor.normalized ? *p / 255.0 : *p;
    default:
      fail(path, "unsupported accessor component type");
  }
}

namespace {

// tinygltf's image hook: keep the stored bytes (PNG, JPEG) as they are.
bool keep_image_bytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

}  // namespace

tinygltf::Model read_gltf(const std::string& path) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keep_image_bytes, nullptr);
  tinygltf::Model model;
  std::string error, warning;
  const bool binary = std::filesystem::path(path).extension() == ".glb";
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &error, &warning, path)
                         : loader.LoadASCIIFromFile(&model, &error, &warning, path);
  if (!ok) fail(path, error.empty() ? "cannot read glTF" : error.substr(0, error.find('\n')));
  return model;
}

namespace {

void walk_nodes(const tinygltf::Model& model, int index, const Eigen::Matrix4d& parent,
                const std::function<void(const tinygltf::Node&, const Eigen::Matrix4d&)>& visit,
                int depth = 0) {
  if (index < 0 || index >= int(model.nodes.size()) || depth > 64) return;
  const tinygltf::Node& node = model.nodes[index];
  const Eigen::Matrix4d transform = parent * node_matrix(node);
  visit(node, transform);
  for (int child : node.children) walk_nodes(model, child, transform, visit, depth + 1);
}

}  // namespace

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

}  // namespace flowscape
