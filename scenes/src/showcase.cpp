#include "flowscape/scenes/showcase.h"

#include <stdexcept>

#include "city_materials.h"
#include "city_models.h"
#include "flowscape/scenes/actors.h"
#include "flowscape/scenes/shapes.h"

namespace flowscape {
namespace {

using assets::Family;
using assets::Livery;
using assets::Look;

struct VehicleEntry {
  const char* name;
  Family family;
  Livery livery;
};
const VehicleEntry kVehicles[] = {
    {"hatchback", Family::Hatchback, Livery::Plain}, {"saloon", Family::Saloon, Livery::Plain},
    {"estate", Family::Estate, Livery::Plain},       {"suv", Family::Suv, Livery::Plain},
    {"pickup", Family::Pickup, Livery::Plain},       {"van", Family::Van, Livery::Plain},
    {"taxi", Family::Saloon, Livery::Taxi},          {"police", Family::Estate, Livery::Police},
    {"delivery_van", Family::Van, Livery::Delivery}, {"city_bus", Family::CityBus, Livery::Plain},
    {"box_truck", Family::BoxTruck, Livery::Plain},  {"lorry", Family::Lorry, Livery::Plain},
    {"motorbike", Family::Motorbike, Livery::Plain}, {"bicycle", Family::Bicycle, Livery::Plain}};
const char* const kPeople[] = {"man", "woman", "child", "umbrella", "jogger"};

// A straight track along +x through the origin at `speed`, sampled as traffic samples it.
std::shared_ptr<const Track> straight(double speed, double through_at) {
  Track track{1.0 / 60, {}, {}};
  for (int k = 0; k <= 600; ++k) {
    const double t = k * track.step, d = speed * t;
    track.poses.push_back(Pose(Eigen::Translation3d(d - speed * through_at, 0, 0)));
    track.distance.push_back(d);
  }
  return std::make_shared<const Track>(std::move(track));
}

Look person_look(const std::string& name, int variant) {
  std::uint64_t seed = std::uint64_t(variant);
  for (char c : name) seed = mix_bits(seed * 131 + std::uint64_t(c));
  Random random(seed);
  Look look = assets::random_look(random, name == "child", name == "umbrella");
  if (name == "man" || name == "jogger") look.female = false, look.height = 1.78 + 0.05 * variant;
  if (name == "woman") look.female = true, look.height = 1.66 + 0.04 * variant;
  if (name == "umbrella") look.umbrella = true, look.top = Look::Top::Coat;
  if (name == "jogger") look.top = Look::Top::TShirt, look.bottom = Look::Bottom::Shorts;
  return look;
}

}  // namespace

std::vector<std::string> showcase_models() {
  std::vector<std::string> names;
  for (const VehicleEntry& v : kVehicles) names.push_back(v.name);
  names.insert(names.end(), std::begin(kPeople), std::end(kPeople));
  return names;
}

Showcase showcase(const std::string& name, int variant) {
  Showcase out;
  Scene& scene = out.scene;
  Mesh ground;
  const Paint asphalt{SemanticClass::Road, add_material(scene, city_materials::asphalt(5))};
  add_quad(ground, {-60, -60, 0}, {60, -60, 0}, {60, 60, 0}, {-60, 60, 0}, asphalt);
  scene.world = std::move(ground);
  std::uint64_t seed = std::uint64_t(variant);
  for (char c : name) seed = mix_bits(seed * 131 + std::uint64_t(c));
  ActorLibrary library(scene, seed, name == "umbrella");
  for (const VehicleEntry& v : kVehicles)
    if (name == v.name)
      scene.actors = library.vehicle_of(v.family, variant % 3, v.livery, 1, straight(0, 0));
  for (const char* person : kPeople)
    if (name == person)
      scene.actors = {library.person_of(person_look(name, variant), 1,
                                        straight(name == "jogger" ? 3.2 : 1.3, 1.0),
                                        name == "jogger" ? 3.2 : 1.3)};
  if (scene.actors.empty()) throw std::invalid_argument("no built-in model \"" + name + "\"");
  scene.lamps = library.head_lamps(scene.actors.front(), 0);  // shining once the lamps are on
  for (const Actor& actor : scene.actors) {                   // a two-wheeler with its rider
    const Box3 box = actor_box(actor, 1.0);
    out.length = std::max(out.length, box.size.x());
    out.height = std::max(out.height, box.pose.translation().z() + box.size.z() / 2);
  }
  return out;
}

}  // namespace flowscape
