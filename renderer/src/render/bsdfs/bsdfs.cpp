// The table of materials: Material::Kind -> its Bsdf.
#include <array>

#include "render/bsdf.h"

namespace flowscape {

const Bsdf& diffuse_bsdf();
const Bsdf& glossy_bsdf();
const Bsdf& metal_bsdf();
const Bsdf& glass_bsdf();
const Bsdf& emissive_bsdf();
const Bsdf& streak_bsdf();
const Bsdf& window_bsdf();

const Bsdf& bsdf_of(Material::Kind kind) {
  // in Material::Kind's order
  static const std::array<const Bsdf*, 7> table{&diffuse_bsdf(), &glossy_bsdf(),   &metal_bsdf(),
                                                &glass_bsdf(),   &emissive_bsdf(), &streak_bsdf(),
                                                &window_bsdf()};
  return *table.at(std::size_t(kind));
}

}  // namespace flowscape
