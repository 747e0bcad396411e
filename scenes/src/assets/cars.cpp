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

BodyShape car_shape(const Proportions& p, const std::vector<V2>& top, const std::vector<V2>& belt,
                    double clearance, double front_overhang, double rear_overhang) {
  BodyShape s;
  s.length = p.length, s.width = p.width;
  const double a = p.length / 2;
  s.top = Curve(top).scaled(a, p.height_scale);
  s.belt = Curve(belt).scaled(a, p.height_scale);
  s.bottom =
      Curve({{-1, clearance + 0.18}, {-0.92, clearance}, {0.9, clearance}, {1, clearance + 0.15}})
          .scaled(a, 1);
  s.wheel_radius = p.wheel_radius;
  s.axles = {-(a - rear_overhang), a - front_overhang};
  return s;
}

// x positions over the half length `a` given as shares of it.
double at(const BodyShape& s, double share) { return share * s.length / 2; }

// One family: its nominal size (varied per variant by `proportions`), profiles (car_shape),
// glazing, pillars, door seams and handles as shares of the half length (front, back), the
// heights of car_faces' lamps, tail lamps, grille and plate, the tyre width, and what else of the
// body differs from BodyShape's defaults.
struct CarSpec {
  Family family;
  double length, width, wheel;
  std::vector<V2> top, belt;
  double clearance, front_overhang, rear_overhang;
  V2 windscreen, rear, side;  // rear (0, 0): no rear window on the top
  std::vector<V2> pillars;
  std::vector<double> seams, handles;
  double lamp_z, tail_z, grille_z, plate_z;
  double tyre_width;
  void (*tune)(BodyShape& s, int variant) = nullptr;
};

VehicleModel build_car(const CarSpec& c, int variant, bool mirrors) {
  const Proportions p = proportions(c.family, variant, c.length, c.width, c.wheel);
  BodyShape s = car_shape(p, c.top, c.belt, c.clearance, c.front_overhang, c.rear_overhang);
  if (c.tune) c.tune(s, variant);
  Glazing& g = s.glazing;
  g.windscreen_front = at(s, c.windscreen.x()), g.windscreen_back = at(s, c.windscreen.y());
  g.rear_front = at(s, c.rear.x()), g.rear_back = at(s, c.rear.y());
  g.side_front = at(s, c.side.x()), g.side_back = at(s, c.side.y());
  for (const V2& pillar : c.pillars) g.pillars.emplace_back(at(s, pillar.x()), at(s, pillar.y()));
  car_faces(s, c.lamp_z, c.tail_z, c.grille_z, c.plate_z);
  for (double seam : c.seams) s.seams.push_back(at(s, seam));
  for (double handle : c.handles) s.handles.push_back(at(s, handle));
  s.mirrors = mirrors;
  return finish_car(c.family, s, c.tyre_width);
}

// clang-format off
const CarSpec kHatchback{Family::Hatchback, 4.05, 1.76, 0.31,
    {{-1, 0.9}, {-0.985, 1.02}, {-0.95, 1.2}, {-0.88, 1.36}, {-0.78, 1.43}, {-0.4, 1.46},
     {-0.02, 1.45}, {0.1, 1.4}, {0.25, 1.22}, {0.42, 1.0}, {0.55, 0.95}, {0.8, 0.89},
     {0.95, 0.82}, {1, 0.7}},
    {{-1, 0.98}, {-0.5, 0.96}, {0.45, 0.93}, {1, 0.9}}, 0.17, 0.8, 0.6,
    {0.42, 0.02}, {-0.8, -0.975}, {0.42, -0.84}, {{-0.1, -0.03}, {-0.86, -0.66}},
    {-0.06}, {-0.14}, 0.8, 1.0, 0.66, 0.5, 0.2};

const CarSpec kSaloon{Family::Saloon, 4.75, 1.82, 0.32,
    {{-1, 0.95}, {-0.98, 1.02}, {-0.85, 1.06}, {-0.62, 1.1}, {-0.48, 1.25}, {-0.32, 1.4},
     {-0.2, 1.44}, {0.05, 1.44}, {0.15, 1.4}, {0.28, 1.22}, {0.4, 1.02}, {0.55, 0.96},
     {0.85, 0.88}, {0.97, 0.8}, {1, 0.68}},
    {{-1, 1.0}, {-0.6, 0.99}, {0.4, 0.95}, {1, 0.9}}, 0.15, 0.95, 1.0,
    {0.4, 0.05}, {-0.22, -0.6}, {0.39, -0.56}, {{-0.11, -0.05}, {-0.56, -0.46}},
    {-0.08, -0.5}, {-0.16, -0.58}, 0.78, 0.98, 0.65, 0.5, 0.19};

const CarSpec kEstate{Family::Estate, 4.8, 1.83, 0.32,
    {{-1, 0.95}, {-0.985, 1.1}, {-0.96, 1.35}, {-0.9, 1.44}, {-0.2, 1.47}, {0.05, 1.46},
     {0.15, 1.41}, {0.28, 1.22}, {0.4, 1.02}, {0.55, 0.96}, {0.85, 0.88}, {0.97, 0.8},
     {1, 0.68}},
    {{-1, 1.0}, {-0.6, 0.99}, {0.4, 0.95}, {1, 0.9}}, 0.16, 0.95, 1.0,
    {0.4, 0.05}, {-0.9, -0.99}, {0.39, -0.93},
    {{-0.11, -0.05}, {-0.56, -0.5}, {-0.94, -0.86}},
    {-0.08, -0.53}, {-0.16, -0.6}, 0.78, 1.02, 0.65, 0.5, 0.19};

const CarSpec kSuv{Family::Suv, 4.6, 1.9, 0.36,
    {{-1, 1.05}, {-0.985, 1.25}, {-0.95, 1.55}, {-0.88, 1.66}, {-0.1, 1.7}, {0.05, 1.68},
     {0.15, 1.6}, {0.38, 1.2}, {0.55, 1.12}, {0.9, 1.05}, {1, 0.88}},
    {{-1, 1.15}, {0.4, 1.1}, {1, 1.05}}, 0.24, 0.9, 0.85,
    {0.38, 0.05}, {-0.88, -0.985}, {0.37, -0.9},
    {{-0.12, -0.05}, {-0.58, -0.52}, {-0.91, -0.8}},
    {-0.08, -0.55}, {-0.17, -0.62}, 0.95, 1.2, 0.8, 0.62, 0.24,
    [](BodyShape& s, int) { s.plan_exponent = 7, s.trim_height = 0.22, s.sill_radius = 0.1; }};

const CarSpec kPickup{Family::Pickup, 5.3, 1.9, 0.37,
    {{-1, 1.08}, {-0.99, 1.13}, {-0.34, 1.14}, {-0.3, 1.5}, {-0.27, 1.74}, {0.0, 1.79},
     {0.08, 1.75}, {0.3, 1.22}, {0.45, 1.13}, {0.9, 1.08}, {1, 0.9}},
    {{-1, 1.12}, {1, 1.08}}, 0.26, 0.95, 1.2,
    {0.3, 0.08}, {0, 0}, {0.3, -0.27}, {{-0.03, 0.02}},
    {0.0}, {-0.05}, 0.98, 0.95, 0.85, 0.62, 0.24,
    [](BodyShape& s, int) {
      s.plan_exponent = 8, s.trim_height = 0.2;
      s.glazing.rear_face = true;
    }};

const CarSpec kVan{Family::Van, 5.0, 1.98, 0.34,
    {{-1, 1.95}, {-0.98, 2.08}, {-0.93, 2.14}, {0.42, 2.16}, {0.5, 2.08}, {0.6, 1.7},
     {0.72, 1.22}, {0.8, 1.15}, {0.95, 1.02}, {1, 0.78}},
    {{-1, 1.2}, {0.6, 1.18}, {1, 1.0}}, 0.18, 0.95, 0.85,
    {0.72, 0.5}, {0, 0}, {0.68, 0.3}, {},
    {0.28, -0.25}, {0.36, 0.22}, 0.95, 1.0, 0.82, 0.55, 0.22,
    [](BodyShape& s, int variant) {
      s.plan_exponent = 9, s.tumblehome = 0.06, s.roof_radius = 0.12;
      s.glazing.rear_face = variant != 1;  // variant 1: a panel van, no rear glass
    }};
// clang-format on

}  // namespace

VehicleModel car_family(Family family, int variant, bool mirrors) {
  switch (family) {
    case Family::Hatchback:
      return build_car(kHatchback, variant, mirrors);
    case Family::Saloon:
      return build_car(kSaloon, variant, mirrors);
    case Family::Estate:
      return build_car(kEstate, variant, mirrors);
    case Family::Suv:
      return build_car(kSuv, variant, mirrors);
    case Family::Pickup:
      return build_car(kPickup, variant, mirrors);
    default:
      return build_car(kVan, variant, mirrors);
  }
}

}  // namespace flowscape::assets
