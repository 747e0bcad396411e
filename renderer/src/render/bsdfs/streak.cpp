// A rain streak: glows with its opacity and lets the rest of the light through.
#include "render/bsdf.h"

namespace flowscape {
namespace {

class Streak final : public Bsdf {
 public:
  Turn interact(const SurfaceEvent& e, PathState& path, ShadowRay&) const override {
    const Material& m = e.material();
    path.light[path.layer] += path.throughput.cwiseProduct(m.emission.cast<double>()) * m.opacity;
    path.throughput *= 1 - m.opacity;
    path.origin = e.s.position + e.offset * path.dir;
    return Turn::PassesThrough;
  }
  bool see_through() const override { return true; }
  bool ends_other() const override { return false; }
};

}  // namespace

const Bsdf& streak_bsdf() {
  static const Streak bsdf;
  return bsdf;
}

}  // namespace flowscape
