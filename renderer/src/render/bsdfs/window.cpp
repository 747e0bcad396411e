// A thin pane (a car's window): what it mirrors (both faces' Fresnel reflection, taken whole
// rather than sampled: a window would speckle otherwise), and straight through, tinted, to what
// lies behind: the first surface then. Light scattered in from a dark cabin is too little to
// follow: paths that bounced diffusely before end at the pane.
#include <algorithm>
#include <cmath>

#include "render/bsdf.h"
#include "render/light_sampler.h"
#include "render/sampling.h"

namespace flowscape {
namespace {

// What a vehicle's window mirrors: the sky above, and near the horizon, where buildings and
// traffic across the street hide the sky, the dim radiance of the dome below it (a pane would
// otherwise mirror the horizon's glare at the grazing angles it is seen at from the street).
Rgb mirrored_by_pane(const Lights& lights, const Vec3& dir, bool scattered) {
  const double open = std::clamp(dir.z() / 0.4, 0.0, 1.0);  // sin 24 degrees
  return open * sky_seen(lights, dir, scattered) +
         (1 - open) * lights.environment.ground.cast<double>();
}

class Window final : public Bsdf {
 public:
  Turn interact(const SurfaceEvent& e, PathState& path, ShadowRay&) const override {
    const Surface& s = e.s;
    const double f = schlick(std::abs(path.dir.dot(s.normal)), 0.04), reflected = 2 * f / (1 + f);
    path.light[e.first ? kSpecular : path.layer] +=
        path.throughput.cwiseProduct(
            mirrored_by_pane(e.lights, reflect(path.dir, s.normal), path.scattered)) *
        reflected;
    if (path.layer == kIndirect) return Turn::Ends;
    path.throughput = path.throughput.cwiseProduct(s.albedo) * (1 - reflected);
    path.origin = s.position + e.offset * path.dir;
    return Turn::PassesThrough;
  }
  bool see_through() const override { return true; }
  bool ends_other() const override { return false; }
};

}  // namespace

const Bsdf& window_bsdf() {
  static const Window bsdf;
  return bsdf;
}

}  // namespace flowscape
