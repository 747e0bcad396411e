// Ground truth on deforming meshes (linear blend skinning) and on parts fixed to the camera rig,
// against closed forms computed here: the skinned vertices from the bones' affine maps, the hit
// by a ray-triangle test of our own, the point moved as the same barycentric combination, and a
// pinhole projection written out.
#include <catch2/catch.hpp>
#include <optional>

#include "flowscape/renderer/renderer.h"
#include "flowscape/scenes/shapes.h"

using namespace flowscape;

namespace {

constexpr int kSize = 64;
constexpr double kFov = 40;
const double kFocal = kSize / 2.0 / std::tan(kFov * kPi / 360);

// A 2 m square in the plane x = 0 (facing -x) of 16 x 16 quads, skinned to two bones: bone 1's
// weight rises linearly from 0 at y = -1 to 1 at y = +1.
Mesh plate() {
  Mesh mesh;
  const int n = 16;
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k <= n; ++k) {
      const float y = -1 + 2.0f * i / n, z = -1 + 2.0f * k / n;
      mesh.vertices.emplace_back(0, y, z);
      const float w = (y + 1) / 2;
      mesh.bones.push_back({0, 1, 0, 0});
      mesh.weights.emplace_back(1 - w, w, 0, 0);
    }
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      const int a = i * (n + 1) + k, b = a + n + 1;
      for (const Eigen::Vector3i& t :
           {Eigen::Vector3i(a, b, b + 1), Eigen::Vector3i(a, b + 1, a + 1)}) {
        mesh.triangles.push_back(t);
        mesh.classes.push_back(SemanticClass::Dynamic);
      }
    }
  return mesh;
}

// The bones' known fields: bone 0 stretches z by (1 + 0.2 t) and slides along y by 0.3 t; bone 1
// turns about the x axis through (0, 0.5, 0) at 0.8 rad/s.
std::vector<Pose> bones_at(double t) {
  Pose stretch = Pose::Identity();
  stretch.linear() = Eigen::DiagonalMatrix<double, 3>(1, 1, 1 + 0.2 * t);
  stretch.translation() = Vec3(0, 0.3 * t, 0);
  const Pose turn = Pose(Eigen::Translation3d(0, 0.5, 0)) *
                    Pose(Eigen::AngleAxisd(0.8 * t, Vec3::UnitX())) *
                    Pose(Eigen::Translation3d(0, -0.5, 0));
  return {stretch, turn};
}

// The skinned vertex v at t, written out: (w0 B0 + w1 B1) v, then posed by the actor (a shift).
Vec3 vertex_at(const Mesh& mesh, int v, double t) {
  const std::vector<Pose> b = bones_at(t);
  const Eigen::Vector4f w = mesh.weights[std::size_t(v)];
  const Eigen::Matrix<double, 3, 4> m =
      w[0] * b[0].matrix().topRows<3>() + w[1] * b[1].matrix().topRows<3>();
  // the renderer traces float vertices: so does the expectation
  const Eigen::Vector3f skinned =
      (m.leftCols<3>() * mesh.vertices[std::size_t(v)].cast<double>() + m.col(3)).cast<float>();
  return skinned.cast<double>() + Vec3(2, 0, 0);
}

struct Hit {
  int triangle;
  double u, v, distance;
};

// Moeller-Trumbore against every triangle at time t.
std::optional<Hit> trace(const Mesh& mesh, const Vec3& origin, const Vec3& dir, double t) {
  std::optional<Hit> best;
  for (int k = 0; k < int(mesh.triangles.size()); ++k) {
    const Eigen::Vector3i& tri = mesh.triangles[std::size_t(k)];
    const Vec3 p0 = vertex_at(mesh, tri[0], t), e1 = vertex_at(mesh, tri[1], t) - p0,
               e2 = vertex_at(mesh, tri[2], t) - p0;
    const Vec3 p = dir.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-12) continue;
    const Vec3 s = origin - p0, q = s.cross(e1);
    const double u = s.dot(p) / det, v = dir.dot(q) / det, d = e2.dot(q) / det;
    if (u < 0 || v < 0 || u + v > 1 || d <= 0) continue;
    if (!best || d < best->distance) best = Hit{k, u, v, d};
  }
  return best;
}

// The hit triangle's unit normal at t, facing a camera looking along `dir`.
Vec3 normal_at(const Mesh& mesh, const Hit& hit, double t, const Vec3& dir) {
  const Eigen::Vector3i& tri = mesh.triangles[std::size_t(hit.triangle)];
  const Vec3 p0 = vertex_at(mesh, tri[0], t);
  const Vec3 n = (vertex_at(mesh, tri[1], t) - p0).cross(vertex_at(mesh, tri[2], t) - p0);
  return (n.dot(dir) < 0 ? n : -n).normalized();
}

Vec3 point_at(const Mesh& mesh, const Hit& hit, double t) {
  const Eigen::Vector3i& tri = mesh.triangles[std::size_t(hit.triangle)];
  return (1 - hit.u - hit.v) * vertex_at(mesh, tri[0], t) + hit.u * vertex_at(mesh, tri[1], t) +
         hit.v * vertex_at(mesh, tri[2], t);
}

// The pinhole at the origin looking along +x (rig x forward, y left, z up): pixel of a point.
Vec2 pixel_of(const Vec3& p) {
  return {kSize / 2.0 + kFocal * -p.y() / p.x(), kSize / 2.0 + kFocal * -p.z() / p.x()};
}
Vec3 ray_of(Vec2 pixel) {
  return Vec3(kFocal, -(pixel.x() - kSize / 2.0), -(pixel.y() - kSize / 2.0)).normalized();
}

// Checks the ground truth of frame `frame` (30 Hz) against the closed forms: its flow to the next
// frame and back `back` frames, its scene flow and its normals.
void check_skinned_frame(Renderer& renderer, const Mesh& mesh, int frame, int back) {
  const auto time = [](int f) { return f / kFrameRate; };
  const double t0 = time(frame), t1 = time(frame + 1), t_back = time(frame - back);
  TruthRequest request{FramePair{t0, t1, Pose::Identity(), Pose::Identity()}};
  request.more = {Moment{t_back, Pose::Identity()}};
  request.scene_flow = request.normal = true;
  const GroundTruth gt = renderer.ground_truth(Projection::pinhole(kSize, kSize, kFov), request);
  int checked = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const Vec2 pixel(x + 0.5, y + 0.5);
      const std::optional<Hit> hit = trace(mesh, Vec3::Zero(), ray_of(pixel), t0);
      if (!hit) {
        CHECK(*gt.instance.pixel(x, y) == 0);
        continue;
      }
      // away from the triangles' edges, where float hits may pick the neighbour
      if (std::min({hit->u, hit->v, 1 - hit->u - hit->v}) < 1e-3) continue;
      REQUIRE(*gt.instance.pixel(x, y) == 5);
      const Vec3 now = point_at(mesh, *hit, t0), next = point_at(mesh, *hit, t1),
                 before = point_at(mesh, *hit, t_back);
      const Vec2 forward = pixel_of(next) - pixel, backward = pixel_of(before) - pixel;
      CHECK(gt.flow.pixel(x, y)[0] == Approx(forward.x()).margin(1e-3));
      CHECK(gt.flow.pixel(x, y)[1] == Approx(forward.y()).margin(1e-3));
      CHECK(gt.more[0].flow.pixel(x, y)[0] == Approx(backward.x()).margin(1e-3));
      CHECK(gt.more[0].flow.pixel(x, y)[1] == Approx(backward.y()).margin(1e-3));
      const Vec3 moved = next - now;  // camera frame: x right (-y), y down (-z), z forward (x)
      CHECK(gt.scene_flow.pixel(x, y)[0] == Approx(-moved.y()).margin(1e-5));
      CHECK(gt.scene_flow.pixel(x, y)[1] == Approx(-moved.z()).margin(1e-5));
      CHECK(gt.scene_flow.pixel(x, y)[2] == Approx(moved.x()).margin(1e-5));
      const Vec3 normal = normal_at(mesh, *hit, t0, ray_of(pixel));
      CHECK(gt.normal.pixel(x, y)[0] == Approx(-normal.y()).margin(1e-4));
      CHECK(gt.normal.pixel(x, y)[1] == Approx(-normal.z()).margin(1e-4));
      CHECK(gt.normal.pixel(x, y)[2] == Approx(normal.x()).margin(1e-4));
      ++checked;
    }
  CHECK(checked > 1000);
}

}  // namespace

TEST_CASE("a skinned mesh's flow both ways and scene flow follow its bones exactly") {
  Scene scene;
  Actor actor{5, {}, fixed_pose(Pose(Eigen::Translation3d(2, 0, 0)))};
  const auto mesh = std::make_shared<const Mesh>(plate());
  actor.parts.push_back({mesh, fixed_pose(), [](double t) { return bones_at(t); }});
  scene.actors.push_back(actor);
  // frames in turn, as a sequence renders them: each is posed where an earlier frame's targets
  // were (the renderer reuses those posed scenes), then out of turn
  for (int back : {2, 1}) {
    Renderer renderer(scene);
    for (int frame : {15, 16, 17, 18, 12, 16}) {
      CAPTURE(back, frame);
      check_skinned_frame(renderer, *mesh, frame, back);
    }
  }
}

TEST_CASE("a part fixed to the rig has exactly zero flow in the rig's cameras") {
  // the rig drives forward and turns; a box 1 m ahead of it rides with it (an ego's bonnet), a
  // wall far ahead stands still
  const auto rig = [](double t) {
    return Pose(Eigen::Translation3d(3 * t, 0.5 * t * t, 0) *
                Eigen::AngleAxisd(0.4 * t, Vec3::UnitZ()));
  };
  Scene scene;
  add_box(scene.world, {30, -40, -5}, {31, 40, 20}, SemanticClass::Wall);
  Mesh bonnet;
  add_box(bonnet, {1.0f, -0.3f, -0.3f}, {1.4f, 0.3f, -0.1f}, SemanticClass::EgoVehicle);
  Actor ego{3, {}, rig};
  Part body = rigid_part(std::move(bonnet));
  body.on_rig = true;
  ego.parts.push_back(body);
  scene.actors.push_back(ego);
  Renderer renderer(scene);
  TruthRequest request{FramePair{0.4, 0.4 + 1 / kFrameRate, rig(0.4), rig(0.4 + 1 / kFrameRate)}};
  request.camera_on_rig = true;
  const Projection camera = Projection::pinhole(kSize, kSize, 90);
  const GroundTruth on = renderer.ground_truth(camera, request);
  request.camera_on_rig = false;  // the same computed through the poses: zero to rounding
  const GroundTruth through = renderer.ground_truth(camera, request);
  int bonnet_pixels = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      if (*on.instance.pixel(x, y) != 3) {
        CHECK(std::abs(on.flow.pixel(x, y)[0]) > 1e-3);  // the wall moves in the image
        continue;
      }
      ++bonnet_pixels;
      CHECK(on.flow.pixel(x, y)[0] == 0.0f);
      CHECK(on.flow.pixel(x, y)[1] == 0.0f);
      CHECK(*on.valid.pixel(x, y) == 1);
      CHECK(std::abs(through.flow.pixel(x, y)[0]) < 1e-4);
      CHECK(std::abs(through.flow.pixel(x, y)[1]) < 1e-4);
    }
  CHECK(bonnet_pixels > 100);
}
