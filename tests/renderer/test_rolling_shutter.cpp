// Rolling shutter: the crossing solver on closed forms, and the ground truth of rolling-shutter
// cameras against closed forms (a translating camera: a linear equation in the target line) and
// against an independent dense solve (a camera spinning about its optical axis, a sliding box),
// and its reduction to the global shutter.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "flowscape/renderer/renderer.h"
#include "flowscape/renderer/rolling_shutter.h"
#include "flowscape/scenes/test_scenes.h"

using namespace flowscape;

namespace {

constexpr double kDt = 1 / kFrameRate;

// The line at which the point p(t) (a pixel position at time t, nullopt: out of view) is seen in a
// rolling-shutter image read over `readout` seconds of `lines` lines captured around `frame_time`:
// every line scanned at steps of 1/16 line for the first change of sign, then bisected to 1e-9.
std::optional<double> dense_solve(const std::function<std::optional<Vec2>(double)>& p,
                                  const Readout& readout, int lines, double frame_time) {
  const auto f = [&](double s) -> std::optional<double> {
    const auto seen = p(frame_time + readout.seconds * (s / lines - 0.5));
    if (!seen) return std::nullopt;
    return (readout.columns ? seen->x() : seen->y()) - s;
  };
  std::optional<double> previous = f(0);
  for (int k = 1; k <= 16 * lines; ++k) {
    double a = (k - 1) / 16.0, b = k / 16.0;
    const std::optional<double> value = f(b);
    if (value && previous && (*value < 0) != (*previous < 0)) {
      double fa = *previous;
      while (b - a > 1e-9) {
        const double m = (a + b) / 2;
        const std::optional<double> fm = f(m);
        if (!fm) return std::nullopt;
        if ((*fm < 0) == (fa < 0))
          a = m, fa = *fm;
        else
          b = m;
      }
      return (a + b) / 2;
    }
    previous = value;
  }
  return std::nullopt;
}

Scene plane_at(double distance) {
  Scene scene = textured_plane(distance, 4000);
  scene.materials = {Material{}};
  return scene;
}

// A sunlit checkered wall (textured looks shared by a pixel's samples) and a box sliding in front
// of it: colour that varies from pixel to pixel and over time.
Scene lit_wall_with_box() {
  Scene scene = textured_plane(6, 40);
  scene.materials[0].pattern = checker(1, {0.1f, 0.5f, 1.5f});
  scene.environment.sun_direction = Vec3(-0.6, 0.3, 0.74).normalized();  // on the wall's face
  scene.actors.push_back(sliding_box({4.5, 1.2, 0}, {0, -3, 0}, 0));
  return scene;
}

// Each line of a rolling-shutter colour image at `T` equals, bit for bit, the global shutter's
// image at the line's own time (direct and indirect layers); the image is not uniform.
void require_lines_at_their_times(Renderer& renderer, const Projection& p, const CameraTrack& track,
                                  const Readout& readout, double T, const RenderOptions& options) {
  const ColorLayers rolling = renderer.color_layers(p, T, track, readout, options);
  const auto [low, high] =
      std::minmax_element(rolling.direct.data.begin(), rolling.direct.data.end());
  REQUIRE(*high > 2 * *low);
  const int lines = readout.lines(p), length = readout.columns ? p.height : p.width;
  for (int line = 0; line < lines; ++line) {
    const double t = T + readout.offset(line + 0.5, lines);
    const ColorLayers global = renderer.color_layers(p, {t, t, track(t), track(t)}, options);
    for (int k = 0; k < length; ++k) {
      const int x = readout.columns ? line : k, y = readout.columns ? k : line;
      for (int c = 0; c < 3; ++c) {
        REQUIRE(rolling.direct.pixel(x, y)[c] == global.direct.pixel(x, y)[c]);
        REQUIRE(rolling.indirect.pixel(x, y)[c] == global.indirect.pixel(x, y)[c]);
      }
    }
  }
}

}  // namespace

TEST_CASE("first_crossing solves s = a + b s where fixed-point iteration diverges") {
  for (double b : {-3.0, -0.5, 0.5, 3.0}) {
    const double root = 40;  // a = root (1 - b)
    const auto seen = [&](double s) { return std::optional<double>(root * (1 - b) + b * s); };
    const auto found = first_crossing(seen, 100);
    REQUIRE(found);
    CHECK(std::abs(*found - root) < 1e-6);
  }
}

TEST_CASE("first_crossing takes the earliest of two crossings and skips undefined stretches") {
  // seen_at(s) - s = (s - 30)(s - 70) / 100: crossings at 30 and 70
  const auto two = [](double s) { return std::optional<double>(s + (s - 30) * (s - 70) / 100); };
  REQUIRE(first_crossing(two, 100));
  CHECK(std::abs(*first_crossing(two, 100) - 30) < 1e-6);
  // out of view below 50: only the crossing at 70 counts
  const auto half = [&](double s) { return s < 50 ? std::nullopt : two(s); };
  REQUIRE(first_crossing(half, 100));
  CHECK(std::abs(*first_crossing(half, 100) - 70) < 1e-6);
  // never seen on its own line
  CHECK_FALSE(first_crossing([](double s) { return std::optional<double>(s + 5); }, 100));
}

TEST_CASE("capture_times: the frame time plus each line's offset, centred") {
  const Projection p = Projection::pinhole(8, 4, 90);
  const Image<float> rows = capture_times(p, {0.02, false}, 1.0);
  const Image<float> columns = capture_times(p, {0.02, true}, 1.0);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      CHECK(*rows.pixel(x, y) == Approx(1.0 + 0.02 * ((y + 0.5) / 4 - 0.5)).epsilon(1e-7));
      CHECK(*columns.pixel(x, y) == Approx(1.0 + 0.02 * ((x + 0.5) / 8 - 0.5)).epsilon(1e-7));
    }
}

TEST_CASE("rolling shutter, translating camera: the closed-form flow of the skewed image") {
  // A pinhole (focal f, centre c) looks along the rig's x at the plane x = Z and moves to its
  // right (the rig's -y) at V m/s. A point at rig y = Y is seen at u(t) = c + f (-Y - V t) / Z.
  // Column readout: the pixel at column x is captured at t0 = T0 + r ((x + 1/2) / W - 1/2), so
  // Y = -(x + 1/2 - c) Z / f - V t0; at the target frame T1, column s sees it when
  // s = c + f (-Y - V (T1 + r (s / W - 1/2))) / Z, i.e. s = A / (1 + B) with
  // A = c + f (-Y - V T1 + V r / 2) / Z and B = f V r / (Z W). B = 3: fixed-point iteration
  // diverges. Row readout: the row never changes, so the flow is the global shutter's, -f V dt / Z.
  const int W = 64, H = 48;
  const double Z = 2, r = 0.03;
  const Projection p = Projection::pinhole(W, H, 90);
  const double f = p.focal, c = W / 2.0;
  Scene scene = plane_at(Z);
  Renderer renderer(scene);
  for (double B : {0.3, 3.0}) {
    const double V = B * Z * W / (f * r);
    const double T0 = 0.5, T1 = T0 + (B > 1 ? 0.002 : kDt);
    const CameraTrack track = [V](double t) { return Pose(Eigen::Translation3d(0, -V * t, 0)); };
    for (bool columns : {true, false}) {
      INFO("B " << B << (columns ? " columns" : " rows"));
      TruthRequest request{{T0, T1, track(T0), track(T1)}};
      request.readout = {r, columns}, request.track = track;
      const GroundTruth gt = renderer.ground_truth(p, request);
      int checked = 0;
      for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
          const double t0 = T0 + r * ((columns ? x + 0.5 : y + 0.5) / (columns ? W : H) - 0.5);
          const double Y = -(x + 0.5 - c) * Z / f - V * t0;
          double u = -f * V * (T1 - T0) / Z;
          if (columns) {
            const double A = c + f * (-Y - V * T1 + V * r / 2) / Z, s = A / (1 + B);
            u = s - (x + 0.5);
          }
          // a target needs a line of the image (its capture time); off the other axis it is kept,
          // as a global pinhole keeps targets beside the image
          const bool in_view = !columns || (x + 0.5 + u >= 0 && x + 0.5 + u <= W);
          REQUIRE(bool(*gt.valid.pixel(x, y)) == in_view);
          CHECK(*gt.depth.pixel(x, y) ==
                Approx(std::hypot(Z, Z * (x + 0.5 - c) / f, Z * (y + 0.5 - H / 2.0) / f))
                    .epsilon(1e-6));
          if (!in_view) continue;
          ++checked;
          CHECK(std::abs(gt.flow.pixel(x, y)[0] - u) < 1e-4);
          CHECK(std::abs(gt.flow.pixel(x, y)[1]) < 1e-4);
        }
      CHECK(checked > W * H / 4);
    }
  }
}

TEST_CASE("rolling shutter, camera spinning about its optical axis: flow of the dense solve") {
  // 3 rad/s about the view axis with a 30 ms row readout: each row sees the image turned by its
  // own angle; the target row is found by a dense scan and bisection over every line.
  const int W = 48, H = 36;
  const Projection p = Projection::pinhole(W, H, 90);
  Scene scene = plane_at(10);
  Renderer renderer(scene);
  const CameraTrack track = [](double t) { return Pose(Eigen::AngleAxisd(3 * t, Vec3::UnitX())); };
  for (bool columns : {false, true}) {
    INFO((columns ? "columns" : "rows"));
    const Readout readout{0.03, columns};
    const double T0 = 0.1;
    for (double T1 : {T0 + kDt, T0 - 2 * kDt}) {
      TruthRequest request{{T0, T1, track(T0), track(T1)}};
      request.readout = readout, request.track = track;
      const GroundTruth gt = renderer.ground_truth(p, request);
      int checked = 0;
      for (int y = 0; y < H; y += 3)
        for (int x = 0; x < W; x += 3) {
          const Vec2 pixel(x + 0.5, y + 0.5);
          const int lines = readout.lines(p);
          const double t0 = T0 + readout.offset(readout.line_of(pixel), lines);
          const Vec3 world = track(t0).linear() * p.ray(pixel).normalized();
          const auto seen = [&](double t) {
            return p.project(track(t).linear().transpose() * world);
          };
          const auto s = dense_solve(seen, readout, lines, T1);
          REQUIRE(bool(s) == bool(*gt.valid.pixel(x, y)));
          if (!s) continue;
          const Vec2 expected = *seen(T1 + readout.offset(*s, lines)) - pixel;
          CHECK(std::abs(gt.flow.pixel(x, y)[0] - expected.x()) < 1e-4);
          CHECK(std::abs(gt.flow.pixel(x, y)[1] - expected.y()) < 1e-4);
          ++checked;
        }
      CHECK(checked > 50);
    }
  }
}

TEST_CASE("rolling shutter on a moving actor: the box's points follow the dense solve") {
  // A box sliding across the view of a still camera: a point of the box seen at row y is where
  // it was at the row's time, and is found in the target image at the row that sees it then.
  const Eigen::Vector3d centre(8, 2, 0), velocity(0, -60, 0);
  Scene scene = moving_box(centre, velocity);
  scene.materials = {Material{}};
  Renderer renderer(scene);
  const Projection p = Projection::pinhole(40, 30, 90);
  const CameraTrack track = [](double) { return Pose::Identity(); };
  const Readout readout{0.03, true};
  const double T0 = 0.0, T1 = kDt;
  TruthRequest request{{T0, T1, track(T0), track(T1)}};
  request.readout = readout, request.track = track, request.scene_flow = true;
  const GroundTruth gt = renderer.ground_truth(p, request);
  int on_box = 0;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      if (*gt.instance.pixel(x, y) != 7 || !*gt.valid.pixel(x, y)) continue;
      const Vec2 pixel(x + 0.5, y + 0.5);
      const double t0 = T0 + readout.offset(x + 0.5, p.width);
      const Vec3 point = *gt.depth.pixel(x, y) * p.ray(pixel).normalized();
      const auto seen = [&](double t) { return p.project(point + velocity * (t - t0)); };
      const auto s = dense_solve(seen, readout, p.width, T1);
      REQUIRE(s);
      const double t1 = T1 + readout.offset(*s, p.width);
      const Vec2 expected = *seen(t1) - pixel;
      CHECK(std::abs(gt.flow.pixel(x, y)[0] - expected.x()) < 1e-3);
      CHECK(std::abs(gt.flow.pixel(x, y)[1] - expected.y()) < 1e-3);
      // scene flow: the point's motion from its capture time to the target's, camera frame
      const Vec3 moved = p.camera_to_rig().transpose() * (velocity * (t1 - t0));
      for (int i = 0; i < 3; ++i)
        CHECK(gt.scene_flow.pixel(x, y)[i] == Approx(moved[i]).margin(1e-4));
      ++on_box;
    }
  CHECK(on_box > 20);
}

TEST_CASE("a rolling shutter reduces to the global shutter as its readout goes to zero") {
  Scene scene = moving_box({6, 1.5, -1}, {-2, 4, 0.5});
  scene.materials = {Material{}};
  Renderer renderer(scene);
  const Projection p = Projection::pinhole(40, 30, 100);
  const CameraTrack track = [](double t) {
    return Pose(Eigen::Translation3d(3 * t, t, 0) * Eigen::AngleAxisd(0.3 * t, Vec3::UnitZ()));
  };
  const double T0 = 0.2;
  TruthRequest request{{T0, T0 + kDt, track(T0), track(T0 + kDt)}, {{T0 - kDt, track(T0 - kDt)}}};
  request.track = track;
  const GroundTruth global = renderer.ground_truth(p, request);
  request.readout = {1e-9, false};
  const GroundTruth rolling = renderer.ground_truth(p, request);
  CHECK(rolling.depth.data == global.depth.data);
  CHECK(rolling.instance.data == global.instance.data);
  for (auto [r, g] :
       {std::pair{&rolling.flow, &global.flow}, {&rolling.more[0].flow, &global.more[0].flow}})
    for (std::size_t i = 0; i < r->data.size(); ++i)
      CHECK(std::abs(r->data[i] - g->data[i]) < 1e-4);
  CHECK(rolling.valid.data == global.valid.data);
  CHECK(rolling.more[0].valid.data == global.more[0].valid.data);
}

TEST_CASE("rolling-shutter colour: each line is the global colour at its own time") {
  const Scene scene = lit_wall_with_box();  // the renderer holds it
  Renderer renderer(scene);
  const Projection p = Projection::pinhole(16, 12, 100);
  const CameraTrack track = [](double t) { return Pose(Eigen::AngleAxisd(2 * t, Vec3::UnitZ())); };
  RenderOptions options;
  options.samples_per_pixel = 2;
  const Readout readout{0.03, false};
  const double T = 0.25;
  require_lines_at_their_times(renderer, p, track, readout, T, options);
  // and the depth guide follows the same line times
  const Image<float> depth = renderer.depth(p, T, track, readout);
  const int y = 9;
  const double t = T + readout.offset(y + 0.5, p.height);
  const GroundTruth at_line = renderer.ground_truth(p, FramePair{t, t, track(t), track(t)});
  for (int x = 0; x < p.width; ++x) CHECK(*depth.pixel(x, y) == *at_line.depth.pixel(x, y));
}

TEST_CASE(
    "path-traced colour: a pixel's samples give the same colour whatever is traced beside it") {
  // the global shutter traces neighbouring pixels in shared packets (8 at 2 samples each, 5 at 3);
  // a column readout traces each column's pixels one by one
  const Scene scene = lit_wall_with_box();  // the renderer holds it
  Renderer renderer(scene);
  const Projection p = Projection::pinhole(16, 12, 100);
  const CameraTrack track = [](double t) { return Pose(Eigen::AngleAxisd(2 * t, Vec3::UnitZ())); };
  for (const int spp : {2, 3}) {
    RenderOptions options;
    options.samples_per_pixel = spp;
    require_lines_at_their_times(renderer, p, track, Readout{0.03, true}, 0.25, options);
  }
}
