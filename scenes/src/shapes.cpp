#include "flowscape/scenes/shapes.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace flowscape {
namespace {

using V3 = Eigen::Vector3d;

void add_triangle(Mesh& mesh, int a, int b, int c, Paint paint) {
  mesh.triangles.emplace_back(a, b, c);
  mesh.classes.push_back(paint.cls);
  mesh.materials.resize(mesh.triangles.size() - 1, 0);
  mesh.materials.push_back(paint.material);
}

// A vertex with the attributes the mesh keeps (a mesh made by hand without normals or uvs stays
// so).
int add_vertex(Mesh& mesh, const V3& p, const V3& normal, const Eigen::Vector2d& uv) {
  if (mesh.normals.size() == mesh.vertices.size()) mesh.normals.push_back(normal.cast<float>());
  if (mesh.uvs.size() == mesh.vertices.size()) mesh.uvs.push_back(uv.cast<float>());
  mesh.vertices.push_back(p.cast<float>());
  return int(mesh.vertices.size()) - 1;
}

Eigen::Vector2d uv_of(const V3& p, const UvFrame& frame) {
  return {(p - frame.origin).dot(frame.u), (p - frame.origin).dot(frame.v)};
}

// The three attributes of one corner of a part's triangle, for append_mesh.
struct Corner {
  V3 position, normal;
  Eigen::Vector2f uv;
};

}  // namespace

void add_box(Mesh& mesh, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, SemanticClass cls,
             bool inward) {
  const auto corner = [&](int k) {
    return V3(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  };
  // per side: its corners counter-clockwise seen from outside, its normal and its uv axes
  struct Side {
    int corners[4];
    V3 normal, u, v;
  };
  static const Side sides[6] = {
      {{0, 2, 3, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}},  // bottom
      {{4, 5, 7, 6}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}},    // top
      {{0, 1, 5, 4}, {0, -1, 0}, {1, 0, 0}, {0, 0, 1}},   // -y
      {{2, 6, 7, 3}, {0, 1, 0}, {-1, 0, 0}, {0, 0, 1}},   // +y
      {{0, 4, 6, 2}, {-1, 0, 0}, {0, -1, 0}, {0, 0, 1}},  // -x
      {{1, 3, 7, 5}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},    // +x
  };
  for (const Side& s : sides) {
    const int base = int(mesh.vertices.size());
    for (int k : s.corners) {
      const V3 p = corner(k);
      add_vertex(mesh, p, inward ? -s.normal : s.normal, {p.dot(s.u), p.dot(s.v)});
    }
    for (const Eigen::Vector3i& t : {Eigen::Vector3i(0, 1, 2), Eigen::Vector3i(0, 2, 3)}) {
      const Eigen::Vector3i tri = inward ? Eigen::Vector3i(t[0], t[2], t[1]) : t;
      add_triangle(mesh, base + tri[0], base + tri[1], base + tri[2], {cls});
    }
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
  const V3 up = pose.linear() * V3::UnitZ();
  const int bottom = add_vertex(mesh, pose * V3(0, 0, 0), -up, {0, 0});
  const int top = add_vertex(mesh, pose * V3(0, 0, height), up, {0, 0});
  const int side = int(mesh.vertices.size());
  for (int k = 0; k <= sides; ++k) {  // the seam twice, with u = 0 and u = circumference
    const double a = 2 * kPi * k / sides;
    const V3 p(radius * std::cos(a), radius * std::sin(a), 0), out = pose.linear() * (p / radius);
    add_vertex(mesh, pose * p, out, {a * radius, 0});
    add_vertex(mesh, pose * (p + V3(0, 0, height)), out, {a * radius, height});
  }
  const int caps = int(mesh.vertices.size());
  for (int k = 0; k < sides; ++k) {
    const double a = 2 * kPi * k / sides;
    const V3 p(radius * std::cos(a), radius * std::sin(a), 0);
    add_vertex(mesh, pose * p, -up, p.head<2>());
    add_vertex(mesh, pose * (p + V3(0, 0, height)), up, p.head<2>());
  }
  for (int k = 0; k < sides; ++k) {
    const int b0 = side + 2 * k, t0 = b0 + 1, b1 = b0 + 2, t1 = b0 + 3;
    const int cb0 = caps + 2 * k, ct0 = cb0 + 1, cb1 = caps + 2 * ((k + 1) % sides), ct1 = cb1 + 1;
    add_triangle(mesh, b0, b1, t1, paint);
    add_triangle(mesh, b0, t1, t0, paint);
    add_triangle(mesh, bottom, cb1, cb0, paint);
    add_triangle(mesh, top, ct0, ct1, paint);
  }
}

void add_lumpy_ball(Mesh& mesh, const V3& centre, const V3& radii, Paint paint, Random& random,
                    double lumps) {
  // an icosahedron, each face split in four, on the unit sphere
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<V3> points = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                            {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                            {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (V3& p : points) p.normalize();
  const int faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                            {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                            {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                            {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  std::vector<Eigen::Vector3i> triangles;
  std::map<std::pair<int, int>, int> midpoints;  // one per edge, so the lumps leave no cracks
  const auto midpoint = [&](int a, int b) {
    const auto [it, added] = midpoints.emplace(std::minmax(a, b), int(points.size()));
    if (added) points.push_back((points[a] + points[b]).normalized());
    return it->second;
  };
  for (const auto& f : faces) {
    const int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
    for (const Eigen::Vector3i& t : {Eigen::Vector3i(f[0], ab, ca), Eigen::Vector3i(ab, f[1], bc),
                                     Eigen::Vector3i(ca, bc, f[2]), Eigen::Vector3i(ab, bc, ca)})
      triangles.push_back(t);
  }
  Mesh ball;
  const double mean = radii.mean();
  for (const V3& p : points) {
    const double r = 1 + lumps * random.uniform(-1, 1);
    ball.vertices.push_back((r * radii.cwiseProduct(p)).cast<float>());
    ball.normals.push_back(p.cwiseQuotient(radii).normalized().cast<float>());
    ball.uvs.emplace_back(float(std::atan2(p.y(), p.x()) * mean), float(std::asin(p.z()) * mean));
  }
  ball.triangles = triangles;
  ball.classes.assign(triangles.size(), paint.cls);
  ball.materials.assign(triangles.size(), paint.material);
  append_mesh(mesh, ball, Pose(Eigen::Translation3d(centre)));
}

void add_quad(Mesh& mesh, const V3& a, const V3& b, const V3& c, const V3& d, Paint paint,
              const UvFrame& frame) {
  const V3 normal = (b - a).cross(c - a).normalized();
  const int ia = add_vertex(mesh, a, normal, uv_of(a, frame)),
            ib = add_vertex(mesh, b, normal, uv_of(b, frame)),
            ic = add_vertex(mesh, c, normal, uv_of(c, frame)),
            id = add_vertex(mesh, d, normal, uv_of(d, frame));
  add_triangle(mesh, ia, ib, ic, paint);
  add_triangle(mesh, ia, ic, id, paint);
}

void add_quad(Mesh& mesh, const V3& a, const V3& b, const V3& c, const V3& d, Paint paint) {
  const V3 u = (b - a).normalized(), normal = u.cross(c - a).normalized();
  add_quad(mesh, a, b, c, d, paint, {V3::Zero(), u, normal.cross(u)});
}

void append_mesh(Mesh& mesh, const Mesh& part, const Pose& pose) {
  const bool smooth = part.normals.size() == part.vertices.size();
  const bool mapped = part.uvs.size() == part.vertices.size();
  const bool tangents = part.tangents.size() == part.vertices.size() &&
                        (mesh.vertices.empty() || mesh.tangents.size() == mesh.vertices.size());
  if (!tangents) mesh.tangents.clear();
  const auto corner = [&](int v, const V3& face_normal) {
    return Corner{pose * part.vertices[v].cast<double>(),
                  smooth ? pose.linear() * part.normals[v].cast<double>() : face_normal,
                  mapped ? part.uvs[v] : Eigen::Vector2f::Zero()};
  };
  const auto put = [&](const Corner& c) {
    return add_vertex(mesh, c.position, c.normal, c.uv.cast<double>());
  };
  if (smooth) {  // shared vertices stay shared
    const int base = int(mesh.vertices.size());
    for (int v = 0; v < int(part.vertices.size()); ++v) {
      put(corner(v, V3::Zero()));
      if (tangents) {
        const Eigen::Vector4f& t = part.tangents[v];
        const Eigen::Vector3f turned = (pose.linear() * t.head<3>().cast<double>()).cast<float>();
        mesh.tangents.emplace_back(turned.x(), turned.y(), turned.z(), t.w());
      }
    }
    for (std::size_t t = 0; t < part.triangles.size(); ++t) {
      const Eigen::Vector3i& tri = part.triangles[t];
      add_triangle(
          mesh, base + tri[0], base + tri[1], base + tri[2],
          {part.classes[t], part.materials.empty() ? std::uint16_t(0) : part.materials[t]});
    }
    return;
  }
  for (std::size_t t = 0; t < part.triangles.size(); ++t) {  // flat: three vertices per triangle
    const Eigen::Vector3i& tri = part.triangles[t];
    const V3 a = pose * part.vertices[tri[0]].cast<double>(),
             b = pose * part.vertices[tri[1]].cast<double>(),
             c = pose * part.vertices[tri[2]].cast<double>();
    const V3 normal = (b - a).cross(c - a).normalized();
    const int ia = put(corner(tri[0], normal)), ib = put(corner(tri[1], normal)),
              ic = put(corner(tri[2], normal));
    add_triangle(mesh, ia, ib, ic,
                 {part.classes[t], part.materials.empty() ? std::uint16_t(0) : part.materials[t]});
  }
}

std::uint16_t add_material(Scene& scene, const Material& material) {
  scene.materials.push_back(material);
  return std::uint16_t(scene.materials.size() - 1);
}

}  // namespace flowscape
