#pragma once
// What a renderer needs to know of a scene: triangle meshes with a CARLA class per triangle, and
// actors whose parts move rigidly with time. Scenes know nothing of the renderer.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <vector>

namespace flowscape {

using Pose = Eigen::Isometry3d;                   // object -> world (metres; z up)
using PoseTrack = std::function<Pose(double t)>;  // t in seconds

// CARLA 0.9.10-0.9.13 semantic classes (design.md).
enum class SemanticClass : std::uint8_t {
  Unlabeled = 0,
  Building = 1,
  Fence = 2,
  Other = 3,
  Pedestrian = 4,
  Pole = 5,
  RoadLine = 6,
  Road = 7,
  SideWalk = 8,
  Vegetation = 9,
  Vehicles = 10,
  Wall = 11,
  TrafficSign = 12,
  Sky = 13,
  Ground = 14,
  Bridge = 15,
  RailTrack = 16,
  GuardRail = 17,
  TrafficLight = 18,
  Static = 19,
  Dynamic = 20,
  Water = 21,
  Terrain = 22
};

struct Mesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;
  std::vector<SemanticClass> classes;  // one per triangle
};

// A rigid piece of an actor (a car body, a wheel, a leg), posed relative to the actor.
struct Part {
  Mesh mesh;
  PoseTrack pose;
};

struct Actor {
  std::uint16_t instance;  // > 0; 0 is the static world
  std::vector<Part> parts;
  PoseTrack pose;
};

struct Scene {
  Mesh world;  // static geometry, instance 0
  std::vector<Actor> actors;
};

// Pose of a part at time t: the actor's pose times the part's pose in the actor.
inline Pose part_pose(const Actor& actor, const Part& part, double t) {
  return actor.pose(t) * part.pose(t);
}

inline PoseTrack fixed_pose(const Pose& pose = Pose::Identity()) {
  return [pose](double) { return pose; };
}

}  // namespace flowscape
