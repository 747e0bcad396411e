#pragma once
// What a renderer needs to know of a scene: triangle meshes with a CARLA class per triangle, and
// actors whose parts move rigidly with time or deform (linear blend skinning over a skeleton).
// Scenes know nothing of the renderer.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "flowscape/core/types.h"
#include "flowscape/scenes/sky_dome.h"
#include "flowscape/scenes/texture.h"

namespace flowscape {

using PoseTrack = std::function<Pose(double t)>;  // t in seconds

// The classes a scene labels its triangles with: CARLA 0.9.10-0.9.13's (design.md), ids 0-22, and
// finer ones (23-29) that a release writes through its class table (release/classes.h): in the
// carla-0.9.13 table they become Vehicles, in carla-0.9.14 their own ids.
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
  Terrain = 22,
  Rider = 23,  // a person on a bicycle or a motorbike
  Car = 24,    // cars, vans, pickups
  Truck = 25,  // box trucks, lorries
  Bus = 26,
  Motorcycle = 27,
  Bicycle = 28,
  EgoVehicle = 29,  // the car the camera rig is mounted on (Cityscapes' "ego vehicle")
};
inline constexpr int kSceneClasses = 30;

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
    // A thin pane (a car's window): reflects as glass of index 1.5 does at both faces, lets the
    // rest straight through tinted by `albedo`; the sun shines through it. A surface like any
    // other to the ground truth (its class, instance, depth and flow are the pane's).
    Window,
  };
  Kind kind = Kind::Diffuse;
  Eigen::Vector3f albedo{0.6f, 0.6f, 0.6f};  // the mean colour (what is seen without textures)
  float roughness = 0.1f;                    // width of the Glossy / Metal lobe (0 = mirror)
  Eigen::Vector3f emission{0, 0, 0};         // linear radiance, W / (m^2 sr) per channel
  // What it emits when the lamps are on (a lamp's glass, a lit sign), in the sky's units before
  // the exposure: apply_weather makes it Emissive with emission night_emission x lamp_level.
  Eigen::Vector3f night_emission{0, 0, 0};
  // Emissive, it glows for the camera and in mirrors but lights nothing it is found from by chance:
  // a lamp's body (its light comes from its Lamp, Scene::lamps) or a lit window (its light on the
  // street is small next to the lamps', and found only by chance it would be noise).
  bool glow_only = false;
  float opacity = 1;                       // Streak only
  std::shared_ptr<const Pattern> pattern;  // procedural texture (texture.h), or none
  // Where it glows once the lamps are on (a traffic light's lit lamp): apply_weather puts it in
  // place of `pattern`, and the Emissive surface glows with emission x the albedo it gives.
  std::shared_ptr<const Pattern> night_pattern;
  ImageMaps images;  // image textures, or none
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
  // Linear blend skinning: per vertex up to four bones (indices into the part's BoneTrack) and
  // their weights (summing to 1); empty = rigid. The vertices above are the rest pose.
  std::vector<std::array<std::uint8_t, 4>> bones;
  std::vector<Eigen::Vector4f> weights;
  bool skinned() const { return !bones.empty(); }
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
  // The sky above the horizon as a table (weather's physical sky: atmosphere and clouds); null: the
  // gradient from sky_horizon to sky_zenith.
  std::shared_ptr<const SkyDome> sky_dome;
  double exposure = 1;  // the camera's: already applied to every radiance above (recorded)
  // What the lamps' intensities (Scene::lamps) are multiplied by: 0 by day (lamps off), the
  // exposure once the sun has set. At night the sun above is the moon.
  double lamp_level = 0;
  Fog fog;
};

// Where the bones of a skinned part are at time t: bone k maps the mesh's rest pose to the part's
// frame, so a vertex is at sum_k w_k bones[k] * rest (then posed with the part).
using BoneTrack = std::function<std::vector<Pose>(double t)>;

// A piece of an actor (a car body, a wheel, a person's skinned body), posed relative to the actor.
// Meshes are shared: every part showing the same mesh uses one BVH (a model's four wheels, every
// car of one model); `materials` then gives each part its own look.
struct Part {
  std::shared_ptr<const Mesh> mesh;
  PoseTrack pose;
  BoneTrack bones{};  // empty: rigid; else (mesh->skinned()) the skeleton's poses over time
  // The scene material of each material slot of the mesh (mesh->materials index it); empty: the
  // mesh's indices are scene materials.
  std::vector<std::uint16_t> materials{};
  // Fixed to the camera rig (the ego vehicle's body): a camera of the rig sees it at the same
  // pixel at every time, so its flow is exactly zero there.
  bool on_rig = false;
};
inline Part rigid_part(
    Mesh mesh, PoseTrack pose = [](double) { return Pose::Identity(); }) {
  return {std::make_shared<const Mesh>(std::move(mesh)), std::move(pose)};
}

// The material index a part's triangle is drawn with.
inline std::uint16_t part_material(const Part& part, std::size_t triangle) {
  const std::uint16_t slot = part.mesh->materials.empty() ? 0 : part.mesh->materials[triangle];
  return part.materials.empty() ? slot : part.materials[slot];
}

struct Actor {
  std::uint16_t instance;  // > 0; 0 is the static world
  std::vector<Part> parts;
  PoseTrack pose;
  // Seen by colour rays only (rain streaks, puddles): never in flow, ids, depth or validity.
  bool color_only = false;
};

// A lamp's light: a point source (a street lamp's bulb, a vehicle's head lamp) that shines when
// the environment's lamp_level is above 0, reaching surfaces by next-event estimation only; what a
// camera sees of it is its glowing body (its materials' night_emission).
struct Lamp {
  Vec3 position = Vec3::Zero();  // in its actor's frame, or the world's
  Vec3 axis = -Vec3::UnitZ();    // the beam's axis (unit)
  // Full intensity within cos_inner of the axis, none beyond cos_outer, a smooth step between
  // (pbrt's spot light); -1, -1: all round.
  double cos_inner = -1, cos_outer = -1;
  // On the axis, linear RGB, in the sky's units before the exposure (irradiance x m^2: the
  // top-of-atmosphere sun is 1; a 1000 cd street lamp is 0.01).
  Eigen::Vector3f intensity{0, 0, 0};
  int actor = -1;  // index into Scene::actors, or -1: fixed to the world
};

struct Scene {
  Mesh world;  // static geometry, instance 0
  std::vector<Actor> actors;
  std::vector<Lamp> lamps;
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
