// Lambertian reflection.
#include "render/bsdf.h"

namespace flowscape {
namespace {

class Diffuse final : public Bsdf {
 public:
  Turn interact(const SurfaceEvent& e, PathState& path, ShadowRay& shadow) const override {
    if (e.first) first_diffuse_light(e, path.throughput, path, shadow);
    return diffuse_lobe(e, path, shadow);
  }
};

}  // namespace

const Bsdf& diffuse_bsdf() {
  static const Diffuse bsdf;
  return bsdf;
}

}  // namespace flowscape
