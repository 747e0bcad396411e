#include "gltf_read.h"

#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "flowscape/core/files.h"

namespace flowscape {

void fail(const std::string& path, const std::string& problem) { throw FileError(path, problem); }

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

namespace {

struct AccessorLayout {
  const tinygltf::Buffer* buffer;
  std::size_t start, stride, component_size, components;
};

AccessorLayout layout(const tinygltf::Model& model, const tinygltf::Accessor& accessor,
                      const std::string& path) {
  if (accessor.bufferView < 0 || accessor.bufferView >= int(model.bufferViews.size()))
    fail(path, "accessor without a valid buffer view");
  const tinygltf::BufferView& view = model.bufferViews[accessor.bufferView];
  if (view.buffer < 0 || view.buffer >= int(model.buffers.size()))
    fail(path, "a buffer view names a missing buffer");
  const int size = tinygltf::GetComponentSizeInBytes(accessor.componentType);
  const int count = tinygltf::GetNumComponentsInType(accessor.type);
  if (size <= 0 || count <= 0) fail(path, "accessor of an unknown type");
  const std::size_t stride = view.byteStride ? view.byteStride : std::size_t(size * count);
  return {&model.buffers[view.buffer], view.byteOffset + accessor.byteOffset, stride,
          std::size_t(size), std::size_t(count)};
}

}  // namespace

std::size_t accessor_count(const tinygltf::Model& model, const tinygltf::Accessor& accessor,
                           const std::string& path) {
  const AccessorLayout a = layout(model, accessor, path);
  const std::size_t bytes = a.buffer->data.size(), element = a.component_size * a.components;
  if (accessor.count == 0) return 0;
  // (count - 1) * stride + start + element <= bytes, without overflow
  if (a.start > bytes || element > bytes - a.start ||
      (accessor.count - 1) > (bytes - a.start - element) / std::max<std::size_t>(a.stride, 1))
    fail(path, "an accessor of " + std::to_string(accessor.count) + " elements reads past its " +
                   std::to_string(bytes) + "-byte buffer");
  return accessor.count;
}

const tinygltf::Accessor& accessor_at(const tinygltf::Model& model, int index,
                                      const std::string& path) {
  if (index < 0 || index >= int(model.accessors.size()))
    fail(path, "accessor " + std::to_string(index) + " does not exist (the file has " +
                   std::to_string(model.accessors.size()) + ")");
  return model.accessors[index];
}

std::vector<int> triangle_indices(const tinygltf::Model& model,
                                  const tinygltf::Primitive& primitive, std::size_t vertices,
                                  const std::string& path) {
  std::vector<int> indices;
  if (primitive.indices < 0) {
    for (std::size_t k = 0; k < vertices; ++k) indices.push_back(int(k));
    return indices;
  }
  const tinygltf::Accessor& accessor = accessor_at(model, primitive.indices, path);
  const std::size_t count = accessor_count(model, accessor, path);
  for (std::size_t k = 0; k < count; ++k) {
    const double index = accessor_value(model, accessor, k, 0, path);
    if (!(index >= 0 && index < double(vertices)))
      fail(path, "triangle index " + std::to_string(index) + " out of range (the primitive has " +
                     std::to_string(vertices) + " vertices)");
    indices.push_back(int(index));
  }
  return indices;
}

double accessor_value(const tinygltf::Model& model, const tinygltf::Accessor& accessor,
                      std::size_t i, int component, const std::string& path) {
  const AccessorLayout a = layout(model, accessor, path);
  const std::size_t offset = a.start + i * a.stride + std::size_t(component) * a.component_size;
  if (i >= accessor.count || std::size_t(component) >= a.components ||
      offset + a.component_size > a.buffer->data.size())
    fail(path, "accessor reads past its buffer");
  const unsigned char* p = a.buffer->data.data() + offset;
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
  for (const std::string& extension : model.extensionsRequired)
    if (extension != "EXT_texture_webp")
      fail(path, "requires the glTF extension " + extension +
                     ", which this reader does not support (it reads EXT_texture_webp; export "
                     "the file without " +
                     extension + ")");
  return model;
}

namespace {

// A node met on the walk: its index, its parent's transform and its place in the tree.
struct Pending {
  int index;
  Eigen::Matrix4d parent;
  std::size_t depth;
};

// glTF's node hierarchy is a forest: every node is visited at most once, so a file cannot make the
// walk loop or repeat itself; the walk keeps its own stack, so no depth overflows ours.
void walk_nodes(const tinygltf::Model& model, int root, std::vector<bool>& visited,
                const std::string& path, const NodeVisit& visit) {
  std::vector<Pending> pending{{root, Eigen::Matrix4d::Identity(), 0}};
  std::vector<std::string> lineage;  // the names from the root down to the node
  while (!pending.empty()) {
    const Pending here = pending.back();
    pending.pop_back();
    const int index = here.index;
    if (index < 0 || index >= int(model.nodes.size()))
      fail(path, "node " + std::to_string(index) + " does not exist (the file has " +
                     std::to_string(model.nodes.size()) + ")");
    if (visited[index])
      fail(path, "node " + std::to_string(index) +
                     " is reached twice (a cycle, or two parents): glTF nodes form a tree");
    if (here.depth >= kMaxNodeDepth)
      fail(path, "nodes nest more than " + std::to_string(kMaxNodeDepth) + " levels deep");
    visited[index] = true;
    const tinygltf::Node& node = model.nodes[index];
    lineage.resize(here.depth);
    lineage.push_back(node.name);
    const Eigen::Matrix4d transform = here.parent * node_matrix(node);
    visit(node, transform, {lineage.rbegin(), lineage.rend()});
    for (auto child = node.children.rbegin(); child != node.children.rend(); ++child)
      pending.push_back({*child, transform, here.depth + 1});
  }
}

// The nodes no other node lists as a child.
std::vector<int> root_nodes(const tinygltf::Model& model) {
  std::vector<bool> child(model.nodes.size(), false);
  for (const tinygltf::Node& node : model.nodes)
    for (int c : node.children)
      if (c >= 0 && c < int(child.size())) child[c] = true;
  std::vector<int> roots;
  for (int n = 0; n < int(model.nodes.size()); ++n)
    if (!child[n]) roots.push_back(n);
  return roots;
}

}  // namespace

void for_each_node(const tinygltf::Model& model, const std::string& path, const NodeVisit& visit) {
  std::vector<bool> visited(model.nodes.size(), false);
  const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (!model.scenes.empty() && scene >= int(model.scenes.size()))
    fail(path, "\"scene\": " + std::to_string(scene) + " names a scene the file lacks (it has " +
                   std::to_string(model.scenes.size()) + ")");
  const std::vector<int> roots =
      model.scenes.empty() ? root_nodes(model) : model.scenes[scene].nodes;
  for (int n : roots) walk_nodes(model, n, visited, path, visit);
}

}  // namespace flowscape
