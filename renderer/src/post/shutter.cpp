#include "flowscape/renderer/shutter.h"

#include <algorithm>

#include "camera/cube_faces.h"
#include "flowscape/core/profile.h"
#include "flowscape/core/random.h"

namespace flowscape {

Shutter centred_shutter(double time, double angle, double frame_rate) {
  const double open_for = angle / 360 / frame_rate;
  return {time - open_for / 2, time + open_for / 2};
}

RenderOptions shutter_options(const RenderOptions& clean) {
  RenderOptions options = clean;
  options.samples_per_pixel = std::max(1, clean.samples_per_pixel / 2);
  if (clean.indirect_samples > 0)
    options.indirect_samples = std::max(1, clean.indirect_samples / 2);
  options.edge_samples = clean.edge_samples / 2;
  options.seed = derived_seed(clean.seed, 0, 8);
  return options;
}

CubeFrame shutter_cube(Renderer& renderer, int face_size, const Shutter& shutter,
                       const CameraTrack& camera, const RenderOptions& options, bool depth_guide) {
  CubeFrame cube;
  for (Face face : kFaces) {
    const Projection projection = Projection::cube_face(face, face_size);
    on_face(face, [&] {
      {
        const ScopedPhase phase("final pass: path tracing");
        put_face(cube.color, face, renderer.color_layers(projection, shutter, camera, {}, options));
      }
      if (!depth_guide) return;
      const ScopedPhase phase("final pass: depth guide");
      put_face(cube.truth.depth, face, renderer.depth(projection, shutter, camera));
    });
  }
  cube.truth.instance = Image<std::uint16_t>(face_size, 6 * face_size, 1);
  return cube;
}

}  // namespace flowscape
