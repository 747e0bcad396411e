#include "flowscape/scenes/skinning.h"

#include <cmath>
#include <stdexcept>

namespace flowscape {
namespace {

// The blended transform of one vertex: sum_k w_k B_k (an affine map, not a rigid one in general).
Eigen::Matrix<double, 3, 4> blended(const Mesh& rest, std::size_t v,
                                    const std::vector<Pose>& bones) {
  Eigen::Matrix<double, 3, 4> m = Eigen::Matrix<double, 3, 4>::Zero();
  for (int k = 0; k < 4; ++k) {
    const double w = rest.weights[v][k];
    if (w != 0) m += w * bones[rest.bones[v][k]].matrix().topRows<3>();
  }
  return m;
}

// A rest vertex moved by a blended transform, rounded to float (the vertex rays hit).
Eigen::Vector3f moved(const Eigen::Matrix<double, 3, 4>& m, const Eigen::Vector3f& vertex) {
  return (m.leftCols<3>() * vertex.cast<double>() + m.col(3)).cast<float>();
}

}  // namespace

void skin(const Mesh& rest, const std::vector<Pose>& bones, Mesh& posed) {
  if (posed.triangles.size() != rest.triangles.size() ||
      posed.vertices.size() != rest.vertices.size())
    posed = rest;
  for (std::size_t v = 0; v < rest.vertices.size(); ++v) {
    const Eigen::Matrix<double, 3, 4> m = blended(rest, v, bones);
    posed.vertices[v] = moved(m, rest.vertices[v]);
    if (!rest.normals.empty())
      posed.normals[v] =
          (m.leftCols<3>() * rest.normals[v].cast<double>()).normalized().cast<float>();
    if (!rest.tangents.empty()) {
      const Vec3 t = (m.leftCols<3>() * rest.tangents[v].head<3>().cast<double>()).normalized();
      posed.tangents[v] << t.cast<float>(), rest.tangents[v].w();
    }
  }
}

Eigen::Vector3f skinned_vertex(const Mesh& rest, std::size_t v, const std::vector<Pose>& bones) {
  return moved(blended(rest, v, bones), rest.vertices[v]);
}

Mesh part_mesh_at(const Part& part, double t) {
  if (!part.bones) return *part.mesh;
  Mesh posed;
  skin(*part.mesh, part.bones(t), posed);
  return posed;
}

std::vector<Vec3> part_vertices_at(const Part& part, double t) {
  const Pose pose = part.pose(t);
  std::vector<Vec3> out;
  out.reserve(part.mesh->vertices.size());
  if (!part.bones) {
    for (const Eigen::Vector3f& v : part.mesh->vertices) out.push_back(pose * v.cast<double>());
    return out;
  }
  const std::vector<Pose> bones = part.bones(t);
  for (std::size_t v = 0; v < part.mesh->vertices.size(); ++v) {
    // the float vertex the renderer traces, then posed: the same point
    out.push_back(pose * skinned_vertex(*part.mesh, v, bones).cast<double>());
  }
  return out;
}

void require_valid_skin(const Mesh& mesh, std::size_t bone_count, const std::string& name) {
  if (mesh.bones.size() != mesh.vertices.size() || mesh.weights.size() != mesh.vertices.size())
    throw std::invalid_argument(name + ": a skinned mesh needs bones and weights per vertex");
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    double sum = 0;
    for (int k = 0; k < 4; ++k) {
      const float w = mesh.weights[v][k];
      if (!(w >= 0) || (w > 0 && mesh.bones[v][k] >= bone_count))
        throw std::invalid_argument(name + ": vertex " + std::to_string(v) +
                                    " has a bad bone or weight");
      sum += w;
    }
    if (std::abs(sum - 1) > 1e-4)
      throw std::invalid_argument(name + ": the weights of vertex " + std::to_string(v) +
                                  " sum to " + std::to_string(sum) + ", not 1");
  }
}

}  // namespace flowscape
