// Two-way ground truth: backward flow, flow over frame gaps, scene flow and normals, checked
// against closed forms and against each other (round trips, compositions) at exact pixel
// positions (Renderer::ground_truth_at).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>

#include "flowscape/renderer/renderer.h"
#include "flowscape/scenes/test_scenes.h"
#include "independent_math.h"

using namespace flowscape;

namespace {

constexpr double kDt = 1 / kFrameRate;

// A rig that drives forward at 3 m/s, drifts left at 1 m/s and yaws left at 0.3 rad/s.
Pose driving_rig(double t) {
  return Pose(Eigen::Translation3d(3 * t, 1 * t, 0) * Eigen::AngleAxisd(0.3 * t, Vec3::UnitZ()));
}

// The flow from the frame at t to the frame at t + step frames, with the rig of `rig`.
TruthRequest request(double t, int step, Pose (*rig)(double) = driving_rig) {
  const double other = t + step * kDt;
  return {{t, other, rig(t), rig(other)}};
}

// A room with a box sliding across it: static world and a moving actor.
Scene room_with_actor() { return moving_box({6, 1.5, -1}, {-2, 4, 0.5}); }

// u of a flow, the short way round on an ERP of width W (0: a pinhole, no wrap).
double wrap(double u, int W) { return W ? u - W * std::round(u / W) : u; }
int wrap_width(const Projection& p) {
  return p.kind == Projection::Kind::Equirectangular ? p.width : 0;
}

struct View {
  const char* name;
  Projection projection;
  bool sees_actor;  // the sliding box is in the view
};

std::vector<View> views() {
  return {{"erp", Projection::equirectangular(32), true},
          {"front", Projection::cube_face(Face::Front, 24), true},
          {"left", Projection::cube_face(Face::Left, 24), false},
          {"down", Projection::cube_face(Face::Down, 24), false}};
}

}  // namespace

TEST_CASE("forward then backward flow returns to the start on every pixel visible both ways") {
  Scene scene = room_with_actor();
  Renderer renderer(scene);
  for (const View& view : views()) {
    INFO(view.name);
    const Projection& p = view.projection;
    const int W = wrap_width(p);
    const double t = 0.2;
    const GroundTruth forward = renderer.ground_truth(p, request(t, 1));
    std::vector<Vec2> sources, targets;
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) {
        if (!*forward.valid.pixel(x, y)) continue;
        const float* f = forward.flow.pixel(x, y);
        Vec2 target(x + 0.5 + f[0], y + 0.5 + f[1]);
        if (W) target.x() = std::fmod(target.x() + W, W);
        sources.emplace_back(x + 0.5, y + 0.5), targets.push_back(target);
      }
    REQUIRE(sources.size() > std::size_t(p.width * p.height / 2));
    // the flow of frame t + 1 back to t, at exactly the forward flow's targets
    const GroundTruth backward = renderer.ground_truth_at(p, request(t + kDt, -1), targets);
    int both_ways = 0, on_actor = 0;
    double worst = 0;
    for (std::size_t k = 0; k < targets.size(); ++k) {
      if (!*backward.valid.pixel(int(k), 0)) continue;
      const float* b = backward.flow.pixel(int(k), 0);
      const Vec2 back(wrap(targets[k].x() + b[0] - sources[k].x(), W),
                      targets[k].y() + b[1] - sources[k].y());
      worst = std::max(worst, back.norm());
      ++both_ways, on_actor += *backward.instance.pixel(int(k), 0) == 7;
    }
    CHECK(both_ways > int(sources.size() * 9 / 10));
    CHECK((on_actor > 0) == view.sees_actor);
    CHECK(worst < 1e-3);
  }
}

TEST_CASE(
    "ground truth traced in Embree packets has every byte of the same traced ray by ray (0.11's "
    "way), whole images and chosen pixels") {
  Scene scene = room_with_actor();
  Renderer renderer(scene), one_by_one(scene);
  one_by_one.trace_as({.single_rays = true});
  const auto same_bytes = [](const auto& a, const auto& b) {
    return a.data.size() == b.data.size() &&
           std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(a.data[0])) == 0;
  };
  const auto same_truth = [&](const GroundTruth& a, const GroundTruth& b) {
    bool same = same_bytes(a.flow, b.flow) && same_bytes(a.valid, b.valid) &&
                same_bytes(a.depth, b.depth) && same_bytes(a.semantic, b.semantic) &&
                same_bytes(a.instance, b.instance) && same_bytes(a.scene_flow, b.scene_flow) &&
                same_bytes(a.normal, b.normal) && same_bytes(a.shading_normal, b.shading_normal);
    for (std::size_t k = 0; k < a.more.size(); ++k)
      same = same && same_bytes(a.more[k].flow, b.more[k].flow) &&
             same_bytes(a.more[k].valid, b.more[k].valid);
    return same;
  };
  const double t = 0.3;
  TruthRequest packets = request(t, 1);
  packets.more = {{t - kDt, driving_rig(t - kDt)}, {t + 2 * kDt, driving_rig(t + 2 * kDt)}};
  packets.scene_flow = packets.normal = packets.shading_normal = true;
  long valid = 0, hidden = 0;  // the comparison covers points seen and hidden at the targets
  for (const View& view : views()) {
    INFO(view.name);
    const GroundTruth a = renderer.ground_truth(view.projection, packets);
    const GroundTruth b = one_by_one.ground_truth(view.projection, packets);
    CHECK(same_truth(a, b));
    for (const auto* mask : {&a.valid, &a.more[0].valid, &a.more[1].valid})
      for (std::uint8_t v : mask->data) valid += v, hidden += !v;
  }
  CHECK(valid > 0);
  CHECK(hidden > 0);
  std::vector<Vec2> chosen;  // 37 pixels: two full packets and a part
  for (int k = 0; k < 37; ++k) chosen.emplace_back(0.37 + 0.83 * k, 3.1 + 0.41 * k);
  const Projection erp = Projection::equirectangular(32);
  CHECK(same_truth(renderer.ground_truth_at(erp, packets, chosen),
                   one_by_one.ground_truth_at(erp, packets, chosen)));
}

TEST_CASE("backward flow is the ground truth of the reversed pair: valid where the target shows") {
  Scene scene = room_with_actor();
  Renderer renderer(scene);
  const Projection p = Projection::cube_face(Face::Front, 24);
  const double t = 0.5;
  TruthRequest asked = request(t, 1);
  asked.more = {{t - kDt, driving_rig(t - kDt)}};
  const GroundTruth both = renderer.ground_truth(p, asked);
  const GroundTruth reversed = renderer.ground_truth(p, request(t, -1));
  REQUIRE(both.more.size() == 1);
  CHECK(both.more[0].flow.data == reversed.flow.data);
  CHECK(both.more[0].valid.data == reversed.valid.data);
  CHECK(both.flow.data == renderer.ground_truth(p, request(t, 1)).flow.data);
}

TEST_CASE("flow over a gap of k frames of a camera passing a wall is k times the one-frame flow") {
  // the rig slides sideways (to its right, -y) at 0.6 m/s facing a wall at x = 10: a front-face
  // pixel moves by u = f * (0.6 k / 30) / 10 to the left after k frames, v = 0 (closed form)
  Scene scene = textured_plane(10, 400);
  Renderer renderer(scene);
  const auto sideways = [](double t) { return Pose(Eigen::Translation3d(0, -0.6 * t, 0)); };
  const int N = 32;
  const Projection p = Projection::cube_face(Face::Front, N);
  const double f = N / 2.0, t = 1;
  for (int k : {1, 2, 4, -1, -3}) {
    INFO("gap " << k);
    const GroundTruth gt =
        renderer.ground_truth(p, {{t, t + k * kDt, sideways(t), sideways(t + k * kDt)}});
    const double u = -f * 0.6 * k * kDt / 10;
    for (int y = 0; y < N; ++y)
      for (int x = 0; x < N; ++x) {
        CHECK(gt.flow.pixel(x, y)[0] == Approx(u).margin(1e-4));
        CHECK(gt.flow.pixel(x, y)[1] == Approx(0).margin(1e-4));
        CHECK(*gt.valid.pixel(x, y) == 1);
      }
  }
}

TEST_CASE("flow over k frames is the composition of k one-frame flows where the point stays seen") {
  Scene scene = room_with_actor();
  Renderer renderer(scene);
  for (const View& view : views()) {
    INFO(view.name);
    const Projection& p = view.projection;
    const int W = wrap_width(p);
    const double t = 0.1;
    const int k = 4;
    const GroundTruth gap = renderer.ground_truth(p, request(t, k));
    std::vector<Vec2> at;
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) at.emplace_back(x + 0.5, y + 0.5);
    const std::vector<Vec2> start = at;
    std::vector<bool> seen(at.size(), true);
    for (int step = 0; step < k; ++step) {  // follow each pixel one frame at a time
      const GroundTruth one = renderer.ground_truth_at(p, request(t + step * kDt, 1), at);
      for (std::size_t i = 0; i < at.size(); ++i) {
        seen[i] = seen[i] && *one.valid.pixel(int(i), 0);
        at[i] += Vec2(one.flow.pixel(int(i), 0)[0], one.flow.pixel(int(i), 0)[1]);
        if (W) at[i].x() = std::fmod(at[i].x() + W, W);
      }
    }
    int compared = 0;
    double worst = 0;
    for (std::size_t i = 0; i < at.size(); ++i) {
      const int x = int(start[i].x()), y = int(start[i].y());
      if (!seen[i] || !*gap.valid.pixel(x, y)) continue;
      const float* g = gap.flow.pixel(x, y);
      worst = std::max(
          worst,
          Vec2(wrap(start[i].x() + g[0] - at[i].x(), W), start[i].y() + g[1] - at[i].y()).norm());
      ++compared;
    }
    CHECK(compared > int(at.size() / 2));
    CHECK(worst < 1e-3);
  }
}

TEST_CASE("a pixel's point plus its scene flow, seen by the camera at t + 1, is its flow target") {
  Scene scene = room_with_actor();
  Renderer renderer(scene);
  for (const View& view : views()) {
    INFO(view.name);
    const Projection& p = view.projection;
    const bool erp = p.kind == Projection::Kind::Equirectangular;
    const double t = 0.3;
    TruthRequest asked = request(t, 1);
    asked.scene_flow = true;
    const GroundTruth gt = renderer.ground_truth(p, asked);
    REQUIRE(gt.scene_flow.channels == 3);
    // the camera frame (x right, y down, z forward) in the rig, written out by hand
    const int face = erp ? 0
                         : int(view.name == std::string("front")  ? Face::Front
                               : view.name == std::string("left") ? Face::Left
                                                                  : Face::Down);
    const indep::Axes& axes = indep::faces()[face];
    Mat3 camera_to_rig;
    camera_to_rig << axes.right.x, axes.down.x, axes.forward.x, axes.right.y, axes.down.y,
        axes.forward.y, axes.right.z, axes.down.z, axes.forward.z;
    const Pose now = driving_rig(t), next = driving_rig(t + kDt);
    double worst = 0;
    int moving = 0;
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) {
        const indep::V3 d = erp ? indep::erp_direction(x + 0.5, y + 0.5, p.width)
                                : indep::face_direction(face, x + 0.5, y + 0.5, p.width);
        const Vec3 ray = Vec3(d.x, d.y, d.z).normalized();  // rig frame
        const Vec3 point = ray * double(*gt.depth.pixel(x, y));
        const float* s = gt.scene_flow.pixel(x, y);
        const Vec3 moved_rig = point + camera_to_rig * Vec3(s[0], s[1], s[2]);
        const Vec3 world = now * moved_rig;
        const Vec3 seen = next.inverse() * world;  // rig frame at t + 1
        const indep::V3 v{seen.x(), seen.y(), seen.z()};
        Vec2 target;
        if (erp) {
          target = {(indep::longitude(v) + indep::pi) * p.width / (2 * indep::pi),
                    (indep::latitude(v) + indep::pi / 2) * p.height / indep::pi};
        } else {
          const indep::FaceHit hit = indep::face_hit(v, p.width);
          if (hit.face != face) continue;  // left the face
          target = {hit.s, hit.t};
        }
        const float* f = gt.flow.pixel(x, y);
        const Vec2 flow_target(x + 0.5 + f[0], y + 0.5 + f[1]);
        worst = std::max(worst, Vec2(wrap(flow_target.x() - target.x(), erp ? p.width : 0),
                                     flow_target.y() - target.y())
                                    .norm());
        moving += Vec3(s[0], s[1], s[2]).norm() > 0.1;  // static points have none: the box
      }
    CHECK((moving > 0) == view.sees_actor);
    CHECK(worst < 1e-3);
  }
}

TEST_CASE("scene flow and normals of the sky are NaN") {
  Scene scene = textured_plane(10, 4);  // a small wall, sky round it
  Renderer renderer(scene);
  TruthRequest asked = request(0, 1);
  asked.scene_flow = asked.normal = asked.shading_normal = true;
  const GroundTruth gt = renderer.ground_truth(Projection::equirectangular(16), asked);
  int sky = 0;
  for (int i = 0; i < 32 * 16; ++i)
    if (std::isinf(gt.depth.data[std::size_t(i)])) {
      ++sky;
      for (const Image<float>* image : {&gt.scene_flow, &gt.normal, &gt.shading_normal})
        for (int c = 0; c < 3; ++c) CHECK(std::isnan(image->data[std::size_t(3 * i + c)]));
    }
  CHECK(sky > 400);
}

TEST_CASE("the normals of known planes are exact, in each view's camera frame, facing it") {
  // box_room: floor z = -10 (normal up, +z), ceiling, walls x = +-10, y = +-10, seen from inside
  Scene scene = box_room(10);
  Renderer renderer(scene);
  TruthRequest asked = request(0, 1, [](double) { return Pose(Pose::Identity()); });
  asked.normal = asked.shading_normal = true;
  struct Expected {
    Face face;
    Vec3 normal;  // camera frame: the front face looks at the wall x = 10 (normal -x rig = -z
                  // camera); the down face at the floor (normal +z rig = -z camera)
  };
  for (const Expected& e : {Expected{Face::Front, {0, 0, -1}}, Expected{Face::Down, {0, 0, -1}},
                            Expected{Face::Left, {0, 0, -1}}, Expected{Face::Up, {0, 0, -1}}}) {
    const GroundTruth gt = renderer.ground_truth(Projection::cube_face(e.face, 8), asked);
    for (int i = 0; i < 64; ++i)
      for (int c = 0; c < 3; ++c) {
        CHECK(gt.normal.data[std::size_t(3 * i + c)] == Approx(e.normal[c]).margin(1e-6));
        CHECK(gt.shading_normal.data[std::size_t(3 * i + c)] == Approx(e.normal[c]).margin(1e-6));
      }
  }
  // the ERP's camera frame is the front face's: the floor straight below (theta = pi/2) has
  // normal rig +z = camera -y; the wall straight ahead rig -x = camera -z
  const GroundTruth erp = renderer.ground_truth(Projection::equirectangular(16), asked);
  const float* below = erp.normal.pixel(16, 15);
  const float* ahead = erp.normal.pixel(16, 8);
  CHECK(below[1] == Approx(-1).margin(1e-6));
  CHECK(ahead[2] == Approx(-1).margin(1e-6));
}

TEST_CASE("a tilted plane's normal is its analytic normal, whatever the pixel") {
  // a plane through (8, 0, 0) tilted 30 degrees back from facing the rig: normal (-cos, 0, sin)
  const double a = 30 * indep::pi / 180;
  Scene scene;
  const Vec3 n(-std::cos(a), 0, std::sin(a)), along(std::sin(a), 0, std::cos(a));
  const Vec3 c(8, 0, 0), side(0, 1, 0);
  for (const Vec3& corner :
       std::vector<Vec3>{c - 20 * along - 20 * side, c + 20 * along - 20 * side,
                         c + 20 * along + 20 * side, c - 20 * along + 20 * side})
    scene.world.vertices.push_back(corner.cast<float>());
  scene.world.triangles = {{0, 2, 1}, {0, 3, 2}};
  scene.world.classes = {SemanticClass::Wall, SemanticClass::Wall};
  Renderer renderer(scene);
  TruthRequest asked = request(0, 1, [](double) { return Pose(Pose::Identity()); });
  asked.normal = true;
  const GroundTruth gt = renderer.ground_truth(Projection::cube_face(Face::Front, 16), asked);
  const Vec3 expected(0, -std::sin(a), -std::cos(a));  // (n.right, n.down, n.forward), front face
  for (int i = 0; i < 16 * 16; ++i)
    for (int c = 0; c < 3; ++c)
      CHECK(gt.normal.data[std::size_t(3 * i + c)] == Approx(expected[c]).margin(1e-6));
}
