// The detailed actor models (scenes/src/assets, internal): closed, outward-facing bodies, feet
// that stay put while they bear weight, riders on their bikes, parked vehicles and the ego as
// actors with instances.
#include <catch2/catch.hpp>
#include <map>
#include <set>

#include "assets/gait.h"
#include "assets/loft.h"
#include "assets/people.h"
#include "assets/vehicles.h"
#include "flowscape/scenes/actors.h"
#include "flowscape/scenes/city.h"
#include "flowscape/scenes/shapes.h"
#include "flowscape/scenes/skinning.h"

using namespace flowscape;
using namespace flowscape::assets;

namespace {

// The connected parts of a mesh (triangles sharing a welded vertex), each as a mesh.
std::vector<Mesh> components(const Mesh& mesh) {
  std::map<std::array<float, 3>, int> ids;
  std::vector<int> id(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    id[v] = ids.try_emplace({mesh.vertices[v].x(), mesh.vertices[v].y(), mesh.vertices[v].z()},
                            int(ids.size()))
                .first->second;
  std::vector<int> parent(ids.size());
  for (std::size_t k = 0; k < parent.size(); ++k) parent[k] = int(k);
  const std::function<int(int)> root = [&](int k) {
    return parent[std::size_t(k)] == k ? k : parent[std::size_t(k)] = root(parent[std::size_t(k)]);
  };
  for (const Eigen::Vector3i& t : mesh.triangles)
    for (int c = 1; c < 3; ++c) parent[std::size_t(root(id[t[c]]))] = root(id[t[0]]);
  std::map<int, Mesh> parts;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    Mesh& part = parts[root(id[mesh.triangles[t][0]])];
    for (int c = 0; c < 3; ++c) part.vertices.push_back(mesh.vertices[mesh.triangles[t][c]]);
    const int n = int(part.vertices.size());
    part.triangles.emplace_back(n - 3, n - 2, n - 1);
  }
  std::vector<Mesh> out;
  for (auto& [root_id, part] : parts) out.push_back(std::move(part));
  return out;
}

std::size_t largest(const std::vector<Mesh>& parts) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < parts.size(); ++k)
    if (parts[k].triangles.size() > parts[best].triangles.size()) best = k;
  return best;
}

// Map 0 with `vehicles` and `pedestrians` for `duration` seconds, from `seed`.
City map0_city(std::uint64_t seed, int vehicles, int pedestrians, double duration) {
  CityConfig config;
  config.map = 0, config.seed = seed, config.vehicles = vehicles, config.pedestrians = pedestrians;
  config.duration = duration;
  return make_city(config);
}

// The centres of `mesh`'s triangles drawn with `slot`.
std::vector<Vec3> slot_centres(const Mesh& mesh, Slot slot) {
  std::vector<Vec3> centres;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    if (mesh.materials[t] == slot) {
      Vec3 c = Vec3::Zero();
      for (int k = 0; k < 3; ++k) c += mesh.vertices[mesh.triangles[t][k]].cast<double>() / 3;
      centres.push_back(c);
    }
  return centres;
}

}  // namespace

TEST_CASE("every vehicle's shell and wheels are closed and face outwards") {
  for (int f = 0; f < kFamilies; ++f)
    for (int variant = 0; variant < kVariants; ++variant) {
      const Family family = Family(f);
      INFO(family_name(family) << " variant " << variant);
      const VehicleModel model = build_vehicle(family, variant);
      if (family != Family::Bicycle && family != Family::Motorbike) {
        // the lofted shell: the body's largest part (lorries and trucks: the cab's)
        const std::vector<Mesh> parts = components(*model.body);
        const Closure shell = closure(parts[largest(parts)]);
        CHECK(shell.watertight);
        CHECK(shell.volume > 0.5);
      }
      for (const auto& wheel : model.wheels)
        for (const Mesh& part : components(*wheel)) {
          const Closure c = closure(part);
          CHECK(c.watertight);
          CHECK(c.volume > 0);
        }
      CHECK(model.length > 1.5);
      CHECK(model.body->classes.front() == family_class(family));
    }
}

TEST_CASE("a person's body, limbs, hands, head and shoes are closed and face outwards") {
  Random random(5);
  for (int k = 0; k < 12; ++k) {
    const Look look = random_look(random, k % 4 == 3, k % 3 == 0);
    const PersonModel person = build_person(look, SemanticClass::Pedestrian);
    INFO("person " << k);
    int closed = 0;
    for (const Mesh& part : components(*person.mesh)) {
      const Closure c = closure(part);
      if (!c.watertight) continue;  // hair, skirts and coats are open shells
      CHECK(c.volume > 0);
      ++closed;
    }
    CHECK(closed >= 12);  // torso, neck, head, nose, 2 ears, 2 eyes, 2 legs, 2 arms, 2 shoes...
    require_valid_skin(*person.mesh, kBones, "person");
  }
}

TEST_CASE("a walking foot does not slide while it bears weight, and the leg reaches it") {
  // a walker on a quarter circle of 6 m radius at 1.4 m/s, sampled as traffic samples
  Track track{1.0 / 60, {}, {}};
  const double radius = 6, speed = 1.4;
  for (int k = 0; k <= 600; ++k) {
    const double t = k * track.step, angle = speed * t / radius;
    Pose pose =
        Pose(Eigen::Translation3d(radius * std::sin(angle), radius * (1 - std::cos(angle)), 0.15)) *
        Pose(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
    track.poses.push_back(pose), track.distance.push_back(speed * t);
  }
  const auto shared = std::make_shared<const Track>(track);
  Random random(3);
  const PersonModel person =
      build_person(random_look(random, false, false), SemanticClass::Pedestrian);
  const Gait gait = gait_for(person.skeleton, speed, 11, false);
  const BoneTrack bones = walking(person, shared, gait);
  int planted_samples = 0;
  for (int side : {1, -1}) {
    bool was_planted = false;
    Vec3 last_contact = Vec3::Zero();
    for (double t = 0.5; t < 8; t += 1.0 / 240) {
      const FootState foot = foot_state(person.skeleton, gait, track, side, t);
      if (foot.planted) {
        ++planted_samples;
        // the point the foot rests or rolls on (heel, sole, ball) stays put: from one sample to
        // the next it is the same point, or the foot has rolled onto another (5 cm and more)
        if (was_planted) {
          const double moved = (foot.contact_world - last_contact).norm();
          CHECK((moved == 0 || moved > 0.05));
        }
        last_contact = foot.contact_world;
      }
      was_planted = foot.planted;
      // the skinned leg reaches the ankle the gait asks for
      const std::vector<Pose> posed = bones(t);
      const int bone = side > 0 ? kFootL : kFootR;
      const Vec3 ankle =
          shared->pose(t) * (posed[std::size_t(bone)] * person.skeleton.joints[std::size_t(bone)]);
      CHECK((ankle - foot.ankle_world).norm() < 0.02);
    }
  }
  CHECK(planted_samples > 1500);
}

TEST_CASE("riders ride their bikes, and parked vehicles and the ego are actors with boxes") {
  const City city = map0_city(4, 60, 30, 2);
  REQUIRE(city.actors.size() == city.scene.actors.size());
  int riders = 0, parked = 0, egos = 0;
  for (std::size_t a = 0; a < city.actors.size(); ++a) {
    const ActorRecord& record = city.actors[a];
    const Actor& actor = city.scene.actors[a];
    CHECK(actor.instance == a + 1);
    if (record.kind == ActorKind::Rider) {
      ++riders;
      const ActorKind bike = city.actors[a - 1].kind;
      CHECK((bike == ActorKind::Bike || bike == ActorKind::Motorbike));
      CHECK(actor_class(actor) == SemanticClass::Rider);
      for (double t : {0.0, 1.0, 2.0}) {  // the rider's hips stay over the bike
        const Box3 body = actor_box(actor, t), ride = actor_box(city.scene.actors[a - 1], t);
        CHECK((body.pose.translation() - ride.pose.translation()).head<2>().norm() < 0.6);
      }
    }
    if (record.parked) {
      ++parked;
      const Box3 box = actor_box(actor, 0);
      CHECK((box.size.x() > 3 && box.size.x() < 6));
      CHECK(actor.pose(0).matrix() == actor.pose(2).matrix());
    }
    if (record.ego) {
      ++egos;
      CHECK(record.instance == city.ego_instance);
      CHECK(actor_class(actor) == SemanticClass::EgoVehicle);
      CHECK(actor.parts.front().on_rig);
      for (double t : {0.0, 0.7, 1.9})  // the body rides with the rig, its height below it
        CHECK((actor.pose(t).inverse() * city.rig(t))
                  .translation()
                  .isApprox(Vec3(0, 0, city.mount.height), 1e-9));
    }
  }
  CHECK(riders > 0);
  CHECK(parked > 10);
  CHECK(egos == 1);
}

TEST_CASE("a bus's windows are lit from inside at night, other vehicles' are not") {
  const City city = map0_city(4, 60, 0, 0.2);
  int buses = 0, others = 0;
  for (std::size_t a = 0; a < city.actors.size(); ++a) {
    const ActorKind kind = city.actors[a].kind;
    if (kind == ActorKind::Pedestrian || kind == ActorKind::Rider) continue;
    const Material& glass =
        city.scene.materials[city.scene.actors[a].parts.front().materials[assets::kGlass]];
    CHECK(glass.kind == Material::Kind::Window);  // a pane by day, seen through
    const bool bus = kind == ActorKind::Bus;
    ++(bus ? buses : others);
    CHECK(glass.night_emission.isZero() == !bus);  // glows once the lamps are on
  }
  CHECK(buses > 0);
  CHECK(others > 10);
}

TEST_CASE("trucks carry amber side markers at most 3 m apart, lit at night; bicycles a rear lamp") {
  for (Family family : {Family::BoxTruck, Family::Lorry}) {
    const VehicleModel model = build_vehicle(family, 0, true);
    const Mesh& cargo = family == Family::Lorry ? *model.trailer : *model.body;
    double rear = 0;
    for (const Eigen::Vector3f& v : cargo.vertices) rear = std::min(rear, double(v.x()));
    for (double side : {-1.0, 1.0}) {
      std::set<double> along;  // the markers' x on this side, a lamp's triangles merged
      for (const Vec3& c : slot_centres(cargo, kMarker))
        if (c.y() * side > 1.2) along.insert(std::round(c.x() * 10) / 10);
      CAPTURE(family_name(family), side);
      REQUIRE(along.size() >= 3);
      CHECK(*along.begin() - rear < 1.0);
      for (auto x = along.begin(); std::next(x) != along.end(); ++x)
        CHECK(*std::next(x) - *x <= 3.0);
    }
  }
  // a bicycle's rear lamp: behind the seat post, below the saddle
  const VehicleModel bicycle = build_vehicle(Family::Bicycle, 0, true);
  const std::vector<Vec3> rear_lamp = slot_centres(*bicycle.body, kTailLamp);
  REQUIRE(!rear_lamp.empty());
  for (const Vec3& c : rear_lamp) CHECK((c.x() < -0.15 && c.z() > 0.7 && c.z() < 1.0));
  const City city = map0_city(4, 60, 0, 0.2);
  int trucks = 0;
  for (std::size_t a = 0; a < city.actors.size(); ++a) {
    const ActorKind kind = city.actors[a].kind;
    if (kind != ActorKind::Truck && kind != ActorKind::Lorry) continue;
    ++trucks;
    const Eigen::Vector3f glow =
        city.scene.materials[city.scene.actors[a].parts.front().materials[kMarker]].night_emission;
    CHECK((glow.x() > glow.y() && glow.y() > glow.z() && glow.z() >= 0));  // amber
    CHECK(glow.x() > 0);
  }
  CHECK(trucks > 0);
}

TEST_CASE("each built-in vehicle's record names the family whose model it shows") {
  const City city = map0_city(5, 80, 6, 0.2);
  std::map<std::string, ActorKind> kind_of;  // each family's traffic kind
  for (int f = 0; f < kFamilies; ++f) {
    const std::string name = family_name(Family(f));
    kind_of[name] = name == "city_bus"    ? ActorKind::Bus
                    : name == "box_truck" ? ActorKind::Truck
                    : name == "lorry"     ? ActorKind::Lorry
                    : name == "motorbike" ? ActorKind::Motorbike
                    : name == "bicycle"   ? ActorKind::Bike
                                          : ActorKind::Car;
  }
  std::set<std::string> seen;
  for (std::size_t a = 0; a < city.actors.size(); ++a) {
    const ActorRecord& record = city.actors[a];
    const bool built_in_vehicle =
        record.kind != ActorKind::Pedestrian && record.kind != ActorKind::Rider && !record.ego;
    CHECK(record.family.empty() == !built_in_vehicle);
    if (!built_in_vehicle) continue;
    REQUIRE(kind_of.count(record.family) == 1);
    CHECK(kind_of[record.family] == record.kind);
    // the actor is as long as one of its family's variants (a lorry's trailer swings: 1 m)
    const Box3 box = actor_box(city.scene.actors[a], 0);
    bool fits = false;
    for (int f = 0; f < kFamilies; ++f)
      if (family_name(Family(f)) == record.family)
        for (int variant = 0; variant < kVariants; ++variant)
          fits = fits || std::abs(box.size.x() - build_vehicle(Family(f), variant).length) <
                             (record.kind == ActorKind::Lorry ? 1.0 : 0.12);
    CAPTURE(record.family, box.size.x());
    CHECK(fits);
    seen.insert(record.family);
  }
  CHECK(seen.count("van") == 1);
  CHECK(seen.size() >= 6);
}

TEST_CASE("no ego vehicle fits cameras inside the car: the rig is refused, naming them") {
  CityConfig config;
  config.map = 0, config.vehicles = 2, config.pedestrians = 0, config.duration = 0.5;
  config.ego_cameras = {Vec3(0.5, 0, -1.0)};  // in the cabin
  CHECK_THROWS_WITH(make_city(config), Catch::Contains("no ego vehicle fits") &&
                                           Catch::Contains("(0.500000, 0.000000, -1.000000)"));
  config.draw_ego = false;
  CHECK_NOTHROW(make_city(config));
}
