#pragma once
// Internal: a city's actors assembled from its placed traffic (city_spawn.h): the user's models,
// flowscape 0.9's box actors, the detailed families with riders, parked cars and the ego vehicle,
// the scripted actors and the head lamps; make_city's second half.
#include <map>
#include <vector>

#include "city_models.h"
#include "city_spawn.h"
#include "standing.h"

namespace flowscape {

// The user's models by actor kind (CityConfig::models), loaded into the scene.
std::map<ActorKind, Mesh> user_models(const CityConfig& config, Scene& scene);
// The user's model of a kind, or null (the built-in one).
const Mesh* user_model_of(const std::map<ActorKind, Mesh>& models, ActorKind kind);

// flowscape 0.9's actors, in its order and from its random stream.
void add_legacy_actors(const PlacedTraffic& traffic, const std::map<ActorKind, Mesh>& models,
                       Random& random, City& city);
// The detailed actors: traffic (two-wheelers with their riders), walkers (one in eight of those in
// groups a child), the parked cars and the ego vehicle, instances in that order.
void add_detailed_actors(const PlacedTraffic& traffic, const std::map<ActorKind, Mesh>& models,
                         const std::vector<Pose>& parked, ActorLibrary& library, City& city);
// The people standing (place_standing), after the actors above: legacy boxes from `random`, or
// detailed people (standing still, their weight shifting, their heads turning).
void add_legacy_standing(const std::vector<StandingPerson>& people,
                         const std::map<ActorKind, Mesh>& models, Random& random, City& city);
void add_standing(const std::vector<StandingPerson>& people,
                  const std::map<ActorKind, Mesh>& models, ActorLibrary& library, City& city);
// The actors scripted by waypoints (CityConfig::scripted), after all others, each with its rider if
// it has one.
void add_scripted_actors(const std::map<ActorKind, Mesh>& models, ActorLibrary& library,
                         City& city);
// The head lamps of every vehicle but the parked ones (walkers and riders have none).
void add_head_lamps(const ActorLibrary& library, City& city);

}  // namespace flowscape
