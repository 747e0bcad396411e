// A smooth dielectric of index 1.5: reflected or refracted, chosen by its Fresnel reflectance.
#include <cmath>

#include "render/bsdf.h"
#include "render/sampling.h"

namespace flowscape {
namespace {

class Glass final : public Bsdf {
 public:
  Turn interact(const SurfaceEvent& e, PathState& path, ShadowRay&) const override {
    const Surface& s = e.s;
    const double cos_i = -path.dir.dot(s.normal), eta = s.front ? 1 / 1.5 : 1.5;
    begin_specular(e, path);
    if (e.choice.x() < dielectric_fresnel(cos_i, eta)) {
      path.origin = e.above(), path.dir = reflect(path.dir, s.normal);
      return Turn::Reflected;
    }
    const double cos_t = std::sqrt(1 - eta * eta * (1 - cos_i * cos_i));
    path.origin = e.below(),
    path.dir = (eta * path.dir + (eta * cos_i - cos_t) * s.normal).normalized();
    return Turn::Transmitted;
  }
};

}  // namespace

const Bsdf& glass_bsdf() {
  static const Glass bsdf;
  return bsdf;
}

}  // namespace flowscape
