#include "loft.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

namespace flowscape::assets {
namespace {

using Key = std::array<float, 3>;
Key key_of(const V3& p) { return {float(p.x()), float(p.y()), float(p.z())}; }

double signed_volume(const Mesh& mesh, std::size_t first_triangle) {
  double volume = 0;
  for (std::size_t t = first_triangle; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    volume += mesh.vertices[tri[0]].cast<double>().dot(mesh.vertices[tri[1]].cast<double>().cross(
                  mesh.vertices[tri[2]].cast<double>())) /
              6;
  }
  return volume;
}

// Turns the triangles from first_triangle on (and the normals of their vertices) inside out.
void flip_from(Mesh& mesh, std::size_t first_triangle, std::size_t first_vertex) {
  for (std::size_t t = first_triangle; t < mesh.triangles.size(); ++t)
    std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);
  for (std::size_t v = first_vertex; v < mesh.normals.size(); ++v)
    mesh.normals[v] = -mesh.normals[v];
}

// Keeps the per-vertex arrays of a mesh that has them in step with its vertices.
void pad_attributes(Mesh& mesh, std::size_t vertices_before) {
  if (mesh.normals.size() < vertices_before) mesh.normals.resize(vertices_before, {0, 0, 1});
  if (mesh.uvs.size() < vertices_before) mesh.uvs.resize(vertices_before, {0, 0});
  if (mesh.materials.size() < mesh.triangles.size())
    mesh.materials.resize(mesh.triangles.size(), 0);
}

}  // namespace

Curve::Curve(std::initializer_list<V2> points) : Curve(std::vector<V2>(points)) {}

Curve::Curve(std::vector<V2> points) : points_(std::move(points)) {
  const std::size_t n = points_.size();
  if (n == 0) throw std::invalid_argument("a curve needs a point");
  for (std::size_t i = 1; i < n; ++i)
    if (!(points_[i].x() > points_[i - 1].x()))
      throw std::invalid_argument("curve points must have increasing x");
  std::vector<double> secant(n > 1 ? n - 1 : 0);
  for (std::size_t i = 0; i + 1 < n; ++i)
    secant[i] = (points_[i + 1].y() - points_[i].y()) / (points_[i + 1].x() - points_[i].x());
  slopes_.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (i == 0 || i + 1 == n) {
      slopes_[i] = n > 1 ? secant[i == 0 ? 0 : n - 2] : 0;
    } else if (secant[i - 1] * secant[i] > 0) {  // Fritsch-Carlson: harmonic mean, no overshoot
      slopes_[i] = 2 / (1 / secant[i - 1] + 1 / secant[i]);
    }
  }
}

double Curve::operator()(double x) const {
  if (x <= points_.front().x()) return points_.front().y();
  if (x >= points_.back().x()) return points_.back().y();
  const auto upper = std::upper_bound(points_.begin(), points_.end(), x,
                                      [](double v, const V2& p) { return v < p.x(); });
  const std::size_t i = std::size_t(upper - points_.begin()) - 1;
  const double h = points_[i + 1].x() - points_[i].x(), s = (x - points_[i].x()) / h;
  const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s),
               h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
  return h00 * points_[i].y() + h10 * h * slopes_[i] + h01 * points_[i + 1].y() +
         h11 * h * slopes_[i + 1];
}

Curve Curve::scaled(double sx, double sy) const {
  std::vector<V2> points;
  for (const V2& p : points_) points.emplace_back(p.x() * sx, p.y() * sy);
  return Curve(points);
}

// A triangle of a grid before its vertices are made: positions' weld ids, unit normal, area.
struct GridTriangle {
  std::array<int, 3> position;
  std::array<int, 3> point;  // grid point (r * (C + 1) + c) of each corner, for uvs
  V3 normal;
  double area;
  QuadPaint paint;
};

void add_grid(Mesh& mesh, const Grid& grid, const std::function<QuadPaint(int, int)>& paint) {
  const int R = grid.rows, C = grid.columns, quads_across = grid.closed ? C : C - 1;
  if (R < 2 || C < 2 || int(grid.points.size()) != R * C)
    throw std::invalid_argument("a grid needs at least 2 x 2 points");
  const std::size_t first_vertex = mesh.vertices.size(), first_triangle = mesh.triangles.size();
  pad_attributes(mesh, first_vertex);
  const auto point = [&](int r, int c) -> const V3& {
    return grid.points[std::size_t(r) * C + (c % C)];
  };
  // texture coordinates: metres along the sweep (per column) and around the section (per row)
  std::vector<double> along(std::size_t(R) * (C + 1), 0), around(std::size_t(R) * (C + 1), 0);
  for (int r = 0; r < R; ++r)
    for (int c = 0; c <= C; ++c) {
      const std::size_t g = std::size_t(r) * (C + 1) + c;
      if (r > 0) along[g] = along[g - (C + 1)] + (point(r, c) - point(r - 1, c)).norm();
      if (c > 0) around[g] = around[g - 1] + (point(r, c) - point(r, c - 1)).norm();
    }
  std::map<Key, int> positions;  // welded position -> id
  std::vector<V3> welded;
  const auto position_id = [&](int r, int c) {
    const auto [it, fresh] = positions.try_emplace(key_of(point(r, c)), int(welded.size()));
    if (fresh) welded.push_back(point(r, c));
    return it->second;
  };
  std::vector<GridTriangle> triangles;
  for (int r = 0; r + 1 < R; ++r)
    for (int c = 0; c < quads_across; ++c) {
      const QuadPaint p = paint(r, c);
      if (p.skip) continue;
      const int rows[4] = {r, r + 1, r + 1, r}, cols[4] = {c, c, c + 1, c + 1};
      const bool short_diagonal = (point(r, c) - point(r + 1, c + 1)).squaredNorm() <=
                                  (point(r + 1, c) - point(r, c + 1)).squaredNorm();
      const int tris[2][3] = {{0, 1, 2}, {0, 2, 3}}, other[2][3] = {{0, 1, 3}, {1, 2, 3}};
      for (const auto& t : short_diagonal ? tris : other) {
        GridTriangle tri{};
        for (int k = 0; k < 3; ++k) {
          tri.position[k] = position_id(rows[t[k]], cols[t[k]]);
          tri.point[k] = rows[t[k]] * (C + 1) + cols[t[k]];
        }
        if (tri.position[0] == tri.position[1] || tri.position[1] == tri.position[2] ||
            tri.position[0] == tri.position[2])
          continue;
        const V3 n = (welded[tri.position[1]] - welded[tri.position[0]])
                         .cross(welded[tri.position[2]] - welded[tri.position[0]]);
        tri.area = n.norm() / 2;
        tri.normal = tri.area > 0 ? V3(n.normalized()) : V3::UnitZ();
        tri.paint = p;
        triangles.push_back(tri);
      }
    }
  // a section folding back on its neighbour (where a ring collapses) leaves coincident triangles
  // facing each other: they cancel, and dropping both keeps the surface closed
  std::map<std::array<int, 3>, std::vector<int>> by_corners;
  for (int t = 0; t < int(triangles.size()); ++t) {
    std::array<int, 3> key = triangles[t].position;
    std::sort(key.begin(), key.end());
    by_corners[key].push_back(t);
  }
  std::vector<bool> dropped(triangles.size(), false);
  for (const auto& [key, same] : by_corners)
    for (std::size_t i = 0; i < same.size(); ++i)
      for (std::size_t j = i + 1; j < same.size(); ++j)
        if (!dropped[same[i]] && !dropped[same[j]] &&
            triangles[same[i]].normal.dot(triangles[same[j]].normal) < 0)
          dropped[same[i]] = dropped[same[j]] = true;
  std::vector<GridTriangle> kept;
  for (std::size_t t = 0; t < triangles.size(); ++t)
    if (!dropped[t]) kept.push_back(triangles[t]);
  triangles = std::move(kept);
  // smooth normals: at each corner the area-weighted normals of the triangles of its slot round
  // its position that turn from its own by less than the crease angle
  std::vector<std::vector<int>> around_position(welded.size());
  for (int t = 0; t < int(triangles.size()); ++t)
    for (int k = 0; k < 3; ++k) around_position[triangles[t].position[k]].push_back(t);
  constexpr double kCrease = 0.5;  // cos 60 degrees
  std::map<std::tuple<int, int, std::uint16_t, std::array<int, 3>>, int> vertex_of;
  for (const GridTriangle& tri : triangles) {
    Eigen::Vector3i corners;
    for (int k = 0; k < 3; ++k) {
      V3 sum = V3::Zero();
      for (int t : around_position[tri.position[k]]) {
        const GridTriangle& other = triangles[t];
        if (other.paint.slot == tri.paint.slot && other.normal.dot(tri.normal) > kCrease)
          sum += other.area * other.normal;
      }
      const V3 normal = sum.norm() > 0 ? V3(sum.normalized()) : tri.normal;
      const std::array<int, 3> quantized{int(std::lround(normal.x() * 1e4)),
                                         int(std::lround(normal.y() * 1e4)),
                                         int(std::lround(normal.z() * 1e4))};
      const auto [it, fresh] = vertex_of.try_emplace(
          {tri.position[k], tri.point[k], tri.paint.slot, quantized}, int(mesh.vertices.size()));
      if (fresh) {
        mesh.vertices.push_back(welded[tri.position[k]].cast<float>());
        mesh.normals.push_back(normal.cast<float>());
        mesh.uvs.emplace_back(float(along[tri.point[k]]), float(around[tri.point[k]]));
      }
      corners[k] = it->second;
    }
    mesh.triangles.push_back(corners);
    mesh.classes.push_back(tri.paint.cls);
    mesh.materials.push_back(tri.paint.slot);
  }
  if (grid.closed && signed_volume(mesh, first_triangle) < 0)
    flip_from(mesh, first_triangle, first_vertex);
}

void add_lathe(Mesh& mesh, const std::vector<V2>& profile, int sides, SemanticClass cls,
               std::uint16_t slot) {
  Grid grid{int(profile.size()), sides, true, {}};
  for (const V2& p : profile)
    for (int k = 0; k < sides; ++k) {
      const double a = 2 * kPi * k / sides;
      grid.points.emplace_back(p.x() * std::cos(a), p.y(), p.x() * std::sin(a));
    }
  add_grid(mesh, grid, [&](int, int) { return QuadPaint{cls, slot}; });
}

void add_tube(Mesh& mesh, const std::vector<V3>& path, const std::vector<double>& radii, int sides,
              SemanticClass cls, std::uint16_t slot) {
  const int n = int(path.size());
  Grid grid{n + 2, sides, true, {}};
  V3 normal = Eigen::Vector3d::UnitZ();
  const auto ring = [&](int i) {
    const V3 tangent = (path[std::min(i + 1, n - 1)] - path[std::max(i - 1, 0)]).normalized();
    normal = (normal - normal.dot(tangent) * tangent);
    if (normal.norm() < 1e-6) normal = tangent.unitOrthogonal();
    normal.normalize();
    const V3 binormal = tangent.cross(normal);
    for (int k = 0; k < sides; ++k) {
      const double a = 2 * kPi * k / sides;
      grid.points.push_back(path[i] + radii[i] * (std::cos(a) * normal + std::sin(a) * binormal));
    }
  };
  grid.points.insert(grid.points.end(), sides, path.front());
  for (int i = 0; i < n; ++i) ring(i);
  grid.points.insert(grid.points.end(), sides, path.back());
  add_grid(mesh, grid, [&](int, int) { return QuadPaint{cls, slot}; });
}

void add_rounded_box(Mesh& mesh, const Pose& pose, const V3& half, double radius, SemanticClass cls,
                     std::uint16_t slot, int steps) {
  radius = std::min({radius, half.x(), half.y(), half.z()});
  const V3 core = half - V3::Constant(radius);
  // positions along an axis of half extent h: `steps` over each rounded end, the middle in one
  const auto coordinates = [&](double h) {
    std::vector<double> c;
    for (int k = 0; k <= steps; ++k) c.push_back(-h + radius * k / steps);
    for (int k = 0; k <= steps; ++k) c.push_back(h - radius + radius * k / steps);
    return c;
  };
  const auto rounded = [&](const V3& p) {
    const V3 inner = p.cwiseMax(-core).cwiseMin(core), d = p - inner;
    return pose * (d.norm() > 0 ? V3(inner + radius * d.normalized()) : inner);
  };
  // the six faces of the box, each a grid over the other two axes, rows x columns = u x v with
  // e_u x e_v pointing out of the face
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {-1.0, 1.0}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const std::vector<double> cu = coordinates(half[u]), cv = coordinates(half[v]);
      Grid grid{int(cu.size()), int(cv.size()), false, {}};
      for (double a : cu)
        for (double b : cv) {
          V3 p;
          p[axis] = side * half[axis], p[u] = side * a, p[v] = b;
          grid.points.push_back(rounded(p));
        }
      add_grid(mesh, grid, [&](int, int) { return QuadPaint{cls, slot}; });
    }
}

void add_ellipsoid(Mesh& mesh, const V3& centre, const V3& radii, SemanticClass cls,
                   std::uint16_t slot, int rings, int sides) {
  Grid grid{rings + 1, sides, true, {}};
  for (int r = 0; r <= rings; ++r) {
    const double lat = -kPi / 2 + kPi * r / rings;
    for (int k = 0; k < sides; ++k) {
      const double lon = 2 * kPi * k / sides;
      const V3 d(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
      grid.points.push_back(centre + d.cwiseProduct(radii));
    }
  }
  add_grid(mesh, grid, [&](int, int) { return QuadPaint{cls, slot}; });
}

void append_with_skin(Mesh& mesh, const Mesh& part, const Pose& pose) {
  const int base = int(mesh.vertices.size());
  pad_attributes(mesh, mesh.vertices.size());
  const bool skinned = part.skinned();
  if (skinned && mesh.bones.size() < mesh.vertices.size()) {
    mesh.bones.resize(mesh.vertices.size(), {0, 0, 0, 0});
    mesh.weights.resize(mesh.vertices.size(), {1, 0, 0, 0});
  }
  for (std::size_t v = 0; v < part.vertices.size(); ++v) {
    mesh.vertices.push_back((pose * part.vertices[v].cast<double>()).cast<float>());
    mesh.normals.push_back(
        part.normals.empty()
            ? Eigen::Vector3f(0, 0, 1)
            : (pose.linear() * part.normals[v].cast<double>()).normalized().cast<float>());
    mesh.uvs.push_back(part.uvs.empty() ? Eigen::Vector2f(0, 0) : part.uvs[v]);
    if (skinned) mesh.bones.push_back(part.bones[v]), mesh.weights.push_back(part.weights[v]);
  }
  for (std::size_t t = 0; t < part.triangles.size(); ++t) {
    mesh.triangles.push_back(part.triangles[t] + Eigen::Vector3i::Constant(base));
    mesh.classes.push_back(part.classes[t]);
    mesh.materials.push_back(part.materials.empty() ? 0 : part.materials[t]);
  }
}

Closure closure(const Mesh& mesh) {
  std::map<Key, int> positions;
  std::vector<int> id(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    id[v] = positions.try_emplace(key_of(mesh.vertices[v].cast<double>()), int(positions.size()))
                .first->second;
  std::map<std::pair<int, int>, int> edges;  // directed edge -> count
  for (const Eigen::Vector3i& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{id[t[k]], id[t[(k + 1) % 3]]}];
  Closure c;
  c.watertight = !mesh.triangles.empty();
  for (const auto& [edge, count] : edges) {
    const auto back = edges.find({edge.second, edge.first});
    if (count != 1 || back == edges.end() || back->second != 1) c.watertight = false;
  }
  c.volume = signed_volume(mesh, 0);
  return c;
}

}  // namespace flowscape::assets
