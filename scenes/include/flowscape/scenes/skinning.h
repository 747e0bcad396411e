#pragma once
// Linear blend skinning (Mesh::bones, Mesh::weights, Part::bones): a vertex of a skinned mesh is
// v(t) = sum_k w_k B_k(t) v_rest, its normal the same blend of the bones' rotations, renormalized.
// A surface point is the barycentric combination of its triangle's vertices at every time, which
// is what makes the flow of a deforming body exact (docs/scenes.md).
#include <string>
#include <vector>

#include "flowscape/scenes/scene.h"

namespace flowscape {

// `posed` gets `rest`'s vertices, normals and tangents moved by `bones` (its other attributes are
// copied from rest when its sizes differ, else left as they are).
void skin(const Mesh& rest, const std::vector<Pose>& bones, Mesh& posed);
// Vertex v of `rest` moved by `bones`, rounded to float as skin() stores it (what rays hit).
Eigen::Vector3f skinned_vertex(const Mesh& rest, std::size_t v, const std::vector<Pose>& bones);
// A part's mesh in the part's frame at time t: the mesh itself (rigid) or skinned then.
Mesh part_mesh_at(const Part& part, double t);
// A part's vertices in the actor's frame at time t (part pose and skinning applied).
std::vector<Vec3> part_vertices_at(const Part& part, double t);
// Throws std::invalid_argument naming `name` unless the weights are one per vertex, the bones
// below bone_count and the weights non-negative, summing to 1 (to 1e-4).
void require_valid_skin(const Mesh& mesh, std::size_t bone_count, const std::string& name);

}  // namespace flowscape
