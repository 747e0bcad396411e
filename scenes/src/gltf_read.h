#pragma once
// Internal: reading glTF files (tinygltf) and the axis conventions shared by import and export.
#include <tiny_gltf.h>

#include <functional>
#include <string>
#include <vector>

#include "flowscape/core/types.h"

namespace flowscape {

[[noreturn]] void fail(const std::string& path, const std::string& problem);

// glTF and assimp: y up, z forward, x = y_up x z_forward (left); ours: x forward, y left, z up.
inline Eigen::Vector3d from_y_up(const Vec3& p) { return {p.z(), p.x(), p.y()}; }
inline Vec3 to_y_up(const Eigen::Vector3f& p) { return {p.y(), p.z(), p.x()}; }

// The whole file; images are kept as the bytes they are stored in (not decoded).
tinygltf::Model read_gltf(const std::string& path);

// Deeper than any model's node tree; a chain of nodes deeper than this is refused.
inline constexpr std::size_t kMaxNodeDepth = 256;
// visit(node, its world transform, the names of the node and its ancestors, the node's first).
using NodeVisit = std::function<void(const tinygltf::Node&, const Eigen::Matrix4d&,
                                     const std::vector<std::string>&)>;
// Every node of the default scene (or every root when there is none), parents before children,
// siblings in order. A scene index the file lacks, a node that is its own ancestor or has two
// parents, or nodes nested more than kMaxNodeDepth deep are an error naming the file.
void for_each_node(const tinygltf::Model& model, const std::string& path, const NodeVisit& visit);

// The accessor's element count, after checking that its last element lies inside its buffer.
std::size_t accessor_count(const tinygltf::Model& model, const tinygltf::Accessor& accessor,
                           const std::string& path);
// The accessor `index` names, or an error naming the file.
const tinygltf::Accessor& accessor_at(const tinygltf::Model& model, int index,
                                      const std::string& path);
// A triangle primitive's vertex indices (0..vertices-1 without an index accessor), each checked
// against `vertices`.
std::vector<int> triangle_indices(const tinygltf::Model& model,
                                  const tinygltf::Primitive& primitive, std::size_t vertices,
                                  const std::string& path);
// Component `component` of element `i` of an accessor, checked against its buffer; normalized
// integers become [0, 1].
double accessor_value(const tinygltf::Model& model, const tinygltf::Accessor& accessor,
                      std::size_t i, int component, const std::string& path);

}  // namespace flowscape
