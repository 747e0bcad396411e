#pragma once
// Internal: the built-in actor models (cars, trucks, buses, bikes, pedestrians) with moving parts:
// wheels that roll with the distance travelled and limbs that swing with the walking cycle.
#include <memory>

#include "flowscape/core/random.h"
#include "flowscape/scenes/city.h"
#include "traffic.h"

namespace flowscape {

struct KindSize {
  double length, width;
};
KindSize kind_size(ActorKind kind);

// An actor following `track`; `user_model` (if not null) replaces the built-in body.
Actor make_actor(ActorKind kind, std::uint16_t instance, std::shared_ptr<const Track> track,
                 const Mesh* user_model, Random& random, Scene& scene);
// A vehicle standing at `pose` for good, baked into the static world (class Vehicles, instance 0).
void add_parked_vehicle(ActorKind kind, const Pose& pose, const Mesh* user_model, Random& random,
                        Scene& scene);

}  // namespace flowscape
