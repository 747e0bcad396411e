#pragma once
// Internal: surfaces swept through cross-sections (lofts and lathes), the way the built-in models
// are made: a grid of points (rows along the sweep, columns around each section) becomes a mesh
// with smooth normals, texture coordinates in metres, and a material slot and class per quad.
#include <functional>
#include <vector>

#include "flowscape/scenes/scene.h"

namespace flowscape::assets {

using V3 = Eigen::Vector3d;
using V2 = Eigen::Vector2d;

// A smooth curve through (x, value) points with x increasing: monotone cubic interpolation
// (Fritsch-Carlson), so it never overshoots a control point; flat beyond the ends.
class Curve {
 public:
  Curve() = default;
  Curve(std::initializer_list<V2> points);
  explicit Curve(std::vector<V2> points);
  double operator()(double x) const;
  Curve scaled(double sx, double sy) const;  // x and values multiplied

 private:
  std::vector<V2> points_;
  std::vector<double> slopes_;
};

// A grid surface: rows x columns points, row r column c at points[r * columns + c]; columns wrap
// around when `closed` (a ring). Quad (r, c) joins rows r, r + 1 and columns c, c + 1; paint(r, c)
// gives its slot and class. The mesh's vertices are welded where they coincide (closing the ring
// and the ends a section shrinks to), degenerate triangles dropped, normals smooth across quads
// of one slot and creased between slots.
struct Grid {
  int rows = 0, columns = 0;
  bool closed = true;
  std::vector<V3> points;
  V3& at(int r, int c) { return points[std::size_t(r) * columns + c]; }
};
struct QuadPaint {
  SemanticClass cls;
  std::uint16_t slot;
  bool skip = false;  // leave the quad out (a hole)
};
void add_grid(Mesh& mesh, const Grid& grid, const std::function<QuadPaint(int, int)>& paint);

// A surface of revolution about the y axis (a wheel's axle): `profile` points (radius, y) from one
// end to the other, `sides` facets around; closed ends when the profile starts and ends on the
// axis.
void add_lathe(Mesh& mesh, const std::vector<V2>& profile, int sides, SemanticClass cls,
               std::uint16_t slot);
// A tube along a polyline with circular sections of the given radii (one per point), capped.
void add_tube(Mesh& mesh, const std::vector<V3>& path, const std::vector<double>& radii, int sides,
              SemanticClass cls, std::uint16_t slot);
// A box with rounded edges (a mirror, a seat, a lamp housing): half extents `half`, edge radius
// `radius`, placed by `pose`.
void add_rounded_box(Mesh& mesh, const Pose& pose, const V3& half, double radius, SemanticClass cls,
                     std::uint16_t slot, int steps = 3);
// An ellipsoid of semi-axes `radii` at `centre` (head, hand, hub cap).
void add_ellipsoid(Mesh& mesh, const V3& centre, const V3& radii, SemanticClass cls,
                   std::uint16_t slot, int rings = 8, int sides = 12);

// Appends `part` with its material slots shifted by nothing: the same as shapes.h's append_mesh
// but keeping per-vertex skin weights when both have them.
void append_with_skin(Mesh& mesh, const Mesh& part, const Pose& pose = Pose::Identity());

// Whether a closed mesh is watertight (every edge shared by exactly two triangles, once each way)
// and its signed volume (positive: normals point outward).
struct Closure {
  bool watertight = false;
  double volume = 0;
};
Closure closure(const Mesh& mesh);

}  // namespace flowscape::assets
