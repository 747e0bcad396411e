#include "city_models.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "assets/car_parts.h"
#include "assets/gait.h"
#include "assets/people.h"
#include "assets/vehicles.h"
#include "city_materials.h"
#include "flowscape/scenes/shapes.h"

namespace flowscape {
namespace {

using namespace assets;
namespace cm = city_materials;
using Rgb = city_materials::Rgb;

Pose at(const V3& p) { return Pose(Eigen::Translation3d(p)); }

// The generalized winding number of a point with respect to a mesh: about 1 inside a closed
// surface, 0 outside (the solid angles of its triangles, Van Oosterom and Strackee).
double winding(const Mesh& mesh, const V3& p) {
  double sum = 0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const V3 a = mesh.vertices[t[0]].cast<double>() - p, b = mesh.vertices[t[1]].cast<double>() - p,
             c = mesh.vertices[t[2]].cast<double>() - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    sum += 2 * std::atan2(a.dot(b.cross(c)),
                          la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la);
  }
  return sum / (4 * kPi);
}

// Whether every point within `clearance` of p is outside the mesh (tested on a sphere of points).
bool clear_of(const Mesh& mesh, const V3& p, double clearance) {
  if (winding(mesh, p) > 0.5) return false;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k)
        if ((i || j || k) && winding(mesh, p + clearance * V3(i, j, k).normalized()) > 0.5)
          return false;
  return true;
}

// A vehicle model stretched along x by sx, moved by shift and scaled in height by sz (wheels stay
// round and on the ground), every triangle of class `cls`.
VehicleModel fitted(VehicleModel model, double sx, double shift, double sz, SemanticClass cls) {
  const Eigen::Vector3d scale(sx, 1, sz);
  Mesh moved = *model.body;
  for (Eigen::Vector3f& v : moved.vertices)
    v = (v.cast<double>().cwiseProduct(scale) + V3(shift, 0, 0)).cast<float>();
  for (Eigen::Vector3f& n : moved.normals)
    n = n.cast<double>().cwiseQuotient(scale).normalized().cast<float>();
  std::fill(moved.classes.begin(), moved.classes.end(), cls);
  model.body = std::make_shared<const Mesh>(std::move(moved));
  for (auto& wheel : model.wheels) {
    Mesh relabelled = *wheel;
    std::fill(relabelled.classes.begin(), relabelled.classes.end(), cls);
    wheel = std::make_shared<const Mesh>(std::move(relabelled));
  }
  for (WheelMount& mount : model.mounts) mount.hub.x() = mount.hub.x() * sx + shift;
  model.roof_z *= sz, model.roof_x = model.roof_x * sx + shift, model.wheelbase *= sx;
  return model;
}

// The curvature of a track's path where it has covered `distance` (its heading's change per metre).
double curvature(const Track& track, double distance) {
  const double h = 0.5;
  return wrapped_angle(yaw_of(pose_at_distance(track, distance + h)) -
                       yaw_of(pose_at_distance(track, distance - h))) /
         (2 * h);
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
    case ActorKind::Lorry:
      return {16.5, 2.55};
    case ActorKind::Motorbike:
      return {2.1, 0.8};
    case ActorKind::Rider:
      return {0.6, 0.6};
  }
  return {1, 1};
}

struct ActorLibrary::Impl {
  Scene& scene;
  std::uint64_t seed;
  bool wet;
  std::map<std::pair<Family, int>, VehicleModel> vehicles;
  std::map<std::tuple<int, int, int, int, int, int, int, int, int, int>, PersonModel> people;
  std::map<Livery, std::shared_ptr<const Mesh>> roofs;
  std::map<double, std::uint16_t> tyres;
  std::uint16_t glass, bus_glass, trim, chrome, head_lamp, tail_lamp, indicator, marker, interior,
      underbody, grille, eyes, dark_head_lamp, dark_tail_lamp;

  Impl(Scene& s, std::uint64_t city_seed, bool rain) : scene(s), seed(city_seed), wet(rain) {
    glass = add_material(scene, cm::clear_glass());
    // a bus's cabin lit at night (cool-white ceiling lights, as bright as a lit room's window)
    bus_glass = add_material(scene, cm::clear_glass(Rgb(0.95f, 0.97f, 1.0f) * 3e-4f));
    trim = add_material(scene, cm::trim_plastic());
    chrome = add_material(scene, cm::chrome());
    head_lamp = add_material(scene, cm::lamp({0.85f, 0.85f, 0.82f}, Rgb(1, 0.97f, 0.9f) * 0.03f));
    tail_lamp = add_material(scene, cm::lamp({0.6f, 0.03f, 0.02f}, {0.003f, 1e-5f, 1e-5f}));
    indicator = add_material(scene, cm::lamp({0.8f, 0.35f, 0.02f}, {0, 0, 0}));
    marker = add_material(scene, cm::lamp({0.8f, 0.35f, 0.02f}, Rgb(1, 0.45f, 0.04f) * 0.003f));
    dark_head_lamp = add_material(scene, cm::lamp({0.85f, 0.85f, 0.82f}));
    dark_tail_lamp = add_material(scene, cm::lamp({0.6f, 0.03f, 0.02f}));
    interior = add_material(scene, cm::upholstery(seed));
    underbody = add_material(scene, cm::underbody());
    grille = add_material(scene, cm::grille());
    eyes = add_material(scene, cm::eyes());
  }

  const VehicleModel& vehicle_model(Family family, int variant) {
    auto it = vehicles.find({family, variant});
    if (it == vehicles.end())
      it = vehicles.emplace(std::pair{family, variant}, build_vehicle(family, variant)).first;
    return it->second;
  }

  std::uint16_t tyre(double width) {
    auto [it, fresh] = tyres.try_emplace(width, 0);
    if (fresh) it->second = add_material(scene, cm::tyre(width));
    return it->second;
  }

  // The vehicle's slots: shared trim, its own paint, plate, rims and livery.
  std::vector<std::uint16_t> vehicle_slots(const VehicleModel& model, Livery livery,
                                           std::uint64_t look) {
    Random random(look);
    Rgb paint = cm::popular_car_colour(random.bits());
    Rgb second = cm::popular_car_colour(random.bits());
    Material body;
    switch (livery) {
      case Livery::Taxi:
        paint = {0.75f, 0.55f, 0.02f};
        body = cm::body_paint(paint, look);
        break;
      case Livery::Police:
        body =
            cm::banded_paint({0.78f, 0.78f, 0.76f}, {0.03f, 0.08f, 0.45f}, 0.55, 0.85, true, look);
        break;
      case Livery::Delivery:
        body = cm::banded_paint({0.8f, 0.8f, 0.78f}, second, 0.9, 1.5, false, look);
        break;
      case Livery::Plain:
        body = cm::body_paint(paint, look);
        break;
    }
    if (model.family == Family::CityBus) {  // buses in a fleet colour
      static const Rgb kFleets[] = {{0.5f, 0.03f, 0.03f},
                                    {0.03f, 0.12f, 0.45f},
                                    {0.05f, 0.3f, 0.1f},
                                    {0.75f, 0.55f, 0.05f},
                                    {0.78f, 0.78f, 0.76f}};
      body = cm::body_paint(kFleets[random.below(5)], look);
    }
    std::vector<std::uint16_t> slots(kSlotCount, trim);
    slots[kPaint] = add_material(scene, body);
    slots[kGlass] = model.family == Family::CityBus ? bus_glass : glass;
    slots[kTrim] = trim, slots[kChrome] = chrome;
    slots[kHeadLamp] = head_lamp, slots[kTailLamp] = tail_lamp, slots[kIndicator] = indicator;
    slots[kMarker] = marker;
    slots[kPlate] = add_material(scene, cm::number_plate(random.bits()));
    slots[kInterior] = interior, slots[kUnderbody] = underbody, slots[kGrille] = grille;
    slots[kTyre] = tyre(model.family == Family::Bicycle ? 0.036 : 0.25);
    slots[kRim] = add_material(scene, cm::wheel_rim(random.bits()));
    const Rgb band = livery == Livery::Taxi     ? Rgb(0.9f, 0.9f, 0.88f)
                     : livery == Livery::Police ? Rgb(0.05f, 0.1f, 0.6f)
                                                : Rgb(random.chance(0.5) ? 0.8f : second.x(),
                                                      random.chance(0.5) ? 0.8f : second.y(),
                                                      random.chance(0.5) ? 0.78f : second.z());
    const bool cargo = model.family == Family::BoxTruck || model.family == Family::Lorry;
    slots[kLivery] = add_material(
        scene, cm::body_paint(cargo ? cm::cargo_box_colour(random.bits()) : band, look + 1));
    slots[kSkin] = interior;
    return slots;
  }

  const PersonModel& person_model(const Look& look, SemanticClass cls) {
    const auto key = std::tuple{int(look.female),
                                int(look.child),
                                int(std::lround(look.height * 20)),
                                int(std::lround(look.build * 10)),
                                int(look.top),
                                int(look.bottom),
                                int(look.hair),
                                int(look.bag),
                                int(look.umbrella),
                                int(cls)};
    auto it = people.find(key);
    if (it == people.end()) {
      Look rounded = look;
      rounded.height = std::get<2>(key) / 20.0, rounded.build = std::get<3>(key) / 10.0;
      it = people.emplace(key, build_person(rounded, cls)).first;
    }
    return it->second;
  }

  std::vector<std::uint16_t> person_slots(const Look& look, std::uint64_t id) {
    std::vector<std::uint16_t> slots(kPersonSlots);
    slots[kSkinTone] = add_material(scene, cm::skin(id));
    slots[kTop] = add_material(scene, cm::clothing(id + 1, false));
    slots[kBottom] = look.bottom == Look::Bottom::Dress
                         ? slots[kTop]
                         : add_material(scene, cm::clothing(id + 2, true));
    slots[kShoes] = add_material(scene, cm::shoes(id + 3));
    slots[kHair] = add_material(scene, cm::hair(id + 4));
    slots[kBag] = add_material(scene, cm::bag(id + 5));
    slots[kUmbrella] = look.umbrella ? add_material(scene, cm::umbrella(id + 6)) : slots[kBag];
    slots[kEyes] = eyes;
    return slots;
  }

  // The wheels (and a lorry's trailer, a bicycle's cranks) of a vehicle following `track`, as
  // parts of its actor; `body` maps the actor frame to where the wheels' road frame is (the ego's
  // body sways on its springs, its wheels stay on the road).
  void add_running_gear(Actor& actor, const VehicleModel& model,
                        const std::vector<std::uint16_t>& slots,
                        const std::shared_ptr<const Track>& track,
                        const std::function<Pose(double)>& road_in_actor) {
    const auto trailer = [model, track](double t) {  // trailer -> road frame of the tractor
      const Pose now = track->pose(t);
      const double d = track->distance_at(t);
      const V3 kingpin = now * model.kingpin;
      const V3 axle =
          pose_at_distance(*track, d + model.kingpin.x() - model.trailer_axles).translation() +
          V3(0, 0, model.kingpin.z());
      const V3 x = (kingpin - axle).normalized(), y = V3::UnitZ().cross(x).normalized();
      Pose world = Pose::Identity();
      world.linear() << x, y, x.cross(y);
      world.translation() = kingpin;
      return Pose(now.inverse() * world);
    };
    if (model.trailer) {
      Part part{model.trailer, [=](double t) { return road_in_actor(t) * trailer(t); }};
      part.materials = slots;
      actor.parts.push_back(part);
    }
    for (const WheelMount& mount : model.mounts) {
      const double radius = model.wheel_radius[std::size_t(mount.mesh)];
      const double wheelbase = model.wheelbase;
      Part part{model.wheels[std::size_t(mount.mesh)], [=](double t) {
                  const double d = track->distance_at(t);
                  const Pose roll(Eigen::AngleAxisd(d / radius, V3::UnitY()));
                  if (mount.trailer)
                    return Pose(road_in_actor(t) * trailer(t) * at(mount.hub) * roll);
                  const double steer =
                      mount.steers
                          ? std::clamp(std::atan(wheelbase * curvature(*track, d)), -0.6, 0.6)
                          : 0;
                  return Pose(road_in_actor(t) * at(mount.hub) *
                              Pose(Eigen::AngleAxisd(steer, V3::UnitZ())) * roll);
                }};
      part.materials = slots;
      actor.parts.push_back(part);
    }
    if (model.cranks) {
      Part part{
          model.cranks, [=](double t) {
            const double turns = track->distance_at(t) / (model.wheel_radius.front() * model.gear);
            return Pose(at(model.bottom_bracket) * Pose(Eigen::AngleAxisd(turns, V3::UnitY())));
          }};
      part.materials = slots;
      actor.parts.push_back(part);
    }
  }
};

ActorLibrary::ActorLibrary(Scene& scene, std::uint64_t seed, bool wet)
    : impl_(std::make_unique<Impl>(scene, seed, wet)) {}
ActorLibrary::~ActorLibrary() = default;

namespace {

// What a built-in vehicle of `kind` shows, drawn from the city's seed and its instance.
struct DrawnVehicle {
  Family family;
  Livery livery;
  int variant;
};
DrawnVehicle draw_vehicle(std::uint64_t seed, ActorKind kind, std::uint16_t instance) {
  Random random(derived_seed(seed, instance, 0x76656869636c65ull));  // "vehicle"
  const auto [family, livery] = family_of(kind, random);
  return {family, livery, random.below(kVariants)};
}

}  // namespace

std::vector<Actor> ActorLibrary::vehicle(ActorKind kind, std::uint16_t instance,
                                         std::shared_ptr<const Track> track,
                                         const Mesh* user_model) {
  if (user_model) {
    Actor actor{instance, {}, [track](double t) { return track->pose(t); }};
    actor.parts.push_back(rigid_part(*user_model));
    return {std::move(actor)};
  }
  const DrawnVehicle drawn = draw_vehicle(impl_->seed, kind, instance);
  return vehicle_of(drawn.family, drawn.variant, drawn.livery, instance, std::move(track));
}

std::string ActorLibrary::family(ActorKind kind, std::uint16_t instance) const {
  return family_name(draw_vehicle(impl_->seed, kind, instance).family);
}

std::vector<Actor> ActorLibrary::vehicle_of(Family family, int variant, Livery livery,
                                            std::uint16_t instance,
                                            std::shared_ptr<const Track> track) {
  Impl& lib = *impl_;
  Random random(derived_seed(lib.seed, instance, 0x6c6f6f6bull));  // "look"
  Actor actor{instance, {}, [track](double t) { return track->pose(t); }};
  const VehicleModel& model = lib.vehicle_model(family, variant);
  const std::vector<std::uint16_t> slots = lib.vehicle_slots(model, livery, random.bits());
  actor.parts.push_back({model.body, [](double) { return Pose::Identity(); }, {}, slots});
  lib.add_running_gear(actor, model, slots, track, [](double) { return Pose::Identity(); });
  if (livery == Livery::Taxi || livery == Livery::Police) {
    auto& roof = lib.roofs[livery];
    if (!roof) roof = std::make_shared<const Mesh>(livery_roof(livery));
    actor.parts.push_back({roof,
                           [z = model.roof_z, x = model.roof_x](double) {
                             return Pose(Eigen::Translation3d(x, 0, z - 0.01));
                           },
                           {},
                           slots});
  }
  std::vector<Actor> actors{std::move(actor)};
  if (family != Family::Bicycle && family != Family::Motorbike) return actors;
  Look rider = random_look(random, false, false);
  rider.height = rider_height(model), rider.umbrella = false;
  if (rider.bottom == Look::Bottom::Skirt || rider.bottom == Look::Bottom::Dress)
    rider.bottom = Look::Bottom::Trousers;
  if (rider.top == Look::Top::Coat) rider.top = Look::Top::Jacket;
  const PersonModel& person = lib.person_model(rider, SemanticClass::Rider);
  Actor on{std::uint16_t(instance + 1), {}, [track](double t) { return track->pose(t); }};
  on.parts.push_back({person.mesh, [](double) { return Pose::Identity(); },
                      riding(person, model, track), lib.person_slots(rider, random.bits())});
  actors.push_back(std::move(on));
  return actors;
}

std::vector<Actor> ActorLibrary::pack_vehicle(std::shared_ptr<const Mesh> body,
                                              const PackModel& pack, std::uint16_t instance,
                                              std::shared_ptr<const Track> track) {
  Impl& lib = *impl_;
  Actor actor{instance, {}, [track](double t) { return track->pose(t); }};
  actor.parts.push_back({body, [](double) { return Pose::Identity(); }});
  if (!pack.axles.empty()) {
    VehicleModel wheels;
    wheels.family = Family::Saloon;
    const int left = add_wheel_meshes(wheels, pack.wheel_radius, pack.tyre_width, 0.62);
    for (double axle : pack.axles)
      for (int side : {1, -1})
        wheels.mounts.push_back({V3(axle, side * pack.track, pack.wheel_radius), axle > 0, false,
                                 side > 0 ? left : left + 1});
    wheels.wheelbase = pack.axles.front() - pack.axles.back();
    const std::vector<std::uint16_t> slots =
        lib.vehicle_slots(wheels, Livery::Plain, derived_seed(lib.seed, instance, 0x7061636bull));
    lib.add_running_gear(actor, wheels, slots, track, [](double) { return Pose::Identity(); });
  }
  return {std::move(actor)};
}

Actor ActorLibrary::ego(std::uint16_t instance, PoseTrack rig, std::shared_ptr<const Track> ego,
                        double height, const std::vector<Vec3>& cameras) {
  Impl& lib = *impl_;
  std::vector<V3> seen;  // the cameras in the body's frame (the rig's, lowered to the road)
  for (const Vec3& c : cameras) seen.push_back(c + V3(0, 0, height));
  std::optional<VehicleModel> chosen;
  for (Family family : {Family::Estate, Family::Hatchback})
    for (bool mirrors : {true, false}) {
      const VehicleModel model = build_vehicle(family, 0, mirrors);
      double sz = 1;  // lowered (to 85 %) under cameras above the roof
      for (const V3& c : seen)
        if (std::abs(c.x()) < model.length / 2 && std::abs(c.y()) < model.width / 2 &&
            c.z() > 0.85 * model.roof_z)
          sz = std::min(sz, (c.z() - 2 * kEgoClearance) / model.roof_z);
      for (double sx : {1.0, 0.95, 0.9, 0.85})
        for (double shift : {0.0, -0.1, 0.1, -0.2, 0.2, -0.3, 0.3}) {
          if (chosen || sz < 0.85) continue;
          VehicleModel candidate = fitted(model, sx, shift, sz, SemanticClass::EgoVehicle);
          if (std::all_of(seen.begin(), seen.end(),
                          [&](const V3& c) { return clear_of(*candidate.body, c, kEgoClearance); }))
            chosen = std::move(candidate);
        }
    }
  if (!chosen) {
    std::string where;
    for (const V3& c : seen)
      where += " (" + std::to_string(c.x()) + ", " + std::to_string(c.y()) + ", " +
               std::to_string(c.z() - height) + ")";
    throw std::invalid_argument(
        "no ego vehicle fits round the rig's cameras at" + where +
        " (rig frame, m): each must be " + std::to_string(kEgoClearance) +
        " m outside the car; move them or leave the ego undrawn (--no-ego)");
  }
  const VehicleModel& model = *chosen;
  const Pose lowered(Eigen::Translation3d(0, 0, -height));
  Actor actor{instance, {}, [rig, lowered](double t) { return Pose(rig(t) * lowered); }};
  const std::vector<std::uint16_t> slots =
      lib.vehicle_slots(model, Livery::Plain, derived_seed(lib.seed, instance, 0x65676full));
  Part body{model.body, [](double) { return Pose::Identity(); }, {}, slots};
  body.on_rig = true;
  actor.parts.push_back(std::move(body));
  lib.add_running_gear(actor, model, slots, ego, [rig, ego, lowered](double t) {
    return Pose((rig(t) * lowered).inverse() * ego->pose(t));
  });
  return actor;
}

Actor ActorLibrary::pedestrian(std::uint16_t instance, std::shared_ptr<const Track> track,
                               double speed, bool child, const Mesh* user_model,
                               std::optional<double> gait_phase) {
  if (user_model) {
    Actor actor{instance, {}, [track](double t) { return track->pose(t); }};
    actor.parts.push_back(rigid_part(*user_model));
    return actor;
  }
  Random random(derived_seed(impl_->seed, instance, 0x706572736f6eull));  // "person"
  return person_of(random_look(random, child, impl_->wet), instance, std::move(track), speed,
                   gait_phase);
}

Actor ActorLibrary::standing_person(std::uint16_t instance, std::shared_ptr<const Track> still,
                                    bool child, const Mesh* user_model) {
  return pedestrian(instance, std::move(still), 0, child, user_model, assets::kStandingPhase);
}

Actor ActorLibrary::person_of(const Look& look, std::uint16_t instance,
                              std::shared_ptr<const Track> track, double speed,
                              std::optional<double> gait_phase) {
  Impl& lib = *impl_;
  const std::uint64_t id = derived_seed(lib.seed, instance, 0x636c6f74686573ull);  // "clothes"
  Actor actor{instance, {}, [track](double t) { return track->pose(t); }};
  const PersonModel& person = lib.person_model(look, SemanticClass::Pedestrian);
  Gait gait = gait_for(person.skeleton, speed, id, look.umbrella);
  if (gait_phase) gait.phase = *gait_phase;
  actor.parts.push_back({person.mesh, [](double) { return Pose::Identity(); },
                         walking(person, track, gait), lib.person_slots(look, id)});
  return actor;
}

// Two low beams, one at the centre of each side's head-lamp glass (the vehicle's frame: x
// forward, y left), 12 000 cd, aimed 2 degrees down with a 6-20 degree edge: the road ahead lit
// from a few metres on, as a dipped beam's cut-off keeps it.
std::vector<Lamp> ActorLibrary::head_lamps(const Actor& vehicle, int actor_index) const {
  Eigen::Vector3d sums[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  double weights[2] = {0, 0};
  for (const Part& part : vehicle.parts) {
    const Pose pose = part.pose(0);
    for (std::size_t t = 0; t < part.mesh->triangles.size(); ++t) {
      if (part_material(part, t) != impl_->head_lamp) continue;
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k)
        centre += pose * part.mesh->vertices[part.mesh->triangles[t][k]].cast<double>() / 3;
      sums[centre.y() > 0] += centre, weights[centre.y() > 0] += 1;
    }
  }
  std::vector<Lamp> lamps;
  for (int side = 0; side < 2; ++side) {
    if (weights[side] == 0) continue;
    Lamp beam;
    beam.position = sums[side] / weights[side] + Eigen::Vector3d(0.05, 0, 0);  // before the glass
    beam.axis = Eigen::Vector3d(1, 0, -std::tan(2 * kPi / 180)).normalized();
    beam.cos_inner = std::cos(6 * kPi / 180), beam.cos_outer = std::cos(20 * kPi / 180);
    beam.intensity = Eigen::Vector3f(1.0f, 0.97f, 0.9f) * 0.12f;
    beam.actor = actor_index;
    lamps.push_back(beam);
  }
  return lamps;
}

void ActorLibrary::switch_off_lamps(Actor& vehicle) const {
  for (Part& part : vehicle.parts)
    for (std::uint16_t& material : part.materials) {
      if (material == impl_->head_lamp) material = impl_->dark_head_lamp;
      if (material == impl_->tail_lamp) material = impl_->dark_tail_lamp;
      if (material == impl_->marker) material = impl_->indicator;  // the same amber, unlit
    }
}

}  // namespace flowscape
