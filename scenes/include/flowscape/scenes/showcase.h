#pragma once
// The built-in actor models one at a time on an open square of asphalt in sky light: what the
// gallery (city_preview --actors) shows and what tests check (watertight bodies, boxes).
#include <string>
#include <vector>

#include "flowscape/scenes/scene.h"

namespace flowscape {

// "hatchback", "saloon", "estate", "suv", "pickup", "van", "taxi", "police", "delivery_van",
// "city_bus", "box_truck", "lorry", "motorbike", "bicycle", "man", "woman", "child", "umbrella",
// "jogger"
std::vector<std::string> showcase_models();

struct Showcase {
  Scene scene;                    // the model is actor 0 (instance 1), a rider actor 1
  double length = 0, height = 0;  // of the model's box at time 0
};
// The model `name` (variant 0-2) at the origin facing +x: vehicles standing (their head lamps'
// beams in Scene::lamps), people walking past the origin at time 1 s (a jogger running). Throws
// std::invalid_argument for an unknown name.
Showcase showcase(const std::string& name, int variant);

}  // namespace flowscape
