#include "flowscape/renderer/shutter.h"

#include <cmath>
#include <limits>

#include "flowscape/core/random.h"
#include "flowscape/stitcher/geometry.h"

namespace flowscape {
namespace {

void accumulate(Image<float>& sum, const Image<float>& add, float weight) {
  for (std::size_t i = 0; i < sum.data.size(); ++i) sum.data[i] += weight * add.data[i];
}

void put_face(Image<float>& stacked, Face face, const Image<float>& image) {
  if (stacked.data.empty()) stacked = Image<float>(image.width, 6 * image.width, image.channels);
  std::copy(image.data.begin(), image.data.end(), face_view(stacked.view(), face).data);
}

}  // namespace

Shutter centred_shutter(double time, double angle) {
  const double open_for = angle / 360 / kFrameRate;
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
                           const CameraTrack& camera, const RenderOptions& options) {
  const int steps = shutter_steps(options);
  RenderOptions step_options = options;
  step_options.samples_per_pixel = options.samples_per_pixel / steps;
  if (options.indirect_samples > 0)
    step_options.indirect_samples = options.indirect_samples / steps;
  ColorLayers sum;
  const float weight = 1.0f / float(steps);
  int k = 0;
  for (double time : shutter_times(shutter, steps)) {
    step_options.seed = derived_seed(options.seed, std::uint64_t(k++), 7);
    const ColorLayers step =
        renderer.color_layers(projection, {time, time, camera(time), camera(time)}, step_options);
    if (sum.direct.data.empty()) {
      sum = step;
      for (Image<float>* layer :
           {&sum.direct, &sum.indirect, &sum.specular, &sum.other, &sum.albedo, &sum.variance})
        for (float& value : layer->data) value *= layer == &sum.variance ? weight * weight : weight;
      continue;
    }
    accumulate(sum.direct, step.direct, weight), accumulate(sum.indirect, step.indirect, weight);
    accumulate(sum.specular, step.specular, weight), accumulate(sum.other, step.other, weight);
    accumulate(sum.albedo, step.albedo, weight), accumulate(sum.normal, step.normal, 1);
    accumulate(sum.variance, step.variance, weight * weight);  // of a mean of independent means
  }
  return sum;
}

Image<float> shutter_depth(Renderer& renderer, const Projection& projection, const Shutter& shutter,
                           const CameraTrack& camera, int steps) {
  Image<float> sum(projection.width, projection.height, 1), count(sum.width, sum.height, 1);
  for (double time : shutter_times(shutter, steps)) {
    const GroundTruth truth =
        renderer.ground_truth(projection, FramePair{time, time, camera(time), camera(time)});
    for (std::size_t i = 0; i < sum.data.size(); ++i)
      if (std::isfinite(truth.depth.data[i])) sum.data[i] += truth.depth.data[i], ++count.data[i];
  }
  for (std::size_t i = 0; i < sum.data.size(); ++i)
    sum.data[i] =
        count.data[i] > 0 ? sum.data[i] / count.data[i] : std::numeric_limits<float>::infinity();
  return sum;
}

CubeFrame shutter_cube(Renderer& renderer, int face_size, const Shutter& shutter,
                       const CameraTrack& camera, const RenderOptions& options) {
  CubeFrame cube;
  ColorLayers& c = cube.color;
  for (Face face : kFaces) {
    const Projection projection = Projection::cube_face(face, face_size);
    const ColorLayers layers = shutter_layers(renderer, projection, shutter, camera, options);
    put_face(c.direct, face, layers.direct), put_face(c.indirect, face, layers.indirect);
    put_face(c.specular, face, layers.specular), put_face(c.other, face, layers.other);
    put_face(c.albedo, face, layers.albedo), put_face(c.normal, face, layers.normal);
    put_face(c.variance, face, layers.variance);
    put_face(cube.truth.depth, face,
             shutter_depth(renderer, projection, shutter, camera, shutter_steps(options)));
  }
  cube.truth.instance = Image<std::uint16_t>(face_size, 6 * face_size, 1);
  return cube;
}

}  // namespace flowscape
