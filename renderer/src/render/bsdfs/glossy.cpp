// A diffuse base under a clear coat (car paint, plastic): Schlick's Fresnel (f0 0.04) picks the
// coat's rough mirror or the base.
#include "render/bsdf.h"
#include "render/sampling.h"

namespace flowscape {
namespace {

class Glossy final : public Bsdf {
 public:
  Turn interact(const SurfaceEvent& e, PathState& path, ShadowRay& shadow) const override {
    const double fresnel = schlick(-path.dir.dot(e.s.normal), 0.04);
    // At the first surface the base's direct light and albedo are taken whatever the path does
    // next; half the paths then take the coat, half the base.
    if (e.first) first_diffuse_light(e, path.throughput * (1 - fresnel), path, shadow);
    const double coat = e.first ? 0.5 : fresnel;
    const bool base = e.choice.x() >= coat;
    path.throughput *= base ? (1 - fresnel) / (1 - coat) : fresnel / coat;
    if (base) return diffuse_lobe(e, path, shadow);
    begin_specular(e, path);
    return rough_mirror(e, path);
  }
};

}  // namespace

const Bsdf& glossy_bsdf() {
  static const Glossy bsdf;
  return bsdf;
}

}  // namespace flowscape
