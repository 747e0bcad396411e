#pragma once
// Internal: the built-in vehicle families (the project's own procedural models, CC BY 4.0 with a
// release): each a function of a variant number that varies its proportions and trim. A model is
// built once per scene and shared by every actor showing it (one BVH per mesh); the actor brings
// its own paint, plate and livery through the material slots (vehicle_body.h's Slot).
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "flowscape/core/random.h"
#include "flowscape/scenes/city.h"
#include "vehicle_body.h"

namespace flowscape::assets {

// A new family: its entry here, its row in vehicles.cpp's kFamilyTable (name, class, builder,
// the traffic kind it is drawn for and its share of it, its liveries), and its builder.
enum class Family : std::uint8_t {
  Hatchback,
  Saloon,
  Estate,
  Suv,
  Pickup,
  Van,
  CityBus,
  BoxTruck,
  Lorry,  // an articulated lorry: tractor and semi-trailer
  Motorbike,
  Bicycle,
};
inline constexpr int kFamilies = 11, kVariants = 3;
std::string family_name(Family family);
SemanticClass family_class(Family family);  // the fine class (Car, Truck, Bus, Motorcycle, ...)

// Liveries painted over a family's own colours: taxis (saloons, estates), police (estates,
// SUVs), delivery vans.
enum class Livery : std::uint8_t { Plain, Taxi, Police, Delivery };
// The family a vehicle of traffic kind `kind` is drawn as (by the families' shares of that kind)
// and its livery (by the family's odds), from `random` (no draw for a kind of one family).
std::pair<Family, Livery> family_of(ActorKind kind, Random& random);

struct WheelMount {
  V3 hub;        // in the vehicle's frame (the trailer's for trailer wheels)
  bool steers;   // turns with the steering
  bool trailer;  // on the semi-trailer
  int mesh;      // index into VehicleModel::wheels
};

// A built vehicle: its meshes and where its moving parts go.
struct VehicleModel {
  Family family;
  double length = 0, width = 0, height = 0;  // of the whole vehicle (lorry: tractor + trailer)
  double wheelbase = 0;                      // first to last axle of the (tractor) body
  std::shared_ptr<const Mesh> body;  // glass included (the renderer's BVH keeps its panes apart)
  std::vector<std::shared_ptr<const Mesh>> wheels;  // [left, right] meshes per wheel size
  std::vector<double> wheel_radius;                 // per wheel mesh
  std::vector<WheelMount> mounts;
  // Lorry: the trailer's mesh (its frame: x forward, the kingpin at its origin), where the kingpin
  // sits on the tractor (vehicle frame), and the distance from the kingpin to the trailer's axles.
  std::shared_ptr<const Mesh> trailer;
  V3 kingpin = V3::Zero();
  double trailer_axles = 0;
  // Two-wheelers: the cranks (bicycle) turning with the pedals, about the bottom bracket.
  std::shared_ptr<const Mesh> cranks;
  V3 bottom_bracket = V3::Zero();
  double crank_length = 0.17, gear = 2.6;  // wheel turns per crank turn
  // where a rider sits: hips, hands, feet (pegs for motorbikes), in the vehicle's frame
  V3 saddle = V3::Zero(), grips = V3::Zero(), pegs = V3::Zero();
  double grip_spread = 0.3, peg_spread = 0.3;
  // the roof's height and length: where a taxi sign or a police light bar goes
  double roof_x = 0, roof_z = 0;
};

// `mirrors`: false leaves a car's wing mirrors off (an ego vehicle with cameras where they are).
VehicleModel build_vehicle(Family family, int variant, bool mirrors = true);
// A livery's extra geometry on the roof (taxi sign, police light bar), in slots; empty mesh for
// none.
Mesh livery_roof(Livery livery);

}  // namespace flowscape::assets
