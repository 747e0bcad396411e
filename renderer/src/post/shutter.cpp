#include "flowscape/renderer/shutter.h"

#include <array>
#include <cmath>
#include <limits>

#include "camera/cube_faces.h"
#include "flowscape/core/profile.h"
#include "flowscape/core/random.h"

namespace flowscape {
namespace {

void accumulate(Image<float>& sum, const Image<float>& add, float weight) {
  for (std::size_t i = 0; i < sum.data.size(); ++i) sum.data[i] += weight * add.data[i];
}

// sum += weight x step, the normals summed, the variances weight^2 x (of a mean of independent
// means); an empty sum takes the step.
void add_step(ColorLayers& sum, ColorLayers step, float weight) {
  const bool first = sum.direct.data.empty();
  for (auto [to, from] : {std::pair{&sum.direct, &step.direct},
                          {&sum.indirect, &step.indirect},
                          {&sum.specular, &step.specular},
                          {&sum.other, &step.other},
                          {&sum.albedo, &step.albedo}}) {
    if (first) *to = Image<float>(from->width, from->height, from->channels);
    accumulate(*to, *from, weight);
  }
  if (first)
    sum.normal = Image<float>(step.normal.width, step.normal.height, 3),
    sum.variance = Image<float>(step.variance.width, step.variance.height, 3);
  accumulate(sum.normal, step.normal, 1), accumulate(sum.variance, step.variance, weight * weight);
}

// One step's colour layers and its depth guide, each timed as a phase of the final pass.
ColorLayers step_layers(Renderer& renderer, const Projection& projection, double time,
                        const CameraTrack& camera, const Readout& readout,
                        const RenderOptions& step) {
  const ScopedPhase phase("final pass: path tracing");
  return renderer.color_layers(projection, time, camera, readout, step);
}
Image<float> step_depth(Renderer& renderer, const Projection& projection, double time,
                        const CameraTrack& camera, const Readout& readout) {
  const ScopedPhase phase("final pass: depth guide");
  return renderer.depth(projection, time, camera, readout);
}

// Calls step(time, its options, its weight) for each step of the shutter.
template <class Step>
void for_each_step(const Shutter& shutter, const RenderOptions& options, Step&& step) {
  const int steps = shutter_steps(options);
  RenderOptions step_options = options;
  step_options.samples_per_pixel = options.samples_per_pixel / steps;
  if (options.indirect_samples > 0)
    step_options.indirect_samples = options.indirect_samples / steps;
  int k = 0;
  for (double time : shutter_times(shutter, steps)) {
    step_options.seed = derived_seed(options.seed, std::uint64_t(k++), 7);
    step(time, step_options, 1.0f / float(steps));
  }
}

// The middle times of the shutter's first and last thirds.
std::array<double, 2> outer_third_times(const Shutter& shutter) {
  const double sixth = (shutter.close - shutter.open) / 6;
  return {shutter.open + sixth, shutter.close - sixth};
}

// Calls step(time, its options) for the outer thirds of the shutter, with a quarter of `options`'
// samples each (shutter_layers with a centre).
template <class Step>
void for_each_outer_third(const Shutter& shutter, const RenderOptions& options, Step&& step) {
  RenderOptions outer = options;
  outer.samples_per_pixel = std::max(1, options.samples_per_pixel / 4);
  if (options.indirect_samples > 0)
    outer.indirect_samples = std::max(1, options.indirect_samples / 4);
  const std::array<double, 2> times = outer_third_times(shutter);
  for (int k = 0; k < 2; ++k) {
    outer.seed = derived_seed(options.seed, std::uint64_t(k), 8);
    step(times[std::size_t(k)], outer);
  }
}

// The depth of a pixel's centre ray summed where finite, and how often it was.
struct DepthSum {
  Image<float> sum, count;
  void add(const Image<float>& depth) {
    if (sum.data.empty())
      sum = Image<float>(depth.width, depth.height, 1),
      count = Image<float>(depth.width, depth.height, 1);
    for (std::size_t i = 0; i < sum.data.size(); ++i)
      if (std::isfinite(depth.data[i])) sum.data[i] += depth.data[i], ++count.data[i];
  }
  Image<float> mean() const {
    Image<float> out = sum;
    for (std::size_t i = 0; i < out.data.size(); ++i)
      out.data[i] =
          count.data[i] > 0 ? sum.data[i] / count.data[i] : std::numeric_limits<float>::infinity();
    return out;
  }
};

}  // namespace

Shutter centred_shutter(double time, double angle, double frame_rate) {
  const double open_for = angle / 360 / frame_rate;
  return {time - open_for / 2, time + open_for / 2};
}

int shutter_steps(const RenderOptions& options) {
  for (int steps = kMaxShutterSteps; steps > 1; --steps) {
    const bool some_indirect =
        options.indirect_samples > 0 && options.indirect_samples < options.samples_per_pixel;
    if (options.samples_per_pixel % steps == 0 &&
        (!some_indirect || options.indirect_samples % steps == 0))
      return steps;
  }
  return 1;
}

std::vector<double> shutter_times(const Shutter& shutter, int steps) {
  std::vector<double> times;
  for (int k = 0; k < steps; ++k)
    times.push_back(shutter.open + (k + 0.5) / steps * (shutter.close - shutter.open));
  return times;
}

ColorLayers shutter_layers(Renderer& renderer, const Projection& projection, const Shutter& shutter,
                           const CameraTrack& camera, const RenderOptions& options,
                           const Readout& readout) {
  ColorLayers sum;
  for_each_step(shutter, options, [&](double time, const RenderOptions& step, float weight) {
    add_step(sum, step_layers(renderer, projection, time, camera, readout, step), weight);
  });
  return sum;
}

ColorLayers shutter_layers(Renderer& renderer, const Projection& projection, const Shutter& shutter,
                           const CameraTrack& camera, const RenderOptions& options,
                           const Readout& readout, const ColorLayers& centre) {
  ColorLayers sum;
  add_step(sum, centre, 1.0f / 3);
  for_each_outer_third(shutter, options, [&](double time, const RenderOptions& outer) {
    add_step(sum, step_layers(renderer, projection, time, camera, readout, outer), 1.0f / 3);
  });
  return sum;
}

Image<float> shutter_depth(Renderer& renderer, const Projection& projection, const Shutter& shutter,
                           const CameraTrack& camera, const Readout& readout,
                           const Image<float>& centre) {
  DepthSum depth;
  depth.add(centre);
  for (double time : outer_third_times(shutter))
    depth.add(step_depth(renderer, projection, time, camera, readout));
  return depth.mean();
}

CubeFrame shutter_cube(Renderer& renderer, int face_size, const Shutter& shutter,
                       const CameraTrack& camera, const RenderOptions& options, bool depth_guide,
                       const CubeFrame* centre) {
  // step by step, every face at each (the scene posed once per step)
  std::array<ColorLayers, 6> faces;
  std::array<DepthSum, 6> depths;
  const auto trace_step = [&](double time, const RenderOptions& step, float weight) {
    for (Face face : kFaces) {
      const Projection projection = Projection::cube_face(face, face_size);
      const int f = int(face);
      on_face(face, [&] {
        add_step(faces[f], step_layers(renderer, projection, time, camera, {}, step), weight);
        if (depth_guide) depths[f].add(step_depth(renderer, projection, time, camera, {}));
      });
    }
  };
  if (centre) {
    for (Face face : kFaces) {
      add_step(faces[int(face)], face_of(centre->color, face), 1.0f / 3);
      if (depth_guide) depths[int(face)].add(face_of(centre->truth.depth, face));
    }
    for_each_outer_third(shutter, options, [&](double time, const RenderOptions& outer) {
      trace_step(time, outer, 1.0f / 3);
    });
  } else {
    for_each_step(shutter, options, trace_step);
  }
  CubeFrame cube;
  for (Face face : kFaces) {
    put_face(cube.color, face, faces[int(face)]);
    if (depth_guide) put_face(cube.truth.depth, face, depths[int(face)].mean());
  }
  cube.truth.instance = Image<std::uint16_t>(face_size, 6 * face_size, 1);
  return cube;
}

}  // namespace flowscape
