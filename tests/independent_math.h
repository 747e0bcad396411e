#pragma once
// Expectations derived by hand for the tests, written without the library's geometry code.
//   Rig: x forward, y left, z up. ERP column x <-> longitude phi = 2 pi (x / W) - pi
//   (right-positive), row y <-> latitude theta = pi (y / H) - pi / 2 (down-positive). Faces
//   (forward, right, down): front (+x, -y, -z), right (-y, -x, -z), back (-x, +y, -z), left (+y,
//   +x, -z), up (+z, -y, +x), down (-z, -y, -x). Pixel (i, j) of an N x N face looks along forward
//   + a right + b down with a = 2 (i + 0.5) / N - 1, b = 2 (j + 0.5) / N - 1.
#include <array>
#include <cmath>

namespace indep {

constexpr double pi = 3.14159265358979323846;

struct V3 {
  double x, y, z;
};

inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

struct Axes {
  V3 forward, right, down;
};

inline const std::array<Axes, 6>& faces() {
  static const std::array<Axes, 6> table{{
      {{1, 0, 0}, {0, -1, 0}, {0, 0, -1}},
      {{0, -1, 0}, {-1, 0, 0}, {0, 0, -1}},
      {{-1, 0, 0}, {0, 1, 0}, {0, 0, -1}},
      {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},
      {{0, 0, 1}, {0, -1, 0}, {1, 0, 0}},
      {{0, 0, -1}, {0, -1, 0}, {-1, 0, 0}},
  }};
  return table;
}

// Direction of a continuous face coordinate (s, t) in [0, N).
inline V3 face_direction(int face, double s, double t, int N) {
  const Axes& f = faces()[face];
  return f.forward + (2 * s / N - 1) * f.right + (2 * t / N - 1) * f.down;
}

inline V3 erp_direction(double x, double y, int W) {
  const double phi = 2 * pi * x / W - pi, theta = pi * y / (W / 2) - pi / 2;
  return {std::cos(theta) * std::cos(phi), -std::cos(theta) * std::sin(phi), -std::sin(theta)};
}

inline double longitude(V3 d) { return std::atan2(-d.y, d.x); }
inline double latitude(V3 d) { return std::atan2(-d.z, std::sqrt(d.x * d.x + d.y * d.y)); }

// Face and continuous face coordinate of a direction: the face with the largest forward component.
struct FaceHit {
  int face;
  double s, t;
};
inline FaceHit face_hit(V3 d, int N) {
  int best = 0;
  for (int f = 1; f < 6; ++f)
    if (dot(d, faces()[f].forward) > dot(d, faces()[best].forward)) best = f;
  const Axes& f = faces()[best];
  const double depth = dot(d, f.forward);
  return {best, N / 2.0 * (1 + dot(d, f.right) / depth), N / 2.0 * (1 + dot(d, f.down) / depth)};
}

// Pinhole flow on face `face` at normalised coordinates (a, b) when the camera yaws left by psi.
// Horizontal faces: the horizontal angle alpha = atan(a) grows by psi, the elevation stays, so
// a' = tan(alpha + psi) and b' = b cos(alpha) / cos(alpha + psi). Up and down faces: the image
// turns about its centre by psi (clockwise on up, counter-clockwise on down, seen in image
// coordinates). Returns the flow in pixels of an N x N face.
inline std::array<double, 2> yaw_face_flow(int face, double a, double b, double psi, int N) {
  double a2, b2;
  if (face < 4) {
    const double alpha = std::atan(a);
    a2 = std::tan(alpha + psi);
    b2 = b * std::cos(alpha) / std::cos(alpha + psi);
  } else if (face == 4) {
    a2 = a * std::cos(psi) + b * std::sin(psi);
    b2 = b * std::cos(psi) - a * std::sin(psi);
  } else {
    a2 = a * std::cos(psi) - b * std::sin(psi);
    b2 = b * std::cos(psi) + a * std::sin(psi);
  }
  return {(a2 - a) * N / 2, (b2 - b) * N / 2};
}

// A smooth colour pattern on the sphere (intensities 0-255), channel c, for any direction d.
inline double pattern(V3 d, int c) {
  d = (1 / std::sqrt(dot(d, d))) * d;
  switch (c) {
    case 0:
      return 127.5 + 90 * std::sin(2.5 * d.x + 1.5 * d.y - d.z);
    case 1:
      return 127.5 + 90 * std::cos(3 * d.y + 2 * d.z);
    default:
      return 127.5 + 60 * std::sin(2 * d.x + d.y) + 30 * d.z;
  }
}

}  // namespace indep
