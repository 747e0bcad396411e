#pragma once
// Mesh builders for procedural scenes: every triangle gets a semantic class and a material, every
// vertex a shading normal and texture coordinates in metres along the surface (so a texture's
// scale is physical and continues across neighbouring faces).
#include "flowscape/core/random.h"
#include "flowscape/scenes/scene.h"

namespace flowscape {

// Appends an axis-aligned box [lo, hi] to a mesh; `inward` turns its faces to the inside. Side
// faces map u to the horizontal coordinate growing to the right seen from outside and v to z; top
// and bottom map (x, y).
void add_box(Mesh& mesh, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, SemanticClass cls,
             bool inward = false);

// What the builders below stamp on the triangles they add.
struct Paint {
  SemanticClass cls;
  std::uint16_t material = 0;
};

// How a flat face is mapped to uv: uv = ((p - origin) . u, (p - origin) . v).
struct UvFrame {
  Vec3 origin = Vec3::Zero(), u = Vec3::UnitX(), v = Vec3::UnitY();
};

// A box of half extents `half` placed by `pose` (its centre and orientation); uvs in its own frame.
void add_oriented_box(Mesh& mesh, const Pose& pose, const Eigen::Vector3d& half, Paint paint);
// A closed cylinder along the pose's z axis, from z = 0 to z = height, `sides` facets with smooth
// normals around it (u = arc length, v = height) and flat caps.
void add_cylinder(Mesh& mesh, const Pose& pose, double radius, double height, Paint paint,
                  int sides = 12);
// A lumpy ball (a leaf cluster, a boulder): an icosphere of semi-axes `radii` around `centre`
// whose vertices move in and out by up to `lumps` of the radius, smoothly shaded; uv = (longitude,
// latitude) times the mean radius.
void add_lumpy_ball(Mesh& mesh, const Eigen::Vector3d& centre, const Eigen::Vector3d& radii,
                    Paint paint, Random& random, double lumps = 0.25);
// A quad with corners a, b, c, d counter-clockwise seen from the side it faces. Without a frame,
// u runs along a -> b and v across it, both measured from the world origin.
void add_quad(Mesh& mesh, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
              const Eigen::Vector3d& c, const Eigen::Vector3d& d, Paint paint);
void add_quad(Mesh& mesh, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
              const Eigen::Vector3d& c, const Eigen::Vector3d& d, Paint paint,
              const UvFrame& frame);
// Appends `part` to `mesh`, every vertex moved by `pose` (classes, materials, uvs kept; normals and
// tangents turned). A part without normals keeps its look: its triangles become flat-shaded.
void append_mesh(Mesh& mesh, const Mesh& part, const Pose& pose = Pose::Identity());

std::uint16_t add_material(Scene& scene, const Material& material);

}  // namespace flowscape
