// The car-sized families: hatchback, saloon, estate, SUV, pickup and van. Profiles are given over
// x / (length / 2) from the tail (-1) to the nose (+1), heights in metres.
#include "car_parts.h"

namespace flowscape::assets {
namespace {

// What varies between variants of a family: size, height and the wheel.
struct Proportions {
  double length, width, height_scale, wheel_radius;
};

Proportions proportions(Family family, int variant, double length, double width, double wheel) {
  Random random(mix_bits(std::uint64_t(family) * 131 + std::uint64_t(variant) + 7));
  return {length * random.uniform(0.96, 1.04), width * random.uniform(0.98, 1.02),
          random.uniform(0.97, 1.03), wheel * random.uniform(0.97, 1.05)};
}

// Front and rear faces of a car: lamps, grille, intake, plates, indicators.
void car_faces(BodyShape& s, double lamp_z, double tail_z, double grille_z, double plate_z) {
  const double b = s.width / 2;
  for (double side : {-1.0, 1.0}) {
    s.front.push_back({side * (b - 0.24), lamp_z, 0.19, 0.065, kHeadLamp});
    s.front.push_back({side * (b - 0.1), lamp_z - 0.1, 0.05, 0.025, kIndicator});
    s.rear.push_back({side * (b - 0.2), tail_z, 0.17, 0.07, kTailLamp});
  }
  s.front.push_back({0, grille_z, 0.34, 0.075, kGrille});
  s.front.push_back({0, grille_z - 0.26, 0.5, 0.06, kGrille});
  s.front.push_back({0, plate_z, 0.26, 0.055, kPlate});
  s.rear.push_back({0, plate_z + 0.1, 0.26, 0.055, kPlate});
}

BodyShape car_shape(const Proportions& p, std::initializer_list<V2> top, std::initializer_list<V2> belt,
                    double clearance, double front_overhang, double rear_overhang) {
  BodyShape s;
  s.length = p.length, s.width = p.width;
  const double a = p.length / 2;
  s.top = Curve(top).scaled(a, p.height_scale);
  s.belt = Curve(belt).scaled(a, p.height_scale);
  s.bottom = Curve({{-1, clearance + 0.18}, {-0.92, clearance}, {0.9, clearance}, {1, clearance + 0.15}})
                 .scaled(a, 1);
  s.wheel_radius = p.wheel_radius;
  s.axles = {-(a - rear_overhang), a - front_overhang};
  return s;
}

// x positions over the half length `a` given as shares of it.
double at(const BodyShape& s, double share) { return share * s.length / 2; }

VehicleModel hatchback(int variant, bool mirrors) {
  const Proportions p = proportions(Family::Hatchback, variant, 4.05, 1.76, 0.31);
  BodyShape s = car_shape(p,
                          {{-1, 0.9}, {-0.985, 1.02}, {-0.95, 1.2}, {-0.88, 1.36}, {-0.78, 1.43},
                           {-0.4, 1.46}, {-0.02, 1.45}, {0.1, 1.4}, {0.25, 1.22}, {0.42, 1.0},
                           {0.55, 0.95}, {0.8, 0.89}, {0.95, 0.82}, {1, 0.7}},
                          {{-1, 0.98}, {-0.5, 0.96}, {0.45, 0.93}, {1, 0.9}}, 0.17, 0.8, 0.6);
  Glazing& g = s.glazing;
  g.windscreen_front = at(s, 0.42), g.windscreen_back = at(s, 0.02);
  g.rear_front = at(s, -0.8), g.rear_back = at(s, -0.975);
  g.side_front = at(s, 0.42), g.side_back = at(s, -0.84);
  g.pillars = {{at(s, -0.1), at(s, -0.03)}, {at(s, -0.86), at(s, -0.66)}};
  car_faces(s, 0.8, 1.0, 0.66, 0.5);
  s.seams = {at(s, -0.06)};
  s.handles = {at(s, -0.14)};
  s.mirrors = mirrors;
  return finish_car(Family::Hatchback, s, 0.2);
}

VehicleModel saloon(int variant, bool mirrors) {
  const Proportions p = proportions(Family::Saloon, variant, 4.75, 1.82, 0.32);
  BodyShape s = car_shape(p,
                          {{-1, 0.95}, {-0.98, 1.02}, {-0.85, 1.06}, {-0.62, 1.1}, {-0.48, 1.25},
                           {-0.32, 1.4}, {-0.2, 1.44}, {0.05, 1.44}, {0.15, 1.4}, {0.28, 1.22},
                           {0.4, 1.02}, {0.55, 0.96}, {0.85, 0.88}, {0.97, 0.8}, {1, 0.68}},
                          {{-1, 1.0}, {-0.6, 0.99}, {0.4, 0.95}, {1, 0.9}}, 0.15, 0.95, 1.0);
  Glazing& g = s.glazing;
  g.windscreen_front = at(s, 0.4), g.windscreen_back = at(s, 0.05);
  g.rear_front = at(s, -0.22), g.rear_back = at(s, -0.6);
  g.side_front = at(s, 0.39), g.side_back = at(s, -0.56);
  g.pillars = {{at(s, -0.11), at(s, -0.05)}, {at(s, -0.56), at(s, -0.46)}};
  car_faces(s, 0.78, 0.98, 0.65, 0.5);
  s.seams = {at(s, -0.08), at(s, -0.5)};
  s.handles = {at(s, -0.16), at(s, -0.58)};
  s.mirrors = mirrors;
  return finish_car(Family::Saloon, s, 0.19);
}

VehicleModel estate(int variant, bool mirrors) {
  const Proportions p = proportions(Family::Estate, variant, 4.8, 1.83, 0.32);
  BodyShape s = car_shape(p,
                          {{-1, 0.95}, {-0.985, 1.1}, {-0.96, 1.35}, {-0.9, 1.44}, {-0.2, 1.47},
                           {0.05, 1.46}, {0.15, 1.41}, {0.28, 1.22}, {0.4, 1.02}, {0.55, 0.96},
                           {0.85, 0.88}, {0.97, 0.8}, {1, 0.68}},
                          {{-1, 1.0}, {-0.6, 0.99}, {0.4, 0.95}, {1, 0.9}}, 0.16, 0.95, 1.0);
  Glazing& g = s.glazing;
  g.windscreen_front = at(s, 0.4), g.windscreen_back = at(s, 0.05);
  g.rear_front = at(s, -0.9), g.rear_back = at(s, -0.99);
  g.side_front = at(s, 0.39), g.side_back = at(s, -0.93);
  g.pillars = {{at(s, -0.11), at(s, -0.05)}, {at(s, -0.56), at(s, -0.5)}, {at(s, -0.94), at(s, -0.86)}};
  car_faces(s, 0.78, 1.02, 0.65, 0.5);
  s.seams = {at(s, -0.08), at(s, -0.53)};
  s.handles = {at(s, -0.16), at(s, -0.6)};
  s.mirrors = mirrors;
  return finish_car(Family::Estate, s, 0.19);
}

VehicleModel suv(int variant, bool mirrors) {
  const Proportions p = proportions(Family::Suv, variant, 4.6, 1.9, 0.36);
  BodyShape s = car_shape(p,
                          {{-1, 1.05}, {-0.985, 1.25}, {-0.95, 1.55}, {-0.88, 1.66}, {-0.1, 1.7},
                           {0.05, 1.68}, {0.15, 1.6}, {0.38, 1.2}, {0.55, 1.12}, {0.9, 1.05},
                           {1, 0.88}},
                          {{-1, 1.15}, {0.4, 1.1}, {1, 1.05}}, 0.24, 0.9, 0.85);
  s.plan_exponent = 7, s.trim_height = 0.22, s.sill_radius = 0.1;
  Glazing& g = s.glazing;
  g.windscreen_front = at(s, 0.38), g.windscreen_back = at(s, 0.05);
  g.rear_front = at(s, -0.88), g.rear_back = at(s, -0.985);
  g.side_front = at(s, 0.37), g.side_back = at(s, -0.9);
  g.pillars = {{at(s, -0.12), at(s, -0.05)}, {at(s, -0.58), at(s, -0.52)}, {at(s, -0.91), at(s, -0.8)}};
  car_faces(s, 0.95, 1.2, 0.8, 0.62);
  s.seams = {at(s, -0.08), at(s, -0.55)};
  s.handles = {at(s, -0.17), at(s, -0.62)};
  s.mirrors = mirrors;
  return finish_car(Family::Suv, s, 0.24);
}

VehicleModel pickup(int variant, bool mirrors) {
  const Proportions p = proportions(Family::Pickup, variant, 5.3, 1.9, 0.37);
  BodyShape s = car_shape(p,
                          {{-1, 1.08}, {-0.99, 1.13}, {-0.34, 1.14}, {-0.3, 1.5}, {-0.27, 1.74},
                           {0.0, 1.79}, {0.08, 1.75}, {0.3, 1.22}, {0.45, 1.13}, {0.9, 1.08},
                           {1, 0.9}},
                          {{-1, 1.12}, {1, 1.08}}, 0.26, 0.95, 1.2);
  s.plan_exponent = 8, s.trim_height = 0.2;
  Glazing& g = s.glazing;
  g.windscreen_front = at(s, 0.3), g.windscreen_back = at(s, 0.08);
  g.rear_face = true;
  g.side_front = at(s, 0.3), g.side_back = at(s, -0.27);
  g.pillars = {{at(s, -0.03), at(s, 0.02)}};
  car_faces(s, 0.98, 0.95, 0.85, 0.62);
  s.seams = {at(s, 0.0)};
  s.handles = {at(s, -0.05)};
  s.mirrors = mirrors;
  return finish_car(Family::Pickup, s, 0.24);
}

VehicleModel van(int variant, bool mirrors) {
  const Proportions p = proportions(Family::Van, variant, 5.0, 1.98, 0.34);
  BodyShape s = car_shape(p,
                          {{-1, 1.95}, {-0.98, 2.08}, {-0.93, 2.14}, {0.42, 2.16}, {0.5, 2.08},
                           {0.6, 1.7}, {0.72, 1.22}, {0.8, 1.15}, {0.95, 1.02}, {1, 0.78}},
                          {{-1, 1.2}, {0.6, 1.18}, {1, 1.0}}, 0.18, 0.95, 0.85);
  s.plan_exponent = 9, s.tumblehome = 0.06, s.roof_radius = 0.12;
  Glazing& g = s.glazing;
  g.windscreen_front = at(s, 0.72), g.windscreen_back = at(s, 0.5);
  g.rear_face = variant != 1;
  g.side_front = at(s, 0.68), g.side_back = at(s, 0.3);
  car_faces(s, 0.95, 1.0, 0.82, 0.55);
  s.seams = {at(s, 0.28), at(s, -0.25)};
  s.handles = {at(s, 0.36), at(s, 0.22)};
  s.mirrors = mirrors;
  return finish_car(Family::Van, s, 0.22);
}

}  // namespace

VehicleModel car_family(Family family, int variant, bool mirrors) {
  switch (family) {
    case Family::Hatchback: return hatchback(variant, mirrors);
    case Family::Saloon: return saloon(variant, mirrors);
    case Family::Estate: return estate(variant, mirrors);
    case Family::Suv: return suv(variant, mirrors);
    case Family::Pickup: return pickup(variant, mirrors);
    default: return van(variant, mirrors);
  }
}

}  // namespace flowscape::assets
