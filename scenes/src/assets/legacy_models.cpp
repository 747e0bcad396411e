// The actor models of flowscape 0.9 and before (--actors legacy): boxes on cylinder wheels, box
// people with swinging limbs. Kept byte for byte: a legacy release rerun renders the same files.
#include <cmath>

#include "../city_materials.h"
#include "../city_models.h"
#include "flowscape/scenes/shapes.h"

namespace flowscape {
namespace {

using V3 = Eigen::Vector3d;
using C = SemanticClass;
constexpr double kStride = 1.4;

Pose at(double x, double y, double z) { return Pose(Eigen::Translation3d(x, y, z)); }

// A wheel of `radius` at `hub` in the actor's frame, turning about its axle with the distance:
// a tyre and, a millimetre proud of its sidewalls, a rim with spokes.
Part wheel(const V3& hub, double radius, double width, std::uint16_t tyre, std::uint16_t rim,
           std::shared_ptr<const Track> track) {
  Mesh mesh;
  const Pose axle(Eigen::AngleAxisd(kPi / 2, V3::UnitX()));
  add_cylinder(mesh, axle * at(0, 0, -width / 2), radius, width, {C::Vehicles, tyre}, 16);
  add_cylinder(mesh, axle * at(0, 0, -width / 2 - 0.002), 0.62 * radius, width + 0.004,
               {C::Vehicles, rim}, 16);
  return rigid_part(std::move(mesh), [hub, radius, track](double t) {
    return Pose(Eigen::Translation3d(hub) *
                Eigen::AngleAxisd(track->distance_at(t) / radius, V3::UnitY()));
  });
}

// A limb hanging from `joint`, swinging about the actor's y axis with the walking cycle.
Part limb(const V3& joint, const V3& half, double swing, double phase, std::uint16_t material,
          std::shared_ptr<const Track> track) {
  Mesh mesh;
  add_oriented_box(mesh, at(0, 0, -half.z()), half, {C::Pedestrian, material});
  return rigid_part(std::move(mesh), [joint, swing, phase, track](double t) {
    const double angle = swing * std::sin(2 * kPi * track->distance_at(t) / kStride + phase);
    return Pose(Eigen::Translation3d(joint) * Eigen::AngleAxisd(angle, V3::UnitY()));
  });
}

// What a vehicle body is painted with.
struct Livery {
  std::uint16_t body, glass, head_light, tail_light, plate;
};

// Head lights at the front, tail lights and a number plate at the back of a body whose front is
// at x = L, back at x = -L, `low` the height of the lights.
void lights(Mesh& mesh, double L, double W, double low, const Livery& l) {
  for (double side : {-1.0, 1.0}) {
    add_oriented_box(mesh, at(L + 0.005, side * 0.7 * W, low), V3(0.02, 0.16, 0.06),
                     {C::Vehicles, l.head_light});
    add_oriented_box(mesh, at(-L - 0.005, side * 0.75 * W, low + 0.05), V3(0.02, 0.12, 0.05),
                     {C::Vehicles, l.tail_light});
  }
  add_oriented_box(mesh, at(-L - 0.01, 0, low - 0.1), V3(0.01, 0.26, 0.055),
                   {C::Vehicles, l.plate});
}

Mesh vehicle_body(ActorKind kind, const Livery& l) {
  Mesh mesh;
  const KindSize size = kind_size(kind);
  const double L = size.length / 2, W = size.width / 2;
  const std::uint16_t body = l.body, glass = l.glass;
  switch (kind) {
    case ActorKind::Car:
      add_oriented_box(mesh, at(0, 0, 0.7), V3(L, W, 0.35), {C::Vehicles, body});
      add_oriented_box(mesh, at(-0.15 * L, 0, 1.3), V3(0.55 * L, 0.92 * W, 0.27),
                       {C::Vehicles, glass});
      lights(mesh, L, W, 0.75, l);
      break;
    case ActorKind::Truck:
      add_oriented_box(mesh, at(0.78 * L, 0, 1.5), V3(0.22 * L, W, 0.95), {C::Vehicles, body});
      add_oriented_box(mesh, at(0.92 * L, 0, 2.0), V3(0.09 * L, 0.95 * W, 0.4),
                       {C::Vehicles, glass});
      add_oriented_box(mesh, at(-0.22 * L, 0, 2.0), V3(0.76 * L, W, 1.4), {C::Vehicles, body});
      lights(mesh, L, W, 0.8, l);
      break;
    case ActorKind::Bus:
      add_oriented_box(mesh, at(0, 0, 1.7), V3(L, W, 1.3), {C::Vehicles, body});
      add_oriented_box(mesh, at(0, 0, 2.0), V3(0.98 * L, 1.01 * W, 0.45), {C::Vehicles, glass});
      lights(mesh, L, W, 0.7, l);
      break;
    case ActorKind::Bike:
      add_oriented_box(mesh, at(0, 0, 0.75), V3(0.6, 0.12, 0.2), {C::Vehicles, body});
      add_oriented_box(mesh, at(-0.1, 0, 1.25), V3(0.2, 0.2, 0.35), {C::Vehicles, glass});
      add_oriented_box(mesh, at(-0.05, 0, 1.72), V3(0.12, 0.12, 0.13), {C::Vehicles, body});
      break;
    default:  // pedestrians; the detailed actors' kinds never come here
      break;
  }
  return mesh;
}

void add_wheels(Actor& actor, ActorKind kind, Random& random, Scene& scene,
                const std::shared_ptr<const Track>& track) {
  const KindSize size = kind_size(kind);
  const double radius = kind == ActorKind::Car ? 0.33 : kind == ActorKind::Bike ? 0.32 : 0.5;
  const double width = kind == ActorKind::Bike ? 0.1 : 0.25;
  const std::uint16_t tyre = add_material(scene, city_materials::tyre(width)),
                      rim = add_material(scene, city_materials::wheel_rim(random.bits()));
  if (kind == ActorKind::Bike) {
    for (double x : {-0.6, 0.6})
      actor.parts.push_back(wheel(V3(x, 0, radius), radius, width, tyre, rim, track));
    return;
  }
  const double axle = size.length / 2 - (kind == ActorKind::Car ? 0.8 : 1.4);
  for (double x : {-axle, axle})
    for (double y : {-size.width / 2 + 0.15, size.width / 2 - 0.15})
      actor.parts.push_back(wheel(V3(x, y, radius), radius, width, tyre, rim, track));
}

void add_body(Actor& actor, const std::shared_ptr<const Track>& track, Random& random,
              Scene& scene) {
  namespace cm = city_materials;
  const auto seed = random.bits();
  const std::uint16_t shirt = add_material(scene, cm::clothing(seed, false)),
                      trousers = add_material(scene, cm::clothing(seed + 1, true)),
                      skin = add_material(scene, cm::skin(seed + 2)),
                      hair = add_material(scene, cm::hair(seed + 3));
  Mesh torso;
  add_oriented_box(torso, at(0, 0, 1.15), V3(0.13, 0.22, 0.3), {C::Pedestrian, shirt});
  add_oriented_box(torso, at(0, 0, 1.6), V3(0.1, 0.09, 0.12), {C::Pedestrian, skin});
  add_oriented_box(torso, at(-0.015, 0, 1.71), V3(0.105, 0.095, 0.03), {C::Pedestrian, hair});
  actor.parts.push_back(rigid_part(std::move(torso)));
  for (int side : {-1, 1}) {
    const double phase = side > 0 ? 0 : kPi;
    actor.parts.push_back(
        limb(V3(0, side * 0.1, 0.85), V3(0.08, 0.08, 0.425), 0.45, phase, trousers, track));
    actor.parts.push_back(
        limb(V3(0, side * 0.29, 1.42), V3(0.055, 0.055, 0.32), 0.35, phase + kPi, shirt, track));
  }
}

}  // namespace

Actor legacy_actor(ActorKind kind, std::uint16_t instance, std::shared_ptr<const Track> track,
                   const Mesh* user_model, Random& random, Scene& scene) {
  Actor actor{instance, {}, [track](double t) { return track->pose(t); }};
  if (user_model) {
    actor.parts.push_back(rigid_part(*user_model));
    return actor;
  }
  if (kind == ActorKind::Pedestrian) {
    add_body(actor, track, random, scene);
    return actor;
  }
  namespace cm = city_materials;
  const auto seed = random.bits();
  const Livery livery{add_material(scene, cm::car_paint(seed)),
                      add_material(scene, cm::vehicle_glass()),
                      add_material(scene, cm::lamp({0.85f, 0.85f, 0.8f})),
                      add_material(scene, cm::lamp({0.6f, 0.03f, 0.02f})),
                      add_material(scene, cm::number_plate(seed + 1))};
  actor.parts.push_back(rigid_part(vehicle_body(kind, livery)));
  add_wheels(actor, kind, random, scene, track);
  return actor;
}

void add_legacy_parked_vehicle(ActorKind kind, const Pose& pose, const Mesh* user_model,
                               Random& random, Scene& scene) {
  const auto still = std::make_shared<const Track>(Track{1, {pose}, {0}});
  const Actor actor = legacy_actor(kind, 0, still, user_model, random, scene);
  for (const Part& part : actor.parts) append_mesh(scene.world, *part.mesh, pose * part.pose(0));
}

}  // namespace flowscape
