#pragma once
// What the image-quality benches share: a frame of a sequence with its ground truth and converged
// reference colour, and the non-sky PSNR of 8-bit sRGB colour against that reference.
#include <algorithm>
#include <cmath>

#include "flowscape/formats/srgb.h"
#include "flowscape/release/sequence.h"

namespace flowscape {

inline double psnr(const Image<float>& image, const Image<float>& reference,
                   const GroundTruth& truth) {
  const Image<std::uint8_t> a = linear_to_srgb8(image.view()),
                            b = linear_to_srgb8(reference.view());
  double squared = 0;
  long count = 0;
  for (std::size_t i = 0; i < truth.semantic.data.size(); ++i) {
    if (truth.semantic.data[i] == std::uint8_t(SemanticClass::Sky)) continue;
    for (int c = 0; c < 3; ++c) {
      const double d = double(a.data[3 * i + c]) - b.data[3 * i + c];
      squared += d * d, ++count;
    }
  }
  return 10 * std::log10(255.0 * 255.0 / std::max(squared / count, 1e-12));
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
    RenderOptions options = reference_options(frame, spp);
    options.full_sky_when_scattered = true;
    return renderer.color(erp, pair, options);
  }
  Sequence sequence;
  Renderer renderer;
  FramePair pair;
  Projection erp;
  GroundTruth truth;
  Image<float> reference;
};

}  // namespace flowscape
