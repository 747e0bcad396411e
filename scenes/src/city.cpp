// A city: its map and world, its traffic and actors (city_spawn, city_actors), the rig on its ego.
#include "flowscape/scenes/city.h"

#include <memory>

#include "city_actors.h"
#include "city_layout.h"
#include "city_spawn.h"
#include "city_world.h"
#include "flowscape/scenes/model_io.h"
#include "standing.h"
#include "traffic.h"

namespace flowscape {
namespace {

// A city of a user's world model: its static world and scripted actors, no roads and no traffic.
City make_world_city(const CityConfig& config) {
  City city;
  city.config = config;
  city.scene.world = load_world(*config.world, city.scene);
  city.area_at = [](const Eigen::Vector2d&) { return Area::Outside; };
  city.ground_height = [](const Eigen::Vector2d&) { return 0.0; };
  city.ego_spawn = {-1, 0, Pose::Identity()};
  city.ego = fixed_pose();
  city.ego_distance = [](double) { return 0.0; };
  city.mount = random_mount(config.seed);
  ActorLibrary library(city.scene, config.seed, config.wet);
  add_scripted_actors(user_models(config, city.scene), library, city);
  add_head_lamps(library, city);
  return city;
}

}  // namespace

City make_city(const CityConfig& config) {
  validate(config);
  if (config.world) return make_world_city(config);
  auto layout = std::make_shared<const Layout>(make_layout(config.map, config.seed));
  City city;
  city.config = config;
  city.solids = build_world(*layout, config.seed, city.scene);
  const std::map<ActorKind, Mesh> models = user_models(config, city.scene);
  const bool legacy = config.actors == ActorStyle::Legacy;
  std::vector<Pose> parked;
  park_cars(*layout, config.seed, city, [&](const Pose& pose, Random& random) {
    if (legacy)
      add_legacy_parked_vehicle(ActorKind::Car, pose, user_model_of(models, ActorKind::Car), random,
                                city.scene);
    else
      parked.push_back(pose);
  });
  city.start_points = start_points(*layout);
  city.area_at = [layout](const Eigen::Vector2d& p) { return layout->area(p); };
  city.ground_height = [layout](const Eigen::Vector2d& p) { return layout->height(p); };
  const std::vector<SidewalkLoop> loops = sidewalk_loops(*layout);
  PlacedTraffic traffic = place_traffic(*layout, loops, city.start_points, config);
  city.ego_spawn = traffic.ego, city.ego_tries = traffic.tries;
  const auto ego = std::make_shared<const Track>(traffic.tracks.vehicles[0]);
  city.ego = [ego](double t) { return ego->pose(t); };
  city.ego_distance = [ego](double t) { return ego->distance_at(t); };
  city.mount = random_mount(config.seed);
  const std::vector<StandingPerson> standing =
      place_standing(*layout, traffic.tracks, config.standing, config.seed, config.wet);
  if (legacy) {
    add_legacy_actors(traffic, models, traffic.random, city);
    add_legacy_standing(standing, models, traffic.random, city);
    return city;
  }
  ActorLibrary library(city.scene, config.seed, config.wet);
  add_detailed_actors(traffic, models, parked, library, city);
  add_standing(standing, models, library, city);
  add_scripted_actors(models, library, city);
  add_head_lamps(library, city);
  return city;
}

}  // namespace flowscape
