// A glow-only body (a lamp's, a lit window): seen directly and in mirrors, reflecting nothing. A
// lamp's light on surfaces comes from its point source (Scene::lamps), as the sun's does.
#include "render/bsdf.h"

namespace flowscape {
namespace {

class Emissive final : public Bsdf {
 public:
  Turn interact(const SurfaceEvent& e, PathState& path, ShadowRay&) const override {
    const Material& m = e.material();
    const Rgb glow = m.night_pattern ? Rgb(m.emission.cast<double>().cwiseProduct(e.s.albedo))
                                     : Rgb(m.emission.cast<double>());
    if (path.sun_visible || !m.glow_only)
      path.light[path.layer] += path.throughput.cwiseProduct(glow);
    return Turn::Ends;
  }
  bool ends_other() const override { return false; }
};

}  // namespace

const Bsdf& emissive_bsdf() {
  static const Emissive bsdf;
  return bsdf;
}

}  // namespace flowscape
