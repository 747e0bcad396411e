#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <set>

#include "flowscape/renderer/renderer.h"
#include "flowscape/scenes/city.h"
#include "flowscape/scenes/model_io.h"
#include "flowscape/scenes/skinning.h"
#include "footprint.h"
#include "temp_dir.h"

using namespace flowscape;
using V2 = Eigen::Vector2d;
using test::Box2, test::corners, test::footprint, test::overlap;

namespace {

constexpr double kFrame = 1 / kFrameRate;  // one frame

Box2 ego_footprint(const City& city, double t) {
  const Pose pose = city.ego(t);
  return {
      pose.translation().head<2>(),
      {pose.linear().col(0).head<2>().normalized(), pose.linear().col(1).head<2>().normalized()},
      {city.ego_size.x() / 2, city.ego_size.y() / 2}};
}

double yaw(const Pose& p) { return std::atan2(p.linear()(1, 0), p.linear()(0, 0)); }

// The traffic tests below watch the traffic simulation: with legacy actors (one box per road user,
// no riders, parked cars in the static world) what they measure is the traffic alone.
CityConfig busy(int map) {
  CityConfig config;
  config.actors = ActorStyle::Legacy;
  config.map = map, config.seed = 7, config.vehicles = 120, config.pedestrians = 80;
  config.duration = 100 * kFrame, config.ego_start = 11 * map;
  return config;
}

}  // namespace

TEST_CASE("the same seed gives the same city and another seed another one") {
  CityConfig config;
  config.map = 4, config.seed = 3, config.vehicles = 30, config.pedestrians = 20;
  const City a = make_city(config), b = make_city(config);
  CHECK(a.scene.world.vertices == b.scene.world.vertices);
  CHECK(a.scene.world.triangles == b.scene.world.triangles);
  CHECK(a.scene.world.classes == b.scene.world.classes);
  REQUIRE(a.scene.actors.size() == a.actors.size());
  int vehicles = 0, walkers = 0;
  for (const ActorRecord& r : a.actors) {
    vehicles +=
        r.kind != ActorKind::Pedestrian && r.kind != ActorKind::Rider && !r.parked && !r.ego;
    walkers += r.kind == ActorKind::Pedestrian;
  }
  CHECK(vehicles == 30);
  CHECK(walkers == 20);
  for (double t : {0.0, 1.0, 2.5})
    for (std::size_t k = 0; k < a.scene.actors.size(); ++k)
      CHECK(a.scene.actors[k].pose(t).matrix() == b.scene.actors[k].pose(t).matrix());
  CHECK(a.ego(2.0).matrix() == b.ego(2.0).matrix());
  config.seed = 4;
  const City c = make_city(config);
  CHECK(c.scene.world.vertices != a.scene.world.vertices);
}

TEST_CASE("every map has 100-120 start points on its roads and classes on every triangle") {
  const std::set<SemanticClass> everywhere{SemanticClass::Road,     SemanticClass::RoadLine,
                                           SemanticClass::SideWalk, SemanticClass::Building,
                                           SemanticClass::Pole,     SemanticClass::Vegetation};
  std::set<SemanticClass> seen;
  std::set<std::vector<float>> first_vertices;
  for (int map = 0; map < kMapCount; ++map) {
    CityConfig config;
    config.map = map, config.vehicles = 20, config.pedestrians = 20;
    const City city = make_city(config);
    INFO("map " << map_name(map));
    CHECK(city.start_points.size() >= 100);
    CHECK(city.start_points.size() <= 120);
    for (const StartPoint& p : city.start_points)
      CHECK(city.area_at(p.pose.translation().head<2>()) == Area::Road);
    const auto check_mesh = [&](const Part& part) {
      const Mesh& mesh = *part.mesh;
      REQUIRE(mesh.classes.size() == mesh.triangles.size());
      REQUIRE(mesh.materials.size() == mesh.triangles.size());
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        REQUIRE(int(mesh.classes[t]) < kSceneClasses);
        REQUIRE(mesh.classes[t] != SemanticClass::Unlabeled);
        REQUIRE(mesh.classes[t] != SemanticClass::Sky);
        REQUIRE(part_material(part, t) < city.scene.materials.size());
        seen.insert(mesh.classes[t]);
      }
    };
    std::set<SemanticClass> classes_here;
    check_mesh(rigid_part(city.scene.world));
    for (SemanticClass c : city.scene.world.classes) classes_here.insert(c);
    for (SemanticClass c : everywhere) CHECK(classes_here.count(c) == 1);
    for (const Actor& actor : city.scene.actors)
      for (const Part& part : actor.parts) check_mesh(part);
    first_vertices.insert({city.scene.world.vertices[40].x(), city.scene.world.vertices[40].y()});
  }
  CHECK(first_vertices.size() == kMapCount);  // eight different maps
  for (SemanticClass c :
       {SemanticClass::Car, SemanticClass::Pedestrian, SemanticClass::Fence,
        SemanticClass::TrafficLight, SemanticClass::TrafficSign, SemanticClass::GuardRail,
        SemanticClass::Water, SemanticClass::Terrain, SemanticClass::RailTrack,
        SemanticClass::Bridge, SemanticClass::Wall, SemanticClass::Static, SemanticClass::Ground}) {
    INFO("class " << class_name(c));
    CHECK(seen.count(c) == 1);
  }
}

TEST_CASE(
    "over 100 frames no actor meets a building or another actor and all keep to their ground") {
  for (int map = 0; map < kMapCount; ++map) {
    const City city = make_city(busy(map));
    INFO("map " << map_name(map));
    // the solid footprints cover every building vertex (windows sit 3 cm proud of the walls)
    for (std::size_t t = 0; t < city.scene.world.triangles.size(); t += 7) {
      if (city.scene.world.classes[t] != SemanticClass::Building) continue;
      const V2 p =
          city.scene.world.vertices[city.scene.world.triangles[t][0]].head<2>().cast<double>();
      const bool inside = std::any_of(city.solids.begin(), city.solids.end(), [&](auto& f) {
        return p.x() >= f[0].x() - 0.05 && p.x() <= f[2].x() + 0.05 && p.y() >= f[0].y() - 0.05 &&
               p.y() <= f[2].y() + 0.05;
      });
      REQUIRE(inside);
    }
    int moving = 0;
    for (int frame = 0; frame <= 100; frame += 2) {
      const double t = frame * kFrame;
      std::vector<std::array<V2, 4>> boxes{corners(ego_footprint(city, t))};
      std::vector<bool> walker{false};
      for (std::size_t a = 0; a < city.scene.actors.size(); ++a) {
        boxes.push_back(corners(footprint(city.scene.actors[a], t)));
        walker.push_back(city.actors[a].kind == ActorKind::Pedestrian);
      }
      for (std::size_t a = 0; a < boxes.size(); ++a) {
        for (const V2& c : boxes[a]) {
          const Area area = city.area_at(c);
          INFO("actor " << a << ", frame " << frame << ", corner " << c.transpose());
          if (walker[a])
            REQUIRE((area == Area::SideWalk || area == Area::Crossing));
          else
            REQUIRE((area == Area::Road || area == Area::Junction || area == Area::Crossing));
        }
        for (const auto& solid : city.solids) REQUIRE_FALSE(overlap(boxes[a], solid));
        for (std::size_t b = a + 1; b < boxes.size(); ++b) {
          INFO("frame " << frame << ", actors " << a << " and " << b);
          REQUIRE_FALSE(overlap(boxes[a], boxes[b]));
        }
      }
    }
    for (const Actor& actor : city.scene.actors)
      moving += (actor.pose(100 * kFrame).translation() - actor.pose(0).translation()).norm() > 1;
    CHECK(moving > int(city.scene.actors.size()) / 3);
  }
}

TEST_CASE("vehicles stop at junctions and go on and pedestrians swing their limbs") {
  CityConfig config;
  config.actors = ActorStyle::Legacy;  // (the traffic, and legacy walkers' swinging limbs)
  config.map = 0, config.seed = 1, config.vehicles = 60, config.pedestrians = 10;
  config.duration = 40;
  const City city = make_city(config);
  int stopped_then_moved = 0;
  for (std::size_t a = 0; a < city.scene.actors.size(); ++a) {
    if (city.actors[a].kind == ActorKind::Pedestrian) continue;
    const Actor& actor = city.scene.actors[a];
    bool stopped = false;
    for (double t = 1; t < 39; t += 0.5) {
      const double speed =
          (actor.pose(t + 0.5).translation() - actor.pose(t).translation()).norm() / 0.5;
      if (speed < 0.05)
        stopped = true;
      else if (stopped && speed > 3) {
        ++stopped_then_moved;
        break;
      }
    }
  }
  CHECK(stopped_then_moved > 5);
  // several vehicles cross a junction together where their ways do not meet (the footprint test
  // above shows they never touch): two vehicles in the junction area within 25 m of each other
  int shared = 0;
  for (double t = 0; t < 39; t += 0.5) {
    std::vector<Eigen::Vector2d> inside;
    for (std::size_t a = 0; a < city.scene.actors.size(); ++a) {
      const Eigen::Vector2d p = city.scene.actors[a].pose(t).translation().head<2>();
      if (city.actors[a].kind != ActorKind::Pedestrian && city.area_at(p) == Area::Junction)
        inside.push_back(p);
    }
    for (std::size_t i = 0; i < inside.size(); ++i)
      for (std::size_t k = i + 1; k < inside.size(); ++k)
        shared += (inside[i] - inside[k]).norm() < 25;
  }
  CHECK(shared > 10);
  for (std::size_t a = 0; a < city.scene.actors.size(); ++a) {
    if (city.actors[a].kind != ActorKind::Pedestrian) continue;
    const Actor& walker = city.scene.actors[a];
    REQUIRE(walker.parts.size() > 1);
    const Part& leg = walker.parts[1];  // a limb moves relative to the body
    CHECK((leg.pose(0.2).linear() - leg.pose(0.6).linear()).norm() > 0.01);
  }
}

TEST_CASE("vehicles change lanes on multi-lane roads, sideways by exactly one lane") {
  // Roads run along x or y (but one diagonal street) and lanes are straight: between junctions a
  // vehicle heads off its road's axis only while it changes lanes, at most atan(3.5 * 1.875 / 20)
  // = 18 degrees off (or rounds a bend at a map's corner, ending on the other axis, or takes the
  // diagonal, 45 degrees off), and from the last frame on one lane's axis to the first on the
  // other's it moves 3.5 m (a lane's width) across the road.
  CityConfig config = busy(0);
  config.duration = 20;
  const City city = make_city(config);
  int changes = 0;
  for (std::size_t a = 0; a < city.scene.actors.size(); ++a) {
    if (city.actors[a].kind == ActorKind::Pedestrian) continue;
    const PoseTrack& track = city.scene.actors[a].pose;
    int start = -1;
    double most_off = 0;
    for (int frame = 1; frame < 600; ++frame) {
      const Pose p = track(frame * kFrame);
      const double off = std::abs(std::remainder(yaw(p), kPi / 2));
      const bool off_axis = city.area_at(p.translation().head<2>()) == Area::Road && off > 1e-6;
      if (off_axis && start < 0) start = frame - 1, most_off = 0;
      most_off = std::max(most_off, off);
      if (off_axis || start < 0) continue;
      const Pose before = track(start * kFrame);
      start = -1;
      if (std::abs(std::remainder(yaw(p) - yaw(before), 2 * kPi)) > 1e-6 ||
          most_off > 20 * kPi / 180)
        continue;  // a bend or the diagonal street
      CHECK(most_off < 18.5 * kPi / 180);
      const bool along_x = std::abs(std::cos(yaw(before))) > 0.5;
      const Eigen::Vector3d moved = p.translation() - before.translation();
      CHECK(std::abs(along_x ? moved.y() : moved.x()) == Approx(3.5).margin(1e-6));
      ++changes;
    }
  }
  CHECK(changes >= 5);
}

TEST_CASE("pedestrians cross roads on the crosswalks, and vehicles never meet them there") {
  for (const int map : {0, 4}) {  // lights and a roundabout (walkers have priority there)
    CityConfig config;
    config.actors = ActorStyle::Legacy;  // (the traffic: one box per road user)
    config.map = map, config.seed = 3, config.vehicles = 100, config.pedestrians = 100;
    config.duration = 40, config.ego_start = 5;
    const City city = make_city(config);
    INFO("map " << map_name(map));
    int crossing = 0;
    for (double t = 0; t < 40; t += 0.25) {
      std::vector<std::array<V2, 4>> walkers, vehicles{corners(ego_footprint(city, t))};
      for (std::size_t a = 0; a < city.scene.actors.size(); ++a) {
        const Box2 box = footprint(city.scene.actors[a], t);
        if (city.actors[a].kind != ActorKind::Pedestrian)
          vehicles.push_back(corners(box));
        else if (city.area_at(box.centre) == Area::Crossing)
          walkers.push_back(corners(box));
      }
      crossing += int(walkers.size());
      for (const auto& w : walkers)
        for (const auto& v : vehicles) REQUIRE_FALSE(overlap(w, v));
    }
    CHECK(crossing > 20);  // walker samples on a crosswalk
  }
}

TEST_CASE("user models from assimp's test set replace built-in actors") {
  const std::string gltf = "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf";
  const std::string obj = "/usr/share/assimp/models/OBJ/box.obj";
  REQUIRE(std::filesystem::exists(gltf));  // Debian's assimp-testmodels (scripts/install_deps.sh)
  Scene scene;
  const Mesh box = load_model(gltf, SemanticClass::Vehicles, 4.5, scene);
  CHECK(box.triangles.size() == 12);
  Eigen::Vector3f lo = box.vertices[0], hi = lo;
  for (const auto& v : box.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  CHECK(hi.x() - lo.x() == Approx(4.5));
  CHECK(lo.z() == Approx(0).margin(1e-6));
  CHECK((lo.x() + hi.x()) == Approx(0).margin(1e-5));
  CHECK(load_model(obj, SemanticClass::Pedestrian, 0.5, scene).triangles.size() == 12);
  CityConfig config;
  config.map = 1, config.vehicles = 20, config.pedestrians = 5, config.models = {{"car", gltf}};
  config.draw_ego = false;
  const City city = make_city(config);
  int replaced = 0;
  for (std::size_t a = 0; a < city.actors.size(); ++a)
    if (city.actors[a].kind == ActorKind::Car) {
      REQUIRE(city.scene.actors[a].parts.size() == 1);
      CHECK(city.scene.actors[a].parts[0].mesh->triangles.size() == 12);
      ++replaced;
    }
  CHECK(replaced > 0);
  TempDir dir;
  const std::string corrupt = (dir.path / "broken.gltf").string();
  std::ofstream(corrupt) << "{ not json";
  CHECK_THROWS_WITH(load_model(corrupt, SemanticClass::Vehicles, 4, scene),
                    Catch::Contains(corrupt));
  CHECK_THROWS_WITH(load_model((dir.path / "none.obj").string(), SemanticClass::Vehicles, 4, scene),
                    Catch::Contains("none.obj: no such model file"));
  config.models = {{"plane", gltf}};
  CHECK_THROWS_WITH(make_city(config), Catch::Contains("unknown actor kind \"plane\""));
}

TEST_CASE("a map exported as glTF reads back with the same triangles and classes") {
  CityConfig config;
  config.map = 6, config.vehicles = 5, config.pedestrians = 5;
  const City city = make_city(config);
  TempDir dir;
  const std::string path = (dir.path / "map.gltf").string();
  export_gltf(city.scene, 0.5, path);
  const std::vector<ExportedMesh> meshes = import_gltf(path);
  REQUIRE(meshes.size() == 1 + city.scene.actors.size());
  const auto triangle_set = [](const Mesh& mesh,
                               const std::function<Eigen::Vector3f(int)>& vertex) {
    std::multiset<std::vector<float>> set;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      std::vector<float> key{float(mesh.classes[t])};
      for (int c = 0; c < 3; ++c)
        for (int a = 0; a < 3; ++a) key.push_back(vertex(mesh.triangles[t][c])[a]);
      set.insert(key);
    }
    return set;
  };
  const Mesh& world = city.scene.world;
  CHECK(meshes[0].instance == 0);
  CHECK(triangle_set(meshes[0].mesh, [&](int v) { return meshes[0].mesh.vertices[v]; }) ==
        triangle_set(world, [&](int v) { return world.vertices[v]; }));
  const Actor& actor = city.scene.actors[2];
  CHECK(meshes[3].instance == actor.instance);
  std::size_t triangles = 0;
  for (const Part& part : actor.parts) triangles += part.mesh->triangles.size();
  CHECK(meshes[3].mesh.triangles.size() == triangles);
  const Eigen::Vector3f expected =
      (actor.pose(0.5) * part_vertices_at(actor.parts[0], 0.5)[0]).cast<float>();
  float nearest = 1e9;
  for (const auto& v : meshes[3].mesh.vertices) nearest = std::min(nearest, (v - expected).norm());
  CHECK(nearest < 1e-5f);
  std::ofstream(dir.path / "bad.gltf")
      << "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [{\"mesh\": 0}]}";
  CHECK_THROWS(import_gltf((dir.path / "bad.gltf").string()));
}

TEST_CASE("a scene record in JSON reproduces the scene and rejects bad values") {
  CityConfig config;
  config.map = 5, config.seed = 11, config.vehicles = 25, config.pedestrians = 15;
  config.ego_start = 42, config.ego_route = EgoRoute::Turn;
  const City city = make_city(config);
  const nlohmann::json record = nlohmann::json::parse(to_json(city).dump());
  CHECK(record["map_name"] == "waterfront");
  CHECK(record["actors"].size() == city.actors.size());
  CHECK(record["actors"].size() >= 40);
  CHECK(record["actor_style"] == "detailed");
  CHECK(record["ego_route"] == "turn");
  CHECK(record["ego"]["tries"] == city.ego_tries);
  const City again = city_from_record(record);
  for (double t : {0.0, 1.7, 3.9}) {
    CHECK(again.ego(t).matrix() == city.ego(t).matrix());
    for (std::size_t a = 0; a < city.scene.actors.size(); ++a)
      CHECK(again.scene.actors[a].pose(t).matrix() == city.scene.actors[a].pose(t).matrix());
  }
  nlohmann::json changed = record;
  changed["actors"][0]["s"] = 1234.5;
  CHECK_THROWS_WITH(city_from_record(changed), Catch::Contains("other actors than the record"));
  const auto bad = [&](const char* key, nlohmann::json value, const char* message) {
    nlohmann::json r = record;
    r[key] = value;
    CHECK_THROWS_WITH(config_from_json(r), Catch::Contains(message));
  };
  bad("map", 8, "map 8 is not in 0..7");
  bad("vehicles", -1, "must not be negative");
  bad("vehicles", 190, "at most 200");
  bad("ego_start", 100, "ego start 100");
  bad("duration", -2.0, "duration");
  bad("ego_route", "loop", "unknown ego route \"loop\"");
  bad("seed", "x", "scene record");
}

namespace {

// The class every pixel of an actor has (the detailed models').
SemanticClass class_of(const ActorRecord& actor) {
  if (actor.ego) return SemanticClass::EgoVehicle;
  switch (actor.kind) {
    case ActorKind::Pedestrian:
      return SemanticClass::Pedestrian;
    case ActorKind::Rider:
      return SemanticClass::Rider;
    case ActorKind::Bike:
      return SemanticClass::Bicycle;
    case ActorKind::Motorbike:
      return SemanticClass::Motorcycle;
    case ActorKind::Bus:
      return SemanticClass::Bus;
    case ActorKind::Truck:
    case ActorKind::Lorry:
      return SemanticClass::Truck;
    default:
      return SemanticClass::Car;
  }
}

}  // namespace

TEST_CASE("a rendered city frame shows its classes and the instances of its actors") {
  CityConfig config;
  config.map = 0, config.seed = 2, config.vehicles = 120, config.pedestrians = 60;
  config.ego_start = 30, config.duration = 1.2;
  const City city = make_city(config);
  Renderer renderer(city.scene);
  const FramePair frames{1.0, 1.0 + kFrame, city.rig(1.0), city.rig(1.0 + kFrame)};
  const GroundTruth gt = renderer.ground_truth(Projection::equirectangular(96), frames);
  std::set<int> classes, instances;
  for (std::size_t i = 0; i < gt.semantic.data.size(); ++i) {
    classes.insert(gt.semantic.data[i]);
    const int instance = gt.instance.data[i];
    if (instance == 0) continue;
    instances.insert(instance);
    REQUIRE(instance <= int(city.scene.actors.size()));
    CHECK(gt.semantic.data[i] == int(class_of(city.actors[std::size_t(instance - 1)])));
  }
  for (SemanticClass c : {SemanticClass::Road, SemanticClass::SideWalk, SemanticClass::Building,
                          SemanticClass::Sky, SemanticClass::RoadLine})
    CHECK(classes.count(int(c)) == 1);
  CHECK(instances.size() >= 3);
}

namespace {

// Every vehicle of the city (and the ego) over 100 frames keeps the model's bounds (below),
// measured from the poses at 30 Hz, with the slack of finite differences.
void check_vehicle_model(const City& city) {
  const auto ground = [](const Pose& p) { return Eigen::Vector2d(p.translation().head<2>()); };
  std::vector<PoseTrack> vehicles{city.ego};
  for (std::size_t k = 0; k < city.actors.size(); ++k)
    if (city.actors[k].kind != ActorKind::Pedestrian) vehicles.push_back(city.scene.actors[k].pose);
  for (const PoseTrack& track : vehicles)
    for (int frame = 1; frame < 100; ++frame) {
      const Pose a = track((frame - 1) * kFrame), b = track(frame * kFrame),
                 c = track((frame + 1) * kFrame);
      const double rate0 = std::remainder(yaw(b) - yaw(a), 2 * kPi) / kFrame;
      const double rate1 = std::remainder(yaw(c) - yaw(b), 2 * kPi) / kFrame;
      const double v0 = (ground(b) - ground(a)).norm() / kFrame;
      const double v1 = (ground(c) - ground(b)).norm() / kFrame;
      REQUIRE(std::abs(rate1 - rate0) < 0.118 * 1.05);
      REQUIRE((v1 - v0) / kFrame < 2.5 * 1.02);
      REQUIRE((v0 - v1) / kFrame < 3.0 * 1.02);
      REQUIRE(std::abs(rate1) * v1 < 3.0 * 1.04);
      if (v1 > 1) REQUIRE(std::abs(rate1) / v1 < 1.0 / 3);
    }
}

}  // namespace

TEST_CASE("vehicles drive as a vehicle model allows: bounded acceleration, braking, cornering") {
  // Paths have continuous curvature k (clothoid transitions of at least 2.5 m, no radius under
  // 3 m) and speeds a bounded acceleration a (2.5 m/s^2 up, 3 down, Gipps' braking rule), with
  // v^2 |k| <= 3 m/s^2 and curves braked for ahead at 2 m/s^2. The yaw rate w = v k then changes at
  // dw/dt = a k + v^2 k': a k <= 3 / 3, and on a transition of length T to curvature K the look-
  // ahead keeps v^2 <= 3 / K + 2 * 2 * T, so v^2 k' <= 3 / T + 4 K <= 3 / 2.5 + 4 / 3: in all
  // |dw/dt| <= 3.53 rad/s^2, 0.118 rad/s from one frame to the next. Before this model the yaw
  // rate changed by up to 3.4 rad/s per frame (polygonal arcs), then 1.76 (instant braking in
  // curves, kinks onto the roundabouts' octagons); now at most 0.08 (bench_motion).
  for (int map = 0; map < kMapCount; ++map)
    for (const auto& [seed, route] : {std::pair{7, EgoRoute::Free},
                                      {2, EgoRoute::Free},
                                      {7, EgoRoute::Drive},
                                      {7, EgoRoute::Turn}}) {
      CityConfig config = busy(map);
      config.seed = std::uint64_t(seed), config.ego_route = route;
      INFO("map " << map_name(map) << ", seed " << seed << ", ego route " << route_name(route));
      check_vehicle_model(make_city(config));
    }
}

TEST_CASE("nobody changes lanes just ahead of a vehicle about to turn into that lane") {
  // bench_motion's highway city of seed 8: a vehicle changed into a lane 2 m past the junction
  // that another, holding the junction at 13 m/s, was about to turn into; it braked at 137 m/s^2
  CityConfig config;
  config.actors = ActorStyle::Legacy;
  config.map = 2, config.seed = 8, config.vehicles = 120, config.pedestrians = 80;
  config.duration = 101 * kFrame, config.ego_start = (11 * 2 + 37 * 8) % 100;
  check_vehicle_model(make_city(config));
}

TEST_CASE("the camera rig sways with the distance driven and sits at a per-sequence height") {
  const double degree = kPi / 180;
  std::set<double> heights;  // of the cities' seed and of seeds 0..7
  for (int map = 0; map < kMapCount; ++map) {
    const City city = make_city(busy(map));
    const RigMount& m = city.mount;
    INFO("map " << map_name(map));
    CHECK((m.height >= 1.5 && m.height <= 2.0));
    CHECK((m.pitch_amplitude >= 0.2 * degree && m.pitch_amplitude <= 0.6 * degree));
    CHECK((m.roll_amplitude >= 0.1 * degree && m.roll_amplitude <= 0.4 * degree));
    heights.insert(m.height);
    for (int frame = 0; frame <= 100; frame += 5) {
      const double t = frame * kFrame, d = city.ego_distance(t);
      // the rig in the ego's frame, by hand: raised by the height, pitched about y, rolled about x
      const double pitch = m.pitch_amplitude * std::sin(2 * kPi * d / 9 + m.pitch_phase);
      const double roll = m.roll_amplitude * std::sin(2 * kPi * d / 14 + m.roll_phase);
      const double cp = std::cos(pitch), sp = std::sin(pitch), cr = std::cos(roll),
                   sr = std::sin(roll);
      Eigen::Matrix3d expected;
      expected << cp, sp * sr, sp * cr, 0, cr, -sr, -sp, cp * sr, cp * cr;
      const Pose relative = city.ego(t).inverse() * city.rig(t);
      REQUIRE((relative.linear() - expected).norm() < 1e-12);
      REQUIRE((relative.translation() - Eigen::Vector3d(0, 0, m.height)).norm() < 1e-12);
    }
  }
  for (std::uint64_t seed = 0; seed < 8; ++seed) heights.insert(random_mount(seed).height);
  CHECK(heights.size() >= 8);  // every seed (every sequence of a release) its own mount
}

TEST_CASE("the ego's route: Turn turns it at a junction, Drive keeps its way clear at spawn") {
  // 8 maps, one city each: a Turn ego heads 45 degrees or more off its start within 101 frames,
  // driving at least half its lane's speed on average; a Drive ego has no vehicle starting on
  // its lane within kEgoClearAhead metres ahead, and drives at least as fast as a Free one.
  double free_speed = 0, drive_speed = 0;
  for (int map = 0; map < kMapCount; ++map) {
    CityConfig config = busy(map);
    config.duration = 101 * kFrame;
    const auto turned = [&](const City& city) {
      double most = 0;
      for (int f = 0; f <= 100; ++f)
        most = std::max(
            most, std::abs(std::remainder(yaw(city.ego(f * kFrame)) - yaw(city.ego(0)), 2 * kPi)));
      return most * 180 / kPi;
    };
    const auto speed = [&](const City& city) {
      return city.ego_distance(100 * kFrame) / (100 * kFrame);
    };
    INFO("map " << map_name(map));
    config.ego_route = EgoRoute::Turn;
    const City turning = make_city(config);
    CHECK(turned(turning) >= kEgoTurnDegrees);
    CHECK(turning.ego_tries <= kEgoTries);
    config.ego_route = EgoRoute::Drive;
    const City driving = make_city(config);
    for (const ActorRecord& a : driving.actors)
      if (a.kind != ActorKind::Pedestrian && a.lane == driving.ego_spawn.lane)
        CHECK(!(a.s > driving.ego_spawn.s && a.s < driving.ego_spawn.s + kEgoClearAhead));
    config.ego_route = EgoRoute::Free;
    drive_speed += speed(driving), free_speed += speed(make_city(config));
  }
  CHECK(drive_speed > free_speed);
}

TEST_CASE("the ego's lane change: on its lane until asked, then exactly one lane's width across") {
  // Lanes are straight between junctions: until lane_change_at the ego keeps its start's line;
  // once back on its road's heading after the change it is 3.5 m (a lane's width) to its side.
  int maps_with_two_lanes = 0;
  for (int map = 0; map < kMapCount; ++map) {
    CityConfig config = busy(map);
    config.duration = 241 * kFrame, config.ego_route = EgoRoute::LaneChange;
    config.lane_change_at = 1.5;
    INFO("map " << map_name(map));
    City city;
    try {
      city = make_city(config);
    } catch (const std::invalid_argument& e) {
      CHECK_THAT(e.what(), Catch::Contains("long enough for a lane change at 1.5"));
      continue;
    }
    ++maps_with_two_lanes;
    const Pose start = city.ego(0);
    const auto across = [&](double t) {  // metres to the start's left, off its line
      return (city.ego(t).translation() - start.translation()).dot(start.linear().col(1));
    };
    const auto on_heading = [&](double t) {
      return std::abs(std::remainder(yaw(city.ego(t)) - yaw(start), 2 * kPi)) < 1e-9;
    };
    for (int f = 0; f * kFrame < 1.5; ++f) CHECK(std::abs(across(f * kFrame)) < 1e-6);
    bool changed = false, left_line = false;  // back on its heading after leaving it
    for (int f = 0; f <= 240 && !changed; ++f) {
      const double t = f * kFrame;
      if (!on_heading(t)) {
        left_line = true;
      } else if (left_line) {
        CHECK(std::abs(across(t)) == Approx(3.5).margin(1e-6));
        changed = true;
      }
    }
    CHECK(changed);
    const nlohmann::json record = to_json(city);
    CHECK(record["ego_route"] == "lane_change");
    CHECK(record["lane_change_at"] == 1.5);
  }
  CHECK(maps_with_two_lanes >= 2);
}

TEST_CASE(
    "actors placed one by one: a vehicle from a start with the traffic, a walker by waypoints") {
  CityConfig config = busy(2);
  config.duration = 121 * kFrame, config.actors = ActorStyle::Detailed;
  const City plain = make_city(config);
  const Vec3 spot = plain.start_points[7].pose.translation();
  const Vec3 side = plain.start_points[7].pose.linear().col(1);
  ScriptedActor car{ActorKind::Car, "", {}, Eigen::Vector2d((spot + 0.5 * side).head<2>()), 6.0};
  ScriptedActor walker{ActorKind::Pedestrian, "", {}};
  walker.waypoints = {{Vec3(spot.x(), spot.y(), 0), 0.0, {}, {}},
                      {Vec3(spot.x() + 5, spot.y(), 0), {}, 1.25, {}}};
  config.scripted = {car, walker};
  const City city = make_city(config);
  std::vector<std::size_t> scripted;
  for (std::size_t a = 0; a < city.actors.size(); ++a)
    if (city.actors[a].scripted) scripted.push_back(a);
  REQUIRE(scripted.size() == 2);
  const Actor& driven = city.scene.actors[scripted[0]];
  const Actor& walked = city.scene.actors[scripted[1]];
  CHECK(city.actors[scripted[0]].kind == ActorKind::Car);
  CHECK(walked.instance == city.scene.actors.size());  // waypoint actors come last
  // the car starts on the start point's lane line, 0.5 m from the spot given, and keeps to 6 m/s
  CHECK((driven.pose(0).translation() - spot).head<2>().norm() < 0.3);
  double most = 0;
  for (int f = 0; f < 120; ++f)
    most = std::max(
        most, (driven.pose((f + 1) * kFrame).translation() - driven.pose(f * kFrame).translation())
                      .norm() /
                  kFrame);
  CHECK(most <= 6 + 1e-6);
  CHECK(most > 1);
  // the walker: 5 m at 1.25 m/s, there at 4 s and standing after
  CHECK((walked.pose(2).translation() - Vec3(spot.x() + 2.5, spot.y(), 0)).norm() < 1e-3);
  CHECK((walked.pose(4).translation() - Vec3(spot.x() + 5, spot.y(), 0)).norm() < 1e-3);
  // a start off the roads, or on the ego, is refused by name
  config.scripted = {car};
  config.scripted[0].start = Eigen::Vector2d(1e4, 1e4);
  CHECK_THROWS_WITH(make_city(config), Catch::Contains("is not within 1.75"));
  config.scripted[0].start = city.ego(0).translation().head<2>();
  CHECK_THROWS_WITH(make_city(config), Catch::Contains("has no room"));
}
