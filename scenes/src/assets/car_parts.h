#pragma once
// Internal to the vehicle families: what their files share.
#include "flowscape/core/random.h"
#include "flowscape/scenes/shapes.h"
#include "vehicles.h"

namespace flowscape::assets {

// The mesh with every triangle of class `cls`.
Mesh labelled(Mesh mesh, SemanticClass cls);
// A model of a body with road wheels at its axles (front axle steering), tyres `tyre_width` wide.
VehicleModel finish_car(Family family, const BodyShape& shape, double tyre_width);
VehicleModel finish_car(Family family, const BodyShape& shape, double tyre_width, Mesh body);
// Adds a left and a right wheel mesh of this size; returns the index of the left one.
int add_wheel_meshes(VehicleModel& model, double radius, double width, double rim_share);

VehicleModel car_family(Family family, int variant, bool mirrors);  // cars.cpp
VehicleModel heavy_family(Family family, int variant);              // heavy_vehicles.cpp
VehicleModel two_wheeler_family(Family family, int variant);        // two_wheelers.cpp

}  // namespace flowscape::assets
