#include "flowscape/stitcher/stitch.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace flowscape {
namespace {

template <class Body>
void parallel_rows(int rows, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& range) {
    for (int row = range.begin(); row != range.end(); ++row) body(row);
  });
}

int cube_index(Face face, int i, int j, int face_size) {
  return (int(face) * face_size + j) * face_size + i;
}

template <class Resolve>
Stencil make_stencil(Vec2 position, const Resolve& resolve) {
  const double sx = position.x() - 0.5, sy = position.y() - 0.5;
  const int i0 = int(std::floor(sx)), j0 = int(std::floor(sy));
  return {{resolve(i0, j0), resolve(i0 + 1, j0), resolve(i0, j0 + 1), resolve(i0 + 1, j0 + 1)},
          float(sx - i0),
          float(sy - j0)};
}

std::array<float, 4> bilinear_weights(const Stencil& st) {
  const float fx = st.fx, fy = st.fy;
  return {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
}

// Stencil on one face whose taps are clamped to the face.
Stencil face_stencil(Face face, Vec2 position, int face_size) {
  return make_stencil(position, [&](int i, int j) {
    return cube_index(face, std::clamp(i, 0, face_size - 1), std::clamp(j, 0, face_size - 1),
                      face_size);
  });
}

// ERP pixel of tap (i, j): wraps horizontally and continues over the pole, where the column turns
// half way round.
int erp_tap(int i, int j, int width, bool& over_pole) {
  const int height = width / 2;
  over_pole = j < 0 || j >= height;
  if (over_pole) {
    j = j < 0 ? -1 - j : 2 * height - 1 - j;
    i += width / 2;
  }
  i = ((i % width) + width) % width;
  return j * width + i;
}

void require_positive_sizes(int face_size, int erp_height) {
  if (face_size < 2)
    throw std::invalid_argument("cube face size must be >= 2, got " + std::to_string(face_size));
  if (erp_height < 2)
    throw std::invalid_argument("ERP height must be >= 2, got " + std::to_string(erp_height));
}

template <class T>
void require_source(const Sampling& sampling, ImageView<T> src, int channels, const char* what) {
  if (src.width != sampling.src_width || src.height != sampling.src_height)
    throw std::invalid_argument(std::string(what) + " is " + std::to_string(src.width) + "x" +
                                std::to_string(src.height) + ", the map expects " +
                                std::to_string(sampling.src_width) + "x" +
                                std::to_string(sampling.src_height));
  if (channels > 0 && src.channels != channels)
    throw std::invalid_argument(std::string(what) + " has " + std::to_string(src.channels) +
                                " channels, expected " + std::to_string(channels));
}

void require_flow_input(const Sampling& sampling, const FlowInput& in) {
  require_source(sampling, in.flow, 2, "flow");
  if (in.instance.data) require_source(sampling, in.instance, 1, "instance image");
  if (in.valid.data) require_source(sampling, in.valid, 1, "valid mask");
}

// A bilinear blend never leaves the range of its taps, so integers only need rounding.
template <class T>
T from_float(float value) {
  if constexpr (std::is_floating_point_v<T>) {
    return value;
  } else {
    return T(value + 0.5f);
  }
}

template <class T>
void blend_source(const Stencil& st, ImageView<const T> src, float* out) {
  const auto w = bilinear_weights(st);
  for (int c = 0; c < src.channels; ++c) {
    out[c] = 0;
    for (int k = 0; k < 4; ++k)
      out[c] += w[k] * src.data[std::size_t(st.tap[k]) * src.channels + c];
  }
}

// The source pixel nearest to a stencil's sample point (never an apron pixel's blend).
int nearest_source(const Sampling& sampling, const Stencil& st) {
  const int tap = st.tap[st.nearest_tap()];
  return tap >= 0 ? tap : sampling.apron[-1 - tap].tap[sampling.apron[-1 - tap].nearest_tap()];
}

// One tap's flow in the plane the destination blends in, with what decides whether it may blend.
struct TapFlow {
  float u = 0, v = 0;
  std::uint16_t instance = 0;
  bool known = false;
};

// kInstances: whether `in` has an instance image (a template flag, so the per-tap test folds away).
template <bool kInstances = true>
TapFlow source_flow(const FlowInput& in, int index) {
  const float* f = in.flow.data + 2 * std::size_t(index);
  return {f[0], f[1], kInstances && in.instance.data ? in.instance.data[index] : std::uint16_t(0),
          is_known_flow(f[0], f[1])};
}

// Bilinear blend of the known flows of the taps that share the nearest tap's instance;
// tap_at(k) gives tap k.
template <class TapAt>
TapFlow blend_flows(const Stencil& st, const TapAt& tap_at) {
  const std::uint16_t instance = tap_at(st.nearest_tap()).instance;
  const auto w = bilinear_weights(st);
  float u = 0, v = 0, total = 0;
  for (int k = 0; k < 4; ++k) {
    const TapFlow tap = tap_at(k);
    const bool usable = tap.known && tap.instance == instance;
    // select, not multiply: 0 * NaN would poison the sum
    u += usable ? w[k] * tap.u : 0.f, v += usable ? w[k] * tap.v : 0.f;
    total += usable ? w[k] : 0.f;
  }
  if (total <= 0) return {0, 0, instance, false};
  const float normalise = 1 / total;
  return {u * normalise, v * normalise, instance, true};
}

std::uint8_t source_valid(const Sampling& sampling, const Stencil& st, const FlowInput& in) {
  return in.valid.data ? in.valid.data[nearest_source(sampling, st)] != 0 : 1;
}

// Flow of each apron pixel in its own face's (extended) plane: the neighbour's blended target,
// projected onto this face's plane.
std::vector<TapFlow> apron_flows(const CubeToErp& map, const FlowInput& in) {
  const int N = map.face_size;
  std::vector<TapFlow> flows(map.apron_pixels.size());
  tbb::parallel_for(std::size_t(0), flows.size(), [&](std::size_t a) {
    const Stencil& st = map.sampling.apron[a];
    const ApronPixel& pixel = map.apron_pixels[a];
    TapFlow blended = blend_flows(st, [&](int k) { return source_flow(in, st.tap[k]); });
    if (blended.known) {
      const Vec3 target =
          ray_from_cube(pixel.neighbour, pixel.position + Vec2(blended.u, blended.v), N);
      const auto plane = face_plane_from_direction(pixel.face, target, N);
      blended.known = plane.has_value();
      if (plane)
        blended.u = float(plane->x() - (pixel.i + 0.5)),
        blended.v = float(plane->y() - (pixel.j + 0.5));
    }
    flows[a] = blended;
  });
  return flows;
}

void write_flow_pixel(std::optional<Vec2> flow, std::uint8_t source_valid, float* out,
                      std::uint8_t* valid) {
  out[0] = flow ? float(flow->x()) : kUnknownFlow;
  out[1] = flow ? float(flow->y()) : kUnknownFlow;
  *valid = flow && source_valid;
}

}  // namespace

CubeToErp make_cube_to_erp(int face_size, int erp_height) {
  require_positive_sizes(face_size, erp_height);
  const int W = 2 * erp_height, N = face_size, P = N + 2;
  CubeToErp map{N,
                W,
                {W, erp_height, N, 6 * N, std::vector<Stencil>(std::size_t(W) * erp_height), {}},
                std::vector<std::uint8_t>(std::size_t(W) * erp_height),
                {}};
  // tap of every pixel of the extended faces (apron included), apron pixels numbered in order
  std::vector<std::int32_t> extended_tap(std::size_t(6) * P * P);
  for (Face face : kFaces)
    for (int j = -1; j <= N; ++j)
      for (int i = -1; i <= N; ++i) {
        std::int32_t& tap = extended_tap[(std::size_t(face) * P + j + 1) * P + i + 1];
        if (i >= 0 && j >= 0 && i < N && j < N) {
          tap = cube_index(face, i, j, N);
          continue;
        }
        const CubePoint p = cube_from_direction(ray_from_cube(face, {i + 0.5, j + 0.5}, N), N);
        map.apron_pixels.push_back({face, i, j, p.face, p.pixel});
        map.sampling.apron.push_back(face_stencil(p.face, p.pixel, N));
        tap = -std::int32_t(map.sampling.apron.size());
      }
  parallel_rows(erp_height, [&](int y) {
    for (int x = 0; x < W; ++x) {
      const CubePoint p = cube_from_direction(direction_from_erp({x + 0.5, y + 0.5}, W), N);
      map.faces[std::size_t(y) * W + x] = std::uint8_t(p.face);
      map.sampling.stencils[std::size_t(y) * W + x] = make_stencil(p.pixel, [&](int i, int j) {
        return extended_tap[(std::size_t(p.face) * P + j + 1) * P + i + 1];
      });
    }
  });
  return map;
}

ErpToCube make_erp_to_cube(int erp_height, int face_size) {
  require_positive_sizes(face_size, erp_height);
  const int W = 2 * erp_height, N = face_size;
  ErpToCube map{W,
                N,
                {N, 6 * N, W, erp_height, std::vector<Stencil>(std::size_t(N) * 6 * N), {}},
                std::vector<std::uint8_t>(std::size_t(N) * 6 * N)};
  parallel_rows(6 * N, [&](int row) {
    for (int i = 0; i < N; ++i) {
      const std::size_t index = std::size_t(row) * N + i;
      const Vec3 d = ray_from_cube(Face(row / N), {i + 0.5, row % N + 0.5}, N);
      int tap_number = 0;
      map.sampling.stencils[index] = make_stencil(erp_from_direction(d, W), [&](int x, int y) {
        bool over_pole = false;
        const int tap = erp_tap(x, y, W, over_pole);
        map.over_pole[index] |= std::uint8_t(over_pole) << tap_number++;
        return tap;
      });
    }
  });
  return map;
}

// Bilinear gather of one row with the channel count known at compile time (C > 0), or not (0).
template <class T, int kChannels>
void bilinear_row(const Sampling& sampling, ImageView<const T> src, const std::vector<float>& apron,
                  int y, T* out) {
  const int C = kChannels > 0 ? kChannels : src.channels;
  const Stencil* st = &sampling.stencils[std::size_t(y) * sampling.dst_width];
  for (int x = 0; x < sampling.dst_width; ++x, ++st, out += C) {
    const auto w = bilinear_weights(*st);
    if ((st->tap[0] | st->tap[1] | st->tap[2] | st->tap[3]) >= 0) {
      const T* p[4];
      for (int k = 0; k < 4; ++k) p[k] = src.data + std::size_t(st->tap[k]) * C;
      for (int c = 0; c < C; ++c)
        out[c] = from_float<T>(w[0] * p[0][c] + w[1] * p[1][c] + w[2] * p[2][c] + w[3] * p[3][c]);
      continue;
    }
    for (int c = 0; c < C; ++c) {
      float value = 0;
      for (int k = 0; k < 4; ++k) {
        const int tap = st->tap[k];
        value += w[k] * (tap >= 0 ? float(src.data[std::size_t(tap) * C + c])
                                  : apron[std::size_t(-1 - tap) * C + c]);
      }
      out[c] = from_float<T>(value);
    }
  }
}

template <class T>
Image<T> resample_bilinear(const Sampling& sampling, ImageView<const T> src) {
  require_source(sampling, src, 0, "source image");
  const int C = src.channels;
  std::vector<float> apron(sampling.apron.size() * C);
  for (std::size_t a = 0; a < sampling.apron.size(); ++a)
    blend_source(sampling.apron[a], src, &apron[a * C]);
  Image<T> out(sampling.dst_width, sampling.dst_height, C);
  const auto row = C == 1   ? bilinear_row<T, 1>
                   : C == 2 ? bilinear_row<T, 2>
                   : C == 3 ? bilinear_row<T, 3>
                   : C == 4 ? bilinear_row<T, 4>
                            : bilinear_row<T, 0>;
  parallel_rows(sampling.dst_height, [&](int y) { row(sampling, src, apron, y, out.pixel(0, y)); });
  return out;
}

template <class T>
Image<T> resample_nearest(const Sampling& sampling, ImageView<const T> src) {
  require_source(sampling, src, 0, "source image");
  const int C = src.channels;
  Image<T> out(sampling.dst_width, sampling.dst_height, C);
  parallel_rows(sampling.dst_height, [&](int y) {
    for (int x = 0; x < sampling.dst_width; ++x) {
      const Stencil& st = sampling.stencils[std::size_t(y) * sampling.dst_width + x];
      const T* p = src.data + std::size_t(nearest_source(sampling, st)) * C;
      std::copy(p, p + C, out.pixel(x, y));
    }
  });
  return out;
}

Image<float> cube_to_erp_vectors(const CubeToErp& map, ImageView<const float> cube) {
  require_source(map.sampling, cube, 3, "vector image");
  Image<float> common(cube.width, cube.height, 3);
  const Mat3 to_front = face_rotation(Face::Front).transpose();
  for (Face face : kFaces) {
    const Eigen::Matrix3f turn = (to_front * face_rotation(face)).cast<float>();
    const ImageView<const float> from = face_view(cube, face);
    const ImageView<float> to = face_view(common.view(), face);
    for (std::size_t i = 0; i < from.pixel_count(); ++i)
      Eigen::Map<Eigen::Vector3f>(to.data + 3 * i) =
          turn * Eigen::Map<const Eigen::Vector3f>(from.data + 3 * i);
  }
  return resample_nearest(map.sampling, ImageView<const float>(common.view()));
}

#define FLOWSCAPE_RESAMPLE(T)                                               \
  template Image<T> resample_bilinear(const Sampling&, ImageView<const T>); \
  template Image<T> resample_nearest(const Sampling&, ImageView<const T>);
FLOWSCAPE_RESAMPLE(std::uint8_t)
FLOWSCAPE_RESAMPLE(std::uint16_t)
FLOWSCAPE_RESAMPLE(float)
#undef FLOWSCAPE_RESAMPLE

namespace {

// The blended flow of a destination pixel: face pixels read straight from the cube (the common
// case, with the instance test compiled in or out), apron pixels from their precomputed flows.
TapFlow blend_stencil(const Stencil& st, const FlowInput& in, const std::vector<TapFlow>& apron) {
  if ((st.tap[0] | st.tap[1] | st.tap[2] | st.tap[3]) >= 0) {
    if (in.instance.data)
      return blend_flows(st, [&](int k) { return source_flow<true>(in, st.tap[k]); });
    return blend_flows(st, [&](int k) { return source_flow<false>(in, st.tap[k]); });
  }
  return blend_flows(st, [&](int k) {
    return st.tap[k] >= 0 ? source_flow(in, st.tap[k]) : apron[-1 - st.tap[k]];
  });
}

// A stencil's taps lie on two face rows far apart in memory; asking for their cache lines a few
// pixels ahead hides most of the wait.
constexpr int kPrefetchDistance = 16;
void prefetch_taps(const Stencil& st, const FlowInput& in) {
  for (int k : {0, 2}) {
    const std::size_t tap = std::size_t(std::max(0, st.tap[k]));
    __builtin_prefetch(in.flow.data + 2 * tap);
    if (in.instance.data) __builtin_prefetch(in.instance.data + tap);
    if (in.valid.data) __builtin_prefetch(in.valid.data + tap);
  }
}

// What every row of cube_to_erp_flow shares.
struct FlowRows {
  const CubeToErp& map;
  const FlowInput& cube;
  FlowMode mode;
  std::vector<TapFlow> apron;
  std::vector<double> cos_phi, sin_phi;  // per ERP column
  FlowOutput& out;
};

// Per-row work arrays, one element per ERP column.
struct FlowRowScratch {
  std::vector<float> u, v;              // blended face-plane flow, then the ERP flow
  std::vector<float> lon_sin, lon_cos;  // sine and cosine parts of the longitude change
  std::vector<float> lat_sin, lat_cos;  // and of the latitude change
  std::vector<std::uint8_t> known;
  void resize(int width) {
    for (auto* part : {&u, &v, &lon_sin, &lon_cos, &lat_sin, &lat_cos}) part->resize(width);
    known.resize(width);
  }
};

// Pixels [x0, x1) of a row, all on one face: the pixel's ray s scaled onto the face plane and moved
// by the blended face-plane flow (u, v) gives the target ray t; the angle changes from s to t come
// as sine and cosine parts, computed in double and kept in float (a small angle's sine part keeps
// float's relative accuracy, so small flows stay exact to 1e-7 of their size). Constant face axes
// and unaliased arrays let this loop vectorise. This and angle_changes are also compiled for AVX2,
// picked at run time: same bits, as every operation is IEEE-rounded the same way and nothing is
// fused or reordered.
__attribute__((target_clones("avx2", "default"))) void angle_parts(
    const FaceBasis& b, double step, double cos_theta, double sin_theta, int x0, int x1,
    const double* __restrict cos_phi, const double* __restrict sin_phi, const float* __restrict u,
    const float* __restrict v, float* __restrict lon_sin, float* __restrict lon_cos,
    float* __restrict lat_sin, float* __restrict lat_cos) {
  const double f0 = b.forward.x(), f1 = b.forward.y(), f2 = b.forward.z();
  const double r0 = b.right.x(), r1 = b.right.y(), r2 = b.right.z();
  const double d0 = b.down.x(), d1 = b.down.y(), d2 = b.down.z();
  for (int x = x0; x < x1; ++x) {
    const double s0 = cos_theta * cos_phi[x], s1 = -cos_theta * sin_phi[x], s2 = -sin_theta;
    const double scale = 1 / (s0 * f0 + s1 * f1 + s2 * f2);
    const double du = step * u[x], dv = step * v[x];
    const double t0 = s0 * scale + du * r0 + dv * d0;
    const double t1 = s1 * scale + du * r1 + dv * d1;
    const double t2 = s2 * scale + du * r2 + dv * d2;
    const double rho_t = std::sqrt(t0 * t0 + t1 * t1);
    lon_sin[x] = float(t0 * s1 - t1 * s0);
    lon_cos[x] = float(t0 * s0 + t1 * s1);
    lat_sin[x] = float(s2 * rho_t - t2 * cos_theta);
    lat_cos[x] = float(rho_t * cos_theta + t2 * s2);
  }
}

__attribute__((target_clones("avx2", "default"))) void angle_changes(
    int width, const float* __restrict lon_sin, const float* __restrict lon_cos,
    const float* __restrict lat_sin, const float* __restrict lat_cos, float* __restrict lon,
    float* __restrict lat) {
  for (int x = 0; x < width; ++x) {
    lon[x] = fast_atan2(lon_sin[x], lon_cos[x]);
    lat[x] = fast_atan2(lat_sin[x], lat_cos[x]);
  }
}

// One ERP row: blend the taps (gathers), the angle parts face run by face run, the two angle
// changes (vectorised), then the flow.
void flow_row(const FlowRows& rows, int y) {
  const int W = rows.map.erp_width;
  thread_local FlowRowScratch r;
  r.resize(W);
  const std::size_t row = std::size_t(y) * W;
  std::uint8_t* valid = rows.out.valid.pixel(0, y);
  for (int x = 0; x < W; ++x) {
    const Stencil& st = rows.map.sampling.stencils[row + x];
    if (x % 4 == 0 && x + kPrefetchDistance < W) prefetch_taps((&st)[kPrefetchDistance], rows.cube);
    const TapFlow blended = blend_stencil(st, rows.cube, rows.apron);
    r.u[x] = blended.u, r.v[x] = blended.v, r.known[x] = blended.known;
    valid[x] = blended.known && source_valid(rows.map.sampling, st, rows.cube);
  }
  const double theta = angles_from_erp({0.0, y + 0.5}, W).theta;
  const double cos_theta = std::cos(theta), sin_theta = std::sin(theta);
  const std::uint8_t* faces = &rows.map.faces[row];
  for (int x0 = 0, x1 = 0; x0 < W; x0 = x1) {
    while (x1 < W && faces[x1] == faces[x0]) ++x1;
    angle_parts(face_basis(Face(faces[x0])), 2.0 / rows.map.face_size, cos_theta, sin_theta, x0, x1,
                rows.cos_phi.data(), rows.sin_phi.data(), r.u.data(), r.v.data(), r.lon_sin.data(),
                r.lon_cos.data(), r.lat_sin.data(), r.lat_cos.data());
  }
  angle_changes(W, r.lon_sin.data(), r.lon_cos.data(), r.lat_sin.data(), r.lat_cos.data(),
                r.u.data(), r.v.data());
  const float pixels_per_radian = float(W / (2 * kPi));
  float* o = rows.out.flow.pixel(0, y);
  for (int x = 0; x < W; ++x) {
    const float u = r.u[x] * pixels_per_radian, v = r.v[x] * pixels_per_radian;
    o[2 * x] = r.known[x] ? float(erp_flow_u(u, x + 0.5, W, rows.mode)) : kUnknownFlow;
    o[2 * x + 1] = r.known[x] ? v : kUnknownFlow;
  }
}

}  // namespace

FlowOutput cube_to_erp_flow(const CubeToErp& map, const FlowInput& cube, FlowMode mode) {
  require_flow_input(map.sampling, cube);
  const int W = map.erp_width, H = W / 2;
  FlowOutput out{Image<float>(W, H, 2), Image<std::uint8_t>(W, H, 1)};
  FlowRows rows{
      map, cube, mode, apron_flows(map, cube), std::vector<double>(W), std::vector<double>(W), out};
  for (int x = 0; x < W; ++x) {
    const double phi = angles_from_erp({x + 0.5, 0.0}, W).phi;
    rows.cos_phi[x] = std::cos(phi), rows.sin_phi[x] = std::sin(phi);
  }
  parallel_rows(H, [&](int y) { flow_row(rows, y); });
  return out;
}

FlowOutput erp_to_cube_flow(const ErpToCube& map, const FlowInput& erp) {
  require_flow_input(map.sampling, erp);
  const int W = map.erp_width, N = map.face_size;
  FlowOutput out{Image<float>(N, 6 * N, 2), Image<std::uint8_t>(N, 6 * N, 1)};
  parallel_rows(6 * N, [&](int row) {
    const Face face = Face(row / N);
    for (int i = 0; i < N; ++i) {
      const std::size_t index = std::size_t(row) * N + i;
      const Stencil& st = map.sampling.stencils[index];
      const TapFlow blended = blend_flows(st, [&](int k) {
        TapFlow tap = source_flow(erp, st.tap[k]);
        tap.u = float(wrap_360(tap.u, W));  // classic flow blends like 360-degree flow
        if (map.over_pole[index] >> k & 1) tap.v = -tap.v;  // rows count the other way there
        return tap;
      });
      const Vec2 centre{i + 0.5, row % N + 0.5};
      std::optional<Vec2> flow;
      if (blended.known) {
        const Vec2 sample = erp_from_direction(ray_from_cube(face, centre, N), W);
        const Vec3 target = direction_from_erp(sample + Vec2(blended.u, blended.v), W);
        if (const auto plane = face_plane_from_direction(face, target, N)) flow = *plane - centre;
      }
      write_flow_pixel(flow, source_valid(map.sampling, st, erp), out.flow.pixel(i, row),
                       out.valid.pixel(i, row));
    }
  });
  return out;
}

}  // namespace flowscape
