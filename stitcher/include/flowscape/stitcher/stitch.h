#pragma once
// Cubemap <-> ERP resampling for every modality (cubemaps stacked as geometry.h's face_view says).
// The maps are built once per size and reused for every frame.
#include <cstdint>
#include <vector>

#include "flowscape/core/image.h"
#include "flowscape/geometry/geometry.h"

namespace flowscape {

// A bilinear stencil: four source pixel indices (top-left, top-right, bottom-left, bottom-right)
// and the weights fx, fy of the right and bottom taps.
struct Stencil {
  std::int32_t tap[4];
  float fx, fy;
  int nearest_tap() const { return (fx >= 0.5f) + 2 * (fy >= 0.5f); }
};

// How each destination pixel samples the source. A tap >= 0 is a source pixel; a tap < 0 is
// apron[-1 - tap], a point just off a cube face that is itself sampled from the neighbouring face.
struct Sampling {
  int dst_width = 0, dst_height = 0;
  int src_width = 0, src_height = 0;
  std::vector<Stencil> stencils;  // one per destination pixel
  std::vector<Stencil> apron;
};

// A pixel of the one-pixel apron around a face (integer coordinates -1 or N on one axis), and
// where its direction falls on the neighbouring face.
struct ApronPixel {
  Face face;
  int i, j;
  Face neighbour;
  Vec2 position;  // continuous, on the neighbour
};

// Cube faces -> ERP. Stencils never leave their face: the taps beyond an edge are apron pixels,
// resampled from the neighbouring face along their exact directions, so there is no seam.
struct CubeToErp {
  int face_size = 0, erp_width = 0;
  Sampling sampling;
  std::vector<std::uint8_t> faces;       // per ERP pixel: the Face its direction falls into
  std::vector<ApronPixel> apron_pixels;  // parallel to sampling.apron
};
CubeToErp make_cube_to_erp(int face_size, int erp_height);

// ERP -> cube faces. Taps wrap around horizontally and continue over the poles.
struct ErpToCube {
  int erp_width = 0, face_size = 0;
  Sampling sampling;
  std::vector<std::uint8_t>
      over_pole;  // per destination pixel: bit k set when tap k is over a pole
};
ErpToCube make_erp_to_cube(int erp_height, int face_size);

// Colour (and any smooth quantity): bilinear. Integer types round to nearest.
template <class T>
Image<T> resample_bilinear(const Sampling& sampling, ImageView<const T> src);
// Ids, depth, masks: the nearest source pixel, never blended.
template <class T>
Image<T> resample_nearest(const Sampling& sampling, ImageView<const T> src);

template <class T>
Image<T> resample_bilinear(const Sampling& sampling, const Image<T>& src) {
  return resample_bilinear(sampling, src.view());
}
template <class T>
Image<T> resample_nearest(const Sampling& sampling, const Image<T>& src) {
  return resample_nearest(sampling, src.view());
}

// 3-vectors in each face's camera frame (normals, scene flow) -> the ERP's camera frame (the
// front face's, geometry.h): each face's turned into it, then the nearest source pixel. NaN
// (no vector) stays NaN.
Image<float> cube_to_erp_vectors(const CubeToErp& map, ImageView<const float> cube);

struct FlowInput {
  ImageView<const float> flow;                // 2 channels, u right, v down, pixels
  ImageView<const std::uint16_t> instance{};  // optional: blend only taps of one instance
  ImageView<const std::uint8_t> valid{};      // optional: validity of the source pixels
};
struct FlowOutput {
  Image<float> flow;          // unknown targets hold kUnknownFlow
  Image<std::uint8_t> valid;  // 1 where the nearest source is valid and the target is known
};

// Each face holds pinhole flow on its own image plane; the ERP flow of a pixel is
// ERP(direction of its target) - ERP(pixel), in 360-degree or classic form. The target is the
// bilinear blend of the taps' targets in the face plane (exact for any affine motion of the plane).
FlowOutput cube_to_erp_flow(const CubeToErp& map, const FlowInput& cube, FlowMode mode);
// ERP flow (360-degree or classic, both read the same) -> per-face pinhole flow; the target is
// blended in ERP coordinates (exact for a camera yaw) and projected onto the face plane.
FlowOutput erp_to_cube_flow(const ErpToCube& map, const FlowInput& erp);

}  // namespace flowscape
