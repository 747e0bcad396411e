// People standing on the pavements (CityConfig::standing) and the maps' street life.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "flowscape/scenes/city.h"
#include "flowscape/scenes/skinning.h"
#include "footprint.h"

using namespace flowscape;
using V2 = Eigen::Vector2d;

namespace {

constexpr double kFrame = 1 / kFrameRate, kPavementLift = 0.15;  // the kerb's height

// Map `map` with its own street life for 60 frames.
City street(int map, std::uint64_t seed, bool wet = false) {
  CityConfig config;
  config.map = map, config.seed = seed, config.vehicles = 120, config.wet = wet;
  const StreetLife life = street_life(map);
  config.pedestrians = life.walking, config.standing = life.standing;
  config.ego_start = 5 * map, config.ego_route = EgoRoute::Drive, config.duration = 61 * kFrame;
  return make_city(config);
}

// The lowest point of an actor's posed triangles at time t.
double lowest(const Actor& actor, double t) {
  double bottom = 1e9;
  for (const Part& part : actor.parts)
    for (const Eigen::Vector3d& v : part_vertices_at(part, t))
      bottom = std::min(bottom, (actor.pose(t) * v).z());
  return bottom;
}

bool inside(const test::Box2& box, const V2& p) {
  for (int k = 0; k < 2; ++k)
    if (std::abs(box.axis[k].dot(p - box.centre)) >= box.half[k]) return false;
  return true;
}

std::vector<std::size_t> people_standing(const City& city) {
  std::vector<std::size_t> out;
  for (std::size_t a = 0; a < city.actors.size(); ++a)
    if (city.actors[a].standing) out.push_back(a);
  return out;
}

}  // namespace

TEST_CASE(
    "people standing stay put on the pavement, clear of the road, poles, facades and "
    "everyone passing") {
  for (int map = 0; map < kMapCount; ++map)
    for (bool wet : {false, true}) {
      if (wet && map != 0) continue;  // umbrellas: the busiest map
      const City city = street(map, 3, wet);
      INFO("map " << map_name(map) << (wet ? ", wet" : ""));
      const std::vector<std::size_t> standing = people_standing(city);
      REQUIRE(int(standing.size()) == street_life(map).standing);
      std::vector<V2> furniture;  // poles, signals, signs and building walls
      const Mesh& world = city.scene.world;
      for (std::size_t t = 0; t < world.triangles.size(); ++t) {
        const SemanticClass c = world.classes[t];
        if (c == SemanticClass::Pole || c == SemanticClass::TrafficLight ||
            c == SemanticClass::TrafficSign || c == SemanticClass::Building)
          for (int k = 0; k < 3; ++k)
            furniture.push_back(world.vertices[world.triangles[t][k]].head<2>().cast<double>());
      }
      for (int frame : {0, 30, 60}) {
        const double t = frame * kFrame;
        std::vector<std::array<V2, 4>> people;
        for (std::size_t a = 0; a < city.actors.size(); ++a)
          if (city.actors[a].kind == ActorKind::Pedestrian)
            people.push_back(test::corners(test::footprint(city.scene.actors[a], t)));
        for (std::size_t a : standing) {
          const Actor& actor = city.scene.actors[a];
          INFO("actor " << a << ", frame " << frame);
          REQUIRE(actor.pose(t).isApprox(actor.pose(0), 1e-12));
          const test::Box2 me = test::footprint(actor, t);
          for (const V2& corner : test::corners(me))
            REQUIRE(city.area_at(corner) == Area::SideWalk);
          const V2 middle = actor.pose(t).translation().head<2>();
          // feet flat on the pavement (on a hill the feet stand a little off its height here)
          CHECK(std::abs(lowest(actor, t) - city.ground_height(middle) - kPavementLift) < 0.02);
          REQUIRE(std::none_of(furniture.begin(), furniture.end(),
                               [&](const V2& p) { return inside(me, p); }));
          int met = 0;  // its own footprint, and nobody else's
          for (const auto& other : people) met += test::overlap(test::corners(me), other);
          REQUIRE(met == 1);
        }
      }
    }
}

TEST_CASE("a group stands round its middle, each facing it") {
  const City city = street(0, 11);
  const std::vector<std::size_t> standing = people_standing(city);
  const auto at = [&](std::size_t a) {
    return V2(city.scene.actors[a].pose(0).translation().head<2>());
  };
  int grouped = 0;
  for (std::size_t a : standing) {
    std::vector<V2> group;  // within a metre of it: its group (groups stand 1.2 m apart or more)
    for (std::size_t b : standing)
      if ((at(b) - at(a)).norm() < 1.0) group.push_back(at(b));
    if (group.size() < 2) continue;
    ++grouped;
    V2 middle = V2::Zero();
    for (const V2& p : group) middle += p / double(group.size());
    const V2 forward = city.scene.actors[a].pose(0).linear().col(0).head<2>().normalized();
    INFO("actor " << a << " in a group of " << group.size());
    CHECK(forward.dot((middle - at(a)).normalized()) > std::cos(0.35));
  }
  CHECK(grouped >= 4);
}

TEST_CASE("the maps' street life: downtown busy, rural sparse, people within the 200") {
  CHECK(people_on_foot(0, 120, -1, -1).walking == street_life(0).walking);
  CHECK(people_on_foot(0, 120, -1, -1).standing == street_life(0).standing);
  // 150 vehicles leave room for 50 people of downtown's 56 + 24, in that proportion
  CHECK(people_on_foot(0, 150, -1, -1).walking == 56 * 50 / 80);
  CHECK(people_on_foot(0, 150, -1, -1).standing == 24 * 50 / 80);
  CHECK(people_on_foot(0, 120, 10, -1).standing == 4);  // 10 x 24 / 56, rounded
  CHECK(people_on_foot(0, 190, 10, -1).standing == 0);  // no room left
  CHECK(people_on_foot(0, 120, 10, 7).standing == 7);
  CHECK(people_on_foot(0, 180, -1, 10).walking == 10);  // the 10 left of 20
  CHECK(people_on_foot(kUserWorldMap, 0, -1, -1).walking == 0);
  // people within 30 m of the ego, three sequences each
  const auto near_the_ego = [](int map) {
    int count = 0;
    for (std::uint64_t seed : {1, 2, 3}) {
      const City city = street(map, seed);
      for (std::size_t a = 0; a < city.actors.size(); ++a)
        count += city.actors[a].kind == ActorKind::Pedestrian &&
                 (city.scene.actors[a].pose(0).translation() - city.ego(0).translation())
                         .head<2>()
                         .norm() < 30;
    }
    return count;
  };
  const int downtown = near_the_ego(0), rural = near_the_ego(3);
  INFO("downtown " << downtown << ", rural " << rural);
  CHECK(downtown > 4 * rural);
  CHECK(rural > 0);
  CityConfig config;
  config.vehicles = 120, config.pedestrians = 56, config.standing = 25;
  CHECK_THROWS_WITH(validate(config), Catch::Contains("asked for 201"));
  config.standing = -1;
  CHECK_THROWS_WITH(validate(config), Catch::Contains("must not be negative"));
}

TEST_CASE("a city's record lists its people standing and rebuilds them") {
  const City city = street(5, 2);
  const nlohmann::json record = to_json(city);
  CHECK(record.at("standing") == street_life(5).standing);
  int listed = 0;
  for (const auto& actor : record.at("actors"))
    if (actor.value("standing", false)) {
      ++listed;
      CHECK(actor.at("lane") == -1);
      CHECK(actor.at("speed") == 0);
    }
  CHECK(listed == street_life(5).standing);
  const City again = city_from_record(record);
  CHECK(to_json(again) == record);
  nlohmann::json older = record;  // a record from before people stood
  older.erase("standing");
  CHECK_THROWS_WITH(city_from_record(older), Catch::Contains("other actors"));
  CHECK(config_from_json(older).standing == 0);
}
