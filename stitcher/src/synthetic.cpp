#include "flowscape/stitcher/synthetic.h"

#include <Eigen/Geometry>
#include <cmath>

namespace flowscape {

void synthetic_color(const Vec3& d, std::uint8_t rgb[3]) {
  const Angles a = angles_from_direction(d);
  const double r = 128 + 100 * std::sin(5 * a.phi) * std::cos(3 * a.theta);
  const double g = 128 + 100 * std::cos(3 * a.phi + 1) * std::sin(4 * a.theta);
  const double b = 128 + 100 * std::sin(2 * a.phi + 7 * a.theta);
  rgb[0] = std::uint8_t(std::lround(r));
  rgb[1] = std::uint8_t(std::lround(g));
  rgb[2] = std::uint8_t(std::lround(b));
}

SyntheticCubemap make_yaw_cubemap(int face_size, double yaw_degrees) {
  const int N = face_size;
  SyntheticCubemap cube{Image<std::uint8_t>(N, 6 * N, 3),  Image<std::uint8_t>(N, 6 * N, 3),
                        Image<float>(N, 6 * N, 2),         Image<std::uint8_t>(N, 6 * N, 1),
                        Image<std::uint16_t>(N, 6 * N, 1), Image<float>(N, 6 * N, 1, 100.f),
                        Image<std::uint8_t>(N, 6 * N, 1)};
  // Frame 1 sees world direction yaw * d; a world point seen at d in frame 0 is at yaw^T * d.
  const Mat3 yaw = Eigen::AngleAxisd(yaw_degrees * kPi / 180, Vec3::UnitZ()).toRotationMatrix();
  for (int row = 0; row < 6 * N; ++row)
    for (int i = 0; i < N; ++i) {
      const Face face = Face(row / N);
      const Vec2 centre{i + 0.5, row % N + 0.5};
      const Vec3 d = ray_from_cube(face, centre, N).normalized();
      synthetic_color(d, cube.color0.pixel(i, row));
      synthetic_color(yaw * d, cube.color1.pixel(i, row));
      const bool sky = d.z() > 0;
      *cube.semantic.pixel(i, row) = sky ? 13 : 22;
      *cube.instance.pixel(i, row) = sky ? 1 : 2;
      const auto target = face_plane_from_direction(face, yaw.transpose() * d, N);
      float* f = cube.flow.pixel(i, row);
      f[0] = target ? float(target->x() - centre.x()) : kUnknownFlow;
      f[1] = target ? float(target->y() - centre.y()) : kUnknownFlow;
      *cube.valid.pixel(i, row) = target.has_value();
    }
  return cube;
}

}  // namespace flowscape
