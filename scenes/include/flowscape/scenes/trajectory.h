#pragma once
// Timed paths a scenario gives a rig (a handheld camera, a drone): through waypoints, or replayed
// from a pose file of a tracker or SfM tool. Poses are rig -> world (x forward, y left, z up) or,
// for a file's camera, the camera's own frame (x right, y down, z forward), as Pose.
#include <filesystem>
#include <optional>
#include <vector>

#include "flowscape/scenes/scene.h"

namespace flowscape {

// The turn by yaw (left, about z), then pitch (up), then roll (about the forward x axis,
// right-handed), in the rig's axes (x forward, y left, z up): waypoints' orientation keys, a pose
// file's origin, and renderer/rig.h's look() (which starts from the forward camera's frame).
Mat3 yaw_pitch_roll(double yaw_degrees, double pitch_degrees, double roll_degrees);

// A point a path passes: at a time (seconds from the sequence's start) or, for every point after
// the first, reached at a speed (m/s, the mean over the chord from the point before: the time
// between them is chord / speed), not both; optionally the rig's orientation there.
struct Waypoint {
  Vec3 position = Vec3::Zero();                // metres, world
  std::optional<double> time, speed;           // one of them (the first point: time or 0)
  std::optional<Vec3> yaw_pitch_roll_degrees;  // rig.h's look() angles, in the world
};

// The times the waypoints are passed at (the first at its time or 0). Throws std::invalid_argument
// naming the waypoint: fewer than 2 points, both or neither of time and speed, times not
// increasing, a speed not positive, some points with orientation keys and others without.
std::vector<double> waypoint_times(const std::vector<Waypoint>& waypoints);

// The rig's pose through the waypoints: positions on a natural cubic spline through them at their
// times (C2: position, velocity and acceleration continuous; zero curvature at the ends), and the
// orientation either from the keys (yaw, pitch and roll each a natural cubic spline of the
// unwrapped angles: C2 angles, so C2 rotations) or, without keys, looking along the velocity
// (yaw from its horizontal direction, pitch from its climb, no roll). Before the first time and
// after the last the path holds its end pose.
PoseTrack waypoint_track(const std::vector<Waypoint>& waypoints);

// A pose file's poses at their times.
struct TimedPose {
  double time;  // seconds from the file's first pose
  Pose pose;    // the file's frame -> its world
};
// TUM (each line: time tx ty tz qx qy qz qw, camera -> world; '#' comments), KITTI (each line the
// 12 numbers of a 3x4 camera -> world, row-major; the k-th at k / rate), COLMAP images.txt
// (IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME, world -> camera, each followed by a line of 2-D
// points; ordered by NAME, the k-th at k / rate). Times are shifted so that the first pose is at 0.
// Throws FileError naming the file and line: a malformed line, a quaternion of length far from 1,
// times not increasing, fewer than 2 poses.
enum class PoseFormat { Tum, Kitti, Colmap };
PoseFormat pose_format(const std::string& name);  // "tum", "kitti", "colmap"
std::vector<TimedPose> read_pose_file(const std::filesystem::path& file, PoseFormat format,
                                      double rate = 10);

// How a pose file's world lies in ours (x and y on the ground, z up), for poses of camera frames
// (x right, y down, z forward): "z_up" (as it is: TUM's motion-capture and EuRoC's worlds),
// "y_down" (a camera's own frame: KITTI's world is its first camera's, x right, y down, z
// forward), "gravity" (up the mean of every camera's up, -y of its frame, as a COLMAP
// reconstruction of a camera held or driven upright has it; forward the first camera's view), or
// "up" with the file's up direction given (forward the first camera's view).
struct PoseWorld {
  std::string frame = "z_up";
  Vec3 up = Vec3::UnitZ();  // for "up": in the file's world
};
// The rotation from the file's world to ours. Throws std::invalid_argument naming the frame: an
// unknown one, an up that is zero or along the first camera's view.
Mat3 ours_from_file_world(const PoseWorld& world, const std::vector<TimedPose>& poses);

// The poses between their times: positions linearly, rotations by slerp (C0: the file's own
// samples, nothing invented between them); before the first and after the last, the end poses.
PoseTrack interpolated_track(std::vector<TimedPose> poses);

}  // namespace flowscape
