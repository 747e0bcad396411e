#pragma once
// What the image-quality benches share: a frame of a sequence with its ground truth and converged
// reference colour, and the non-sky PSNR of 8-bit sRGB colour against that reference.
#include <algorithm>
#include <cmath>
#include <vector>

#include "flowscape/release/adaptive_sampling.h"
#include "flowscape/release/sequence.h"

namespace flowscape {

inline double psnr(const Image<float>& image, const Image<float>& reference,
                   const GroundTruth& truth) {
  const std::vector<double> squared = squared_srgb_difference(image, reference);
  double sum = 0;
  long count = 0;
  for (std::size_t i = 0; i < squared.size(); ++i)
    if (truth.semantic.data[i] != std::uint8_t(SemanticClass::Sky)) sum += squared[i], count += 3;
  return 10 * std::log10(255.0 * 255.0 / std::max(sum / count, 1e-12));
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
