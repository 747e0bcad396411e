#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>

#include "../temp_dir.h"
#include "flowscape/scenes/trajectory.h"

using namespace flowscape;

namespace {

Vec3 position(const PoseTrack& track, double t) { return track(t).translation(); }

// Second derivative from one side only (h > 0: right of t, h < 0: left), O(h) accurate.
Vec3 one_sided_acceleration(const PoseTrack& track, double t, double h) {
  return (position(track, t) - 2 * position(track, t + h) + position(track, t + 2 * h)) / (h * h);
}

Pose known_pose(int k) {
  Pose pose = Pose::Identity();
  pose.linear() =
      Eigen::AngleAxisd(0.3 + 0.1 * k, Vec3(0.2, -0.5, 1).normalized()).toRotationMatrix();
  pose.translation() = Vec3(1.5 * k, -0.25 * k * k, 0.1 + 0.01 * k);
  return pose;
}

double angle_between(const Mat3& a, const Mat3& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

}  // namespace

TEST_CASE("a waypoint path passes its points at their times, C2, looking where it goes") {
  const std::vector<Waypoint> points = {{{0, 0, 20}, 0.0, {}, {}},
                                        {{10, 2, 21}, 1.5, {}, {}},
                                        {{18, 10, 20}, {}, 8.0, {}},  // reached at 8 m/s
                                        {{20, 25, 18}, 5.0, {}, {}}};
  const std::vector<double> times = waypoint_times(points);
  CHECK(times[2] == Approx(1.5 + std::hypot(8.0, 8.0, 1.0) / 8));
  const PoseTrack track = waypoint_track(points);
  for (std::size_t k = 0; k < points.size(); ++k)
    CHECK((position(track, times[k]) - points[k].position).norm() < 1e-3);  // 1 mm
  for (std::size_t k = 1; k + 1 < points.size(); ++k) {  // acceleration continuous at the joints
    const double h = 1e-4;
    const Vec3 left = one_sided_acceleration(track, times[k], -h);
    const Vec3 right = one_sided_acceleration(track, times[k], h);
    CHECK((left - right).norm() < 1e-2 * (1 + left.norm()));
    const Vec3 v_left = (position(track, times[k]) - position(track, times[k] - h)) / h;
    const Vec3 v_right = (position(track, times[k] + h) - position(track, times[k])) / h;
    CHECK((v_left - v_right).norm() < 1e-2);
  }
  // natural ends: no acceleration at the first and last point
  CHECK(one_sided_acceleration(track, times.front(), 1e-4).norm() < 1e-2);
  // without orientation keys the rig looks along its velocity (x forward)
  const double t = 2.0, h = 1e-6;
  const Vec3 velocity = (position(track, t + h) - position(track, t - h)) / (2 * h);
  CHECK(track(t).linear().col(0).isApprox(velocity.normalized(), 1e-6));
  CHECK(track(t).linear().col(1).z() == Approx(0).margin(1e-12));  // no roll: y stays level
  // holds its end poses outside its times
  CHECK((position(track, 99) - points.back().position).norm() < 1e-9);
}

TEST_CASE("orientation keys turn the rig through the yaw, pitch and roll they give") {
  const std::vector<Waypoint> points = {{{0, 0, 1.6}, 0.0, {}, Vec3(170, 0, 0)},
                                        {{1, 0, 1.6}, 1.0, {}, Vec3(-170, -10, 5)},  // 20 deg on
                                        {{2, 1, 1.6}, 2.0, {}, Vec3(-150, 0, 0)}};
  const PoseTrack track = waypoint_track(points);
  const auto expected = [](double yaw, double pitch, double roll) {
    const double d = kPi / 180;
    return Mat3(
        (Eigen::AngleAxisd(yaw * d, Vec3::UnitZ()) * Eigen::AngleAxisd(-pitch * d, Vec3::UnitY()) *
         Eigen::AngleAxisd(roll * d, Vec3::UnitX()))
            .toRotationMatrix());
  };
  CHECK(angle_between(track(0).linear(), expected(170, 0, 0)) < 1e-9);
  CHECK(angle_between(track(1).linear(), expected(-170, -10, 5)) < 1e-9);
  // unwrapped: half way it turns through 180, not back through 0
  CHECK(track(0.5).linear().col(0).x() < -0.99);
}

TEST_CASE("bad waypoints are named") {
  const auto fails = [](std::vector<Waypoint> points, const std::string& says) {
    CHECK_THROWS_WITH(waypoint_track(points), Catch::Contains(says));
  };
  fails({{{0, 0, 0}, 0.0, {}, {}}}, "at least 2 waypoints");
  fails({{{0, 0, 0}, 0.0, {}, {}}, {{1, 0, 0}, 1.0, 3.0, {}}},
        "waypoint 1: give its time or its speed, not both");
  fails({{{0, 0, 0}, 0.0, {}, {}}, {{1, 0, 0}, 0.0, {}, {}}}, "waypoint 1: times must increase");
  fails({{{0, 0, 0}, 0.0, {}, {}}, {{1, 0, 0}, {}, -2.0, {}}},
        "waypoint 1: its speed must be positive");
  fails({{{0, 0, 0}, 0.0, {}, Vec3(0, 0, 0)}, {{1, 0, 0}, 1.0, {}, {}}},
        "waypoint 1: give yaw_pitch_roll_degrees at every waypoint or at none");
}

TEST_CASE("TUM, KITTI and COLMAP pose files replay their poses at their times") {
  TempDir dir;
  std::ofstream tum(dir.path / "tum.txt"), kitti(dir.path / "kitti.txt"),
      colmap(dir.path / "images.txt");
  tum << "# timestamp tx ty tz qx qy qz qw\n";
  colmap << "# Image list with two lines of data per image:\n";
  char line[400];
  for (int k = 0; k < 5; ++k) {
    const Pose p = known_pose(k);
    const Eigen::Quaterniond q(p.linear());
    const Vec3 t = p.translation();
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n",
                  1e9 + 0.2 * k, t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
    tum << line;
    const Eigen::Matrix<double, 3, 4, Eigen::RowMajor> m = p.matrix().topRows<3>();
    for (int i = 0; i < 12; ++i) kitti << (i ? " " : "") << std::setprecision(17) << m.data()[i];
    kitti << "\n";
    const Pose w2c = p.inverse();  // COLMAP stores world -> camera, qw first, in any order
    const Eigen::Quaterniond qc(w2c.linear());
    std::snprintf(line, sizeof line,
                  "%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g 1 frame_%02d.png\n", 9 - k, qc.w(),
                  qc.x(), qc.y(), qc.z(), w2c.translation().x(), w2c.translation().y(),
                  w2c.translation().z(), 4 - k);
    colmap << line << "10.5 20.25 -1 30 40 7\n";
  }
  tum.close(), kitti.close(), colmap.close();
  const auto same = [](const Pose& a, const Pose& b) {
    return (a.translation() - b.translation()).norm() < 1e-9 &&
           angle_between(a.linear(), b.linear()) < 1e-9;
  };
  const auto tum_poses = read_pose_file(dir.path / "tum.txt", PoseFormat::Tum);
  const auto kitti_poses = read_pose_file(dir.path / "kitti.txt", PoseFormat::Kitti, 5);
  const auto colmap_poses = read_pose_file(dir.path / "images.txt", PoseFormat::Colmap, 5);
  REQUIRE(tum_poses.size() == 5);
  REQUIRE(kitti_poses.size() == 5);
  REQUIRE(colmap_poses.size() == 5);
  const PoseTrack replay = interpolated_track(tum_poses);
  for (int k = 0; k < 5; ++k) {
    CHECK(tum_poses[k].time == Approx(0.2 * k).margin(1e-6));  // shifted to start at 0
    CHECK(kitti_poses[k].time == Approx(0.2 * k));
    CHECK(same(tum_poses[k].pose, known_pose(k)));
    CHECK(same(kitti_poses[k].pose, known_pose(k)));
    CHECK(same(colmap_poses[k].pose, known_pose(4 - k)));  // ordered by name
    CHECK(same(replay(tum_poses[k].time), known_pose(k)));
  }
  // half way: the mean position, the rotation half way along the geodesic
  const Pose mid = interpolated_track(kitti_poses)(0.1);
  CHECK(
      (mid.translation() - (known_pose(0).translation() + known_pose(1).translation()) / 2).norm() <
      1e-12);
  CHECK(angle_between(mid.linear(), known_pose(0).linear()) ==
        Approx(angle_between(known_pose(0).linear(), known_pose(1).linear()) / 2));

  std::ofstream(dir.path / "bad.txt") << "0 1 2 3 0 0 0 1\n0.1 1 2 x 0 0 0 1\n";
  CHECK_THROWS_WITH(read_pose_file(dir.path / "bad.txt", PoseFormat::Tum),
                    Catch::Contains("bad.txt: line 2: a TUM pose is"));
  std::ofstream(dir.path / "back.txt") << "0 1 2 3 0 0 0 1\n0 1 2 3 0 0 0 1\n";
  CHECK_THROWS_WITH(read_pose_file(dir.path / "back.txt", PoseFormat::Tum),
                    Catch::Contains("back.txt: times must increase"));
  CHECK_THROWS_WITH(pose_format("euroc"), Catch::Contains("tum, kitti, colmap"));
}

TEST_CASE("hostile pose files and waypoints: one line each, with the file and line") {
  TempDir dir;
  const auto refused = [&](const std::string& name, const std::string& text, PoseFormat format,
                           const std::string& says) {
    std::ofstream(dir.path / name) << text;
    CHECK_THROWS_WITH(read_pose_file(dir.path / name, format),
                      Catch::Contains(name) && Catch::Contains(says));
  };
  // COLMAP writes a points line after every image, an empty one for an image without points:
  // a file without them lost every second image
  refused("nopoints.txt",
          "1 1 0 0 0 0 0 0 1 a.png\n2 1 0 0 0 1 0 0 1 b.png\n3 1 0 0 0 2 0 0 1 c.png\n",
          PoseFormat::Colmap, "line 2: not the line of 2-D points");
  refused("twice.txt", "1 1 0 0 0 0 0 0 1 a.png\n\n2 1 0 0 0 1 0 0 1 a.png\n\n", PoseFormat::Colmap,
          "line 3: image \"a.png\" is listed twice");
  refused("close.txt", "0 0 0 0 0 0 0 1\n1e-300 1 0 0 0 0 0 1\n", PoseFormat::Tum,
          "times must increase by at least a microsecond");
  refused("far.txt", "0 1e308 0 0 0 0 0 1\n0.1 0 0 0 0 0 0 1\n", PoseFormat::Tum,
          "line 1: its position lies beyond 1,000 km");
  std::filesystem::create_directories(dir.path / "folder.txt");
  CHECK_THROWS_WITH(read_pose_file(dir.path / "folder.txt", PoseFormat::Tum),
                    Catch::Contains("folder.txt: is a folder, expected a file"));
  CHECK_THROWS_WITH(read_pose_file("/dev/zero", PoseFormat::Tum),
                    Catch::Contains("/dev/zero: not a regular file"));
  {  // 200 MB (sparse): refused before a byte is read
    std::ofstream big(dir.path / "big.txt");
    big.seekp(200 << 20);
    big << "\n";
  }
  CHECK_THROWS_WITH(read_pose_file(dir.path / "big.txt", PoseFormat::Kitti),
                    Catch::Contains("big.txt: too large: "));
  const std::vector<Waypoint> close = {{{0, 0, 0}, 0.0, {}, {}}, {{1, 0, 0}, 1e-300, {}, {}}};
  CHECK_THROWS_WITH(waypoint_times(close),
                    Catch::Contains("waypoint 1: times must increase by at least a microsecond"));
}

TEST_CASE("a pose file's world turned into ours: KITTI's y-down world, COLMAP's by its gravity") {
  // cameras upright on a road that turns: their up is the world's, each looking along the road
  std::vector<TimedPose> upright;
  const Mat3 tilt = Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized()).toRotationMatrix();
  for (int k = 0; k < 6; ++k) {
    const double heading = 0.3 * k;  // about the world's up
    // a camera frame (x right, y down, z forward) looking along `heading` in a z-up world
    const Vec3 forward(std::cos(heading), std::sin(heading), 0), up(0, 0, 1);
    Mat3 camera;
    camera.col(2) = forward, camera.col(1) = -up, camera.col(0) = (-up).cross(forward);
    Pose pose = Pose::Identity();
    pose.linear() = tilt * camera;  // the reconstruction's arbitrary world
    pose.translation() = tilt * Vec3(2 * k, 0.1 * k, 1.5);
    upright.push_back({0.1 * k, pose});
  }
  const Mat3 gravity = ours_from_file_world({"gravity"}, upright);
  for (const TimedPose& p : upright) {
    const Mat3 ours = gravity * p.pose.linear();
    CHECK((ours.col(1) - Vec3(0, 0, -1)).norm() < 1e-12);  // every camera's down is ours
  }
  // the first camera looks along our x
  CHECK(((gravity * upright[0].pose.linear()).col(2) - Vec3::UnitX()).norm() < 1e-12);
  // up given: the same turn
  CHECK(ours_from_file_world({"up", tilt * Vec3::UnitZ()}, upright).isApprox(gravity, 1e-12));
  // KITTI: x right, y down, z forward -> ours x forward, y left, z up
  const Mat3 kitti = ours_from_file_world({"y_down"}, upright);
  CHECK((kitti * Vec3::UnitZ() - Vec3::UnitX()).norm() == 0);
  CHECK((kitti * Vec3::UnitX() + Vec3::UnitY()).norm() == 0);
  CHECK((kitti * Vec3::UnitY() + Vec3::UnitZ()).norm() == 0);
  CHECK(ours_from_file_world({"z_up"}, upright) == Mat3::Identity());
  CHECK_THROWS_WITH(ours_from_file_world({"y_up"}, upright), Catch::Contains("\"y_up\" is not"));
  CHECK_THROWS_WITH(ours_from_file_world({"up", upright[0].pose.linear().col(2)}, upright),
                    Catch::Contains("looks straight along the up direction"));
}
