#include "flowscape/scenes/trajectory.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "flowscape/core/files.h"

namespace flowscape {
namespace {

constexpr double kDegree = kPi / 180;
// The least time between two waypoints or poses: closer ones would make the spline's slopes
// overflow (waypoints 1e-300 s apart), and no tracker samples faster.
constexpr double kShortestStep = 1e-6;
// The largest pose file read: some 400,000 KITTI lines, a day of a 5 Hz tracker.
constexpr std::uintmax_t kMaxPoseFileBytes = std::uintmax_t(1) << 26;

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// A natural cubic spline of one value over increasing knots (Numerical Recipes' spline/splint):
// second derivatives M from the tridiagonal system, M at both ends 0.
class NaturalSpline {
 public:
  NaturalSpline(std::vector<double> t, std::vector<double> y)
      : t_(std::move(t)), y_(std::move(y)), m_(t_.size(), 0) {
    const std::size_t n = t_.size();
    std::vector<double> u(n, 0);
    for (std::size_t i = 1; i + 1 < n; ++i) {  // forward sweep
      const double sig = (t_[i] - t_[i - 1]) / (t_[i + 1] - t_[i - 1]);
      const double p = sig * m_[i - 1] + 2;
      m_[i] = (sig - 1) / p;
      u[i] = (y_[i + 1] - y_[i]) / (t_[i + 1] - t_[i]) - (y_[i] - y_[i - 1]) / (t_[i] - t_[i - 1]);
      u[i] = (6 * u[i] / (t_[i + 1] - t_[i - 1]) - sig * u[i - 1]) / p;
    }
    m_[n - 1] = 0;
    for (std::size_t k = n - 1; k-- > 0;) m_[k] = m_[k] * m_[k + 1] + u[k];
  }
  double value(double t) const {
    const auto [i, a, b, h] = segment(t);
    return a * y_[i] + b * y_[i + 1] +
           ((a * a * a - a) * m_[i] + (b * b * b - b) * m_[i + 1]) * h * h / 6;
  }
  double slope(double t) const {
    const auto [i, a, b, h] = segment(t);
    return (y_[i + 1] - y_[i]) / h - (3 * a * a - 1) / 6 * h * m_[i] +
           (3 * b * b - 1) / 6 * h * m_[i + 1];
  }

 private:
  struct Segment {
    std::size_t i;
    double a, b, h;
  };
  Segment segment(double t) const {
    t = std::clamp(t, t_.front(), t_.back());
    const std::size_t i =
        std::min<std::size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin(),
                              t_.size() - 1) -
        1;
    const double h = t_[i + 1] - t_[i];
    return {i, (t_[i + 1] - t) / h, (t - t_[i]) / h, h};
  }
  std::vector<double> t_, y_, m_;
};

Mat3 rotation_of(double yaw, double pitch, double roll) {  // yaw_pitch_roll's, in radians
  return (Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(-pitch, Vec3::UnitY()) *
          Eigen::AngleAxisd(roll, Vec3::UnitX()))
      .toRotationMatrix();
}

// The angles of the keys, each turned by whole turns to within half a turn of the one before.
std::vector<double> unwrapped(const std::vector<Waypoint>& waypoints, int axis) {
  std::vector<double> angles;
  for (const Waypoint& w : waypoints) {
    double a = (*w.yaw_pitch_roll_degrees)[axis] * kDegree;
    if (!angles.empty()) a -= 2 * kPi * std::round((a - angles.back()) / (2 * kPi));
    angles.push_back(a);
  }
  return angles;
}

std::string line_error(int line, const std::string& what) {
  return "line " + std::to_string(line) + ": " + what;
}

Pose pose_of(const Vec3& t, const Eigen::Quaterniond& q, int line) {
  require(std::abs(q.norm() - 1) < 1e-3, line_error(line, "its quaternion is not a unit one"));
  Pose pose = Pose::Identity();
  pose.linear() = q.normalized().toRotationMatrix();
  pose.translation() = t;
  return pose;
}

// The numbers of a line, or nothing for a blank or comment line.
std::vector<double> numbers_of(const std::string& line) {
  std::istringstream in(line);
  std::vector<double> numbers;
  for (std::string word; in >> word;) {
    if (word[0] == '#') break;
    std::size_t used = 0;
    double value = 0;
    try {
      value = std::stod(word, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != word.size() || !std::isfinite(value)) return {std::nan("")};
    numbers.push_back(value);
  }
  return numbers;
}

// A pose file's camera must lie where Embree can trace from (kFarthestPosition).
void require_within_world(const Pose& pose, int line) {
  require(within_world(pose.translation()),
          line_error(line, "its position lies beyond 1,000 km of the origin"));
}

std::vector<TimedPose> tum_or_kitti(std::istream& in, PoseFormat format, double rate) {
  std::vector<TimedPose> poses;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    const std::vector<double> v = numbers_of(text);
    if (v.empty()) continue;
    if (format == PoseFormat::Tum) {
      require(v.size() == 8, line_error(line, "a TUM pose is: time tx ty tz qx qy qz qw"));
      poses.push_back({v[0], pose_of({v[1], v[2], v[3]}, {v[7], v[4], v[5], v[6]}, line)});
      require_within_world(poses.back().pose, line);
    } else {
      require(v.size() == 12, line_error(line, "a KITTI pose is 12 numbers (3 x 4, row-major)"));
      Pose pose = Pose::Identity();
      pose.matrix().topRows<3>() =
          Eigen::Map<const Eigen::Matrix<double, 3, 4, Eigen::RowMajor>>(v.data());
      const Mat3 r = pose.linear();
      require((r.transpose() * r - Mat3::Identity()).norm() < 1e-5 && r.determinant() > 0,
              line_error(line, "its 3 x 3 part is not a rotation"));
      require_within_world(pose, line);
      poses.push_back({double(poses.size()) / rate, pose});
    }
  }
  return poses;
}

std::vector<TimedPose> colmap(std::istream& in, double rate) {
  std::map<std::string, Pose> by_name;  // COLMAP lists images in any order
  std::string text;
  bool points_line = false;
  for (int line = 1; std::getline(in, text); ++line) {
    if (!text.empty() && text[0] == '#') continue;
    std::istringstream words(text);
    if (points_line) {  // X Y POINT3D_ID triples; empty for an image without points
      points_line = false;
      std::size_t count = 0;
      for (std::string word; words >> word;) ++count;
      require(count % 3 == 0,
              line_error(line,
                         "not the line of 2-D points (X Y POINT3D_ID ...) that COLMAP "
                         "writes after each image, an empty one for an image without "
                         "points"));
      continue;
    }
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    double id, qw, qx, qy, qz, tx, ty, tz, camera;
    std::string name;
    require(bool(words >> id >> qw >> qx >> qy >> qz >> tx >> ty >> tz >> camera >> name),
            line_error(line, "a COLMAP image is: IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME"));
    const Pose world_to_camera = pose_of({tx, ty, tz}, {qw, qx, qy, qz}, line);
    require(by_name.emplace(name, world_to_camera.inverse()).second,
            line_error(line, "image \"" + name + "\" is listed twice"));
    require_within_world(by_name[name], line);
    points_line = true;
  }
  std::vector<TimedPose> poses;
  for (const auto& [name, pose] : by_name) poses.push_back({double(poses.size()) / rate, pose});
  return poses;
}

}  // namespace

Mat3 yaw_pitch_roll(double yaw_degrees, double pitch_degrees, double roll_degrees) {
  return rotation_of(yaw_degrees * kDegree, pitch_degrees * kDegree, roll_degrees * kDegree);
}

std::vector<double> waypoint_times(const std::vector<Waypoint>& waypoints) {
  require(waypoints.size() >= 2, "a path needs at least 2 waypoints");
  std::vector<double> times;
  const bool keys = waypoints.front().yaw_pitch_roll_degrees.has_value();
  for (std::size_t k = 0; k < waypoints.size(); ++k) {
    const Waypoint& w = waypoints[k];
    const std::string what = "waypoint " + std::to_string(k) + ": ";
    require(within_world(w.position), what + "its position must be finite, within 1,000 km");
    require(w.yaw_pitch_roll_degrees.has_value() == keys,
            what + "give yaw_pitch_roll_degrees at every waypoint or at none");
    require(!(w.time && w.speed), what + "give its time or its speed, not both");
    if (k == 0) {
      require(!w.speed, what + "the first waypoint has a time (default 0), not a speed");
      times.push_back(w.time.value_or(0));
    } else if (w.speed) {
      require(*w.speed > 0 && std::isfinite(*w.speed), what + "its speed must be positive");
      times.push_back(times.back() + (w.position - waypoints[k - 1].position).norm() / *w.speed);
    } else {
      require(w.time.has_value(), what + "give its time or the speed it is reached at");
      times.push_back(*w.time);
    }
    require(std::isfinite(times.back()) && (k == 0 || times.back() >= times[k - 1] + kShortestStep),
            what + "times must increase by at least a microsecond (a speed must move it)");
  }
  return times;
}

PoseTrack waypoint_track(const std::vector<Waypoint>& waypoints) {
  const std::vector<double> times = waypoint_times(waypoints);
  std::vector<NaturalSpline> position;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> values;
    for (const Waypoint& w : waypoints) values.push_back(w.position[axis]);
    position.emplace_back(times, values);
  }
  std::vector<NaturalSpline> angles;
  if (waypoints.front().yaw_pitch_roll_degrees)
    for (int axis = 0; axis < 3; ++axis) angles.emplace_back(times, unwrapped(waypoints, axis));
  return [position, angles](double t) {
    Pose pose = Pose::Identity();
    pose.translation() = Vec3(position[0].value(t), position[1].value(t), position[2].value(t));
    if (!angles.empty()) {
      pose.linear() = rotation_of(angles[0].value(t), angles[1].value(t), angles[2].value(t));
    } else {
      const Vec3 v(position[0].slope(t), position[1].slope(t), position[2].slope(t));
      pose.linear() =
          rotation_of(std::atan2(v.y(), v.x()), std::atan2(v.z(), v.head<2>().norm()), 0);
    }
    return pose;
  };
}

PoseFormat pose_format(const std::string& name) {
  if (name == "tum") return PoseFormat::Tum;
  if (name == "kitti") return PoseFormat::Kitti;
  if (name == "colmap") return PoseFormat::Colmap;
  throw std::invalid_argument("unknown pose file format \"" + name + "\" (tum, kitti, colmap)");
}

std::vector<TimedPose> read_pose_file(const std::filesystem::path& file, PoseFormat format,
                                      double rate) {
  require_regular_file(file, kMaxPoseFileBytes);
  std::ifstream in(file, std::ios::binary);
  std::vector<TimedPose> poses;
  try {
    require(rate > 0 && std::isfinite(rate), "the pose rate must be positive");
    poses = format == PoseFormat::Colmap ? colmap(in, rate) : tum_or_kitti(in, format, rate);
    require(poses.size() >= 2, "fewer than 2 poses");
    for (std::size_t k = 1; k < poses.size(); ++k)
      require(poses[k].time >= poses[k - 1].time + kShortestStep,
              "times must increase by at least a microsecond (pose " + std::to_string(k) + ")");
  } catch (const std::invalid_argument& e) {
    throw FileError(file, e.what());
  }
  const double start = poses.front().time;
  for (TimedPose& p : poses) p.time -= start;
  return poses;
}

Mat3 ours_from_file_world(const PoseWorld& world, const std::vector<TimedPose>& poses) {
  if (world.frame == "z_up") return Mat3::Identity();
  if (world.frame == "y_down") return (Mat3() << 0, 0, 1, -1, 0, 0, 0, -1, 0).finished();
  Vec3 up = world.up;
  if (world.frame == "gravity") {
    up = Vec3::Zero();
    for (const TimedPose& p : poses) up -= p.pose.linear().col(1);
  } else {
    require(world.frame == "up", "world_frame \"" + world.frame +
                                     "\" is not z_up, y_down, gravity or {\"up\": [x, y, z]}");
  }
  require(up.norm() > 1e-9, "world_frame: the up direction is zero");
  up.normalize();
  const Vec3 view = poses.front().pose.linear().col(2);
  const Vec3 forward = view - view.dot(up) * up;  // the first camera's view on the ground
  require(forward.norm() > 1e-6,
          "world_frame: the first camera looks straight along the up "
          "direction, so no forward is on the ground");
  Mat3 rows;
  rows.row(0) = forward.normalized().transpose();
  rows.row(2) = up.transpose();
  rows.row(1) = rows.row(2).cross(rows.row(0));  // left = up x forward
  return rows;
}

PoseTrack interpolated_track(std::vector<TimedPose> poses) {
  return [poses = std::move(poses)](double t) {
    if (t <= poses.front().time) return poses.front().pose;
    if (t >= poses.back().time) return poses.back().pose;
    const auto next =
        std::upper_bound(poses.begin(), poses.end(), t,
                         [](double time, const TimedPose& p) { return time < p.time; });
    const TimedPose &a = *(next - 1), &b = *next;
    const double w = (t - a.time) / (b.time - a.time);
    Pose pose = Pose::Identity();
    pose.translation() = (1 - w) * a.pose.translation() + w * b.pose.translation();
    pose.linear() = Eigen::Quaterniond(a.pose.linear())
                        .slerp(w, Eigen::Quaterniond(b.pose.linear()))
                        .toRotationMatrix();
    return pose;
  };
}

}  // namespace flowscape
