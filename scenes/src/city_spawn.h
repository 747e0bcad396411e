#pragma once
// Internal: where a city's traffic starts (start points, spawning near the ego, parked cars) and
// the search for an ego start its route asks for (EgoRoute): make_city's first half.
#include <functional>
#include <vector>

#include "city_layout.h"
#include "city_models.h"
#include "flowscape/core/random.h"
#include "flowscape/scenes/city.h"
#include "traffic.h"

namespace flowscape {

inline constexpr double kRouteFrame = 2 * kTrafficStep;  // routes are judged 2 x 1/30 s short

// The spots traffic and the ego may start at, spread over the map's lanes.
std::vector<StartPoint> start_points(const Layout& layout);

struct Spawned {
  std::vector<VehicleStart> vehicles;  // the ego first, then the placed ones (ScriptedActor::start)
  std::vector<ActorKind> vehicle_kinds;
  std::vector<WalkerStart> walkers;
  int placed = 0;
};

// Cars parked in the shoulder along the kerb, right of the outer lane of two-way streets (not
// within 12 m of a junction, not on three-lane roads), 40 % of the slots taken, each handed to
// `place` (with the parking stream, which legacy models draw their looks from), their footprints
// among the solids moving actors keep clear of.
void park_cars(const Layout& layout, std::uint64_t seed, City& city,
               const std::function<void(const Pose&, Random&)>& place);

// The traffic of a city with its ego placed as its route asks (EgoRoute), and the random stream
// as that spawn left it (the actors' looks draw from it next).
struct PlacedTraffic {
  StartPoint ego;
  int tries = 0;  // starts tried
  Random random{0};
  Spawned spawned;
  TrafficTracks tracks;
};
PlacedTraffic place_traffic(const Layout& layout, const std::vector<SidewalkLoop>& loops,
                            const std::vector<StartPoint>& points, const CityConfig& config);

}  // namespace flowscape
