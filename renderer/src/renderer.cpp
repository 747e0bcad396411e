#include "flowscape/renderer.h"

#include <embree3/rtcore.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace flowscape {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
// The visibility ray stops this fraction short of the target, so the target's own surface does not
// count as an occluder (float hit points are good to about 1e-6 of their distance).
constexpr double kVisibilityMargin = 1e-4;

// One mesh of the scene: the static world (actor < 0) or one part of an actor.
struct MeshRef {
  const Mesh* mesh;
  int actor = -1, part = -1;
  std::uint16_t instance = 0;
};

RTCScene build_bvh(RTCDevice device, const Mesh& mesh) {
  RTCScene bvh = rtcNewScene(device);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                               RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                               mesh.vertices.size()));
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    for (int c = 0; c < 3; ++c) vertices[3 * i + c] = mesh.vertices[i][c];
  auto* indices = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(unsigned), mesh.triangles.size()));
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) indices[3 * t + c] = unsigned(mesh.triangles[t][c]);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(bvh, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(bvh);
  return bvh;
}

void require_valid_mesh(const Mesh& mesh, const std::string& name) {
  if (mesh.classes.size() != mesh.triangles.size())
    throw std::invalid_argument(name + ": needs one semantic class per triangle");
  for (const Eigen::Vector3i& t : mesh.triangles)
    for (int c = 0; c < 3; ++c)
      if (t[c] < 0 || std::size_t(t[c]) >= mesh.vertices.size())
        throw std::invalid_argument(name + ": triangle index out of range");
}

std::string mesh_name(const MeshRef& ref) {
  return ref.actor < 0 ? "world mesh"
                       : "actor " + std::to_string(ref.actor) + " part " + std::to_string(ref.part);
}

struct Hit {
  bool found = false;
  unsigned mesh = 0, triangle = 0;
  double distance = kInfinity;
};

Hit intersect(RTCScene scene, const Vec3& origin, const Vec3& direction) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = float(origin.x()), rh.ray.org_y = float(origin.y()),
  rh.ray.org_z = float(origin.z());
  rh.ray.dir_x = float(direction.x()), rh.ray.dir_y = float(direction.y()),
  rh.ray.dir_z = float(direction.z());
  rh.ray.tnear = 0, rh.ray.tfar = kInfinity, rh.ray.mask = ~0u;
  rh.hit.geomID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
  return {true, rh.hit.instID[0], rh.hit.primID, rh.ray.tfar};
}

bool occluded(RTCScene scene, const Vec3& origin, const Vec3& direction, double distance) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  ray.org_x = float(origin.x()), ray.org_y = float(origin.y()), ray.org_z = float(origin.z());
  ray.dir_x = float(direction.x()), ray.dir_y = float(direction.y()),
  ray.dir_z = float(direction.z());
  ray.tnear = 0, ray.mask = ~0u;
  ray.tfar = std::isinf(distance) ? kInfinity : float(distance * (1 - kVisibilityMargin));
  rtcOccluded1(scene, &context, &ray);
  return ray.tfar < 0;
}

}  // namespace

struct Renderer::Impl {
  const Scene& scene;
  RTCDevice device = nullptr;
  std::vector<MeshRef> meshes;
  std::vector<RTCScene> bvhs;              // one per mesh
  RTCScene now = nullptr, next = nullptr;  // instances of every BVH, posed at the two times

  explicit Impl(const Scene& s) : scene(s) {
    device = rtcNewDevice(nullptr);
    if (!device) throw std::runtime_error("cannot create an Embree device");
    meshes.push_back({&scene.world});
    for (std::size_t a = 0; a < scene.actors.size(); ++a)
      for (std::size_t p = 0; p < scene.actors[a].parts.size(); ++p)
        meshes.push_back(
            {&scene.actors[a].parts[p].mesh, int(a), int(p), scene.actors[a].instance});
    for (const MeshRef& ref : meshes) {
      require_valid_mesh(*ref.mesh, mesh_name(ref));
      bvhs.push_back(build_bvh(device, *ref.mesh));
    }
    now = instances(), next = instances();
  }

  ~Impl() {
    for (RTCScene s : {now, next}) rtcReleaseScene(s);
    for (RTCScene s : bvhs) rtcReleaseScene(s);
    rtcReleaseDevice(device);
  }

  RTCScene instances() const {
    RTCScene top = rtcNewScene(device);
    for (unsigned m = 0; m < bvhs.size(); ++m) {
      RTCGeometry instance = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(instance, bvhs[m]);
      rtcAttachGeometryByID(top, instance, m);
      rtcReleaseGeometry(instance);
    }
    return top;
  }

  Pose pose(unsigned mesh, double t) const {
    const MeshRef& ref = meshes[mesh];
    if (ref.actor < 0) return Pose::Identity();
    const Actor& actor = scene.actors[ref.actor];
    return part_pose(actor, actor.parts[ref.part], t);
  }

  void pose_instances(RTCScene top, double t) const {
    for (unsigned m = 0; m < bvhs.size(); ++m) {
      const Eigen::Matrix<float, 3, 4> transform = pose(m, t).matrix().topRows<3>().cast<float>();
      RTCGeometry instance = rtcGetGeometry(top, m);
      rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, transform.data());
      rtcCommitGeometry(instance);
    }
    rtcCommitScene(top);
  }
};

Renderer::Renderer(const Scene& scene) : impl_(std::make_unique<Impl>(scene)) {}
Renderer::~Renderer() = default;

GroundTruth Renderer::ground_truth(const Projection& projection, const FramePair& frames,
                                   FlowMode mode) {
  Impl& r = *impl_;
  r.pose_instances(r.now, frames.time);
  r.pose_instances(r.next, frames.next_time);
  const int W = projection.width, H = projection.height;
  GroundTruth gt{Image<float>(W, H, 2), Image<std::uint8_t>(W, H, 1), Image<std::uint16_t>(W, H, 1),
                 Image<float>(W, H, 1), Image<std::uint8_t>(W, H, 1)};
  const Vec3 origin = frames.rig.translation(), next_origin = frames.next_rig.translation();
  const Mat3 rotation = frames.rig.linear(), next_rotation = frames.next_rig.linear();
  const bool panorama = projection.kind == Projection::Kind::Equirectangular;
  tbb::parallel_for(0, H, [&](int y) {
    for (int x = 0; x < W; ++x) {
      const Vec2 pixel(x + 0.5, y + 0.5);
      const Vec3 direction = (rotation * projection.ray(pixel)).normalized();
      const Hit hit = intersect(r.now, origin, direction);
      Vec3 target_direction;  // world frame, from the rig at next_time
      double target_distance = kInfinity;
      if (hit.found) {
        const Vec3 point = origin + hit.distance * direction;
        const Vec3 moved =
            r.pose(hit.mesh, frames.next_time) * (r.pose(hit.mesh, frames.time).inverse() * point);
        target_direction = moved - next_origin;
        target_distance = target_direction.norm();
        target_direction /= target_distance;
        *gt.semantic.pixel(x, y) = std::uint8_t(r.meshes[hit.mesh].mesh->classes[hit.triangle]);
        *gt.instance.pixel(x, y) = r.meshes[hit.mesh].instance;
      } else {
        target_direction = direction;
        *gt.semantic.pixel(x, y) = std::uint8_t(SemanticClass::Sky);
      }
      *gt.depth.pixel(x, y) = float(hit.distance);
      const auto target = projection.project(next_rotation.transpose() * target_direction);
      float* f = gt.flow.pixel(x, y);
      if (!target) {
        f[0] = f[1] = kUnknownFlow;
        continue;
      }
      double u = target->x() - pixel.x();
      if (panorama) {
        const double classic = (target->x() >= W ? target->x() - W : target->x()) - pixel.x();
        u = mode == FlowMode::Wrap360 ? wrap_360(classic, W) : classic;
      }
      f[0] = float(u), f[1] = float(target->y() - pixel.y());
      *gt.valid.pixel(x, y) = !occluded(r.next, next_origin, target_direction, target_distance);
    }
  });
  return gt;
}

}  // namespace flowscape
