#pragma once
// Temporal reconstruction: a frame's colour layers averaged with its neighbouring frames' along the
// exact motion, before the denoiser. Each pixel of frame t finds where its surface point is seen in
// frame t + d through the exact flow t -> t + d and its validity (visible there, in view); the
// neighbour's layers are read there bilinearly from the taps that show the same surface (same
// instance, a surface where the centre has one, the same cube face); each layer (direct, indirect,
// specular, other) of a neighbour is then taken only where it agrees with the centre's within the
// noise both carry (A-SVGF's idea of rejecting history whose shading changed: a lamp switched off,
// a moving shadow, a reflection that moved), else dropped. The albedo and normals (the denoiser's
// guides) stay the centre's; the variance becomes that of the mean of what was taken, so the
// denoiser then filters in proportion. docs/renderer.md, "Temporal reconstruction".
#include <cstdint>
#include <vector>

#include "flowscape/renderer/renderer.h"

namespace flowscape {

// One neighbouring frame of the view: its layers and instance ids, and where frame t's pixels are
// seen in it (the flow from frame t's pixel centres, in pixels, and its validity).
struct TemporalNeighbour {
  const ColorLayers* layers;
  ImageView<const std::uint16_t> instance;
  ImageView<const float> flow;
  ImageView<const std::uint8_t> valid;
};

struct TemporalOptions {
  // A neighbour's layer is dropped where its luminance differs from the centre's by more than
  // this many standard deviations of the difference, at the pixel (the centre's variance the
  // 3 x 3 mean around it, the neighbour's as read there) or in the mean of the 3 x 3 pixels
  // around it (where a change too small to see in one noisy pixel shows); where a layer carries
  // no variance (the 'other' layer: sky, emission, fog), by more than relative_tolerance of the
  // larger.
  float sigmas = 2;
  float relative_tolerance = 0.05f;
  bool wraps = false;   // the image wraps around horizontally (the ERP)
  int tile_height = 0;  // > 0: stacked tiles of this height (the cube's faces); taps stay in theirs
};

// Frame t's layers (`centre`, its instance ids `instance`) with the neighbours' averaged in.
ColorLayers temporal_layers(const ColorLayers& centre, ImageView<const std::uint16_t> instance,
                            const std::vector<TemporalNeighbour>& neighbours,
                            const TemporalOptions& options = {});

}  // namespace flowscape
