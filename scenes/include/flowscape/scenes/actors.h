#pragma once
// What a dataset says of an actor at a moment: its 3-D box and how fast it moves, from the scene's
// own poses and meshes (the ground truth a release records per frame in meta.json).
#include "flowscape/scenes/scene.h"

namespace flowscape {

// An oriented box: centre and axes (box -> world; the axes are the actor's: x forward, y left,
// z up) and its full edge lengths along them.
struct Box3 {
  Pose pose = Pose::Identity();
  Vec3 size = Vec3::Zero();
};
// The smallest box in the actor's frame at time t (actor.pose(t)) that holds every vertex of its
// parts, each posed then: legs and wheels move the box with them.
Box3 actor_box(const Actor& actor, double t);

// World-frame velocities at time t: of a point fixed on the actor at `local` (actor frame), m/s,
// and the actor frame's angular velocity (dR/dt = [w]x R), rad/s; central differences over 1 ms.
struct Motion {
  Vec3 linear = Vec3::Zero(), angular = Vec3::Zero();
};
Motion actor_motion(const Actor& actor, double t, const Vec3& local);

// The CARLA class most of the actor's triangles have (a car is Vehicles, a walker Pedestrian).
SemanticClass actor_class(const Actor& actor);

}  // namespace flowscape
