#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <set>

#include "flowscape/stitcher/stitch.h"
#include "independent_math.h"

using namespace flowscape;

namespace {

// A cubemap (N x 6N) whose every pixel holds fill(face, i, j).
template <class T, class Fill>
Image<T> make_cube(int N, int channels, const Fill& fill) {
  Image<T> cube(N, 6 * N, channels);
  for (int row = 0; row < 6 * N; ++row)
    for (int i = 0; i < N; ++i) fill(row / N, i, row % N, cube.pixel(i, row));
  return cube;
}

Image<std::uint8_t> pattern_cube(int N) {
  return make_cube<std::uint8_t>(N, 3, [N](int face, int i, int j, std::uint8_t* p) {
    const indep::V3 d = indep::face_direction(face, i + 0.5, j + 0.5, N);
    for (int c = 0; c < 3; ++c) p[c] = std::uint8_t(std::lround(indep::pattern(d, c)));
  });
}

Image<float> yaw_cube_flow(int N, double psi) {
  return make_cube<float>(N, 2, [N, psi](int face, int i, int j, float* f) {
    const auto uv =
        indep::yaw_face_flow(face, 2 * (i + 0.5) / N - 1, 2 * (j + 0.5) / N - 1, psi, N);
    f[0] = float(uv[0]);
    f[1] = float(uv[1]);
  });
}

struct ErrorStats {
  double sum = 0, worst = 0;
  long count = 0;
  void add(double e) { sum += std::abs(e), worst = std::max(worst, std::abs(e)), ++count; }
  double mean() const { return count ? sum / count : 0; }
};

// ERP pixels whose direction lies within one face pixel of a face edge.
bool near_face_edge(int x, int y, int W, int N) {
  const indep::FaceHit hit = indep::face_hit(indep::erp_direction(x + 0.5, y + 0.5, W), N);
  return hit.s < 1 || hit.t < 1 || hit.s > N - 1 || hit.t > N - 1;
}

}  // namespace

TEST_CASE("a pure camera yaw gives ERP flow u = a/360 W, v = 0 everywhere, across the seam too") {
  const int N = 128, H = 256, W = 2 * H;
  const CubeToErp map = make_cube_to_erp(N, H);
  for (double degrees : {5.0, -12.0}) {
    const Image<float> flow = yaw_cube_flow(N, degrees * indep::pi / 180);
    const double expected = degrees / 360 * W;
    const FlowOutput erp = cube_to_erp_flow(map, {flow.view()}, FlowMode::Wrap360);
    const FlowOutput classic = cube_to_erp_flow(map, {flow.view()}, FlowMode::Classic);
    ErrorStats u_error, v_error, classic_error;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        u_error.add(erp.flow.pixel(x, y)[0] - expected);
        v_error.add(erp.flow.pixel(x, y)[1]);
        CHECK(*erp.valid.pixel(x, y) == 1);
        // classic flow does not wrap: a target past the seam lands at x + u - W (or + W)
        const double target = x + 0.5 + expected;
        const double classic_expected = target >= W  ? expected - W
                                        : target < 0 ? expected + W
                                                     : expected;
        classic_error.add(classic.flow.pixel(x, y)[0] - classic_expected);
      }
    CHECK(u_error.worst < 2e-3);  // the rows next to a pole amplify angles most
    CHECK(v_error.worst < 1e-3);
    CHECK(classic_error.worst < 2e-3);
  }
}

TEST_CASE("a cubemap rendered from an analytic pattern stitches back within 1 intensity level") {
  const int N = 256, H = 256, W = 2 * H;
  const Image<std::uint8_t> erp =
      resample_bilinear(make_cube_to_erp(N, H).sampling, pattern_cube(N));
  REQUIRE(erp.width == W);
  REQUIRE(erp.height == H);
  REQUIRE(erp.channels == 3);
  ErrorStats all, seams;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      for (int c = 0; c < 3; ++c) {
        const double e =
            erp.pixel(x, y)[c] - indep::pattern(indep::erp_direction(x + 0.5, y + 0.5, W), c);
        all.add(e);
        if (near_face_edge(x, y, W, N)) seams.add(e);
      }
  CHECK(seams.count > 1000);
  CHECK(all.mean() < 1.0);
  CHECK(seams.mean() < 1.0);  // no seam: edge pixels are as good as the rest
  CHECK(seams.worst < 4.0);
}

TEST_CASE("ERP -> cube -> ERP round trip keeps colour and flow") {
  const int H = 256, W = 2 * H, N = 192;
  Image<std::uint8_t> erp(W, H, 3);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      for (int c = 0; c < 3; ++c)
        erp.pixel(x, y)[c] =
            std::uint8_t(std::lround(indep::pattern(indep::erp_direction(x + 0.5, y + 0.5, W), c)));
  const ErpToCube to_cube = make_erp_to_cube(H, N);
  const CubeToErp to_erp = make_cube_to_erp(N, H);

  const Image<std::uint8_t> cube = resample_bilinear(to_cube.sampling, erp);
  ErrorStats cube_error;
  for (int row = 0; row < 6 * N; ++row)
    for (int i = 0; i < N; ++i)
      for (int c = 0; c < 3; ++c)
        cube_error.add(
            cube.pixel(i, row)[c] -
            indep::pattern(indep::face_direction(row / N, i + 0.5, row % N + 0.5, N), c));
  CHECK(cube_error.mean() < 1.0);

  const Image<std::uint8_t> back = resample_bilinear(to_erp.sampling, cube);
  ErrorStats round_trip;
  for (std::size_t k = 0; k < back.data.size(); ++k)
    round_trip.add(double(back.data[k]) - erp.data[k]);
  CHECK(round_trip.mean() < 1.0);

  const double psi = 4 * indep::pi / 180, u = psi / (2 * indep::pi) * W;
  Image<float> erp_flow(W, H, 2);
  for (std::size_t k = 0; k < erp_flow.pixel_count(); ++k) erp_flow.data[2 * k] = float(u);
  const FlowOutput cube_flow = erp_to_cube_flow(to_cube, {erp_flow.view()});
  ErrorStats face_error;
  for (int row = 0; row < 6 * N; ++row)
    for (int i = 0; i < N; ++i) {
      const auto expected =
          indep::yaw_face_flow(row / N, 2 * (i + 0.5) / N - 1, 2 * (row % N + 0.5) / N - 1, psi, N);
      face_error.add(cube_flow.flow.pixel(i, row)[0] - expected[0]);
      face_error.add(cube_flow.flow.pixel(i, row)[1] - expected[1]);
    }
  CHECK(face_error.worst < 1e-3);
  const FlowOutput erp_again = cube_to_erp_flow(to_erp, {cube_flow.flow.view()}, FlowMode::Wrap360);
  ErrorStats flow_round_trip;
  for (std::size_t k = 0; k < erp_again.flow.pixel_count(); ++k) {
    flow_round_trip.add(erp_again.flow.data[2 * k] - u);
    flow_round_trip.add(erp_again.flow.data[2 * k + 1]);
  }
  CHECK(flow_round_trip.worst < 1e-3);
}

TEST_CASE("ids are sampled nearest and never mixed") {
  const int N = 64, H = 128, W = 2 * H;
  // every face pixel its own id: an output id names the one source pixel it came from
  const Image<std::uint16_t> ids =
      make_cube<std::uint16_t>(N, 1, [N](int face, int i, int j, std::uint16_t* p) {
        *p = std::uint16_t((face * N + j) * N + i);
      });
  const Image<std::uint16_t> erp = resample_nearest(make_cube_to_erp(N, H).sampling, ids);
  int mismatches = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const indep::FaceHit hit = indep::face_hit(indep::erp_direction(x + 0.5, y + 0.5, W), N);
      const int expected =
          (hit.face * N + std::min(int(hit.t), N - 1)) * N + std::min(int(hit.s), N - 1);
      mismatches += *erp.pixel(x, y) != expected;
    }
  CHECK(mismatches == 0);

  Image<std::uint16_t> erp_ids(W, H, 1);
  for (int k = 0; k < W * H; ++k) erp_ids.data[k] = std::uint16_t(k);
  const Image<std::uint16_t> cube = resample_nearest(make_erp_to_cube(H, N).sampling, erp_ids);
  mismatches = 0;
  for (int row = 0; row < 6 * N; ++row)
    for (int i = 0; i < N; ++i) {
      const indep::V3 d = indep::face_direction(row / N, i + 0.5, row % N + 0.5, N);
      const double x = (indep::longitude(d) + indep::pi) / (2 * indep::pi) * W;
      const double y = (indep::latitude(d) + indep::pi / 2) / indep::pi * H;
      const int expected = std::min(int(y), H - 1) * W + int(x) % W;
      mismatches += *cube.pixel(i, row) != expected;
    }
  CHECK(mismatches == 0);
}

TEST_CASE("flow is blended only between taps of one instance") {
  const int N = 32, H = 256, W = 2 * H;  // ERP pixels 5x denser than face pixels at the centre
  // two objects side by side on every face, moving apart by 2 px on the face plane
  const Image<float> flow = make_cube<float>(N, 2, [N](int, int i, int, float* f) {
    f[0] = i < N / 2 ? -2.f : 2.f;
    f[1] = 0;
  });
  const Image<std::uint16_t> instance = make_cube<std::uint16_t>(
      N, 1, [N](int, int i, int, std::uint16_t* p) { *p = i < N / 2 ? 1 : 2; });
  const CubeToErp map = make_cube_to_erp(N, H);
  const FlowOutput separated =
      cube_to_erp_flow(map, {flow.view(), instance.view()}, FlowMode::Wrap360);
  const FlowOutput blended = cube_to_erp_flow(map, {flow.view()}, FlowMode::Wrap360);
  // at the face centre one face pixel spans (2 / N) / (2 pi / W) ERP pixels
  const double expected = 2 * (2.0 / N) / (2 * indep::pi / W);
  double smallest_separated = 1e9, smallest_blended = 1e9;
  for (int x = W / 2 - 8; x < W / 2 + 8; ++x) {  // across the front face's middle column
    smallest_separated =
        std::min(smallest_separated, double(std::abs(separated.flow.pixel(x, H / 2)[0])));
    smallest_blended =
        std::min(smallest_blended, double(std::abs(blended.flow.pixel(x, H / 2)[0])));
  }
  CHECK(smallest_separated > 0.95 * expected);  // each pixel moves with its own object
  CHECK(smallest_blended < 0.25 * expected);    // without instances the taps average out
}

TEST_CASE("unknown face flow stays unknown and invalid sources stay invalid") {
  const int N = 32, H = 64;
  Image<float> flow(N, 6 * N, 2, 1.f);
  Image<std::uint8_t> valid(N, 6 * N, 1, 1);
  for (int row = 0; row < N; ++row)
    for (int i = 0; i < N; ++i) {  // front face: unknown flow, back face: known but invalid
      flow.pixel(i, row)[0] = flow.pixel(i, row)[1] = kUnknownFlow;
      *valid.pixel(i, 2 * N + row) = 0;
    }
  const FlowOutput erp =
      cube_to_erp_flow(make_cube_to_erp(N, H), {flow.view(), {}, valid.view()}, FlowMode::Wrap360);
  const float* front = erp.flow.pixel(H, H / 2);
  CHECK(front[0] == kUnknownFlow);
  CHECK(*erp.valid.pixel(H, H / 2) == 0);
  CHECK(*erp.valid.pixel(0, H / 2) == 0);  // back
  CHECK(is_known_flow(erp.flow.pixel(0, H / 2)[0], erp.flow.pixel(0, H / 2)[1]));
  CHECK(*erp.valid.pixel(H / 2, H / 2) == 1);  // left face
}

TEST_CASE("inputs of the wrong size are rejected with a clear message") {
  const CubeToErp map = make_cube_to_erp(32, 64);
  const Image<std::uint8_t> wrong(32, 32 * 5, 3);
  CHECK_THROWS_WITH(resample_bilinear(map.sampling, wrong.view()),
                    Catch::Contains("32x160") && Catch::Contains("32x192"));
  const Image<float> one_channel(32, 192, 1);
  CHECK_THROWS_WITH(cube_to_erp_flow(map, {one_channel.view()}, FlowMode::Wrap360),
                    Catch::Contains("channels"));
  CHECK_THROWS_AS(make_cube_to_erp(0, 64), std::invalid_argument);
}

TEST_CASE("the stitch gives the same bytes with 1 and 2 threads") {
  const int N = 64, H = 96;
  const Image<float> flow = yaw_cube_flow(N, 0.2);
  const Image<std::uint8_t> colour = pattern_cube(N);
  const CubeToErp map = make_cube_to_erp(N, H);
  const auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return std::make_pair(cube_to_erp_flow(map, {flow.view()}, FlowMode::Wrap360).flow.data,
                          resample_bilinear(map.sampling, colour).data);
  };
  CHECK(run(1) == run(2));
}
