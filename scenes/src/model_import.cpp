// Users' models for actors: glTF through tinygltf, everything else through assimp, with their uvs,
// normals, tangents and textured materials.
#include <assimp/GltfMaterial.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fnmatch.h>

#include <Eigen/SVD>
#include <algorithm>
#include <assimp/Importer.hpp>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>

#include "flowscape/core/files.h"
#include "flowscape/core/random.h"
#include "flowscape/scenes/model_io.h"
#include "flowscape/scenes/shapes.h"
#include "gltf_read.h"
#include "model_files.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

using V3 = Eigen::Vector3d;

// What one actor model may hold: far more than any real car (1e5-1e6), and a bound on the memory a
// file that instances a mesh many times can claim.
constexpr std::size_t kMaxModelTriangles = std::size_t(1) << 23;

// A texture the file holds inside itself, as a file of its own in the cache (named by its bytes).
std::string cached_texture(const unsigned char* bytes, std::size_t size, const std::string& type) {
  std::uint64_t hash = mix_bits(size);
  for (std::size_t k = 0; k < size; ++k) hash = mix_bits(hash ^ bytes[k]);
  char name[32];
  std::snprintf(name, sizeof name, "%016llx", static_cast<unsigned long long>(hash));
  const fs::path path = fs::path(texture_cache_dir()) / (name + ("." + type));
  if (!fs::exists(path)) write_text(path, std::string(reinterpret_cast<const char*>(bytes), size));
  return path.string();
}

// "%20" and friends in a glTF uri.
std::string decoded_uri(const std::string& uri) {
  std::string out;
  for (std::size_t k = 0; k < uri.size(); ++k) {
    if (uri[k] == '%' && k + 2 < uri.size()) {
      out += char(std::strtol(uri.substr(k + 1, 2).c_str(), nullptr, 16));
      k += 2;
    } else {
      out += uri[k];
    }
  }
  return out;
}

// The names a part goes by: its node's (else its mesh's), then its ancestors', nearest first.
using Lineage = std::vector<std::string>;

// How a file is read: the class of each of its parts (from its lineage) and whether its up axis is
// z (ours) rather than y (glTF's, and most other formats').
struct Reading {
  std::function<SemanticClass(const Lineage& names)> class_of;
  bool z_up = false;
  bool world = false;  // a world holds still: animations and skins are refused
  Eigen::Vector3d axes(const V3& v) const { return z_up ? v : from_y_up(v); }
};

// What import collects: the mesh in our axes and its attributes' availability.
struct Imported {
  Reading reading;
  Mesh mesh;
  bool normals = true, uvs = false, tangents = true;  // every part had them
};

// Appends one part's vertices; attributes that some part lacks are dropped at the end.
void add_part(Imported& out, const std::vector<V3>& positions, const std::vector<V3>& normals,
              const std::vector<Eigen::Vector2d>& uvs, const std::vector<Eigen::Vector4d>& tangents,
              const std::vector<int>& indices, std::uint16_t material, SemanticClass cls,
              const std::string& path) {
  const int base = int(out.mesh.vertices.size());
  out.normals = out.normals && normals.size() == positions.size();
  out.uvs = out.uvs || !uvs.empty();
  out.tangents = out.tangents && tangents.size() == positions.size();
  for (std::size_t v = 0; v < positions.size(); ++v) {
    out.mesh.vertices.push_back(out.reading.axes(positions[v]).cast<float>());
    out.mesh.normals.push_back(
        v < normals.size()
            ? Eigen::Vector3f(out.reading.axes(normals[v]).normalized().cast<float>())
            : Eigen::Vector3f::Zero());
    out.mesh.uvs.push_back(v < uvs.size() ? Eigen::Vector2f(uvs[v].cast<float>())
                                          : Eigen::Vector2f::Zero());
    const Eigen::Vector4d t = v < tangents.size() ? tangents[v] : Eigen::Vector4d::Zero();
    const Eigen::Vector3d turned = out.reading.axes(t.head<3>());
    out.mesh.tangents.emplace_back(float(turned.x()), float(turned.y()), float(turned.z()),
                                   float(t.w()));
  }
  if (out.mesh.triangles.size() + indices.size() / 3 > kMaxModelTriangles ||
      out.mesh.vertices.size() + positions.size() > kMaxModelTriangles)
    fail(path, "more than " + std::to_string(kMaxModelTriangles) +
                   " triangles or vertices (instances included): too large for an actor model");
  for (std::size_t k = 0; k + 2 < indices.size(); k += 3) {
    for (int c = 0; c < 3; ++c)
      if (indices[k + c] < 0 || std::size_t(indices[k + c]) >= positions.size())
        fail(path, "triangle index out of range");
    out.mesh.triangles.emplace_back(base + indices[k], base + indices[k + 1],
                                    base + indices[k + 2]);
    out.mesh.classes.push_back(cls);
    out.mesh.materials.push_back(material);
  }
}

Mesh finished(Imported imported) {
  Mesh& mesh = imported.mesh;
  if (!imported.normals) mesh.normals.clear();
  if (!imported.uvs) mesh.uvs.clear();
  if (!imported.tangents || mesh.normals.empty()) mesh.tangents.clear();
  return std::move(mesh);
}

// glTF's metallic-roughness model in our materials: metal, a clear-coated base while the surface is
// smooth enough to show a coat, Lambertian when it is rough.
Material::Kind pbr_kind(double metallic, double roughness) {
  if (metallic >= 0.5) return Material::Kind::Metal;
  return roughness >= 0.6 ? Material::Kind::Diffuse : Material::Kind::Glossy;
}

// ---- glTF ------------------------------------------------------------------------------------

// A texture's image: its own source, else the source of its EXT_texture_webp extension (files
// that require the extension, Godot's and web-optimised ones, carry only that).
int texture_source(const tinygltf::Texture& texture) {
  if (texture.source >= 0) return texture.source;
  const auto webp = texture.extensions.find("EXT_texture_webp");
  if (webp == texture.extensions.end() || !webp->second.Has("source")) return -1;
  const tinygltf::Value& source = webp->second.Get("source");
  return source.IsInt() ? source.GetNumberAsInt() : -1;
}

std::string gltf_image(const tinygltf::Model& model, int texture, const std::string& path) {
  if (texture < 0) return {};
  if (texture >= int(model.textures.size())) fail(path, "a material names a missing texture");
  const int source = texture_source(model.textures[texture]);
  if (source < 0 || source >= int(model.images.size()))
    fail(path, "texture " + std::to_string(texture) + " names a missing image (" +
                   std::to_string(source) + " of " + std::to_string(model.images.size()) + ")");
  const tinygltf::Image& image = model.images[source];
  if (image.uri.starts_with("data:image/webp"))  // tinygltf decodes no WebP data uri
    fail(path, "image " + std::to_string(source) +
                   " is WebP in a data: uri, which the glTF reader cannot decode: keep it in the "
                   "binary buffer (.glb) or in a file beside the model");
  if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0)
    return (fs::path(path).parent_path() / decoded_uri(image.uri)).string();
  if (image.image.empty()) fail(path, "an embedded image has no bytes");
  const std::string type = image.mimeType == "image/jpeg"   ? "jpg"
                           : image.mimeType == "image/webp" ? "webp"
                                                            : "png";
  return cached_texture(image.image.data(), image.image.size(), type);  // named by its type
}

Material gltf_material(const tinygltf::Model& model, const tinygltf::Material& m,
                       const std::string& path) {
  const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
  Material out;
  if (pbr.baseColorFactor.size() >= 3)
    out.albedo = Eigen::Vector3f(float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]),
                                 float(pbr.baseColorFactor[2]));
  out.kind = pbr_kind(pbr.metallicFactor, pbr.roughnessFactor);
  out.roughness = float(pbr.roughnessFactor);
  out.images.base_color = gltf_image(model, pbr.baseColorTexture.index, path);
  out.images.metallic_roughness = gltf_image(model, pbr.metallicRoughnessTexture.index, path);
  out.images.normal = gltf_image(model, m.normalTexture.index, path);
  if (m.alphaMode == "MASK") out.images.alpha_cutoff = float(m.alphaCutoff);
  if (m.alphaMode == "BLEND") out.images.alpha_cutoff = 0.5f;
  return out;
}

template <int N>
std::vector<Eigen::Matrix<double, N, 1>> gltf_attribute(const tinygltf::Model& model,
                                                        const tinygltf::Primitive& primitive,
                                                        const char* name, const std::string& path) {
  std::vector<Eigen::Matrix<double, N, 1>> values;
  const auto found = primitive.attributes.find(name);
  if (found == primitive.attributes.end()) return values;
  const tinygltf::Accessor& accessor = accessor_at(model, found->second, path);
  if (tinygltf::GetNumComponentsInType(accessor.type) < N)
    fail(path, std::string(name) + " has too few components");
  const std::size_t count = accessor_count(model, accessor, path);
  for (std::size_t i = 0; i < count; ++i) {
    Eigen::Matrix<double, N, 1> value;
    for (int c = 0; c < N; ++c) value[c] = accessor_value(model, accessor, i, c, path);
    values.push_back(value);
  }
  return values;
}

// Places a part's attributes by its node's transform (normals by its inverse transpose).
void transform_part(const Eigen::Matrix4d& transform, std::vector<V3>& positions,
                    std::vector<V3>& normals, std::vector<Eigen::Vector4d>& tangents) {
  const Eigen::Matrix3d linear = transform.topLeftCorner<3, 3>(),
                        normal_matrix = linear.inverse().transpose();
  for (V3& p : positions) p = (transform * p.homogeneous()).head<3>();
  for (V3& n : normals) n = normal_matrix * n;
  for (Eigen::Vector4d& t : tangents) t.head<3>() = linear * t.head<3>();
}

// A world holds still: moving parts belong in actors.
void refuse_motion(bool animations, bool skins, const std::string& path) {
  if (animations) fail(path, "holds animations: a world model is static (script actors instead)");
  if (skins) fail(path, "holds skins: a world model is static (script actors instead)");
}

Mesh load_gltf(const std::string& path, const Reading& reading, Scene& scene,
               std::uint16_t fallback) {
  const tinygltf::Model model = read_gltf(path);
  if (reading.world)
    refuse_motion(!model.animations.empty(),
                  !model.skins.empty() || std::any_of(model.nodes.begin(), model.nodes.end(),
                                                      [](auto& n) { return n.skin >= 0; }),
                  path);
  std::map<int, std::uint16_t> materials;  // glTF material -> scene material
  Imported out{reading, {}};
  for_each_node(
      model, path,
      [&](const tinygltf::Node& node, const Eigen::Matrix4d& transform, Lineage names) {
        if (node.mesh < 0) return;
        if (node.mesh >= int(model.meshes.size()))
          fail(path, "node " + node.name + " refers to a mesh the file lacks");
        if (names.front().empty()) names.front() = model.meshes[node.mesh].name;
        const SemanticClass cls = reading.class_of(names);
        for (const tinygltf::Primitive& primitive : model.meshes[node.mesh].primitives) {
          if (primitive.mode != -1 && primitive.mode != TINYGLTF_MODE_TRIANGLES) continue;
          std::vector<V3> positions = gltf_attribute<3>(model, primitive, "POSITION", path),
                          normals = gltf_attribute<3>(model, primitive, "NORMAL", path);
          if (positions.empty()) fail(path, "a primitive has no POSITION");
          std::vector<Eigen::Vector4d> tangents =
              gltf_attribute<4>(model, primitive, "TANGENT", path);
          transform_part(transform, positions, normals, tangents);
          const std::vector<int> indices =
              triangle_indices(model, primitive, positions.size(), path);
          std::uint16_t material = fallback;
          if (primitive.material >= int(model.materials.size()))
            fail(path, "a primitive names a missing material");
          if (primitive.material >= 0) {
            auto [it, added] = materials.emplace(primitive.material, 0);
            if (added)
              it->second = add_material(
                  scene, gltf_material(model, model.materials[primitive.material], path));
            material = it->second;
          }
          add_part(out, positions, normals, gltf_attribute<2>(model, primitive, "TEXCOORD_0", path),
                   tangents, indices, material, cls, path);
        }
      });
  return finished(std::move(out));
}

// ---- assimp ----------------------------------------------------------------------------------

std::string assimp_texture(const aiScene* scene, const aiMaterial* material,
                           std::initializer_list<aiTextureType> types, const std::string& path) {
  for (aiTextureType type : types) {
    aiString name;
    if (material->GetTexture(type, 0, &name) != AI_SUCCESS) continue;
    if (const aiTexture* embedded = scene->GetEmbeddedTexture(name.C_Str())) {
      if (embedded->mHeight != 0) fail(path, "uncompressed embedded textures are not supported");
      return cached_texture(reinterpret_cast<const unsigned char*>(embedded->pcData),
                            embedded->mWidth,
                            embedded->achFormatHint[0] ? embedded->achFormatHint : "png");
    }
    std::string file = name.C_Str();  // OBJ files from Windows write .\texture.jpg
    std::replace(file.begin(), file.end(), '\\', '/');
    return (fs::path(path).parent_path() / file).lexically_normal().string();
  }
  return {};
}

Material assimp_material(const aiScene* scene, const aiMaterial* m, const std::string& path) {
  Material out;
  aiColor4D colour;
  if (m->Get(AI_MATKEY_BASE_COLOR, colour) == AI_SUCCESS ||
      m->Get(AI_MATKEY_COLOR_DIFFUSE, colour) == AI_SUCCESS)
    out.albedo = Eigen::Vector3f(colour.r, colour.g, colour.b);
  float metallic = 0, roughness = 0.5f;
  m->Get(AI_MATKEY_METALLIC_FACTOR, metallic);
  m->Get(AI_MATKEY_ROUGHNESS_FACTOR, roughness);
  out.kind = pbr_kind(metallic, roughness);
  out.roughness = roughness;
  out.images.base_color =
      assimp_texture(scene, m, {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE}, path);
  out.images.metallic_roughness =
      assimp_texture(scene, m, {aiTextureType_UNKNOWN, aiTextureType_DIFFUSE_ROUGHNESS}, path);
  out.images.normal = assimp_texture(scene, m, {aiTextureType_NORMALS}, path);
  aiString alpha_mode;
  if (m->Get(AI_MATKEY_GLTF_ALPHAMODE, alpha_mode) == AI_SUCCESS &&
      std::string(alpha_mode.C_Str()) != "OPAQUE") {
    float cutoff = 0.5f;
    m->Get(AI_MATKEY_GLTF_ALPHACUTOFF, cutoff);
    out.images.alpha_cutoff = cutoff;
  }
  return out;
}

// One assimp mesh of class `cls`, placed by `transform` (its node's, in the file's frame; null: as
// it is, for a file whose vertices are pre-transformed).
void add_assimp_mesh(Imported& out, const aiScene* file, const aiMesh* source,
                     const Eigen::Matrix4d* transform, SemanticClass cls,
                     std::map<unsigned, std::uint16_t>& materials, Scene& scene,
                     std::uint16_t fallback, const std::string& path) {
  std::vector<V3> positions, normals;
  std::vector<Eigen::Vector2d> uvs;
  std::vector<Eigen::Vector4d> tangents;
  for (unsigned v = 0; v < source->mNumVertices; ++v) {
    const aiVector3D& p = source->mVertices[v];
    positions.emplace_back(p.x, p.y, p.z);
    if (source->HasNormals())
      normals.emplace_back(source->mNormals[v].x, source->mNormals[v].y, source->mNormals[v].z);
    if (source->HasTextureCoords(0))
      uvs.emplace_back(source->mTextureCoords[0][v].x, source->mTextureCoords[0][v].y);
    if (source->HasTangentsAndBitangents() && source->HasNormals()) {
      const V3 t(source->mTangents[v].x, source->mTangents[v].y, source->mTangents[v].z),
          b(source->mBitangents[v].x, source->mBitangents[v].y, source->mBitangents[v].z);
      tangents.emplace_back(t.x(), t.y(), t.z(), normals.back().cross(t).dot(b) < 0 ? -1 : 1);
    }
  }
  if (transform) transform_part(*transform, positions, normals, tangents);
  std::vector<int> indices;
  for (unsigned f = 0; f < source->mNumFaces; ++f)
    if (source->mFaces[f].mNumIndices == 3)
      for (int c = 0; c < 3; ++c) indices.push_back(int(source->mFaces[f].mIndices[c]));
  std::uint16_t material = fallback;
  if (source->mMaterialIndex < file->mNumMaterials) {
    auto [it, added] = materials.emplace(source->mMaterialIndex, 0);
    if (added)
      it->second = add_material(
          scene, assimp_material(file, file->mMaterials[source->mMaterialIndex], path));
    material = it->second;
  }
  add_part(out, positions, normals, uvs, tangents, indices, material, cls, path);
}

Eigen::Matrix4d local_transform(const aiNode* node) {
  Eigen::Matrix4d local;
  const aiMatrix4x4& m = node->mTransformation;
  local << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
      m.d4;
  return local;
}

// Every node under the root, parents first, with its transform to the root and its lineage (the
// root, which assimp names after the file, left out); its own stack, nesting capped as glTF's.
void walk_assimp_nodes(
    const aiNode* root, const std::string& path,
    const std::function<void(const aiNode*, const Eigen::Matrix4d&, const Lineage&)>& visit) {
  struct Pending {
    const aiNode* node;
    Eigen::Matrix4d parent;
    std::size_t depth;
  };
  std::vector<Pending> pending{{root, Eigen::Matrix4d::Identity(), 0}};
  Lineage lineage;  // from the root's first child down
  while (!pending.empty()) {
    const Pending here = pending.back();
    pending.pop_back();
    if (here.depth >= kMaxNodeDepth)
      fail(path, "nodes nest more than " + std::to_string(kMaxNodeDepth) + " levels deep");
    lineage.resize(here.depth == 0 ? 0 : here.depth - 1);
    if (here.depth > 0) lineage.push_back(here.node->mName.C_Str());
    const Eigen::Matrix4d transform = here.parent * local_transform(here.node);
    visit(here.node, transform, {lineage.rbegin(), lineage.rend()});
    for (unsigned k = here.node->mNumChildren; k-- > 0;)
      pending.push_back({here.node->mChildren[k], transform, here.depth + 1});
  }
}

// A model's meshes come pre-transformed (one per material); a world's are walked node by node,
// each named by its node (an OBJ object or group), and refused when the file moves.
Mesh load_with_assimp(const std::string& path, const Reading& reading, Scene& scene,
                      std::uint16_t fallback) {
  Assimp::Importer importer;
  // uvs with their origin at the image's top-left corner, like glTF's and the texture lookups'
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                         aiProcess_CalcTangentSpace | aiProcess_FlipUVs;
  const std::string extension = fs::path(path).extension().string();
  if (extension == ".ply" || extension == ".PLY") check_ply(path, kMaxModelTriangles);
  const std::string grouped = reading.world && (extension == ".obj" || extension == ".OBJ")
                                  ? obj_with_groups_first(path)
                                  : "";
  const unsigned how = reading.world ? flags : flags | aiProcess_PreTransformVertices;
  const aiScene* file =
      grouped.empty() ? importer.ReadFile(path, how)
                      : importer.ReadFileFromMemory(grouped.data(), grouped.size(), how, "obj");
  if (!file || (file->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    fail(path, std::string("assimp cannot read it: ") + importer.GetErrorString());
  std::map<unsigned, std::uint16_t> materials;
  Imported out{reading, {}};
  if (!reading.world) {
    for (unsigned k = 0; k < file->mNumMeshes; ++k)
      add_assimp_mesh(out, file, file->mMeshes[k], nullptr, reading.class_of({""}), materials,
                      scene, fallback, path);
    return finished(std::move(out));
  }
  refuse_motion(file->mNumAnimations > 0,
                std::any_of(file->mMeshes, file->mMeshes + file->mNumMeshes,
                            [](const aiMesh* m) { return m->HasBones(); }),
                path);
  walk_assimp_nodes(file->mRootNode, path,
                    [&](const aiNode* node, const Eigen::Matrix4d& transform, Lineage names) {
                      if (names.empty()) names = {node->mName.C_Str()};  // meshes on the root
                      for (unsigned k = 0; k < node->mNumMeshes; ++k) {
                        const aiMesh* mesh = file->mMeshes[node->mMeshes[k]];
                        Lineage own = names;
                        if (own.front().empty()) own.front() = mesh->mName.C_Str();
                        add_assimp_mesh(out, file, mesh, &transform, reading.class_of(own),
                                        materials, scene, fallback, path);
                      }
                    });
  return finished(std::move(out));
}

// The class of the first pattern that matches the part's name or an ancestor's (a Sketchfab
// model's "Object_4" under its named "Car_body").
SemanticClass world_class(const WorldModel& world, const Lineage& names) {
  std::string patterns, seen;
  for (const WorldClass& c : world.classes) {
    for (const std::string& name : names)
      if (fnmatch(c.pattern.c_str(), name.c_str(), FNM_CASEFOLD) == 0) return c.cls;
    patterns += (patterns.empty() ? "" : ", ") + c.pattern;
  }
  for (std::size_t k = 1; k < names.size(); ++k) seen += (k == 1 ? " (in " : " < ") + names[k];
  fail(world.path, "its part \"" + names.front() + "\"" + (seen.empty() ? "" : seen + ")") +
                       " matches no class pattern (" + patterns +
                       "): add one (\"*\" takes the rest)");
}

// A file's parts as `reading` reads them: glTF through tinygltf, anything else through assimp.
Mesh load_mesh(const std::string& path, const Reading& reading, Scene& scene,
               std::uint16_t fallback) {
  const std::string extension = fs::path(path).extension().string();
  return extension == ".gltf" || extension == ".glb"
             ? load_gltf(path, reading, scene, fallback)
             : load_with_assimp(path, reading, scene, fallback);
}

}  // namespace

std::string texture_cache_dir() {
  if (const char* dir = std::getenv("FLOWSCAPE_TEXTURE_CACHE"); dir && *dir) return dir;
  return (fs::temp_directory_path() / "flowscape-textures").string();
}

Mesh load_world(const WorldModel& world, Scene& scene) {
  const std::string& path = world.path;
  if (!fs::is_regular_file(path)) fail(path, "no such world file");
  if (!(world.metres_per_unit > 0) || !std::isfinite(world.metres_per_unit))
    fail(path, "metres per unit must be positive");
  if (world.classes.empty()) fail(path, "a world needs classes: name patterns and their classes");
  const Reading reading{[&](const Lineage& names) { return world_class(world, names); }, world.z_up,
                        true};
  Material fallback;
  fallback.albedo = {0.5f, 0.5f, 0.5f};
  Mesh mesh = load_mesh(path, reading, scene, add_material(scene, fallback));
  if (mesh.triangles.empty()) fail(path, "the world has no triangles");
  for (Eigen::Vector3f& v : mesh.vertices) {
    v *= float(world.metres_per_unit);
    if (!v.allFinite()) fail(path, "a vertex is not finite");
    if (!within_world(v.cast<double>()))
      fail(path, "a vertex lies beyond 1,000 km of the origin (are the world's units right?)");
  }
  return mesh;
}

Mesh load_model(const std::string& path, SemanticClass cls, double length, Scene& scene,
                const Material& fallback, const Mat3& turn) {
  if (!fs::is_regular_file(path)) fail(path, "no such model file");
  if (!(length > 0)) fail(path, "model length must be positive");
  const Reading reading{[cls](const Lineage&) { return cls; }, false, false};
  Mesh mesh = load_mesh(path, reading, scene, add_material(scene, fallback));
  if (mesh.triangles.empty()) fail(path, "the model has no triangles");
  const Eigen::Matrix3f r = turn.cast<float>();
  for (Eigen::Vector3f& v : mesh.vertices) v = r * v;
  for (Eigen::Vector3f& n : mesh.normals) n = r * n;
  for (Eigen::Vector4f& t : mesh.tangents) t.head<3>() = r * t.head<3>();
  Eigen::Vector3f lo = mesh.vertices[0], hi = mesh.vertices[0];
  for (const Eigen::Vector3f& v : mesh.vertices) {
    if (!v.allFinite()) fail(path, "a vertex is not finite");
    lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  }
  if (!(hi.x() > lo.x())) fail(path, "the model has no extent along its forward axis");
  const float scale = float(length / (hi.x() - lo.x()));
  const Eigen::Vector3f centre((lo.x() + hi.x()) / 2, (lo.y() + hi.y()) / 2, lo.z());
  for (Eigen::Vector3f& v : mesh.vertices) v = (v - centre) * scale;
  return mesh;
}

std::vector<FileCamera> gltf_cameras(const std::string& path) {
  if (!fs::is_regular_file(path)) fail(path, "no such glTF file");
  const tinygltf::Model model = read_gltf(path);
  const Mat3 ours_from_gltf = (Mat3() << 0, 0, 1, 1, 0, 0, 0, 1, 0).finished();  // from_y_up
  const Mat3 gltf_camera_from_optical = Eigen::Vector3d(1, -1, -1).asDiagonal();
  std::vector<FileCamera> cameras;
  for_each_node(model, path,
                [&](const tinygltf::Node& node, const Eigen::Matrix4d& transform, const Lineage&) {
                  if (node.camera < 0) return;
                  if (node.camera >= int(model.cameras.size()))
                    fail(path, "node " + node.name + " refers to a camera the file lacks");
                  const tinygltf::Camera& camera = model.cameras[node.camera];
                  const std::string name = node.name.empty() ? camera.name : node.name;
                  if (camera.type != "perspective")
                    fail(path, "camera " + name + " is " + camera.type +
                                   ": only perspective cameras become rig cameras");
                  const double yfov = camera.perspective.yfov * 180 / kPi;
                  if (!(yfov > 0 && yfov < 180))
                    fail(path, "camera " + name + ": yfov must be between 0 and 180 degrees");
                  // the node's rotation, any scale taken out (polar decomposition)
                  const Eigen::JacobiSVD<Mat3> svd(transform.topLeftCorner<3, 3>(),
                                                   Eigen::ComputeFullU | Eigen::ComputeFullV);
                  const Mat3 rotation = svd.matrixU() * svd.matrixV().transpose();
                  if (!(rotation.determinant() > 0)) fail(path, "camera " + name + " is mirrored");
                  FileCamera out{name, yfov, camera.perspective.aspectRatio, Pose::Identity()};
                  out.pose.linear() = ours_from_gltf * rotation * gltf_camera_from_optical;
                  out.pose.translation() = ours_from_gltf * transform.topRightCorner<3, 1>();
                  if (!within_world(out.pose.translation()))
                    fail(path, "camera " + name + " lies beyond 1,000 km of the origin");
                  cameras.push_back(out);
                });
  return cameras;
}

}  // namespace flowscape
