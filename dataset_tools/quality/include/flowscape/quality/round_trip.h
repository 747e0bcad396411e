#pragma once
// Forward-backward consistency of ground-truth flow: a pixel p of frame F with forward flow V goes
// to q = p + V(p) in frame F + 1, whose backward flow B brings it back; exact flow returns to p.
#include <cstdint>

#include "flowscape/core/image.h"

namespace flowscape {

struct RoundTrip {
  long both_ways = 0;  // pixels visible both ways: forward valid at p, backward valid at q
  long returned = 0;   // of those, |V(p) + B(q)| within the tolerance
  double share() const { return both_ways ? double(returned) / double(both_ways) : 0; }
};

struct RoundTripImages {
  ImageView<const float> forward;         // 2 channels, frame F -> F + 1
  ImageView<const std::uint8_t> visible;  // 1 where the forward target is visible
  ImageView<const float> backward;        // 2 channels, frame F + 1 -> F
  ImageView<const std::uint8_t> visible_back;
  bool panorama = false;  // ERP: q wraps horizontally, and so does V + B (360-degree or classic)
};

// B is sampled bilinearly at q, the backward mask at q's nearest pixel; targets outside the image
// (vertically, or horizontally off a pinhole image) do not count. Pixel centres at +0.5.
RoundTrip round_trip(const RoundTripImages& images, double tolerance = 0.01);

}  // namespace flowscape
