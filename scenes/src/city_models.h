#pragma once
// Internal: the city's actors. Detailed (the default): the vehicle families and people of assets/,
// each model built once per city and shared by the actors showing it, every actor with its own
// paint, plate, clothes; two-wheelers carry a rider (an actor of its own), parked vehicles are
// actors too, and the ego vehicle is drawn under the rig. Legacy: flowscape 0.9's box models
// (assets/legacy_models.cpp), byte for byte.
#include <memory>
#include <optional>
#include <vector>

#include "assets/people.h"
#include "assets/vehicles.h"
#include "flowscape/core/random.h"
#include "flowscape/scenes/city.h"
#include "traffic.h"

namespace flowscape {

struct KindSize {
  double length, width;
};
KindSize kind_size(ActorKind kind);

// flowscape 0.9's models: a vehicle or walker following `track` (`user_model`, if not null,
// replaces the built-in body), and a parked vehicle baked into the static world (instance 0).
Actor legacy_actor(ActorKind kind, std::uint16_t instance, std::shared_ptr<const Track> track,
                   const Mesh* user_model, Random& random, Scene& scene);
void add_legacy_parked_vehicle(ActorKind kind, const Pose& pose, const Mesh* user_model,
                               Random& random, Scene& scene);

// The detailed models of one city.
class ActorLibrary {
 public:
  // `seed`: the city's; `wet`: umbrellas and coats.
  ActorLibrary(Scene& scene, std::uint64_t seed, bool wet);
  ~ActorLibrary();
  ActorLibrary(const ActorLibrary&) = delete;
  ActorLibrary& operator=(const ActorLibrary&) = delete;

  // A vehicle following `track` (standing still for a parked one), and for two-wheelers its rider
  // (instance + 1) after it; `user_model` replaces the built-in body (no rider then).
  std::vector<Actor> vehicle(ActorKind kind, std::uint16_t instance,
                             std::shared_ptr<const Track> track, const Mesh* user_model);
  // The family name (assets::family_name) vehicle() shows without a user model.
  std::string family(ActorKind kind, std::uint16_t instance) const;
  // A person following `track`; `gait_phase`: the gait's at distance 0 (else drawn).
  Actor pedestrian(std::uint16_t instance, std::shared_ptr<const Track> track, double speed,
                   bool child, const Mesh* user_model,
                   std::optional<double> gait_phase = std::nullopt);
  // The same with the family, variant and livery (a person's look) given: galleries and tests.
  std::vector<Actor> vehicle_of(assets::Family family, int variant, assets::Livery livery,
                                std::uint16_t instance, std::shared_ptr<const Track> track);
  Actor person_of(const assets::Look& look, std::uint16_t instance,
                  std::shared_ptr<const Track> track, double speed,
                  std::optional<double> gait_phase = std::nullopt);
  // A person standing where `still` (one pose) puts it, both feet flat, shifting weight and
  // looking round.
  Actor standing_person(std::uint16_t instance, std::shared_ptr<const Track> still, bool child,
                        const Mesh* user_model);
  // An asset pack's model (its own materials) on built-in road wheels where the pack says.
  std::vector<Actor> pack_vehicle(std::shared_ptr<const Mesh> body, const PackModel& model,
                                  std::uint16_t instance, std::shared_ptr<const Track> track);
  // The ego vehicle: a car whose body is fixed to the rig (`rig`, its origin `height` above the
  // ego's road frame `ego`), its wheels on the road, rolling and steering; placed so that every
  // camera (rig frame) is at least kEgoClearance outside it. Throws std::invalid_argument naming
  // the camera when no placement leaves it clear.
  Actor ego(std::uint16_t instance, PoseTrack rig, std::shared_ptr<const Track> ego, double height,
            const std::vector<Vec3>& cameras);
  // The beams of a vehicle's head lamps (none for a body without them), for Scene::lamps.
  std::vector<Lamp> head_lamps(const Actor& vehicle, int actor_index) const;
  // A parked vehicle's head and tail lamps the same glass, but dark at night.
  void switch_off_lamps(Actor& vehicle) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

inline constexpr double kEgoClearance = 0.05;  // metres between a camera and the ego's body

}  // namespace flowscape
