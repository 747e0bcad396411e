#pragma once
// Internal: the static world of a city map (roads, markings, sidewalks, blocks, buildings,
// vegetation, street furniture, terrain, water), appended to a Scene.
#include <array>
#include <vector>

#include "city_layout.h"

namespace flowscape {

// Builds scene.world and its materials; returns the footprints of the solid things actors avoid.
std::vector<std::array<Eigen::Vector2d, 4>> build_world(const Layout& layout, std::uint64_t seed,
                                                        Scene& scene);

}  // namespace flowscape
