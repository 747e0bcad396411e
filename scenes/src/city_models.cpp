#include "city_models.h"

#include <cmath>

#include "flowscape/scenes/shapes.h"

namespace flowscape {
namespace {

using V3 = Eigen::Vector3d;
using C = SemanticClass;
constexpr double kStride = 1.4;

Pose at(double x, double y, double z) { return Pose(Eigen::Translation3d(x, y, z)); }

std::uint16_t paint(Scene& scene, Random& random, Material::Kind kind, double lo, double hi) {
  Material m;
  m.kind = kind;
  m.albedo = {float(random.uniform(lo, hi)), float(random.uniform(lo, hi)),
              float(random.uniform(lo, hi))};
  m.roughness = 0.05f;
  return add_material(scene, m);
}

std::uint16_t tyre_material(Scene& scene) {
  Material m;
  m.albedo = {0.04f, 0.04f, 0.04f}, m.checker_size = 0.12f, m.checker_albedo = {0.2f, 0.2f, 0.2f};
  return add_material(scene, m);
}

// A wheel of `radius` at `hub` in the actor's frame, turning about its axle with the distance.
Part wheel(const V3& hub, double radius, double width, std::uint16_t tyre,
           std::shared_ptr<const Track> track) {
  Part part;
  add_cylinder(part.mesh, Pose(Eigen::AngleAxisd(kPi / 2, V3::UnitX())) * at(0, 0, -width / 2),
               radius, width, {C::Vehicles, tyre}, 12);
  part.pose = [hub, radius, track](double t) {
    return Pose(Eigen::Translation3d(hub) *
                Eigen::AngleAxisd(track->distance_at(t) / radius, V3::UnitY()));
  };
  return part;
}

// A limb hanging from `joint`, swinging about the actor's y axis with the walking cycle.
Part limb(const V3& joint, const V3& half, double swing, double phase, std::uint16_t material,
          std::shared_ptr<const Track> track) {
  Part part;
  add_oriented_box(part.mesh, at(0, 0, -half.z()), half, {C::Pedestrian, material});
  part.pose = [joint, swing, phase, track](double t) {
    const double angle = swing * std::sin(2 * kPi * track->distance_at(t) / kStride + phase);
    return Pose(Eigen::Translation3d(joint) * Eigen::AngleAxisd(angle, V3::UnitY()));
  };
  return part;
}

Mesh vehicle_body(ActorKind kind, std::uint16_t body, std::uint16_t glass) {
  Mesh mesh;
  const KindSize size = kind_size(kind);
  const double L = size.length / 2, W = size.width / 2;
  switch (kind) {
    case ActorKind::Car:
      add_oriented_box(mesh, at(0, 0, 0.7), V3(L, W, 0.35), {C::Vehicles, body});
      add_oriented_box(mesh, at(-0.15 * L, 0, 1.3), V3(0.55 * L, 0.92 * W, 0.27),
                       {C::Vehicles, glass});
      break;
    case ActorKind::Truck:
      add_oriented_box(mesh, at(0.78 * L, 0, 1.5), V3(0.22 * L, W, 0.95), {C::Vehicles, body});
      add_oriented_box(mesh, at(0.92 * L, 0, 2.0), V3(0.09 * L, 0.95 * W, 0.4),
                       {C::Vehicles, glass});
      add_oriented_box(mesh, at(-0.22 * L, 0, 2.0), V3(0.76 * L, W, 1.4), {C::Vehicles, body});
      break;
    case ActorKind::Bus:
      add_oriented_box(mesh, at(0, 0, 1.7), V3(L, W, 1.3), {C::Vehicles, body});
      add_oriented_box(mesh, at(0, 0, 2.0), V3(0.98 * L, 1.01 * W, 0.45), {C::Vehicles, glass});
      break;
    case ActorKind::Bike:
      add_oriented_box(mesh, at(0, 0, 0.75), V3(0.6, 0.12, 0.2), {C::Vehicles, body});
      add_oriented_box(mesh, at(-0.1, 0, 1.25), V3(0.2, 0.2, 0.35), {C::Vehicles, glass});
      add_oriented_box(mesh, at(-0.05, 0, 1.72), V3(0.12, 0.12, 0.13), {C::Vehicles, body});
      break;
    case ActorKind::Pedestrian:
      break;
  }
  return mesh;
}

void add_wheels(Actor& actor, ActorKind kind, std::uint16_t tyre,
                const std::shared_ptr<const Track>& track) {
  const KindSize size = kind_size(kind);
  const double radius = kind == ActorKind::Car ? 0.33 : kind == ActorKind::Bike ? 0.32 : 0.5;
  if (kind == ActorKind::Bike) {
    for (double x : {-0.6, 0.6})
      actor.parts.push_back(wheel(V3(x, 0, radius), radius, 0.1, tyre, track));
    return;
  }
  const double axle = size.length / 2 - (kind == ActorKind::Car ? 0.8 : 1.4);
  for (double x : {-axle, axle})
    for (double y : {-size.width / 2 + 0.15, size.width / 2 - 0.15})
      actor.parts.push_back(wheel(V3(x, y, radius), radius, 0.25, tyre, track));
}

void add_body(Actor& actor, const std::shared_ptr<const Track>& track, Random& random,
              Scene& scene) {
  const std::uint16_t shirt = paint(scene, random, Material::Kind::Diffuse, 0.05, 0.8),
                      trousers = paint(scene, random, Material::Kind::Diffuse, 0.03, 0.4),
                      skin = paint(scene, random, Material::Kind::Diffuse, 0.3, 0.7);
  Part torso{{}, [](double) { return Pose::Identity(); }};
  add_oriented_box(torso.mesh, at(0, 0, 1.15), V3(0.13, 0.22, 0.3), {C::Pedestrian, shirt});
  add_oriented_box(torso.mesh, at(0, 0, 1.6), V3(0.1, 0.09, 0.12), {C::Pedestrian, skin});
  actor.parts.push_back(std::move(torso));
  for (int side : {-1, 1}) {
    const double phase = side > 0 ? 0 : kPi;
    actor.parts.push_back(
        limb(V3(0, side * 0.1, 0.85), V3(0.08, 0.08, 0.425), 0.45, phase, trousers, track));
    actor.parts.push_back(
        limb(V3(0, side * 0.29, 1.42), V3(0.055, 0.055, 0.32), 0.35, phase + kPi, shirt, track));
  }
}

}  // namespace

KindSize kind_size(ActorKind kind) {
  switch (kind) {
    case ActorKind::Car:
      return {4.5, 1.9};
    case ActorKind::Truck:
      return {8.0, 2.5};
    case ActorKind::Bus:
      return {11.0, 2.55};
    case ActorKind::Bike:
      return {1.9, 0.7};
    case ActorKind::Pedestrian:
      return {0.5, 0.6};
  }
  return {1, 1};
}

Actor make_actor(ActorKind kind, std::uint16_t instance, std::shared_ptr<const Track> track,
                 const Mesh* user_model, Random& random, Scene& scene) {
  Actor actor{instance, {}, [track](double t) { return track->pose(t); }};
  if (user_model) {
    actor.parts.push_back({*user_model, [](double) { return Pose::Identity(); }});
    return actor;
  }
  if (kind == ActorKind::Pedestrian) {
    add_body(actor, track, random, scene);
    return actor;
  }
  const std::uint16_t body = paint(scene, random, Material::Kind::Glossy, 0.03, 0.8);
  Material glass;
  glass.kind = Material::Kind::Metal, glass.albedo = {0.2f, 0.22f, 0.25f}, glass.roughness = 0.02f;
  const std::uint16_t window = add_material(scene, glass);
  actor.parts.push_back(
      {vehicle_body(kind, body, window), [](double) { return Pose::Identity(); }});
  add_wheels(actor, kind, tyre_material(scene), track);
  return actor;
}

}  // namespace flowscape
