#pragma once
// Small built-in scenes with motion simple enough to derive ground truth by hand, for tests, and
// the test fixtures' solid checker texture.
#include "flowscape/scenes/scene.h"
#include "flowscape/scenes/shapes.h"

namespace flowscape {

// A closed room around the origin, half-size `half` metres: floor Road, ceiling Other, walls
// Building. A rig inside sees no sky.
Scene box_room(float half = 10);

// One square plane x = distance facing the origin, side `side`, class Wall; sky elsewhere.
Scene textured_plane(double distance = 10, double side = 400);

// A 2 m box (instance 7, Vehicles, every triangle of `material`) centred at `centre` at t = 0 and
// moving with `velocity` (m/s).
Actor sliding_box(const Eigen::Vector3d& centre, const Eigen::Vector3d& velocity,
                  std::uint16_t material = 0);
// box_room plus sliding_box(centre, velocity).
Scene moving_box(const Eigen::Vector3d& centre, const Eigen::Vector3d& velocity);

// A sunlit world: a checkered wall 10 m ahead, a ground plane 1.7 m below the rig, and a green
// clear-coated box (sliding_box, material 2) driving across.
Scene sunlit_street();

// A solid 3-D checker of cells `size` wide in the object's frame (it moves with the object), cells
// centred on multiples of the size: the base albedo and the base times `contrast`. Point sampled
// (a fixture for tests, not a filtered texture).
std::shared_ptr<const Pattern> checker(double size, const Eigen::Vector3f& contrast);

}  // namespace flowscape
