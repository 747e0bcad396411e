#pragma once
// Models in and out of scenes: user models for actors (glTF through tinygltf, OBJ/FBX/... through
// assimp) and whole maps exported as glTF 2.0 with the semantic class of every node in its extras.
// Errors throw std::runtime_error("<path>: <problem>").
#include <string>
#include <vector>

#include "flowscape/scenes/scene.h"

namespace flowscape {

// One mesh of class `cls`, turned from the file's y-up, z-forward frame into ours (x forward, y
// left, z up), scaled to `length` metres along x, centred on the origin in x and y and standing on
// z = 0. It keeps the file's uvs, normals (smooth shading; a file without them is flat-shaded) and
// tangents, and its materials are added to `scene`: base colour, metallic-roughness and normal
// textures, alpha masks (glTF MASK; BLEND is treated as MASK at 0.5). Triangles without a
// material get `fallback`. Textures embedded in the file are written once to the texture cache
// (texture_cache_dir()) so that the renderer's TextureSystem can mip-map them. `turn` turns the
// model after that (TORCS's cars: kTorcsTurn).
Mesh load_model(const std::string& path, SemanticClass cls, double length, Scene& scene,
                const Material& fallback = {}, const Mat3& turn = Mat3::Identity());
// A user's static world (a scenario's world file): its units and up axis as the file has them, and
// the class of each part (a glTF node, else its mesh; an OBJ object or group) from the first
// pattern its name matches (shell globs, case-insensitive: "road*", "*tree*", "*").
struct WorldClass {
  std::string pattern;
  SemanticClass cls;
};
struct WorldModel {
  std::string path;
  double metres_per_unit = 1;
  bool z_up = false;  // up along the file's z (Blender's, CAD's); else along its y (glTF's, OBJ's)
  std::vector<WorldClass> classes;
};
// The world in our frame (x, y on the ground, z up) in metres, placed where the file puts it, with
// its materials and textures as load_model reads them. A part whose name no pattern matches, an
// animation or a skin is an error naming the file.
Mesh load_world(const WorldModel& world, Scene& scene);

// A glTF file's perspective camera (a rig from a 3-D tool's scene: --rig-from scene.gltf): its
// node's name, vertical field of view, aspect ratio (width / height; 0 where the file gives none)
// and pose, its optical frame (x right, y down, z forward; glTF's cameras look along their -z,
// y up) -> the file's world in our axes (x forward, y left, z up), in the file's units.
struct FileCamera {
  std::string name;
  double yfov_degrees = 0, aspect_ratio = 0;
  Pose pose = Pose::Identity();
};
// Every camera node of the default scene, in the order the walk meets them. An orthographic
// camera or a field of view outside (0, 180) degrees is an error naming the file and node.
std::vector<FileCamera> gltf_cameras(const std::string& path);

// What turns TORCS's cars forward: read y-up, their length lies along y (their nose at -y).
inline const Mat3 kTorcsTurn = (Mat3() << 0, -1, 0, 1, 0, 0, 0, 0, 1).finished();

// Where embedded textures go: $FLOWSCAPE_TEXTURE_CACHE, else <temp dir>/flowscape-textures; one
// file per distinct image, named by a hash of its bytes.
std::string texture_cache_dir();

// The world and every actor posed at time t, one glTF node per (instance, class) with extras
// {"class_id": id, "class": name, "instance": id}; y-up as glTF wants it.
void export_gltf(const Scene& scene, double t, const std::string& path);

struct ExportedMesh {
  std::uint16_t instance;
  Mesh mesh;  // back in our frame, one class per triangle from the node extras
};
// Reads a file written by export_gltf, nodes merged per instance in file order.
std::vector<ExportedMesh> import_gltf(const std::string& path);

std::string class_name(SemanticClass cls);  // "Road", "SideWalk", ...
// The class of a name class_name gives (any case); throws std::invalid_argument listing them.
SemanticClass class_from_name(const std::string& name);

}  // namespace flowscape
