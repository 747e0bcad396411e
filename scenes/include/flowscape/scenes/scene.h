#pragma once
// What a renderer needs to know of a scene: triangle meshes with a CARLA class per triangle, and
// actors whose parts move rigidly with time. Scenes know nothing of the renderer.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "flowscape/core/types.h"
#include "flowscape/scenes/texture.h"

namespace flowscape {

using PoseTrack = std::function<Pose(double t)>;  // t in seconds

// CARLA 0.9.10-0.9.13 semantic classes (design.md).
enum class SemanticClass : std::uint8_t {
  Unlabeled = 0,
  Building = 1,
  Fence = 2,
  Other = 3,
  Pedestrian = 4,
  Pole = 5,
  RoadLine = 6,
  Road = 7,
  SideWalk = 8,
  Vegetation = 9,
  Vehicles = 10,
  Wall = 11,
  TrafficSign = 12,
  Sky = 13,
  Ground = 14,
  Bridge = 15,
  RailTrack = 16,
  GuardRail = 17,
  TrafficLight = 18,
  Static = 19,
  Dynamic = 20,
  Water = 21,
  Terrain = 22
};

// Image files of a material (glTF's metallic-roughness model), looked up with mip-mapped filtering
// at the surface's uv. Colours are sRGB-encoded files; the others hold linear data.
struct ImageMaps {
  std::string base_color;          // RGB(A): multiplies the albedo; A is the coverage
  std::string metallic_roughness;  // G: roughness, B: metalness (glTF)
  std::string normal;              // tangent-space normal map (glTF: +y up in the image)
  float alpha_cutoff = -1;         // >= 0: texels with coverage below it are holes (alpha mask)
  bool empty() const { return base_color.empty() && metallic_roughness.empty() && normal.empty(); }
};

// Surface appearance. Albedos are linear RGB reflectances in [0, 1].
struct Material {
  enum class Kind : std::uint8_t {
    Diffuse,   // Lambertian
    Glossy,    // diffuse base under a clear coat (car paint, plastic)
    Metal,     // tinted specular lobe
    Glass,     // smooth dielectric, index 1.5
    Emissive,  // a light: emits `emission`, reflects nothing
    Streak,  // a rain streak: with probability `opacity` glows with `emission`, else lets light by
  };
  Kind kind = Kind::Diffuse;
  Eigen::Vector3f albedo{0.6f, 0.6f, 0.6f};  // the mean colour (what is seen without textures)
  float roughness = 0.1f;                    // width of the Glossy / Metal lobe (0 = mirror)
  Eigen::Vector3f emission{0, 0, 0};         // linear radiance, W / (m^2 sr) per channel
  float opacity = 1;                         // Streak only
  std::shared_ptr<const Pattern> pattern;    // procedural texture (texture.h), or none
  ImageMaps images;                          // image textures, or none
};

// Per-vertex attributes are optional: each is empty or holds one entry per vertex.
struct Mesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;
  std::vector<SemanticClass> classes;    // one per triangle
  std::vector<std::uint16_t> materials;  // one per triangle, into Scene::materials; empty = all 0
  std::vector<Eigen::Vector3f> normals;  // unit shading normals (smooth shading); empty = flat
  std::vector<Eigen::Vector2f> uvs;      // texture coordinates; empty = all 0
  // Tangents along +u with the bitangent's handedness in w (glTF); empty = from the uvs per
  // triangle
  std::vector<Eigen::Vector4f> tangents;
};

// A participating medium whose extinction falls off with height: sigma(z) = density *
// exp(-(z - base) / height). It scatters isotropically with `albedo`; it changes colour only.
struct Fog {
  double density = 0;  // extinction at z = base, 1/m; 0 = clear air
  double height = 20;  // metres for the extinction to fall by e
  double base = 0;
  Eigen::Vector3f albedo{0.9f, 0.9f, 0.9f};
};

// Light from outside the scene (a sun disc and a sky dome) and the air in between.
struct Environment {
  Eigen::Vector3d sun_direction = Eigen::Vector3d(0.4, 0.3, 0.87).normalized();  // towards the sun
  Eigen::Vector3f sun_irradiance{3.0f, 2.85f, 2.6f};  // on a plane facing the sun, linear RGB
  double sun_angular_radius = 0.00465;                // radians (the real sun)
  float sun_disc_visibility = 1;  // share of the disc's radiance seen directly (clouds hide it)
  Eigen::Vector3f sky_zenith{0.25f, 0.4f, 0.8f}, sky_horizon{0.7f, 0.8f, 0.9f};  // radiance
  Eigen::Vector3f ground{0.15f, 0.14f, 0.12f};  // radiance of the dome below the horizon
  Fog fog;
};

// A rigid piece of an actor (a car body, a wheel, a leg), posed relative to the actor.
struct Part {
  Mesh mesh;
  PoseTrack pose;
};

struct Actor {
  std::uint16_t instance;  // > 0; 0 is the static world
  std::vector<Part> parts;
  PoseTrack pose;
  // Seen by colour rays only (rain streaks, puddles): never in flow, ids, depth or validity.
  bool color_only = false;
};

struct Scene {
  Mesh world;  // static geometry, instance 0
  std::vector<Actor> actors;
  std::vector<Material> materials{Material{}};
  Environment environment;
};

// Pose of a part at time t: the actor's pose times the part's pose in the actor.
inline Pose part_pose(const Actor& actor, const Part& part, double t) {
  return actor.pose(t) * part.pose(t);
}

inline PoseTrack fixed_pose(const Pose& pose = Pose::Identity()) {
  return [pose](double) { return pose; };
}

}  // namespace flowscape
