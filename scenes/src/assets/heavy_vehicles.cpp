// The heavy families: a low-floor city bus, a box truck and an articulated lorry (tractor and
// semi-trailer). Sizes follow EU limits (2.55 m wide, a 13.6 m trailer).
#include <cmath>

#include "car_parts.h"

namespace flowscape::assets {
namespace {

using C = SemanticClass;

Pose at(double x, double y, double z) { return Pose(Eigen::Translation3d(x, y, z)); }

void box(Mesh& mesh, const V3& lo, const V3& hi, Slot slot, double radius = 0.02) {
  add_rounded_box(mesh, at((lo + hi).x() / 2, (lo + hi).y() / 2, (lo + hi).z() / 2), (hi - lo) / 2,
                  radius, C::Vehicles, slot, 2);
}

// Rows of seats, a floor and linings inside a bus, from x0 to x1.
void bus_interior(Mesh& mesh, double x0, double x1, double half_width, double floor, double belt) {
  const Paint lining{C::Vehicles, kInterior};
  const V3 up(0, 0, belt - floor);
  const V3 a(x0, -half_width, floor), b(x1, -half_width, floor), c(x1, half_width, floor),
      d(x0, half_width, floor);
  add_quad(mesh, a, d, c, b, lining);
  add_quad(mesh, a, b, b + up, a + up, lining);
  add_quad(mesh, c, d, d + up, c + up, lining);
  for (double x = x0 + 0.6; x < x1 - 0.6; x += 0.85)
    for (double side : {-1.0, 1.0}) {
      const double y = side * (half_width - 0.45);
      box(mesh, V3(x - 0.22, y - 0.42, floor + 0.38), V3(x + 0.22, y + 0.42, floor + 0.48),
          kInterior, 0.05);
      box(mesh, V3(x - 0.3, y - 0.42, floor + 0.45), V3(x - 0.22, y + 0.42, floor + 1.05),
          kInterior, 0.03);
    }
}

VehicleModel city_bus(int variant) {
  Random random(mix_bits(0x627573ull + std::uint64_t(variant)));
  BodyShape s;
  s.length = random.uniform(10.5, 12.0), s.width = 2.55;
  const double a = s.length / 2, b = s.width / 2, h = random.uniform(2.95, 3.1);
  s.plan_exponent = 14, s.tumblehome = 0.02, s.shoulder = 0, s.bulge = 0.01, s.crown = 0.02;
  s.roof_radius = 0.15, s.sill_radius = 0.08, s.trim_height = 0.15;
  s.top = Curve({{-1, h - 0.2},
                 {-0.99, h - 0.08},
                 {-0.975, h - 0.02},
                 {0.975, h},
                 {0.99, h - 0.07},
                 {1, h - 0.2}})
              .scaled(a, 1);
  s.belt = Curve({{-1, 1.3}, {0.93, 1.25}, {0.965, 0.95}, {1, 0.95}}).scaled(a, 1);
  s.bottom = Curve({{-1, 0.55}, {-0.96, 0.35}, {0.96, 0.33}, {1, 0.5}}).scaled(a, 1);
  s.wheel_radius = 0.5, s.arch_clearance = 0.06;
  s.axles = {-(a - 3.4), a - 2.7};
  Glazing& g = s.glazing;
  g.front_face = g.rear_face = true, g.frame = 0.06;
  g.side_back = -a + 0.35, g.side_front = a - 0.2;
  for (double x = -a + 1.6; x < a - 1.0; x += 1.3) g.pillars.push_back({x - 0.05, x + 0.05});
  s.mirrors = false, s.cabin = false;
  for (double side : {-1.0, 1.0}) {
    s.front.push_back({side * (b - 0.3), 0.72, 0.17, 0.08, kHeadLamp});
    s.front.push_back({side * (b - 0.12), 0.6, 0.06, 0.035, kIndicator});
    s.rear.push_back({side * (b - 0.2), 0.95, 0.1, 0.18, kTailLamp});
  }
  s.front.push_back({0, h - 0.28, 0.9, 0.13, kTrim});  // the destination display
  s.front.push_back({0, 0.48, 0.26, 0.055, kPlate});
  s.rear.push_back({0, 0.7, 0.26, 0.055, kPlate});
  s.rear.push_back({0, 1.6, 0.9, 0.3, kTrim});  // the engine grille
  const double door1 = a - 1.05, door2 = random.uniform(-0.6, 0.4);
  for (double x : {door1, door2}) s.panels.push_back({x - 0.6, x + 0.6, 0.3, h - 0.35, -1, kGlass});
  s.panels.push_back({-a + 0.3, a - 0.3, 0.95, 1.18, 1, kLivery});
  s.panels.push_back({-a + 0.3, door2 - 0.65, 0.95, 1.18, -1, kLivery});
  s.panels.push_back({door2 + 0.65, door1 - 0.65, 0.95, 1.18, -1, kLivery});
  Mesh body = vehicle_body(s);
  bus_interior(body, -a + 0.5, a - 0.6, b - 0.08, 0.4, 1.25);
  return finish_car(Family::CityBus, s, 0.3, std::move(body));
}

// A cab-over truck cab, its front at x = front: windscreen, doors, lamps, grille, mirrors.
BodyShape truck_cab(double front, double length, double height, double axle) {
  BodyShape s;
  s.length = length, s.width = 2.45;
  const double a = length / 2, b = s.width / 2;
  s.plan_exponent = 12, s.tumblehome = 0.05, s.shoulder = 0.02, s.bulge = 0.015;
  s.roof_radius = 0.12, s.sill_radius = 0.1, s.trim_height = 0.3, s.crown = 0.03;
  s.top = Curve({{-1, height - 0.05}, {0.5, height}, {0.85, height - 0.1}, {1, height - 0.35}})
              .scaled(a, 1);
  s.belt = Curve({{-1, 1.75}, {0.8, 1.62}, {1, 1.55}}).scaled(a, 1);
  s.bottom = Curve({{-1, 0.6}, {1, 0.55}}).scaled(a, 1);
  s.wheel_radius = 0.5, s.arch_clearance = 0.08, s.axles = {axle - (front - a)};
  Glazing& g = s.glazing;
  g.front_face = true;
  g.windscreen_front = g.windscreen_back = a - 0.1;
  g.side_back = -a + 0.35, g.side_front = a - 0.15;
  for (double side : {-1.0, 1.0}) {
    s.front.push_back({side * (b - 0.3), 0.8, 0.18, 0.09, kHeadLamp});
    s.front.push_back({side * (b - 0.1), 0.95, 0.06, 0.04, kIndicator});
  }
  s.front.push_back({0, 1.15, 0.75, 0.22, kGrille});
  s.front.push_back({0, 0.6, 0.95, 0.1, kTrim});  // bumper
  s.front.push_back({0, 0.75, 0.26, 0.055, kPlate});
  s.seams = {-a + 0.25, a - 0.55};
  s.handles = {-a + 0.35};
  return s;
}

// A cargo box from x = back to front (kLivery) as trucks carry them: aluminium corner posts and top
// rails, a dark bottom rail, and at the rear two doors parted by a seam, each with two lock rods.
void cargo_box(Mesh& mesh, double back, double front, double half_width, double bottom,
               double top) {
  box(mesh, V3(back, -half_width, bottom), V3(front, half_width, top), kLivery, 0.04);
  const double post = 0.035, w = half_width;
  for (double x : {back, front})
    for (double side : {-1.0, 1.0})
      box(mesh, V3(x - post, side * w - post, bottom - 0.01), V3(x + post, side * w + post, top),
          kChrome, 0.01);
  for (double side : {-1.0, 1.0}) {
    box(mesh, V3(back, side * w - 0.02, top - 0.1), V3(front, side * w + 0.02, top + 0.01), kChrome,
        0.01);
    box(mesh, V3(back, side * w - 0.025, bottom - 0.02), V3(front, side * w + 0.025, bottom + 0.16),
        kTrim, 0.01);
  }
  box(mesh, V3(back - 0.015, -0.015, bottom + 0.05), V3(back + 0.01, 0.015, top - 0.05), kTrim,
      0.005);
  for (double y : {0.3, w - 0.3})
    for (double side : {-1.0, 1.0})
      box(mesh, V3(back - 0.04, side * y - 0.02, bottom + 0.1),
          V3(back, side * y + 0.02, top - 0.1), kChrome, 0.01);
}

// A cargo box's marker lamps (UN R48): amber side markers along its lower edge (`low`) at most
// 3 m apart, and its outline lamps at the top corners, ahead in the marker slot and red behind.
void marker_lamps(Mesh& mesh, double back, double front, double half_width, double low,
                  double top) {
  const int gaps = int(std::ceil((front - back - 0.4) / 2.8));
  const double y = half_width + 0.04;
  for (int k = 0; k <= gaps; ++k) {
    const double x = back + 0.2 + (front - back - 0.4) * k / gaps;
    for (double side : {-1.0, 1.0})
      box(mesh, V3(x - 0.05, side * y - 0.015, low - 0.03),
          V3(x + 0.05, side * y + 0.015, low + 0.03), kMarker, 0.01);
  }
  for (double side : {-1.0, 1.0}) {
    const double corner = side * (half_width - 0.15);
    box(mesh, V3(front, corner - 0.06, top - 0.12), V3(front + 0.03, corner + 0.06, top - 0.05),
        kMarker, 0.01);
    box(mesh, V3(back - 0.03, corner - 0.06, top - 0.12), V3(back, corner + 0.06, top - 0.05),
        kTailLamp, 0.01);
  }
}

Mesh translated(const Mesh& mesh, double x) {
  Mesh out;
  append_mesh(out, mesh, at(x, 0, 0));
  return out;
}

void tail_end(Mesh& mesh, double x, double half_width, double z) {
  box(mesh, V3(x - 0.08, -half_width + 0.1, z - 0.1), V3(x, half_width - 0.1, z + 0.05), kTrim);
  for (double side : {-1.0, 1.0})
    box(mesh, V3(x - 0.02, side * (half_width - 0.35) - 0.18, z + 0.08),
        V3(x + 0.01, side * (half_width - 0.35) + 0.18, z + 0.2), kTailLamp, 0.01);
  box(mesh, V3(x - 0.02, -0.26, z - 0.3), V3(x + 0.005, 0.26, z - 0.19), kPlate, 0.005);
}

VehicleModel box_truck(int variant) {
  Random random(mix_bits(0x747275636bull + std::uint64_t(variant)));
  const double L = random.uniform(7.4, 8.4), a = L / 2, cab = 2.2;
  const double front_axle = a - 1.25, rear_axle = -a + random.uniform(1.8, 2.2);
  const BodyShape s = truck_cab(a, cab, random.uniform(2.75, 2.95), front_axle);
  Mesh body = translated(vehicle_body(s), a - cab / 2);
  const double box_top = random.uniform(3.4, 3.7);
  cargo_box(body, -a, a - cab - 0.1, 1.24, 1.1, box_top);
  marker_lamps(body, -a, a - cab - 0.1, 1.24, 1.17, box_top);
  box(body, V3(-a + 0.4, -0.5, 0.7), V3(a - cab + 0.2, 0.5, 1.1), kUnderbody);  // chassis
  for (double side : {-1.0, 1.0})  // side guards between the axles
    box(body, V3(rear_axle + 0.7, side * 1.17 - 0.02, 0.45),
        V3(front_axle - 0.8, side * 1.17 + 0.02, 0.75), kTrim);
  tail_end(body, -a, 1.24, 0.85);
  VehicleModel model;
  model.family = Family::BoxTruck;
  model.length = L, model.width = 2.5, model.height = box_top;
  model.body = std::make_shared<const Mesh>(labelled(std::move(body), C::Truck));
  const int single = add_wheel_meshes(model, 0.5, 0.3, 0.6);
  for (int side : {1, -1}) {
    const int mesh = side > 0 ? single : single + 1;
    model.mounts.push_back({V3(front_axle, side * 1.03, 0.5), true, false, mesh});
    model.mounts.push_back({V3(rear_axle, side * 1.03, 0.5), false, false, mesh});
    model.mounts.push_back({V3(rear_axle, side * 0.7, 0.5), false, false, mesh});
  }
  model.wheelbase = front_axle - rear_axle;
  model.roof_x = a - cab / 2, model.roof_z = box_top;
  return model;
}

VehicleModel lorry(int variant) {
  Random random(mix_bits(0x6c6f727279ull + std::uint64_t(variant)));
  const double L = 16.5, a = L / 2, cab = 2.4, tractor = 6.2;
  const double front_axle = a - 1.35, rear_axle = a - tractor + 1.1;
  const BodyShape s = truck_cab(a, cab, random.uniform(3.3, 3.6), front_axle);
  Mesh body = translated(vehicle_body(s), a - cab / 2);
  const double tail = a - tractor;
  box(body, V3(tail, -0.5, 0.65), V3(a - cab + 0.3, 0.5, 1.05), kUnderbody);  // chassis
  for (double side : {-1.0, 1.0}) {
    add_cylinder(
        body, at(a - cab - 0.5, side * 0.9, 0.72) * Pose(Eigen::AngleAxisd(kPi / 2, V3::UnitY())),
        0.3, 0.9, {C::Vehicles, kChrome}, 16);  // fuel tanks
    box(body, V3(tail - 0.05, side * 1.1 - 0.3, 0.9), V3(tail + 0.05, side * 1.1 + 0.1, 1.25),
        kTrim);  // mudguards
  }
  const V3 kingpin(rear_axle + 0.35, 0, 1.2);
  box(body, V3(kingpin.x() - 0.9, -1.0, 1.05), V3(kingpin.x() + 0.6, 1.0, 1.15), kTrim);
  VehicleModel model;
  model.family = Family::Lorry;
  model.length = L, model.width = 2.55, model.height = 4.0;
  model.body = std::make_shared<const Mesh>(labelled(std::move(body), C::Truck));
  // the semi-trailer, in its own frame with the kingpin at the origin
  Mesh trailer;
  const double front = 1.5, back = -12.1;
  cargo_box(trailer, back, front, 1.27, 0.0, 2.8);
  marker_lamps(trailer, back, front, 1.27, 0.07, 2.8);
  box(trailer, V3(back + 0.3, -0.55, -0.35), V3(front - 0.3, 0.55, 0.0), kUnderbody);
  for (double side : {-1.0, 1.0}) {
    box(trailer, V3(-1.2, side * 0.9 - 0.06, -1.05), V3(-1.05, side * 0.9 + 0.06, -0.35), kTrim);
    box(trailer, V3(-7.6, side * 1.2 - 0.02, -0.75), V3(-1.6, side * 1.2 + 0.02, -0.4), kTrim);
  }
  tail_end(trailer, back, 1.27, -0.35);
  model.trailer = std::make_shared<const Mesh>(labelled(std::move(trailer), C::Truck));
  model.kingpin = kingpin, model.trailer_axles = 9.9;
  const int wheel = add_wheel_meshes(model, 0.5, 0.32, 0.6);
  for (int side : {1, -1}) {
    const int mesh = side > 0 ? wheel : wheel + 1;
    model.mounts.push_back({V3(front_axle, side * 1.03, 0.5), true, false, mesh});
    model.mounts.push_back({V3(rear_axle, side * 1.03, 0.5), false, false, mesh});
    model.mounts.push_back({V3(rear_axle, side * 0.7, 0.5), false, false, mesh});
    for (double x : {-8.6, -9.9, -11.2})
      model.mounts.push_back({V3(x, side * 1.03, 0.5 - kingpin.z()), false, true, mesh});
  }
  model.wheelbase = front_axle - rear_axle;
  model.roof_x = a - cab / 2, model.roof_z = 3.4;
  return model;
}

}  // namespace

VehicleModel heavy_family(Family family, int variant) {
  switch (family) {
    case Family::CityBus:
      return city_bus(variant);
    case Family::BoxTruck:
      return box_truck(variant);
    default:
      return lorry(variant);
  }
}

}  // namespace flowscape::assets
