#include "city_actors.h"

#include <algorithm>
#include <memory>
#include <optional>

#include "flowscape/scenes/model_io.h"
#include "flowscape/scenes/shapes.h"

namespace flowscape {
namespace {

Mesh user_model(ActorKind kind, const std::string& path, Scene& scene) {
  Material material;
  material.kind = kind == ActorKind::Pedestrian ? Material::Kind::Diffuse : Material::Kind::Glossy;
  material.albedo = {0.5f, 0.45f, 0.4f};
  const SemanticClass cls =
      kind == ActorKind::Pedestrian ? SemanticClass::Pedestrian : SemanticClass::Vehicles;
  return load_model(path, cls, kind_size(kind).length, scene, material);
}

// A scripted actor's waypoints sampled as the traffic's tracks are, for `duration` and a frame.
Track scripted_track(const std::vector<Waypoint>& waypoints, double duration) {
  const PoseTrack path = waypoint_track(waypoints);
  const std::vector<double> times = waypoint_times(waypoints);
  Track track{kTrafficStep, {}, {}};
  double travelled = 0;
  for (int n = 0; n * kTrafficStep <= duration + kRouteFrame; ++n) {
    const Pose pose = path(std::clamp(n * kTrafficStep, times.front(), times.back()));
    if (n > 0) travelled += (pose.translation() - track.poses.back().translation()).norm();
    track.poses.push_back(pose), track.distance.push_back(travelled);
  }
  return track;
}

// The models of a city's asset packs, loaded once, and which vehicle shows one: a quarter of the
// cars, by a hash of the instance.
class PackModels {
 public:
  PackModels(const CityConfig& config, Scene& scene) {
    for (const std::string& name : config.asset_packs)
      for (const PackModel& m : asset_pack(name)) {
        Material fallback;
        fallback.kind = Material::Kind::Glossy, fallback.albedo = {0.5f, 0.45f, 0.4f};
        models_.push_back({m, std::make_shared<const Mesh>(load_model(
                                  m.path, SemanticClass::Car, m.length, scene, fallback, m.turn))});
      }
  }
  struct Pick {
    const PackModel* model = nullptr;
    std::shared_ptr<const Mesh> mesh;
  };
  Pick pick(ActorKind kind, std::uint16_t instance, std::uint64_t seed) const {
    std::vector<const std::pair<PackModel, std::shared_ptr<const Mesh>>*> fitting;
    for (const auto& m : models_)
      if (m.first.kind == kind) fitting.push_back(&m);
    const double u = tex::hash01(instance, seed ^ 0x7061636bull);  // "pack"
    if (fitting.empty() || u >= 0.25) return {};
    const auto& [model, mesh] = *fitting[std::size_t(u / 0.25 * double(fitting.size()))];
    return {&model, mesh};
  }

 private:
  std::vector<std::pair<PackModel, std::shared_ptr<const Mesh>>> models_;
};

// Adds a vehicle's or walker's actors with their records: the first is `record`'s, any after it
// the rider it carries (a Rider where the vehicle is, scripted if it is).
void add_actors(std::vector<Actor> actors, ActorRecord record, City& city) {
  for (Actor& actor : actors) {
    city.actors.push_back(record);
    city.scene.actors.push_back(std::move(actor));
    ActorRecord rider{std::uint16_t(city.scene.actors.size() + 1), ActorKind::Rider, record.lane,
                      record.s, record.speed};
    rider.scripted = record.scripted;
    record = rider;
  }
}

// The track of an actor that stands at `pose` all the sequence (a parked car, a person standing).
std::shared_ptr<const Track> still_track(const Pose& pose) {
  return std::make_shared<const Track>(Track{1, {pose}, {0}});
}

// A vehicle with its record: `model`, or (none) the built-in family the library draws for it.
void add_vehicle(ActorLibrary& library, ActorKind kind, std::shared_ptr<const Track> track,
                 const Mesh* model, ActorRecord record, City& city) {
  if (!model) record.family = library.family(kind, record.instance);
  add_actors(library.vehicle(kind, record.instance, std::move(track), model), record, city);
}

// A scripted actor's model: its own file's (loaded into `own`), else the release's for its kind
// (or none: the built-in one).
const Mesh* scripted_model(const ScriptedActor& actor, const std::map<ActorKind, Mesh>& models,
                           std::optional<Mesh>& own, Scene& scene) {
  if (!actor.model.empty()) own = user_model(actor.kind, actor.model, scene);
  return own ? &*own : user_model_of(models, actor.kind);
}

}  // namespace

std::map<ActorKind, Mesh> user_models(const CityConfig& config, Scene& scene) {
  std::map<ActorKind, Mesh> models;
  for (const auto& [name, path] : config.models) {
    const ActorKind kind = kind_from_name(name);
    models[kind] = user_model(kind, path, scene);
  }
  return models;
}

const Mesh* user_model_of(const std::map<ActorKind, Mesh>& models, ActorKind kind) {
  const auto model = models.find(kind);
  return model == models.end() ? nullptr : &model->second;
}

void add_legacy_actors(const PlacedTraffic& traffic, const std::map<ActorKind, Mesh>& models,
                       Random& random, City& city) {
  const Spawned& spawned = traffic.spawned;
  const auto add = [&](ActorKind kind, const Track& track, int lane, double s, double speed) {
    const auto instance = std::uint16_t(city.scene.actors.size() + 1);
    city.scene.actors.push_back(legacy_actor(kind, instance, std::make_shared<const Track>(track),
                                             user_model_of(models, kind), random, city.scene));
    city.actors.push_back({instance, kind, lane, s, speed});
  };
  for (std::size_t v = 1; v < spawned.vehicles.size(); ++v) {
    const VehicleStart& start = spawned.vehicles[v];
    add(spawned.vehicle_kinds[v - 1], traffic.tracks.vehicles[v], start.lane, start.s, start.speed);
  }
  for (std::size_t w = 0; w < spawned.walkers.size(); ++w) {
    const WalkerStart& start = spawned.walkers[w];
    add(ActorKind::Pedestrian, traffic.tracks.walkers[w], start.loop, start.s, start.speed);
  }
}

void add_detailed_actors(const PlacedTraffic& traffic, const std::map<ActorKind, Mesh>& models,
                         const std::vector<Pose>& parked, ActorLibrary& library, City& city) {
  const CityConfig& config = city.config;
  const Spawned& spawned = traffic.spawned;
  const auto next = [&] { return std::uint16_t(city.scene.actors.size() + 1); };
  const PackModels pack(config, city.scene);
  const auto vehicle = [&](ActorKind kind, std::shared_ptr<const Track> track, ActorRecord record) {
    const PackModels::Pick picked = pack.pick(kind, record.instance, config.seed);
    if (picked.model) {
      record.model = model_id(*picked.model);
      add_actors(
          library.pack_vehicle(picked.mesh, *picked.model, record.instance, std::move(track)),
          record, city);
      return;
    }
    add_vehicle(library, kind, std::move(track), user_model_of(models, kind), record, city);
  };
  std::vector<const ScriptedActor*> placed;  // in spawn order
  for (const ScriptedActor& actor : config.scripted)
    if (actor.start) placed.push_back(&actor);
  for (std::size_t v = 1; v < spawned.vehicles.size(); ++v) {
    const VehicleStart& start = spawned.vehicles[v];
    const ActorKind kind = spawned.vehicle_kinds[v - 1];
    const auto track = std::make_shared<const Track>(traffic.tracks.vehicles[v]);
    ActorRecord record{next(), kind, start.lane, start.s, start.speed};
    if (v > placed.size()) {
      vehicle(kind, track, record);
      continue;
    }
    record.scripted = true;
    std::optional<Mesh> own;
    add_vehicle(library, kind, track, scripted_model(*placed[v - 1], models, own, city.scene),
                record, city);
  }
  for (std::size_t w = 0; w < spawned.walkers.size(); ++w) {
    const WalkerStart& start = spawned.walkers[w];
    const bool grouped =
        (w > 0 && spawned.walkers[w - 1].loop == start.loop &&
         spawned.walkers[w - 1].speed == start.speed) ||
        (w + 1 < spawned.walkers.size() && spawned.walkers[w + 1].loop == start.loop &&
         spawned.walkers[w + 1].speed == start.speed);
    const bool child =
        grouped && tex::hash01(std::uint64_t(w), config.seed ^ 0x6368696c64ull) < 0.35;
    const auto track = std::make_shared<const Track>(traffic.tracks.walkers[w]);
    add_actors({library.pedestrian(next(), track, start.speed, child,
                                   user_model_of(models, ActorKind::Pedestrian))},
               {next(), ActorKind::Pedestrian, start.loop, start.s, start.speed}, city);
  }
  for (const Pose& pose : parked) {
    ActorRecord record{next(), ActorKind::Car, -1, 0, 0};
    record.parked = true;
    const std::size_t first = city.scene.actors.size();
    vehicle(ActorKind::Car, still_track(pose), record);
    for (std::size_t a = first; a < city.scene.actors.size(); ++a)
      library.switch_off_lamps(city.scene.actors[a]);
  }
  if (config.draw_ego) {
    ActorRecord record{next(), ActorKind::Car, traffic.ego.lane, traffic.ego.s, 0};
    record.ego = true;
    city.ego_instance = record.instance;
    add_actors({library.ego(record.instance, city.rig_track(),
                            std::make_shared<const Track>(traffic.tracks.vehicles[0]),
                            city.mount.height, config.ego_cameras)},
               record, city);
  }
}

namespace {

// A standing person's record.
ActorRecord standing_record(const City& city) {
  ActorRecord record{std::uint16_t(city.scene.actors.size() + 1), ActorKind::Pedestrian, -1, 0, 0};
  record.standing = true;
  return record;
}

}  // namespace

void add_legacy_standing(const std::vector<StandingPerson>& people,
                         const std::map<ActorKind, Mesh>& models, Random& random, City& city) {
  for (const StandingPerson& person : people) {
    const ActorRecord record = standing_record(city);
    city.scene.actors.push_back(
        legacy_actor(ActorKind::Pedestrian, record.instance, still_track(person.pose),
                     user_model_of(models, ActorKind::Pedestrian), random, city.scene));
    city.actors.push_back(record);
  }
}

void add_standing(const std::vector<StandingPerson>& people,
                  const std::map<ActorKind, Mesh>& models, ActorLibrary& library, City& city) {
  for (const StandingPerson& person : people) {
    const ActorRecord record = standing_record(city);
    add_actors({library.standing_person(record.instance, still_track(person.pose), person.child,
                                        user_model_of(models, ActorKind::Pedestrian))},
               record, city);
  }
}

void add_scripted_actors(const std::map<ActorKind, Mesh>& models, ActorLibrary& library,
                         City& city) {
  for (const ScriptedActor& scripted : city.config.scripted) {
    if (scripted.start) continue;  // driving with the traffic: add_detailed_actors adds it
    const auto track =
        std::make_shared<const Track>(scripted_track(scripted.waypoints, city.config.duration));
    const std::vector<double> times = waypoint_times(scripted.waypoints);
    const double speed = track->distance.back() / (times.back() - times.front());
    std::optional<Mesh> own;
    const Mesh* model = scripted_model(scripted, models, own, city.scene);
    ActorRecord record{std::uint16_t(city.scene.actors.size() + 1), scripted.kind, -1, 0, speed};
    record.scripted = true;
    if (scripted.kind == ActorKind::Pedestrian)
      add_actors({library.pedestrian(record.instance, track, speed, false, model)}, record, city);
    else
      add_vehicle(library, scripted.kind, track, model, record, city);
  }
}

void add_head_lamps(const ActorLibrary& library, City& city) {
  for (std::size_t a = 0; a < city.scene.actors.size(); ++a)
    if (!city.actors[a].parked)
      for (const Lamp& beam : library.head_lamps(city.scene.actors[a], int(a)))
        city.scene.lamps.push_back(beam);
}

}  // namespace flowscape
