#pragma once
// Internal: what the path tracer needs of a surface point: its frame, its material and its look
// with textures (procedural patterns and image maps) filtered over the ray's footprint.
#include "render/embree_scene.h"
#include "render/image_textures.h"

namespace flowscape {

using Rgb = Eigen::Vector3d;

struct Surface {
  Vec3 position;
  Vec3 geometric;  // unit geometric normal, facing the incoming ray
  Vec3 normal;     // unit shading normal (interpolated, bumped, normal-mapped), on the same side
  Vec3 smooth;     // the interpolated normal before textures tilt it
  bool front;      // the ray arrives from the side the geometric normal points to
  const Material* material;
  Rgb albedo;
  double roughness;
};

// A material's look from its textures at one point: albedo, roughness, and how they tilt the
// shading normal (bump slope over uv, normal-map normal in tangent space).
struct TexturedLook {
  Rgb albedo;
  double roughness;
  Vec2 slope = Vec2::Zero();
  Vec3 mapped = Vec3::Zero();  // zero: no normal map
};

bool is_textured(const EmbreeScene& embree, const Hit& hit);
// The look of the hit triangle's material at `point` (world, on the triangle's plane, inside it or
// not) seen along `dir`, filtered over `footprint`: the width of the ray's cone there (metres).
TexturedLook textured_look(const EmbreeScene& embree, const ImageTextures& images, const Hit& hit,
                           const Vec3& point, const Vec3& dir, double footprint);

// The surface `hit` along origin + t dir, with a textured look or (null) its material's plain one.
Surface surface_at(const EmbreeScene& embree, const Hit& hit, const Vec3& origin, const Vec3& dir,
                   const TexturedLook* look);

}  // namespace flowscape
