// The two-wheelers: a bicycle (diamond frame, turning cranks) and a motorbike. Both carry a rider,
// an actor of its own (people.h), placed by the model's saddle, grips and pedals or pegs.
#include <cmath>

#include "car_parts.h"

namespace flowscape::assets {
namespace {

using C = SemanticClass;

void tube(Mesh& mesh, const V3& a, const V3& b, double radius, Slot slot) {
  add_tube(mesh, {a, b}, {radius, radius}, 8, C::Vehicles, slot);
}

// A bicycle wheel about the y axis: a thin tyre, a rim and a hub (the spokes are too thin to see).
Mesh cycle_wheel(double radius, double tyre) {
  Mesh mesh;
  std::vector<V3> ring;
  for (int k = 0; k <= 40; ++k)
    ring.emplace_back(radius * std::cos(2 * kPi * k / 40), 0, radius * std::sin(2 * kPi * k / 40));
  Mesh tyre_mesh, rim;
  add_tube(tyre_mesh, ring, std::vector<double>(ring.size(), tyre), 8, C::Bicycle, kTyre);
  for (V3& p : ring) p *= (radius - 1.6 * tyre) / radius;
  add_tube(rim, ring, std::vector<double>(ring.size(), 0.6 * tyre), 6, C::Bicycle, kChrome);
  append_mesh(mesh, tyre_mesh), append_mesh(mesh, rim);
  add_lathe(mesh, {{0, -0.05}, {0.025, -0.05}, {0.025, 0.05}, {0, 0.05}}, 10, C::Bicycle, kChrome);
  return mesh;
}

VehicleModel bicycle(int variant) {
  Random random(mix_bits(0x6379636c65ull + std::uint64_t(variant)));
  const double r = 0.34, size = random.uniform(0.95, 1.05);
  const V3 rear(-0.5 * size, 0, r), front(0.53 * size, 0, r), bb(-0.02, 0, 0.29),
      seat(-0.17 * size, 0, 0.82 * size), head_top(0.38 * size, 0, 0.86 * size),
      head_bottom(0.42 * size, 0, 0.72 * size);
  Mesh frame;
  tube(frame, seat, head_top, 0.016, kPaint);
  tube(frame, bb, head_bottom, 0.02, kPaint);
  tube(frame, bb, seat, 0.016, kPaint);
  tube(frame, head_bottom, head_top, 0.02, kPaint);
  for (double side : {-1.0, 1.0}) {
    tube(frame, bb + V3(0, side * 0.03, 0), rear + V3(0, side * 0.06, 0), 0.01, kPaint);
    tube(frame, seat + V3(0, side * 0.02, 0), rear + V3(0, side * 0.06, 0), 0.009, kPaint);
    tube(frame, head_bottom + V3(0, side * 0.04, 0), front + V3(0, side * 0.05, 0), 0.012, kPaint);
  }
  const V3 saddle = seat + V3(-0.04, 0, 0.14);
  tube(frame, seat, saddle, 0.013, kChrome);
  add_rounded_box(frame, Pose(Eigen::Translation3d(saddle + V3(0, 0, 0.03))),
                  V3(0.13, 0.065, 0.025), 0.02, C::Bicycle, kTrim, 2);
  // a red rear lamp on the seat post (lit at night, as the law asks)
  add_rounded_box(frame, Pose(Eigen::Translation3d(seat + V3(-0.045, 0, 0.03))),
                  V3(0.015, 0.025, 0.035), 0.008, C::Bicycle, kTailLamp, 1);
  const V3 bar = head_top + V3(0.07, 0, 0.1);
  tube(frame, head_top, bar, 0.014, kChrome);
  tube(frame, bar + V3(0, -0.22, 0), bar + V3(0, 0.22, 0), 0.012, kTrim);
  Mesh cranks;
  const double crank = 0.17;
  for (double side : {-1.0, 1.0}) {
    tube(cranks, V3(0, side * 0.08, 0), V3(side * crank, side * 0.08, 0), 0.012, kChrome);
    add_rounded_box(cranks, Pose(Eigen::Translation3d(side * crank, side * 0.13, 0)),
                    V3(0.05, 0.045, 0.012), 0.006, C::Bicycle, kTrim, 1);
  }
  add_lathe(cranks, {{0, -0.075}, {0.1, -0.075}, {0.1, -0.068}, {0, -0.068}}, 24, C::Bicycle,
            kChrome);
  VehicleModel model;
  model.family = Family::Bicycle;
  model.length = 1.75 * size, model.width = 0.6, model.height = 1.1;
  model.body = std::make_shared<const Mesh>(labelled(std::move(frame), C::Bicycle));
  model.cranks = std::make_shared<const Mesh>(labelled(std::move(cranks), C::Bicycle));
  model.bottom_bracket = bb, model.crank_length = crank;
  model.gear = random.uniform(2.2, 2.9);
  const Mesh wheel = cycle_wheel(r, 0.018);
  model.wheels = {std::make_shared<const Mesh>(wheel)};
  model.wheel_radius = {r};
  model.mounts = {{rear, false, false, 0}, {front, true, false, 0}};
  model.wheelbase = front.x() - rear.x();
  model.saddle = saddle + V3(0.0, 0, 0.07), model.grips = bar, model.grip_spread = 0.2;
  model.pegs = bb, model.peg_spread = 0.13;
  return model;
}

VehicleModel motorbike(int variant) {
  Random random(mix_bits(0x6d6f746f7262ull + std::uint64_t(variant)));
  const double r = 0.31, s = random.uniform(0.95, 1.05);
  Mesh body;
  add_ellipsoid(body, V3(0.15, 0, 0.9) * s, V3(0.28, 0.15, 0.12) * s, C::Motorcycle, kPaint);
  add_rounded_box(body, Pose(Eigen::Translation3d(V3(-0.3, 0, 0.84) * s)), V3(0.3, 0.13, 0.05) * s,
                  0.04, C::Motorcycle, kTrim, 2);
  add_ellipsoid(body, V3(-0.58, 0, 0.86) * s, V3(0.24, 0.1, 0.07) * s, C::Motorcycle, kPaint);
  add_rounded_box(body, Pose(Eigen::Translation3d(V3(0.05, 0, 0.47) * s)), V3(0.24, 0.15, 0.17) * s,
                  0.05, C::Motorcycle, kUnderbody, 2);
  tube(body, V3(0.0, -0.16, 0.36) * s, V3(-0.65, -0.18, 0.52) * s, 0.05, kChrome);
  add_ellipsoid(body, V3(0.6, 0, 1.0) * s, V3(0.13, 0.15, 0.15) * s, C::Motorcycle, kPaint);
  add_ellipsoid(body, V3(0.71, 0, 0.98) * s, V3(0.03, 0.08, 0.07) * s, C::Motorcycle, kHeadLamp);
  add_ellipsoid(body, V3(-0.81, 0, 0.86) * s, V3(0.02, 0.06, 0.03) * s, C::Motorcycle, kTailLamp);
  add_rounded_box(body, Pose(Eigen::Translation3d(V3(-0.8, 0, 0.7) * s)), V3(0.005, 0.1, 0.06),
                  0.003, C::Motorcycle, kPlate, 1);
  const V3 front(0.7 * s, 0, r), rear(-0.68 * s, 0, r), grips(0.48 * s, 0, 1.06 * s);
  for (double side : {-1.0, 1.0}) {
    tube(body, V3(0.56 * s, side * 0.09, 1.02 * s), front + V3(0, side * 0.09, 0), 0.025, kChrome);
    tube(body, V3(-0.05, side * 0.11, 0.42) * s, rear + V3(0, side * 0.1, 0), 0.022, kUnderbody);
    tube(body, grips, grips + V3(-0.05, side * 0.34, 0), 0.014, kTrim);
    tube(body, V3(-0.12 * s, side * 0.12, 0.4 * s), V3(-0.15 * s, side * 0.24, 0.38 * s), 0.012,
         kChrome);
    add_rounded_box(body, Pose(Eigen::Translation3d(grips + V3(0.02, side * 0.3, 0.16))),
                    V3(0.015, 0.05, 0.035), 0.01, C::Motorcycle, kTrim, 1);
  }
  VehicleModel model;
  model.family = Family::Motorbike;
  model.length = 2.1 * s, model.width = 0.8, model.height = 1.15 * s;
  model.body = std::make_shared<const Mesh>(labelled(std::move(body), C::Motorcycle));
  const int wheel = add_wheel_meshes(model, r, 0.16, 0.55);
  model.mounts = {{rear, false, false, wheel}, {front, true, false, wheel}};
  model.wheelbase = front.x() - rear.x();
  model.saddle = V3(-0.3 * s, 0, 0.95 * s), model.grips = grips, model.grip_spread = 0.33;
  model.pegs = V3(-0.15 * s, 0, 0.38 * s), model.peg_spread = 0.24;
  return model;
}

}  // namespace

VehicleModel two_wheeler_family(Family family, int variant) {
  return family == Family::Bicycle ? bicycle(variant) : motorbike(variant);
}

}  // namespace flowscape::assets
