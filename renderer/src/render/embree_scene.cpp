#include "render/embree_scene.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <span>
#include <stdexcept>

#include "flowscape/core/profile.h"
#include "flowscape/renderer/ray_kernels.h"
#include "flowscape/scenes/skinning.h"

namespace flowscape {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Embree's filter: a hit on a hole of an alpha mask is no hit; nor is a window to the sun's rays.
void coverage_filter(const RTCFilterFunctionNArguments* args) {
  const auto* masked = static_cast<const MaskedMesh*>(args->geometryUserPtr);
  const MeshRef& ref = *masked->ref;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned primitive = RTCHitN_primID(args->hit, args->N, i);
    const unsigned triangle = masked->triangles ? (*masked->triangles)[primitive] : primitive;
    const std::uint16_t material = material_of(ref, triangle);
    if ((RTCRayN_mask(args->ray, args->N, i) & kSunMask) &&
        (*masked->materials)[material].kind == Material::Kind::Window) {
      args->valid[i] = 0;
      continue;
    }
    const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    if (masked->coverage && !masked->coverage->covered(material, *ref.rest, triangle, u, v))
      args->valid[i] = 0;
  }
}

void copy_vertices(const std::vector<Eigen::Vector3f>& from, float* vertices) {
  for (std::size_t i = 0; i < from.size(); ++i)
    for (int c = 0; c < 3; ++c) vertices[3 * i + c] = from[i][c];
}
void copy_vertices(const Mesh& mesh, float* vertices) { copy_vertices(mesh.vertices, vertices); }

// How a BVH is built: once for the world, once for an actor's mesh that many actors share (worth
// the slower, better build), or per posed time (skinned): Posed rebuilds it at every pose (its
// geometry's refit hint is ignored by Embree in a scene of the default medium quality; the ground
// truth's bytes were made so), Refit refits it (a low-quality, two-level scene: the rolling
// shutter's, posed once per line).
enum class Build { World, Shared, Posed, Refit };

using StepVertices = std::vector<std::vector<Eigen::Vector3f>>;

// A triangle geometry of `mesh` (of the triangles `only` lists, or all), built as `build` says;
// with `steps`, its vertices at each step of a shutter.
RTCGeometry triangle_geometry(RTCDevice device, const Mesh& mesh, Build build,
                              const StepVertices* steps, const std::vector<unsigned>* only) {
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (build == Build::Posed || build == Build::Refit)
    rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_REFIT);
  if (build == Build::Shared) rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
  if (steps) rtcSetGeometryTimeStepCount(geometry, unsigned(steps->size()));
  const std::size_t slots = steps ? steps->size() : 1;
  for (std::size_t slot = 0; slot < slots; ++slot)
    copy_vertices(steps ? (*steps)[slot] : mesh.vertices,
                  static_cast<float*>(rtcSetNewGeometryBuffer(
                      geometry, RTC_BUFFER_TYPE_VERTEX, unsigned(slot), RTC_FORMAT_FLOAT3,
                      3 * sizeof(float), mesh.vertices.size())));
  const std::size_t count = only ? only->size() : mesh.triangles.size();
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), count));
  for (std::size_t t = 0; t < count; ++t)
    for (int c = 0; c < 3; ++c)
      indices[3 * t + c] = unsigned(mesh.triangles[only ? (*only)[t] : t][c]);
  return geometry;
}

// A BVH of one mesh (with `split`, as its two geometries); with `steps`, of its vertices at each
// step of a shutter (motion blur).
RTCScene build_bvh(RTCDevice device, const Mesh& mesh, const MaskedMesh* masked, Build build,
                   RTCGeometry* geometry_out = nullptr, const StepVertices* steps = nullptr,
                   const PaneSplit* split = nullptr) {
  RTCScene bvh = rtcNewScene(device);
  if (build == Build::Refit) {
    rtcSetSceneFlags(bvh, RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(bvh, RTC_BUILD_QUALITY_LOW);
  }
  if (build == Build::Shared) rtcSetSceneBuildQuality(bvh, RTC_BUILD_QUALITY_HIGH);
  for (int part = 0; part < (split ? 2 : 1); ++part) {
    const std::vector<unsigned>* only = split ? &split->triangles[part] : nullptr;
    RTCGeometry geometry = triangle_geometry(device, mesh, build, steps, only);
    if (masked && (!split || part == 1)) {
      rtcSetGeometryUserData(geometry, const_cast<MaskedMesh*>(masked));
      rtcSetGeometryIntersectFilterFunction(geometry, coverage_filter);
      rtcSetGeometryOccludedFilterFunction(geometry, coverage_filter);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(bvh, geometry);
    if (geometry_out) *geometry_out = geometry;
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(bvh);
  return bvh;
}

void require_per_vertex(std::size_t count, const Mesh& mesh, const char* what,
                        const std::string& name) {
  if (count != 0 && count != mesh.vertices.size())
    throw std::invalid_argument(name + ": " + std::to_string(count) + " " + what + " for " +
                                std::to_string(mesh.vertices.size()) +
                                " vertices (give one per vertex or none)");
}

void require_valid_mesh(const Mesh& mesh, const std::string& name) {
  if (mesh.classes.size() != mesh.triangles.size())
    throw std::invalid_argument(name + ": needs one semantic class per triangle");
  require_per_vertex(mesh.normals.size(), mesh, "normals", name);
  require_per_vertex(mesh.uvs.size(), mesh, "uvs", name);
  require_per_vertex(mesh.tangents.size(), mesh, "tangents", name);
  for (const Eigen::Vector3f& v : mesh.vertices)
    if (!within_world(v.cast<double>()))
      throw std::invalid_argument(name + ": a vertex is not finite or lies beyond 1,000 km");
  for (const Eigen::Vector3i& t : mesh.triangles)
    for (int c = 0; c < 3; ++c)
      if (t[c] < 0 || std::size_t(t[c]) >= mesh.vertices.size())
        throw std::invalid_argument(name + ": triangle index out of range");
}

std::string mesh_name(const MeshRef& ref) {
  return ref.actor < 0 ? "world mesh"
                       : "actor " + std::to_string(ref.actor) + " part " + std::to_string(ref.part);
}

// Embree's kernels take coordinates below FLT_LARGE (1.844e18, its ray.h) and no NaN.
bool embree_takes(float value) { return std::abs(value) < 1.8e18f; }

std::string vector_text(const Vec3& v) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.9g, %.9g, %.9g)", v.x(), v.y(), v.z());
  return text;
}

void require_traceable(const BundleRay& ray, int lane) {
  const Vec3 &o = ray.origin, &d = ray.direction;
  bool takes = !std::isnan(ray.far) && ray.far >= 0;
  for (int c = 0; c < 3; ++c)
    takes = takes && embree_takes(float(o[c])) && embree_takes(float(d[c]));
  if (!takes)
    throw InvalidRay(lane, "a ray from " + vector_text(o) + " along " + vector_text(d) +
                               " cannot be traced (Embree takes finite coordinates below 1.8e18)");
}

RTCRay make_ray(const BundleRay& from) {
  require_traceable(from, 0);
  RTCRay ray{};
  const Vec3 &origin = from.origin, &direction = from.direction;
  ray.org_x = float(origin.x()), ray.org_y = float(origin.y()), ray.org_z = float(origin.z());
  ray.dir_x = float(direction.x()), ray.dir_y = float(direction.y());
  ray.dir_z = float(direction.z());
  ray.tnear = 0, ray.tfar = from.far, ray.mask = kSceneMask, ray.time = from.time;
  return ray;
}

// Copies the rays of a bundle into an Embree packet (RTCRay16 or the ray part of RTCRayHit16).
// Every lane is defined: Embree may read lanes the valid mask leaves out (without native 16-wide
// kernels it traces the packet as a stream, whose lanes count as active where tnear <= tfar), so
// those hold an empty ray (tnear > tfar, mask 0) that nothing can hit.
void fill_packet(const BundleRay* rays, int count, unsigned mask, RTCRay16& packet, int* valid) {
  for (int i = 0; i < kBundleSize; ++i) {
    const bool active = i < count && rays[i].active;
    if (active) require_traceable(rays[i], i);
    const Vec3 o = active ? rays[i].origin : Vec3::Zero();
    const Vec3 d = active ? rays[i].direction : Vec3::UnitX();
    valid[i] = active ? -1 : 0;
    packet.org_x[i] = float(o.x()), packet.org_y[i] = float(o.y()), packet.org_z[i] = float(o.z());
    packet.dir_x[i] = float(d.x()), packet.dir_y[i] = float(d.y()), packet.dir_z[i] = float(d.z());
    packet.tnear[i] = active ? 0.0f : 1.0f, packet.tfar[i] = active ? rays[i].far : 0.0f;
    packet.mask[i] = active ? mask : 0u;
    packet.time[i] = active ? rays[i].time : 0.0f, packet.id[i] = 0, packet.flags[i] = 0;
  }
}

// The mesh's triangle that geometry `geometry`'s primitive `primitive` of mesh `mesh`'s BVH is.
unsigned triangle_of(const std::vector<const PaneSplit*>& splits, unsigned mesh, unsigned geometry,
                     unsigned primitive) {
  return splits[mesh] ? splits[mesh]->triangles[geometry][primitive] : primitive;
}

// Up to kBundleSize rays as one Embree packet, those `mask` lets through.
void intersect_packet(RTCScene scene, const std::vector<const PaneSplit*>& splits,
                      const BundleRay* rays, int count, unsigned mask, Hit* hits) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  alignas(64) RTCRayHit16 packet;
  alignas(64) int valid[kBundleSize];
  fill_packet(rays, count, mask, packet.ray, valid);
  packet.hit = RTCHit16{};  // outputs, but handed over whole like the rays
  std::fill_n(packet.hit.geomID, kBundleSize, RTC_INVALID_GEOMETRY_ID);
  std::fill_n(packet.hit.instID[0], kBundleSize, RTC_INVALID_GEOMETRY_ID);
  rtcIntersect16(valid, scene, &context, &packet);
  const RTCHit16& hit = packet.hit;
  for (int i = 0; i < count; ++i)
    hits[i] = !valid[i] || hit.geomID[i] == RTC_INVALID_GEOMETRY_ID
                  ? Hit{}
                  : Hit{true,
                        hit.instID[0][i],
                        triangle_of(splits, hit.instID[0][i], hit.geomID[i], hit.primID[i]),
                        packet.ray.tfar[i],
                        {hit.Ng_x[i], hit.Ng_y[i], hit.Ng_z[i]},
                        hit.u[i],
                        hit.v[i],
                        rays[i].time};
}

void occluded_packet(RTCScene scene, const BundleRay* rays, int count, unsigned mask,
                     bool* blocked) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  alignas(64) RTCRay16 packet;
  alignas(64) int valid[kBundleSize];
  fill_packet(rays, count, mask, packet, valid);
  rtcOccluded16(valid, scene, &context, &packet);
  for (int i = 0; i < count; ++i) blocked[i] = valid[i] && packet.tfar[i] < 0;
}

void require_valid_materials(const MeshRef& ref, std::size_t material_count,
                             const std::string& name) {
  const Mesh& mesh = *ref.rest;
  if (!mesh.materials.empty() && mesh.materials.size() != mesh.triangles.size())
    throw std::invalid_argument(name + ": needs one material per triangle (or none)");
  const std::size_t slots = ref.slots && !ref.slots->empty() ? ref.slots->size() : material_count;
  for (std::uint16_t m : mesh.materials)
    if (m >= slots) throw std::invalid_argument(name + ": material index out of range");
  if (mesh.materials.empty() && slots == 0)
    throw std::invalid_argument(name + ": material index out of range");
  if (ref.slots)
    for (std::uint16_t m : *ref.slots)
      if (m >= material_count) throw std::invalid_argument(name + ": material index out of range");
}

bool has_alpha_mask(const MeshRef& ref, const std::vector<Material>& materials) {
  for (unsigned t = 0; t < ref.rest->triangles.size(); ++t)
    if (materials[material_of(ref, t)].images.alpha_cutoff >= 0) return true;
  return false;
}

bool has_window(const MeshRef& ref, const std::vector<Material>& materials) {
  for (unsigned t = 0; t < ref.rest->triangles.size(); ++t)
    if (materials[material_of(ref, t)].kind == Material::Kind::Window) return true;
  return false;
}

Vec3 point_on(const Mesh& mesh, unsigned triangle, double u, double v) {
  const Eigen::Vector3i& tri = mesh.triangles[triangle];
  return (1 - u - v) * mesh.vertices[tri[0]].cast<double>() +
         u * mesh.vertices[tri[1]].cast<double>() + v * mesh.vertices[tri[2]].cast<double>();
}

}  // namespace

EmbreeScene::EmbreeScene(const Scene& scene, const CoverageTest* coverage)
    : scene_(scene), coverage_(coverage) {
  const std::string config = embree_config();
  device_ = rtcNewDevice(config.c_str());
  if (!device_)
    throw std::runtime_error(std::string("cannot create an Embree device with ") +
                             kEmbreeConfigVariable + "=\"" + config + "\"");
  meshes_.push_back({&scene.world, &scene.world});
  for (std::size_t a = 0; a < scene.actors.size(); ++a)
    for (std::size_t p = 0; p < scene.actors[a].parts.size(); ++p) {
      const Part& part = scene.actors[a].parts[p];
      if (!part.mesh)
        throw std::invalid_argument(mesh_name({nullptr, nullptr, int(a), int(p)}) +
                                    ": has no mesh");
      MeshRef ref{part.mesh.get(),
                  part.mesh.get(),
                  int(a),
                  int(p),
                  scene.actors[a].instance,
                  scene.actors[a].color_only,
                  &part.materials,
                  part.on_rig};
      if (part.bones) ref.skinned = int(skinned_.size()), skinned_.push_back(meshes_.size());
      meshes_.push_back(ref);
    }
  masked_.reserve(meshes_.size());
  // each BVH, with how it splits its mesh (every part showing it maps its hits so)
  std::map<std::pair<const Mesh*, const std::vector<std::uint16_t>*>,
           std::pair<RTCScene, const PaneSplit*>>
      built;
  for (MeshRef& ref : meshes_) {
    require_valid_mesh(*ref.rest, mesh_name(ref));
    require_valid_materials(ref, scene.materials.size(), mesh_name(ref));
    if (ref.skinned >= 0) {
      const Part& part = scene.actors[ref.actor].parts[ref.part];
      require_valid_skin(*ref.rest, part.bones(0).size(), mesh_name(ref));
    }
    const bool alpha = coverage && has_alpha_mask(ref, scene.materials),
               masked = alpha || has_window(ref, scene.materials);
    if (masked) masked_.push_back({&ref, alpha ? coverage : nullptr, &scene.materials});
    if (ref.skinned >= 0) {
      bvhs_.push_back(nullptr), splits_.push_back(nullptr);
      continue;
    }
    // shared by every part showing the mesh (one whose alpha mask depends on its materials: its
    // own; windows are taken to be windows in every part showing a mesh, as the models' are)
    auto& [bvh, split] = built[{ref.rest, alpha ? ref.slots : nullptr}];
    if (!bvh) {
      split = masked && !alpha ? pane_split(ref) : nullptr;
      if (split) masked_.back().triangles = &split->triangles[1];
      bvh = build_bvh(device_, *ref.rest, masked ? &masked_.back() : nullptr,
                      ref.actor < 0 ? Build::World : Build::Shared, nullptr, nullptr, split);
    } else {
      rtcRetainScene(bvh);
    }
    bvhs_.push_back(bvh), splits_.push_back(split);
  }
  now_ = posed_scene(false);
  use(now_);
}

// The mesh's panes (as `ref` draws them) apart from its solid triangles, or null where it has only
// one kind; made once per mesh, when its BVH is built.
const PaneSplit* EmbreeScene::pane_split(const MeshRef& ref) {
  PaneSplit& split = pane_splits_[ref.rest];
  for (unsigned t = 0; t < ref.rest->triangles.size(); ++t)
    split.triangles[scene_.materials[material_of(ref, t)].kind == Material::Kind::Window].push_back(
        t);
  return split.triangles[0].empty() || split.triangles[1].empty() ? nullptr : &split;
}

EmbreeScene::~EmbreeScene() {
  release(now_);
  if (lines_.top) release(lines_);
  if (shutter_.top) release(shutter_);
  for (PosedScene& target : targets_) release(target);
  for (RTCScene s : bvhs_)
    if (s) rtcReleaseScene(s);
  rtcReleaseDevice(device_);
}

void EmbreeScene::release(PosedScene& scene) {
  rtcReleaseScene(scene.top);
  for (Deformed& d : scene.deformed) rtcReleaseScene(d.bvh);
}

// A top-level scene instancing every BVH (skinned parts: BVHs of its own, posed with it).
EmbreeScene::PosedScene EmbreeScene::posed_scene(bool refit_skinned) {
  PosedScene posed;
  posed.top = rtcNewScene(device_);
  for (unsigned k = 0; k < skinned_.size(); ++k) {
    const MeshRef& ref = meshes_[skinned_[k]];
    const auto masked = std::find_if(masked_.begin(), masked_.end(),
                                     [&](const MaskedMesh& m) { return m.ref == &ref; });
    Deformed d{*ref.rest};
    d.bvh = build_bvh(device_, d.mesh, masked == masked_.end() ? nullptr : &*masked,
                      refit_skinned ? Build::Refit : Build::Posed, &d.geometry);
    posed.deformed.push_back(std::move(d));
  }
  for (unsigned m = 0; m < meshes_.size(); ++m) {
    RTCGeometry instance = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
    const int k = meshes_[m].skinned;
    rtcSetGeometryInstancedScene(instance, k < 0 ? bvhs_[m] : posed.deformed[k].bvh);
    rtcSetGeometryMask(instance, meshes_[m].color_only ? kColorOnlyMask : kSceneMask);
    rtcAttachGeometryByID(posed.top, instance, m);
    rtcReleaseGeometry(instance);
  }
  return posed;
}

Pose EmbreeScene::pose_at(unsigned mesh, double t) const {
  const MeshRef& ref = meshes_[mesh];
  if (ref.actor < 0) return Pose::Identity();
  const Actor& actor = scene_.actors[ref.actor];
  return part_pose(actor, actor.parts[ref.part], t);
}

bool EmbreeScene::pose(PosedScene& scene, double t) const {
  if (scene.posed && scene.time == t) return false;
  const ScopedPhase phase("BVH updates: actors moved, skins rebuilt");
  scene.poses.resize(meshes_.size());
  tbb::parallel_for(std::size_t(0), skinned_.size(), [&](std::size_t k) {
    const MeshRef& ref = meshes_[skinned_[k]];
    Deformed& d = scene.deformed[k];
    skin(*ref.rest, scene_.actors[ref.actor].parts[ref.part].bones(t), d.mesh);
    copy_vertices(d.mesh, static_cast<float*>(
                              rtcGetGeometryBufferData(d.geometry, RTC_BUFFER_TYPE_VERTEX, 0)));
    rtcUpdateGeometryBuffer(d.geometry, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(d.geometry);
    rtcCommitScene(d.bvh);
  });
  for (unsigned m = 0; m < meshes_.size(); ++m) {
    scene.poses[m] = pose_at(m, t);
    const Eigen::Matrix<float, 3, 4> transform = scene.poses[m].matrix().topRows<3>().cast<float>();
    RTCGeometry instance = rtcGetGeometry(scene.top, m);
    rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, transform.data());
    rtcCommitGeometry(instance);
  }
  rtcCommitScene(scene.top);
  scene.inverses.resize(scene.poses.size());
  for (std::size_t m = 0; m < scene.poses.size(); ++m) scene.inverses[m] = scene.poses[m].inverse();
  scene.time = t, scene.posed = true;
  return true;
}

int EmbreeScene::shutter_steps(double seconds) {
  return 1 + std::max(1, int(std::ceil(seconds / kShutterStepSeconds - 1e-9)));
}

namespace {

// Instances `bvh` as mesh `mesh` of `top`, at each of `poses` (one: still).
void attach_instance(RTCDevice device, RTCScene top, unsigned mesh, RTCScene bvh, unsigned mask,
                     const std::vector<Pose>& poses) {
  RTCGeometry instance = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(instance, bvh);
  rtcSetGeometryMask(instance, mask);
  if (poses.size() > 1) rtcSetGeometryTimeStepCount(instance, unsigned(poses.size()));
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const Eigen::Matrix<float, 3, 4> transform = poses[k].matrix().topRows<3>().cast<float>();
    rtcSetGeometryTransform(instance, unsigned(k), RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR,
                            transform.data());
  }
  rtcCommitGeometry(instance);
  rtcAttachGeometryByID(top, instance, mesh);
  rtcReleaseGeometry(instance);
}

}  // namespace

// A skinned part over [open, close]: its shading mesh posed at `middle`, its BVH with its vertices
// at the open and the close (a limb turns little over a shutter; more time steps cost Embree's
// motion-blur builder several times more).
EmbreeScene::Deformed EmbreeScene::shutter_deformed(const MeshRef& ref, double open, double middle,
                                                    double close) const {
  const Part& part = scene_.actors[ref.actor].parts[ref.part];
  Deformed d{*ref.rest};
  skin(*ref.rest, part.bones(middle), d.mesh);
  StepVertices vertices(2);
  for (std::size_t s = 0; s < 2; ++s) {
    const std::vector<Pose> bones = part.bones(s == 0 ? open : close);
    for (std::size_t v = 0; v < ref.rest->vertices.size(); ++v)
      vertices[s].push_back(skinned_vertex(*ref.rest, v, bones));
  }
  const auto masked = std::find_if(masked_.begin(), masked_.end(),
                                   [&](const MaskedMesh& m) { return m.ref == &ref; });
  d.bvh = build_bvh(device_, d.mesh, masked == masked_.end() ? nullptr : &*masked, Build::Posed,
                    &d.geometry, &vertices);
  return d;
}

EmbreeScene::PosedScene EmbreeScene::shutter_scene(double open, double close, int steps) const {
  const ScopedPhase phase("BVH updates: the shutter's motion");
  std::vector<double> times;
  for (int k = 0; k < steps; ++k) times.push_back(open + (close - open) * k / (steps - 1));
  const std::size_t middle = std::size_t(steps / 2);  // stands for the shutter (pose_now, mesh)
  PosedScene scene;
  scene.top = rtcNewScene(device_);
  scene.time = open, scene.close = close, scene.steps = steps, scene.posed = true;
  scene.deformed.resize(skinned_.size());
  tbb::parallel_for(std::size_t(0), skinned_.size(), [&](std::size_t k) {
    scene.deformed[k] = shutter_deformed(meshes_[skinned_[k]], open, times[middle], close);
  });
  scene.poses.resize(meshes_.size());
  scene.inverses.resize(meshes_.size());
  scene.step_poses.resize(meshes_.size());
  for (unsigned m = 0; m < meshes_.size(); ++m) {
    std::vector<Pose> poses;
    for (double t : times) poses.push_back(pose_at(m, t));
    const bool still = std::all_of(poses.begin(), poses.end(), [&](const Pose& p) {
      return p.matrix() == poses.front().matrix();
    });
    const int k = meshes_[m].skinned;
    scene.poses[m] = poses[still ? 0 : middle];
    scene.inverses[m] = scene.poses[m].inverse();
    if (!still) scene.step_poses[m] = poses;
    attach_instance(device_, scene.top, m, k < 0 ? bvhs_[m] : scene.deformed[k].bvh,
                    meshes_[m].color_only ? kColorOnlyMask : kSceneMask,
                    still ? std::vector<Pose>{poses.front()} : poses);
  }
  rtcCommitScene(scene.top);
  return scene;
}

void EmbreeScene::set_shutter(double open, double close, int steps) {
  if (!(close > open) || steps < 2)
    throw std::invalid_argument("set_shutter: needs close > open and at least 2 steps");
  const bool same =
      shutter_.top && shutter_.time == open && shutter_.close == close && shutter_.steps == steps;
  if (!same) {
    if (shutter_.top) release(shutter_);
    shutter_ = shutter_scene(open, close, steps);
  }
  use(shutter_);
}

namespace {

// Where a ray's time falls among `count` evenly spaced steps, as Embree takes it: the step
// before it and the share of the way to the next.
std::pair<std::size_t, double> time_segment(float time, std::size_t count) {
  const double position = std::clamp(double(time), 0.0, 1.0) * double(count - 1);
  const std::size_t step = std::min(std::size_t(position), count - 2);
  return {step, position - double(step)};
}

}  // namespace

Pose EmbreeScene::pose_of(const Hit& hit) const {
  const std::vector<std::vector<Pose>>& steps = current_->step_poses;
  if (steps.empty() || steps[hit.mesh].empty()) return current_->poses[hit.mesh];
  const auto [step, share] = time_segment(hit.time, steps[hit.mesh].size());
  Pose pose;  // Embree interpolates the matrices, not the motions
  pose.matrix() =
      (1 - share) * steps[hit.mesh][step].matrix() + share * steps[hit.mesh][step + 1].matrix();
  return pose;
}

Pose EmbreeScene::world_to_object(const Hit& hit) const {
  const std::vector<std::vector<Pose>>& steps = current_->step_poses;
  if (steps.empty() || steps[hit.mesh].empty()) return current_->inverses[hit.mesh];
  Pose inverse;  // an interpolated rotation is not quite one: its full inverse
  inverse.matrix() = pose_of(hit).matrix().inverse();
  return inverse;
}

void EmbreeScene::use(const PosedScene& scene) {
  current_ = &scene;
  for (unsigned k = 0; k < skinned_.size(); ++k)
    meshes_[skinned_[k]].mesh = &scene.deformed[k].mesh;
}

void EmbreeScene::set_line_time(double t) {
  if (!lines_.top) lines_ = posed_scene(true);
  pose(lines_, t);
  use(lines_);
}

namespace {

// Swaps into `slot` a scene of `others` posed at `t` already, if `slot` is not: a sequence's next
// frame is posed at times its previous frame's targets were (skins rebuilt cost more than a look).
// Else, with `kept`, one posed at none of those times (the slot is posed again at t).
template <class PosedScene>
void reuse_posed(PosedScene& slot, std::span<PosedScene> others, double t,
                 std::span<const double> kept = {}) {
  const auto posed_at = [](double time) {
    return [time](const PosedScene& s) { return s.posed && s.time == time; };
  };
  const auto unkept = [&](const PosedScene& s) {
    return std::none_of(kept.begin(), kept.end(), [&](double k) { return posed_at(k)(s); });
  };
  if (posed_at(t)(slot)) return;
  auto reused = std::find_if(others.begin(), others.end(), posed_at(t));
  if (reused == others.end() && !unkept(slot))
    reused = std::find_if(others.begin(), others.end(), unkept);
  if (reused != others.end()) std::swap(slot, *reused);
}

}  // namespace

void EmbreeScene::set_times(double now, const std::vector<double>& targets) {
  while (targets_.size() < targets.size()) targets_.push_back(posed_scene(false));
  reuse_posed(now_, std::span(targets_), now, std::span(targets));
  pose(now_, now);
  use(now_);
  for (std::size_t k = 0; k < targets.size(); ++k) {
    reuse_posed(targets_[k], std::span(targets_).subspan(k + 1), targets[k],
                std::span(targets).subspan(k + 1));
    pose(targets_[k], targets[k]);
  }
}

Vec3 EmbreeScene::point_at_target(int target, const Hit& hit, const Vec3& point) const {
  const int k = meshes_[hit.mesh].skinned;
  const Pose& then = pose_at_target(target, hit.mesh);
  if (k < 0) return then * (current_->inverses[hit.mesh] * point);
  return then * point_on(targets_[std::size_t(target)].deformed[std::size_t(k)].mesh, hit.triangle,
                         hit.u, hit.v);
}

SurfacePoint EmbreeScene::surface_point(const Hit& hit, const Vec3& point) const {
  return {hit.mesh, hit.triangle, hit.u, hit.v, current_->inverses[hit.mesh] * point};
}

std::vector<Pose> EmbreeScene::bones_at(unsigned mesh, double t) const {
  const MeshRef& ref = meshes_[mesh];
  if (ref.skinned < 0) return {};
  return scene_.actors[ref.actor].parts[ref.part].bones(t);
}

Vec3 EmbreeScene::world_point(const SurfacePoint& p, const Pose& mesh_pose,
                              const std::vector<Pose>* bones) const {
  const MeshRef& ref = meshes_[p.mesh];
  if (ref.skinned < 0) return mesh_pose * p.object;
  const Eigen::Vector3i& tri = ref.rest->triangles[p.triangle];
  Vec3 local = Vec3::Zero();
  const double weights[3] = {1.0 - p.u - p.v, p.u, p.v};
  for (int c = 0; c < 3; ++c)
    local += weights[c] * skinned_vertex(*ref.rest, std::size_t(tri[c]), *bones).cast<double>();
  return mesh_pose * local;
}

Vec3 EmbreeScene::world_point(const SurfacePoint& p, double t) const {
  const std::vector<Pose> bones = bones_at(p.mesh, t);
  return world_point(p, pose_at(p.mesh, t), &bones);
}

Vec3 EmbreeScene::pattern_point(const Hit& hit, const Vec3& point) const {
  const MeshRef& ref = meshes_[hit.mesh];
  if (ref.skinned < 0) return world_to_object(hit) * point;
  return point_on(*ref.rest, hit.triangle, hit.u, hit.v);
}

Hit EmbreeScene::intersect(const Vec3& origin, const Vec3& direction, float time) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray = make_ray({origin, direction, true, kInfinity, time});
  rh.hit.geomID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(current_->top, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
  return {true,
          rh.hit.instID[0],
          triangle_of(splits_, rh.hit.instID[0], rh.hit.geomID, rh.hit.primID),
          rh.ray.tfar,
          {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z},
          rh.hit.u,
          rh.hit.v,
          time};
}

bool EmbreeScene::occluded(int target, const Vec3& origin, const Vec3& direction,
                           double distance) const {
  return occluded(target, BundleRay{origin, direction, true, visibility_far(distance)});
}

bool EmbreeScene::occluded(int target, const BundleRay& bundle_ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray = make_ray(bundle_ray);
  rtcOccluded1(scene_at(target), &context, &ray);
  return ray.tfar < 0;
}

void EmbreeScene::occluded(int target, const BundleRay* rays, int count, bool* blocked) const {
  occluded_packet(scene_at(target), rays, count, kSceneMask, blocked);
}

void EmbreeScene::intersect(const BundleRay* rays, int count, Hit* hits) const {
  intersect_packet(current_->top, splits_, rays, count, kSceneMask | kColorOnlyMask, hits);
}

void EmbreeScene::intersect_scene(const BundleRay* rays, int count, Hit* hits) const {
  intersect_packet(current_->top, splits_, rays, count, kSceneMask, hits);
}

void EmbreeScene::occluded(const BundleRay* rays, int count, bool* blocked) const {
  occluded_packet(current_->top, rays, count, kSceneMask | kSunMask, blocked);
}

}  // namespace flowscape
