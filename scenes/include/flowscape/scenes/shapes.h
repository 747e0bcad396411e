#pragma once
// Mesh builders for procedural scenes: every triangle gets a semantic class and a material.
#include "flowscape/scenes/scene.h"

namespace flowscape {

// Appends an axis-aligned box [lo, hi] to a mesh; `inward` turns its faces to the inside.
void add_box(Mesh& mesh, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, SemanticClass cls,
             bool inward = false);

// What the builders below stamp on the triangles they add.
struct Paint {
  SemanticClass cls;
  std::uint16_t material = 0;
};

// A box of half extents `half` placed by `pose` (its centre and orientation).
void add_oriented_box(Mesh& mesh, const Pose& pose, const Eigen::Vector3d& half, Paint paint);
// A closed cylinder along the pose's z axis, from z = 0 to z = height, `sides` facets.
void add_cylinder(Mesh& mesh, const Pose& pose, double radius, double height, Paint paint,
                  int sides = 12);
// A quad with corners a, b, c, d counter-clockwise seen from the side it faces.
void add_quad(Mesh& mesh, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
              const Eigen::Vector3d& c, const Eigen::Vector3d& d, Paint paint);
// Appends `part` to `mesh`, every vertex moved by `pose` (classes and materials kept).
void append_mesh(Mesh& mesh, const Mesh& part, const Pose& pose = Pose::Identity());

std::uint16_t add_material(Scene& scene, const Material& material);

}  // namespace flowscape
