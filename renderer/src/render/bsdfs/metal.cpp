// A conductor: a rough mirror tinted by its albedo.
#include "render/bsdf.h"

namespace flowscape {
namespace {

class Metal final : public Bsdf {
 public:
  Turn interact(const SurfaceEvent& e, PathState& path, ShadowRay&) const override {
    begin_specular(e, path);
    path.throughput = path.throughput.cwiseProduct(e.s.albedo);
    return rough_mirror(e, path);
  }
};

}  // namespace

const Bsdf& metal_bsdf() {
  static const Metal bsdf;
  return bsdf;
}

}  // namespace flowscape
