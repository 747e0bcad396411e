#pragma once
// What the image-quality benches share: a frame of a sequence with its ground truth and converged
// reference colour, the non-sky PSNR of 8-bit sRGB colour against that reference, and their
// comma-separated arguments.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "flowscape/release/adaptive_sampling.h"
#include "flowscape/release/sequence.h"

namespace flowscape {

inline std::vector<std::string> comma_separated(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');) parts.push_back(part);
  return parts;
}

inline double psnr(const Image<float>& image, const Image<float>& reference,
                   const GroundTruth& truth) {
  const std::vector<double> squared = squared_srgb_difference(image, reference);
  double sum = 0;
  long count = 0;
  for (std::size_t i = 0; i < squared.size(); ++i)
    if (truth.semantic.data[i] != std::uint8_t(SemanticClass::Sky)) sum += squared[i], count += 3;
  return 10 * std::log10(255.0 * 255.0 / std::max(sum / count, 1e-12));
}

// Relative MSE of linear colour over the non-sky pixels, sum (c - r)^2 / sum r^2, comparable
// across exposures and times of day; with `clip`, of the colour a camera records at the
// sequence's exposure (clipped to [0, 1]), else of the whole linear range, where the few
// pixels at the edges of lamps tens of times brighter than white dominate.
inline double relative_mse(const Image<float>& image, const Image<float>& reference,
                           const GroundTruth& truth, bool clip) {
  double error = 0, energy = 0;
  const auto value = [clip](float v) { return clip ? std::clamp(double(v), 0.0, 1.0) : double(v); };
  for (std::size_t i = 0; i < truth.semantic.data.size(); ++i) {
    if (truth.semantic.data[i] == std::uint8_t(SemanticClass::Sky)) continue;
    for (int c = 0; c < 3; ++c) {
      const double r = value(reference.data[3 * i + c]), d = value(image.data[3 * i + c]) - r;
      error += d * d, energy += r * r;
    }
  }
  return error / std::max(energy, 1e-30);
}

// One frame of a sequence with its ground truth and converged reference colour.
struct Setup {
  Setup(const SequenceSpec& spec, int frame, int height, int reference_spp)
      : sequence(make_sequence(spec)),
        renderer(sequence.city.scene),
        pair(sequence.frame_pair(frame)),
        erp(Projection::equirectangular(height)),
        truth(renderer.ground_truth(erp, pair)),
        reference(renderer.color(erp, pair, reference_options(frame, reference_spp))) {}
  RenderOptions reference_options(int frame, int spp) const {
    return {spp, ReleaseConfig{}.max_bounces, sequence.color_seed(frame) + 1};
  }
  // The converged reference of flowscape 0.11's path tracer (the dome's full resolution after a
  // diffuse event): how far the averaged sky moves the converged colour.
  Image<float> reference_before_averaged_sky(int frame, int spp) {
    renderer.trace_as({.full_sky_when_scattered = true});
    Image<float> reference = renderer.color(erp, pair, reference_options(frame, spp));
    renderer.trace_as({});
    return reference;
  }
  Sequence sequence;
  Renderer renderer;
  FramePair pair;
  Projection erp;
  GroundTruth truth;
  Image<float> reference;
};

}  // namespace flowscape
