#pragma once
// Internal: a Scene in Embree. One BVH per rigid mesh, built once and shared by every part that
// shows the mesh; one per skinned part and posed time, refitted when that time changes. Top-level
// scenes instance them, posed at the frame's time and at each target time of its ground truth.
#include <embree3/rtcore.h>

#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "flowscape/geometry/geometry.h"
#include "flowscape/renderer/renderer.h"
#include "flowscape/scenes/scene.h"

namespace flowscape {

// One mesh of the scene: the static world (actor < 0) or one part of an actor.
struct MeshRef {
  const Mesh* mesh;            // what rays hit at `now` (a skinned part: its mesh posed then)
  const Mesh* rest = nullptr;  // the part's own mesh (skinned: its rest pose; patterns stick to it)
  int actor = -1, part = -1;
  std::uint16_t instance = 0;
  bool color_only = false;
  const std::vector<std::uint16_t>* slots = nullptr;  // the part's materials (empty: the mesh's)
  bool on_rig = false;                                // Part::on_rig
  int skinned = -1;  // index of the part among the skinned ones, or -1 (rigid)
};
// The scene material a mesh's triangle is drawn with.
inline std::uint16_t material_of(const MeshRef& ref, unsigned triangle) {
  const std::uint16_t slot = ref.mesh->materials.empty() ? 0 : ref.mesh->materials[triangle];
  return ref.slots && !ref.slots->empty() ? (*ref.slots)[slot] : slot;
}

// Embree ray masks: ground-truth and shadow rays see the scene, colour rays also the colour-only
// actors (rain streaks, puddles); the sun's shadow rays carry kSunMask too and pass windows.
constexpr unsigned kSceneMask = 1, kColorOnlyMask = 2, kSunMask = 4;

// A ray of a bundle traced together; lanes that are not active are skipped.
struct BundleRay {
  Vec3 origin = Vec3::Zero(), direction = Vec3::UnitX();  // unit direction
  bool active = false;
  float far = std::numeric_limits<float>::infinity();  // how far it looks
  float time = 0;  // in a shutter scene (set_shutter): 0 at its open, 1 at its close
};
constexpr int kBundleSize = 16;  // Embree's widest packet

// A ray Embree must not be given: a coordinate NaN, infinite or beyond what its kernels take
// (they assert |x| < 1.8e18). Thrown instead of tracing it; `lane`: its place in the bundle (0
// for a single ray), so that the caller can name the pixel.
struct InvalidRay : std::runtime_error {
  InvalidRay(int lane, const std::string& problem) : std::runtime_error(problem), lane(lane) {}
  int lane;
};

// Runs `trace` for lane `lane` of a bundle traced ray by ray: its InvalidRay names that lane.
template <class Trace>
void naming_lane(int lane, Trace&& trace) {
  try {
    trace();
  } catch (const InvalidRay& e) {
    throw InvalidRay(lane, e.what());
  }
}

// Runs `trace`; a ray of it that Embree could not take becomes a RayError at the pixel
// pixel_of(lane) gives (an {x, y} pair).
template <class Trace, class PixelOf>
void naming_pixels(Trace&& trace, PixelOf&& pixel_of) {
  try {
    trace();
  } catch (const InvalidRay& e) {
    const auto [x, y] = pixel_of(e.lane);
    throw RayError(x, y, e.what());
  }
}

// How far a visibility ray to a point `distance` away looks: a fraction short of it, so that the
// point's own surface does not hide it (float hit points are good to about 1e-6 of their
// distance); infinity stays infinity.
inline float visibility_far(double distance) {
  constexpr double kVisibilityMargin = 1e-4;
  return std::isinf(distance) ? std::numeric_limits<float>::infinity()
                              : float(distance * (1 - kVisibilityMargin));
}

struct Hit {
  bool found = false;
  unsigned mesh = 0, triangle = 0;
  double distance = std::numeric_limits<double>::infinity();
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();  // (v1 - v0) x (v2 - v0) in the mesh's frame
  float u = 0, v = 0;  // barycentric: the point is (1 - u - v) v0 + u v1 + v v2
  float time = 0;      // the ray's (BundleRay::time)
};

// A surface point held by what it lies on, so it can be found at any time: a rigid part's point
// in the part's frame, a skinned part's triangle and barycentrics (`object` unused).
struct SurfacePoint {
  unsigned mesh = 0, triangle = 0;
  float u = 0, v = 0;
  Vec3 object = Vec3::Zero();
};

// Decides per hit whether a surface is there (alpha masks); the same for every ray kind, so the
// ground truth and the colour see the same holes.
class CoverageTest {
 public:
  virtual ~CoverageTest() = default;
  virtual bool covered(std::uint16_t material, const Mesh& mesh, unsigned triangle, float u,
                       float v) const = 0;
};

// What Embree's filter function of a mesh with alpha masks or windows gets (coverage: null for
// windows only).
struct MaskedMesh {
  const MeshRef* ref;
  const CoverageTest* coverage;
  const std::vector<Material>* materials;
  const std::vector<unsigned>* triangles = nullptr;  // its geometry's primID -> triangle, or null
};

// A mesh with window panes (and no alpha mask) as two geometries of one BVH: the solid triangles,
// then the panes, whose filter (sun rays pass them) then runs on panes only; each geometry's
// primID -> the mesh's triangle.
struct PaneSplit {
  std::vector<unsigned> triangles[2];
};

class EmbreeScene {
 public:
  // `coverage` (may be null) is asked about the triangles whose material has an alpha mask.
  EmbreeScene(const Scene& scene, const CoverageTest* coverage);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Poses the scene at `now` and one more top-level scene at each target time (a scene already
  // posed at its time is left as it is: the six faces of one frame).
  void set_times(double now, const std::vector<double>& targets);
  // Poses a scene of its own at `t` and makes it `now` (no targets): a rolling shutter's lines,
  // posed hundreds of times a frame, whose walkers' BVHs are refitted rather than rebuilt.
  void set_line_time(double t);
  // Poses the scene over [open, close] with Embree's motion blur and makes it `now`: each moving
  // part's transform, and a skinned part's vertices, at `steps` (>= 2) evenly spaced times from
  // open to close, which Embree interpolates linearly for each ray at its own time
  // (BundleRay::time). A hit's pose and object frame are then its time's (pose_of ...).
  void set_shutter(double open, double close, int steps);
  // The steps set_shutter takes for `seconds`: one every kShutterStepSeconds at least.
  static int shutter_steps(double seconds);
  static constexpr double kShutterStepSeconds = 1 / 240.0;
  Hit intersect(const Vec3& origin, const Vec3& direction,
                float time = 0) const;  // at `now`; unit direction
  // Whether anything lies within `distance` along the ray (infinity: anywhere), at target time
  // `target` of set_times (kNow: at `now`).
  static constexpr int kNow = -1;
  bool occluded(int target, const Vec3& origin, const Vec3& direction, double distance) const;
  // The same for a ray whose `far` is visibility_far(distance), and for up to kBundleSize of them
  // as one Embree packet (inactive rays: not blocked).
  bool occluded(int target, const BundleRay& ray) const;
  void occluded(int target, const BundleRay* rays, int count, bool* blocked) const;
  // Up to kBundleSize colour rays as one Embree packet at `now` (unbounded): much faster than
  // single rays when they start close together in similar directions (the samples of one pixel).
  void intersect(const BundleRay* rays, int count, Hit* hits) const;
  // The same for ground-truth rays, which see what shadow rays see (not the colour-only actors).
  void intersect_scene(const BundleRay* rays, int count, Hit* hits) const;
  void occluded(const BundleRay* rays, int count, bool* blocked) const;

  // Where the surface point `point` (on `hit`, at `now`) is at target `target` of set_times, in
  // the world: a rigid part's point moves with the part; a skinned one is the same barycentric
  // combination of its triangle's vertices posed then.
  Vec3 point_at_target(int target, const Hit& hit, const Vec3& point) const;
  // The hit point (at `now`) as a SurfacePoint, and where that point is at time t: with the
  // mesh's pose then and, for a skinned part, its bones then (world_point(p, t) evaluates both).
  SurfacePoint surface_point(const Hit& hit, const Vec3& point) const;
  Vec3 world_point(const SurfacePoint& p, const Pose& mesh_pose,
                   const std::vector<Pose>* bones) const;
  Vec3 world_point(const SurfacePoint& p, double t) const;
  // A skinned mesh's bones at time t (empty for a rigid mesh).
  std::vector<Pose> bones_at(unsigned mesh, double t) const;
  Pose pose_at(unsigned mesh, double t) const;
  // The hit point in the frame procedural patterns use: the object frame of a rigid part, the rest
  // pose of a skinned one.
  Vec3 pattern_point(const Hit& hit, const Vec3& point) const;

  // The pose of the mesh `hit` is on and its inverse at the hit's time: in a shutter scene
  // interpolated as Embree does, else pose_now's. (A skinned part's shading takes its mesh as
  // posed at the shutter's middle: its limbs turn little over a shutter.)
  Pose pose_of(const Hit& hit) const;
  Pose world_to_object(const Hit& hit) const;
  // Poses at the times of set_times (evaluated once per call there, not per ray).
  const Pose& pose_now(unsigned mesh) const { return current_->poses[mesh]; }
  RTCScene scene_at(int target) const {  // kNow or a target of set_times
    return target == kNow ? current_->top : targets_[std::size_t(target)].top;
  }
  const Pose& pose_at_target(int target, unsigned mesh) const {
    return targets_[std::size_t(target)].poses[mesh];
  }
  const MeshRef& mesh(unsigned index) const { return meshes_[index]; }
  unsigned mesh_count() const { return unsigned(meshes_.size()); }
  const Scene& scene() const { return scene_; }

 private:
  // A skinned part's mesh and BVH at one posed time.
  struct Deformed {
    Mesh mesh;  // vertices (and normals, tangents) skinned at the scene's time
    RTCScene bvh = nullptr;
    RTCGeometry geometry = nullptr;
  };
  // A top-level scene instancing every BVH, posed at `time`.
  struct PosedScene {
    RTCScene top = nullptr;
    std::vector<Pose> poses{}, inverses{};
    std::vector<Deformed> deformed{};  // one per skinned part
    double time = 0;
    bool posed = false;
    // A shutter scene's (set_shutter, posed from `time` to `close`): each moving mesh's poses at
    // its steps (empty for a still one: `poses` holds it).
    double close = 0;
    int steps = 1;
    std::vector<std::vector<Pose>> step_poses{};
  };
  PosedScene shutter_scene(double open, double close, int steps) const;
  Deformed shutter_deformed(const MeshRef& ref, double open, double middle, double close) const;
  PosedScene posed_scene(bool refit_skinned);    // the line scene's skinned BVHs refit
  void use(const PosedScene& scene);             // `now` is `scene`'s
  bool pose(PosedScene& scene, double t) const;  // false: it was posed at t already
  void release(PosedScene& scene);
  const PaneSplit* pane_split(const MeshRef& ref);

  const Scene& scene_;
  RTCDevice device_ = nullptr;
  std::vector<MeshRef> meshes_;
  std::vector<RTCScene> bvhs_;  // per mesh: its shared BVH (null for skinned parts)
  std::map<const Mesh*, PaneSplit> pane_splits_;
  std::vector<const PaneSplit*> splits_;  // per mesh: how its (shared) BVH splits it, or null
  std::vector<unsigned> skinned_;         // the meshes that are skinned parts
  std::vector<MaskedMesh> masked_;        // reserved up front: Embree keeps pointers into it
  PosedScene now_, lines_;                // set_times' and set_line_time's (made when first asked)
  PosedScene shutter_;                    // set_shutter's (made anew for each shutter)
  const PosedScene* current_ = &now_;     // `now`: the one rays see
  std::vector<PosedScene> targets_;       // grown as requests need, never shrunk
  const CoverageTest* coverage_;
};

}  // namespace flowscape
