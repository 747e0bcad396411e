#include "vehicles.h"

#include "car_parts.h"

namespace flowscape::assets {

namespace {

VehicleModel heavy(Family family, int variant, bool) { return heavy_family(family, variant); }
VehicleModel two_wheeler(Family family, int variant, bool) {
  return two_wheeler_family(family, variant);
}

// The odds of a family's liveries, tried in this order against one uniform draw l: delivery where
// l < delivery, taxi where l < taxi, police where l > police.
struct LiveryOdds {
  double delivery = 0, taxi = 0, police = 1;
};

// Every family: its name, its fine class, the builder of its file (cars.cpp, heavy_vehicles.cpp,
// two_wheelers.cpp), the traffic kind it is drawn for and its share of that kind's vehicles (in
// table order), and its liveries; in Family's order.
struct FamilyRow {
  const char* name;
  SemanticClass cls;
  VehicleModel (*build)(Family family, int variant, bool mirrors);
  ActorKind kind;
  double share = 1;
  LiveryOdds liveries = {};
};
constexpr FamilyRow kFamilyTable[kFamilies] = {
    {"hatchback", SemanticClass::Car, car_family, ActorKind::Car, 0.24},
    {"saloon", SemanticClass::Car, car_family, ActorKind::Car, 0.22, {.taxi = 0.1}},
    {"estate", SemanticClass::Car, car_family, ActorKind::Car, 0.14, {.taxi = 0.1, .police = 0.96}},
    {"suv", SemanticClass::Car, car_family, ActorKind::Car, 0.2, {.police = 0.96}},
    {"pickup", SemanticClass::Car, car_family, ActorKind::Car, 0.08},
    {"van", SemanticClass::Car, car_family, ActorKind::Car, 0.12, {.delivery = 0.3}},
    {"city_bus", SemanticClass::Bus, heavy, ActorKind::Bus},
    {"box_truck", SemanticClass::Truck, heavy, ActorKind::Truck},
    {"lorry", SemanticClass::Truck, heavy, ActorKind::Lorry},
    {"motorbike", SemanticClass::Motorcycle, two_wheeler, ActorKind::Motorbike},
    {"bicycle", SemanticClass::Bicycle, two_wheeler, ActorKind::Bike},
};

}  // namespace

std::string family_name(Family family) { return kFamilyTable[int(family)].name; }

SemanticClass family_class(Family family) { return kFamilyTable[int(family)].cls; }

std::pair<Family, Livery> family_of(ActorKind kind, Random& random) {
  std::vector<int> rows;
  for (int f = 0; f < kFamilies; ++f)
    if (kFamilyTable[f].kind == kind) rows.push_back(f);
  if (rows.empty()) return family_of(ActorKind::Car, random);  // no family of its own: a car
  if (rows.size() == 1) return {Family(rows[0]), Livery::Plain};
  double u = random.uniform();
  std::size_t k = 0;
  while (k + 1 < rows.size() && (u -= kFamilyTable[rows[k]].share) > 0) ++k;
  const FamilyRow& row = kFamilyTable[rows[k]];
  const double l = random.uniform();
  const Livery livery = l < row.liveries.delivery ? Livery::Delivery
                        : l < row.liveries.taxi   ? Livery::Taxi
                        : l > row.liveries.police ? Livery::Police
                                                  : Livery::Plain;
  return {Family(rows[k]), livery};
}

Mesh labelled(Mesh mesh, SemanticClass cls) {
  std::fill(mesh.classes.begin(), mesh.classes.end(), cls);
  return mesh;
}

int add_wheel_meshes(VehicleModel& model, double radius, double width, double rim_share) {
  const SemanticClass cls = family_class(model.family);
  for (int side : {1, -1})
    model.wheels.push_back(
        std::make_shared<const Mesh>(labelled(road_wheel(radius, width, rim_share, side), cls)));
  model.wheel_radius.insert(model.wheel_radius.end(), 2, radius);
  return int(model.wheels.size()) - 2;
}

VehicleModel finish_car(Family family, const BodyShape& shape, double tyre_width) {
  return finish_car(family, shape, tyre_width, vehicle_body(shape));
}

VehicleModel finish_car(Family family, const BodyShape& shape, double tyre_width, Mesh body) {
  VehicleModel model;
  model.family = family;
  model.length = shape.length, model.width = shape.width;
  double top = 0;
  for (double x = -shape.length / 2; x <= shape.length / 2; x += 0.05)
    if (shape.top(x) > top) top = shape.top(x), model.roof_x = x;
  model.height = top + shape.crown, model.roof_z = model.height;
  model.body = std::make_shared<const Mesh>(labelled(std::move(body), family_class(family)));
  const int left = add_wheel_meshes(model, shape.wheel_radius, tyre_width, 0.62);
  const double track = shape.width / 2 - tyre_width / 2 - 0.04;
  for (double axle : shape.axles)
    for (int side : {1, -1})
      model.mounts.push_back({V3(axle, side * track, shape.wheel_radius), axle > 0, false,
                              side > 0 ? left : left + 1});
  model.wheelbase = shape.axles.back() - shape.axles.front();
  return model;
}

VehicleModel build_vehicle(Family family, int variant, bool mirrors) {
  return kFamilyTable[int(family)].build(family, variant, mirrors);
}

Mesh livery_roof(Livery livery) {
  Mesh mesh;
  using C = SemanticClass;
  if (livery == Livery::Taxi) {
    add_rounded_box(mesh, Pose(Eigen::Translation3d(0, 0, 0.09)), V3(0.12, 0.3, 0.08), 0.03, C::Car,
                    kLivery, 2);
  } else if (livery == Livery::Police) {
    add_rounded_box(mesh, Pose(Eigen::Translation3d(0, 0, 0.06)), V3(0.14, 0.55, 0.05), 0.03,
                    C::Car, kTrim, 2);
    for (double side : {-1.0, 1.0})
      add_rounded_box(mesh, Pose(Eigen::Translation3d(0, side * 0.3, 0.11)), V3(0.1, 0.22, 0.04),
                      0.02, C::Car, side > 0 ? kIndicator : kLivery, 2);
  }
  return mesh;
}

}  // namespace flowscape::assets
