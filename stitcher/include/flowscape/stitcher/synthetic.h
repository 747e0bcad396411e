#pragma once
// An analytic panorama with exact ground truth, for the demo, the benchmarks and quick checks:
// a smooth colour pattern on a sphere of radius 100 m around the rig, seen by the cube rig while
// the camera yaws (turns left) by `yaw_degrees` between frame 0 and frame 1.
#include <cstdint>

#include "flowscape/core/image.h"
#include "flowscape/geometry/geometry.h"

namespace flowscape {

struct SyntheticCubemap {
  Image<std::uint8_t> color0, color1;  // RGB, N x 6N
  Image<float> flow;                   // face-plane flow 0 -> 1
  Image<std::uint8_t> semantic;        // Sky above the horizon, Terrain below
  Image<std::uint16_t> instance;       // 1 above the horizon, 2 below
  Image<float> depth;                  // 100 m
  Image<std::uint8_t> valid;           // 1 where the target stays in front of the face
};

// Colour of the pattern in rig direction d (unit).
void synthetic_color(const Vec3& d, std::uint8_t rgb[3]);
SyntheticCubemap make_yaw_cubemap(int face_size, double yaw_degrees);

}  // namespace flowscape
