#include "flowscape/scenes/shapes.h"

#include <cmath>

namespace flowscape {
namespace {

constexpr double kTwoPi = 6.283185307179586;

void add_triangle(Mesh& mesh, int a, int b, int c, Paint paint) {
  mesh.triangles.emplace_back(a, b, c);
  mesh.classes.push_back(paint.cls);
  mesh.materials.resize(mesh.triangles.size() - 1, 0);
  mesh.materials.push_back(paint.material);
}

int add_vertex(Mesh& mesh, const Eigen::Vector3d& p) {
  mesh.vertices.push_back(p.cast<float>());
  return int(mesh.vertices.size()) - 1;
}

}  // namespace

void add_box(Mesh& mesh, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, SemanticClass cls,
             bool inward) {
  const int base = int(mesh.vertices.size());
  for (int k = 0; k < 8; ++k)
    mesh.vertices.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(),
                               k & 4 ? hi.z() : lo.z());
  // two triangles per side, counter-clockwise seen from outside
  const int sides[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& s : sides)
    for (const Eigen::Vector3i& t :
         {Eigen::Vector3i(s[0], s[1], s[2]), Eigen::Vector3i(s[0], s[2], s[3])}) {
      const Eigen::Vector3i tri = inward ? Eigen::Vector3i(t[0], t[2], t[1]) : t;
      add_triangle(mesh, base + tri[0], base + tri[1], base + tri[2], {cls});
    }
}

void add_oriented_box(Mesh& mesh, const Pose& pose, const Eigen::Vector3d& half, Paint paint) {
  Mesh box;
  add_box(box, -half.cast<float>(), half.cast<float>(), paint.cls);
  box.materials.assign(box.triangles.size(), paint.material);
  append_mesh(mesh, box, pose);
}

void add_cylinder(Mesh& mesh, const Pose& pose, double radius, double height, Paint paint,
                  int sides) {
  const int bottom = add_vertex(mesh, pose * Eigen::Vector3d(0, 0, 0));
  const int top = add_vertex(mesh, pose * Eigen::Vector3d(0, 0, height));
  const int ring = int(mesh.vertices.size());
  for (int k = 0; k < sides; ++k) {
    const double a = kTwoPi * k / sides;
    const Eigen::Vector3d p(radius * std::cos(a), radius * std::sin(a), 0);
    add_vertex(mesh, pose * p);
    add_vertex(mesh, pose * (p + Eigen::Vector3d(0, 0, height)));
  }
  for (int k = 0; k < sides; ++k) {
    const int b0 = ring + 2 * k, t0 = b0 + 1, b1 = ring + 2 * ((k + 1) % sides), t1 = b1 + 1;
    add_triangle(mesh, b0, b1, t1, paint);
    add_triangle(mesh, b0, t1, t0, paint);
    add_triangle(mesh, bottom, b1, b0, paint);
    add_triangle(mesh, top, t0, t1, paint);
  }
}

void add_quad(Mesh& mesh, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
              const Eigen::Vector3d& c, const Eigen::Vector3d& d, Paint paint) {
  const int ia = add_vertex(mesh, a), ib = add_vertex(mesh, b), ic = add_vertex(mesh, c),
            id = add_vertex(mesh, d);
  add_triangle(mesh, ia, ib, ic, paint);
  add_triangle(mesh, ia, ic, id, paint);
}

void append_mesh(Mesh& mesh, const Mesh& part, const Pose& pose) {
  const int base = int(mesh.vertices.size());
  for (const Eigen::Vector3f& v : part.vertices)
    mesh.vertices.push_back((pose * v.cast<double>()).cast<float>());
  for (std::size_t t = 0; t < part.triangles.size(); ++t) {
    const Eigen::Vector3i& tri = part.triangles[t];
    add_triangle(mesh, base + tri[0], base + tri[1], base + tri[2],
                 {part.classes[t], part.materials.empty() ? std::uint16_t(0) : part.materials[t]});
  }
}

std::uint16_t add_material(Scene& scene, const Material& material) {
  scene.materials.push_back(material);
  return std::uint16_t(scene.materials.size() - 1);
}

}  // namespace flowscape
