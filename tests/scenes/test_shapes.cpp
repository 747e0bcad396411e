#include <catch2/catch.hpp>
#include <map>

#include "flowscape/scenes/shapes.h"

using namespace flowscape;
using V3 = Eigen::Vector3d;

namespace {

// Every edge of a closed surface is used by exactly two triangles, once in each direction.
bool closed(const Mesh& mesh) {
  std::map<std::pair<int, int>, int> edges;
  for (const Eigen::Vector3i& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  for (const auto& [edge, count] : edges)
    if (count != 1 || edges.count({edge.second, edge.first}) != 1) return false;
  return true;
}

}  // namespace

TEST_CASE("a box has four vertices per side with the side's normal and uvs in metres") {
  Mesh mesh;
  add_box(mesh, {0, 0, 0}, {4, 2, 3}, SemanticClass::Building);
  REQUIRE(mesh.vertices.size() == 24);
  REQUIRE((mesh.normals.size() == 24 && mesh.uvs.size() == 24));
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Eigen::Vector3i& tri = mesh.triangles[t];
    const Eigen::Vector3f a = mesh.vertices[tri[0]], b = mesh.vertices[tri[1]],
                          c = mesh.vertices[tri[2]];
    const Eigen::Vector3f face = (b - a).cross(c - a).normalized();
    for (int k = 0; k < 3; ++k) REQUIRE((mesh.normals[tri[k]] - face).norm() < 1e-6);
    // outward: the normal points away from the box's centre (2, 1, 1.5)
    REQUIRE(face.dot(a - Eigen::Vector3f(2, 1, 1.5)) > 0);
  }
  // the +x side (x = 4): u = y, v = z, so its uv rectangle is 2 x 3 metres
  float umin = 1e9, umax = -1e9, vmin = 1e9, vmax = -1e9;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (mesh.normals[v].x() > 0.5f)
      umin = std::min(umin, mesh.uvs[v].x()), umax = std::max(umax, mesh.uvs[v].x()),
      vmin = std::min(vmin, mesh.uvs[v].y()), vmax = std::max(vmax, mesh.uvs[v].y());
  CHECK(umax - umin == Approx(2));
  CHECK(vmax - vmin == Approx(3));
}

TEST_CASE("a cylinder is shaded round: radial normals on its side, u along its circumference") {
  Mesh mesh;
  add_cylinder(mesh, Pose(Eigen::Translation3d(1, 2, 0)), 0.5, 3, {SemanticClass::Pole}, 8);
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Eigen::Vector3f radial = mesh.vertices[v] - Eigen::Vector3f(1, 2, mesh.vertices[v].z());
    if (std::abs(mesh.normals[v].z()) > 0.5f) continue;  // a cap
    REQUIRE((mesh.normals[v] - radial / 0.5f).norm() < 1e-5);
  }
  float largest_u = 0;
  for (const Eigen::Vector2f& uv : mesh.uvs) largest_u = std::max(largest_u, uv.x());
  CHECK(largest_u == Approx(2 * kPi * 0.5));  // the seam closes at u = circumference
}

TEST_CASE("a lumpy ball is closed, lumps within bounds, normals outward") {
  Mesh mesh;
  Random random(3);
  add_lumpy_ball(mesh, {5, 0, 2}, {1, 1, 0.8}, {SemanticClass::Vegetation}, random, 0.25);
  CHECK(mesh.triangles.size() == 80);
  CHECK(closed(mesh));
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Eigen::Vector3f d = mesh.vertices[v] - Eigen::Vector3f(5, 0, 2);
    const double r = Eigen::Vector3f(d.x(), d.y(), d.z() / 0.8f).norm();
    REQUIRE((r >= 0.75 - 1e-5 && r <= 1.25 + 1e-5));
    REQUIRE(mesh.normals[v].dot(d) > 0);
  }
}

TEST_CASE("appending keeps smooth parts shared and makes parts without normals flat") {
  Mesh smooth;
  add_cylinder(smooth, Pose::Identity(), 1, 1, {SemanticClass::Pole}, 6);
  Mesh flat;  // no normals: two triangles sharing an edge at a right angle
  flat.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  flat.triangles = {{0, 1, 2}, {0, 3, 1}};
  flat.classes.assign(2, SemanticClass::Wall);
  Mesh mesh;
  append_mesh(mesh, smooth, Pose(Eigen::AngleAxisd(kPi / 2, V3::UnitX())));
  CHECK(mesh.vertices.size() == smooth.vertices.size());
  // the turned cylinder's axis is -y: its normals turned with it
  CHECK((mesh.normals[0] - Eigen::Vector3f(0, 1, 0)).norm() < 1e-6);  // the bottom cap faced -z
  append_mesh(mesh, flat);
  REQUIRE(mesh.vertices.size() == smooth.vertices.size() + 6);  // three vertices per triangle
  const std::size_t first = smooth.vertices.size();
  CHECK((mesh.normals[first] - Eigen::Vector3f(0, 0, 1)).norm() < 1e-6);
  CHECK((mesh.normals[first + 3] - Eigen::Vector3f(0, 1, 0)).norm() < 1e-6);
}
