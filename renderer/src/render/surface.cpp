#include "render/surface.h"

#include <algorithm>
#include <cmath>

namespace flowscape {
namespace {

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

std::size_t material_index(const EmbreeScene& embree, const Hit& hit) {
  return material_of(embree.mesh(hit.mesh), hit.triangle);
}

const Material& material_of(const EmbreeScene& embree, const Hit& hit) {
  return embree.scene().materials[material_index(embree, hit)];
}

// How uv runs over a triangle, in the mesh's frame: dp/du, dp/dv, and uv units per metre.
struct UvFrame {
  Vec3 dpdu = Vec3::UnitX(), dpdv = Vec3::UnitY();
  double uv_per_metre = 1;
};

UvFrame uv_frame(const Mesh& mesh, const Eigen::Vector3i& tri) {
  if (mesh.uvs.empty()) return {};
  const Vec3 p0 = mesh.vertices[tri[0]].cast<double>();
  const Vec3 dp1 = mesh.vertices[tri[1]].cast<double>() - p0,
             dp2 = mesh.vertices[tri[2]].cast<double>() - p0;
  const Vec2 uv0 = mesh.uvs[tri[0]].cast<double>();
  const Vec2 duv1 = mesh.uvs[tri[1]].cast<double>() - uv0,
             duv2 = mesh.uvs[tri[2]].cast<double>() - uv0;
  const double det = duv1.x() * duv2.y() - duv2.x() * duv1.y(), area = dp1.cross(dp2).norm();
  if (std::abs(det) < 1e-12 || area < 1e-12) return {};
  return {(duv2.y() * dp1 - duv1.y() * dp2) / det, (duv1.x() * dp2 - duv2.x() * dp1) / det,
          std::sqrt(std::abs(det) / area)};
}

// Barycentric (u, v) of a point of a triangle's plane, in the mesh's frame.
Vec2 barycentric(const Mesh& mesh, const Eigen::Vector3i& tri, const Vec3& point) {
  const Vec3 p0 = mesh.vertices[tri[0]].cast<double>();
  const Vec3 e1 = mesh.vertices[tri[1]].cast<double>() - p0,
             e2 = mesh.vertices[tri[2]].cast<double>() - p0, d = point - p0;
  const double a = e1.dot(e1), b = e1.dot(e2), c = e2.dot(e2), det = a * c - b * b;
  if (std::abs(det) < 1e-30) return Vec2::Zero();
  return {(c * e1.dot(d) - b * e2.dot(d)) / det, (a * e2.dot(d) - b * e1.dot(d)) / det};
}

template <class T>
T interpolate(const std::vector<T>& values, const Eigen::Vector3i& tri, double u, double v) {
  return float(1 - u - v) * values[tri[0]] + float(u) * values[tri[1]] + float(v) * values[tri[2]];
}

// A tilted shading normal is kept only while it stays on the geometric normal's side.
void set_normal(Surface& s, Vec3 normal) {
  normal.normalize();
  if (normal.allFinite() && normal.dot(s.geometric) > 0.05) s.normal = normal;
}

void apply_images(const ImageTextures& images, const ImageTextures::Ids& ids, const Vec2& uv,
                  double footprint, TexturedLook& look) {
  float texel[4];
  if (ids.base_color >= 0) {
    images.lookup(ids.base_color, uv, footprint, 3, texel);
    for (int c = 0; c < 3; ++c) look.albedo[c] *= srgb_to_linear(texel[c]);
  }
  if (ids.metallic_roughness >= 0) {
    images.lookup(ids.metallic_roughness, uv, footprint, 3, texel);
    look.roughness *= texel[1];
  }
  if (ids.normal >= 0) {
    images.lookup(ids.normal, uv, footprint, 3, texel);
    look.mapped = Vec3(2.0 * texel[0] - 1, 2.0 * texel[1] - 1, 2.0 * texel[2] - 1);
  }
}

}  // namespace

bool is_textured(const EmbreeScene& embree, const Hit& hit) {
  const Material& m = material_of(embree, hit);
  return m.pattern || !m.images.empty();
}

TexturedLook textured_look(const EmbreeScene& embree, const ImageTextures& images, const Hit& hit,
                           const Vec3& point, const Vec3& dir, double footprint) {
  const Mesh& mesh = *embree.mesh(hit.mesh).mesh;
  const Eigen::Vector3i& tri = mesh.triangles[hit.triangle];
  const Material& m = material_of(embree, hit);
  const Vec3 local = embree.world_to_object(hit) * point;
  const Vec2 b = barycentric(mesh, tri, local);
  const Vec3 fixed = embree.mesh(hit.mesh).skinned < 0
                         ? local
                         : embree.pattern_point({true, hit.mesh, hit.triangle, hit.distance,
                                                 hit.normal, float(b.x()), float(b.y()), hit.time},
                                                point);
  const Vec2 uv = interpolated_uv(mesh, hit.triangle, b.x(), b.y());
  const UvFrame frame = uv_frame(mesh, tri);
  // the cone's footprint on the surface, lengthened by the slant (the geometric mean of the
  // ellipse's axes), in uv units
  const Vec3 normal = (embree.pose_of(hit).linear() * hit.normal.cast<double>()).normalized();
  const double slant = std::max(std::abs(dir.dot(normal)), 0.05);
  const double uv_footprint = footprint / std::sqrt(slant) * frame.uv_per_metre;
  TexturedLook look{m.albedo.cast<double>(), m.roughness};
  if (m.pattern) {
    const SurfaceLook result = (*m.pattern)({uv, fixed, uv_footprint}, {m.albedo, m.roughness});
    look.albedo = result.albedo.cast<double>(), look.roughness = result.roughness;
    look.slope = result.slope * frame.uv_per_metre;
  }
  if (!m.images.empty())
    apply_images(images, images.of(material_index(embree, hit)), uv, uv_footprint, look);
  return look;
}

Surface surface_at(const EmbreeScene& embree, const Hit& hit, const Vec3& origin, const Vec3& dir,
                   const TexturedLook* look) {
  const Mesh& mesh = *embree.mesh(hit.mesh).mesh;
  const Mat3 rotation = embree.pose_of(hit).linear();
  const Material& m = material_of(embree, hit);
  Surface s;
  s.geometric = (rotation * hit.normal.cast<double>()).normalized();
  s.front = s.geometric.dot(dir) < 0;
  if (!s.front) s.geometric = -s.geometric;
  s.normal = s.smooth = s.geometric;
  s.position = origin + hit.distance * dir;
  s.material = &m;
  s.albedo = look ? look->albedo : m.albedo.cast<double>();
  s.roughness = look ? look->roughness : m.roughness;
  if (mesh.normals.empty() && !look) return s;
  const Eigen::Vector3i& tri = mesh.triangles[hit.triangle];
  if (!mesh.normals.empty()) {
    const Vec3 n = rotation * interpolate(mesh.normals, tri, hit.u, hit.v).cast<double>();
    set_normal(s, s.front ? n : -n);
  }
  s.smooth = s.normal;
  if (!look || (look->slope.isZero() && look->mapped.isZero())) return s;
  const UvFrame frame = uv_frame(mesh, tri);
  Vec3 tangent = (rotation * frame.dpdu).normalized(),
       bitangent = (rotation * frame.dpdv).normalized();
  if (!look->slope.isZero())
    set_normal(s, s.normal - look->slope.x() * tangent - look->slope.y() * bitangent);
  if (!look->mapped.isZero()) {
    if (!mesh.tangents.empty()) {  // the model's own frame (glTF): bitangent = w (n x t)
      const Eigen::Vector4f given = interpolate(mesh.tangents, tri, hit.u, hit.v);
      tangent = (rotation * given.head<3>().cast<double>()).normalized();
      bitangent = given.w() * s.normal.cross(tangent);
    }
    set_normal(
        s, look->mapped.x() * tangent + look->mapped.y() * bitangent + look->mapped.z() * s.normal);
  }
  return s;
}

}  // namespace flowscape
