#pragma once
// Internal: reading glTF files (tinygltf) and the axis conventions shared by import and export.
#include <tiny_gltf.h>

#include <functional>
#include <string>

#include "flowscape/core/types.h"

namespace flowscape {

[[noreturn]] void fail(const std::string& path, const std::string& problem);

// glTF and assimp: y up, z forward, x = y_up x z_forward (left); ours: x forward, y left, z up.
inline Eigen::Vector3d from_y_up(const Vec3& p) { return {p.z(), p.x(), p.y()}; }
inline Vec3 to_y_up(const Eigen::Vector3f& p) { return {p.y(), p.z(), p.x()}; }

// The whole file; images are kept as the bytes they are stored in (not decoded).
tinygltf::Model read_gltf(const std::string& path);

// Every node of the default scene (or every root when there is none) with its world transform.
void for_each_node(const tinygltf::Model& model,
                   const std::function<void(const tinygltf::Node&, const Eigen::Matrix4d&)>& visit);

// Component `component` of element `i` of an accessor, checked against its buffer; normalized
// integers become [0, 1].
double accessor_value(const tinygltf::Model& model, const tinygltf::Accessor& accessor,
                      std::size_t i, int component, const std::string& path);

}  // namespace flowscape
