#include "gait.h"

#include <algorithm>
#include <cmath>

namespace flowscape::assets {
namespace {

using M3 = Eigen::Matrix3d;

constexpr double kHeelRock = 0.26,
                 kToeRock = 0.6;  // radians: toes up at heel strike, heel up at toe off
constexpr double kHeelShare = 0.15,
                 kToeShare = 0.3;  // of the stance: rolling on the heel, on the ball
constexpr double kReach = 0.995;   // of the leg's length, at most

M3 about_y(double a) { return Eigen::AngleAxisd(a, V3::UnitY()).toRotationMatrix(); }
M3 about_z(double a) { return Eigen::AngleAxisd(a, V3::UnitZ()).toRotationMatrix(); }
double smooth(double s) { return s * s * (3 - 2 * s); }

// A rotation taking the rest frame (bone along rest_dir, bending toward rest_hint) to the posed
// one.
M3 frame_turn(const V3& dir, const V3& hint, const V3& rest_dir, const V3& rest_hint) {
  const auto basis = [](const V3& d, const V3& h) {
    const V3 e3 = d.normalized();
    V3 e1 = h - h.dot(e3) * e3;
    e1 = e1.norm() > 1e-9 ? V3(e1.normalized()) : V3(e3.unitOrthogonal());
    M3 b;
    b << e1, e3.cross(e1), e3;
    return b;
  };
  return basis(dir, hint) * basis(rest_dir, rest_hint).transpose();
}

// Two-bone inverse kinematics: the world rotations of the upper and lower bone (lengths l1, l2)
// from `root` reaching for `target`, the middle joint bending toward `hint`.
std::pair<M3, M3> two_bone(const V3& root, const V3& target, double l1, double l2, const V3& hint,
                           const V3& rest_upper, const V3& rest_lower, const V3& rest_hint) {
  V3 d = target - root;
  const double reach = std::clamp(d.norm(), 0.25 * (l1 + l2), kReach * (l1 + l2));
  d = d.norm() > 1e-9 ? V3(d.normalized()) : V3(-V3::UnitZ());
  const double cos_a =
      std::clamp((l1 * l1 + reach * reach - l2 * l2) / (2 * l1 * reach), -1.0, 1.0);
  V3 side = hint - hint.dot(d) * d;
  side = side.norm() > 1e-9 ? V3(side.normalized()) : V3(d.unitOrthogonal());
  const V3 middle = root + l1 * (cos_a * d + std::sqrt(1 - cos_a * cos_a) * side);
  const V3 end = root + reach * d;
  return {frame_turn(middle - root, hint, rest_upper, rest_hint),
          frame_turn(end - middle, hint, rest_lower, rest_hint)};
}

// The rotation of a bone's world frame: the skinning matrix's linear part.
M3 world_of(const std::vector<Pose>& bones, int b) { return bones[std::size_t(b)].linear(); }

Pose pivot(const V3& joint, const M3& rotation) {
  return Pose(Eigen::Translation3d(joint)) * Pose(rotation) * Pose(Eigen::Translation3d(-joint));
}

// Locals of the legs reaching for the two ankles (actor frame), the knees toward `forward`.
void legs(const Skeleton& s, const Pose& pelvis, const V3 ankle[2], const M3 foot[2],
          const V3& forward, std::array<M3, kBones>& local) {
  for (int i = 0; i < 2; ++i) {
    const int o = i == 0 ? 0 : 3;
    const V3 hip = pelvis * s.joints[std::size_t(kThighL + o)];
    const V3 rest_thigh = s.joints[std::size_t(kShinL + o)] - s.joints[std::size_t(kThighL + o)];
    const V3 rest_shin = s.joints[std::size_t(kFootL + o)] - s.joints[std::size_t(kShinL + o)];
    const auto [thigh, shin] =
        two_bone(hip, ankle[i], s.thigh, s.shin, forward, rest_thigh, rest_shin, V3::UnitX());
    local[std::size_t(kThighL + o)] = pelvis.linear().transpose() * thigh;
    local[std::size_t(kShinL + o)] = thigh.transpose() * shin;
    local[std::size_t(kFootL + o)] = shin.transpose() * foot[i];
  }
}

// Where the pelvis is when both ankles must stay within reach: the hip joints no higher than
// the legs allow (continuous in the feet, so the pelvis moves smoothly).
double hip_height(const Skeleton& s, const V3 ankle[2], double rest) {
  double h = rest;
  const double leg = kReach * (s.thigh + s.shin);
  for (int i = 0; i < 2; ++i) {
    const V3 hip(0, (i == 0 ? 1 : -1) * s.hip_y, 0);
    const double horizontal = (ankle[i] - hip).head<2>().norm();
    h = std::min(h, ankle[i].z() + std::sqrt(std::max(0.0, leg * leg - horizontal * horizontal)));
  }
  return h;
}

double moving_share(const Track& track, double t) {
  const double speed = (track.distance_at(t + 0.05) - track.distance_at(t - 0.05)) / 0.1;
  return std::clamp(speed / 0.3, 0.0, 1.0);
}

}  // namespace

Gait gait_for(const Skeleton& skeleton, double speed, std::uint64_t seed, bool umbrella) {
  Random random(mix_bits(seed ^ 0x67616974ull));  // "gait"
  Gait g;
  const double H = skeleton.height, running = speed > 2.2;
  g.step = (running ? 0.62 : 0.38) * H * std::pow(std::max(speed, 0.5) / 1.4, running ? 0.5 : 0.4);
  g.stance = running ? 0.38 : 0.6;
  g.phase = random.uniform();
  g.clearance = (running ? 0.12 : 0.05) * H;
  g.arm_swing = running ? 0.7 : random.uniform(0.25, 0.42);
  g.look_period = random.uniform(4, 9), g.look_phase = random.uniform(0, 2 * kPi);
  g.look_amplitude = random.uniform(0.15, 0.5);
  g.umbrella = umbrella;
  return g;
}

Pose pose_at_distance(const Track& track, double distance) {
  const std::vector<double>& d = track.distance;
  const auto ahead = [](const Pose& p, double by) {
    return p * Pose(Eigen::Translation3d(by, 0, 0));
  };
  if (d.empty()) return track.poses.empty() ? Pose::Identity() : track.poses.front();
  if (distance <= d.front()) return ahead(track.poses.front(), distance - d.front());
  if (distance >= d.back()) return ahead(track.poses.back(), distance - d.back());
  const std::size_t k = std::size_t(std::upper_bound(d.begin(), d.end(), distance) - d.begin()) - 1;
  const double w = (distance - d[k]) / (d[k + 1] - d[k]);
  return track.pose((double(k) + w) * track.step);
}

FootState foot_state(const Skeleton& s, const Gait& g, const Track& track, int side, double t) {
  const double stride = 2 * g.step, offset = side > 0 ? 0 : 0.5;
  const double cycles = track.distance_at(t) / stride + g.phase + offset;
  const double k = std::floor(cycles), u = cycles - k;
  const double heel = 0.24 * s.foot, ball = 0.55 * s.foot;
  // the flat-foot ankle of stance k: under the pelvis 40 % into the stance
  const auto plant = [&](double n) {
    const Pose p = pose_at_distance(track, (n + 0.4 * g.stance - g.phase - offset) * stride) *
                   Pose(Eigen::Translation3d(0, side * s.hip_y, 0));
    return std::pair{V3(p.translation() + V3(0, 0, s.ankle)), yaw_of(p)};
  };
  // the ankle of a foot planted at (ankle, yaw) rolled by `pitch` about its heel (pitch > 0) or
  // ball (< 0), and that contact point
  const auto rolled = [&](const V3& ankle, double yaw, double pitch) {
    const V3 forward(std::cos(yaw), std::sin(yaw), 0);
    const V3 contact = ankle - V3(0, 0, s.ankle) +
                       (pitch > 0   ? -heel
                        : pitch < 0 ? ball
                                    : 0) *
                           forward;
    const V3 arm = ankle - contact;  // from the contact to the ankle, in the foot's vertical plane
    const double along = arm.dot(forward), c = std::cos(pitch), sn = std::sin(pitch);
    const V3 turned = (along * c - arm.z() * sn) * forward + V3(0, 0, along * sn + arm.z() * c);
    return std::pair{V3(contact + turned), contact};
  };
  FootState foot;
  const auto [ankle, yaw] = plant(k);
  if (u < g.stance) {
    const double v = u / g.stance;
    const double pitch = v < kHeelShare      ? kHeelRock * (1 - v / kHeelShare)
                         : v > 1 - kToeShare ? -kToeRock * (v - (1 - kToeShare)) / kToeShare
                                             : 0;
    const auto [at, contact] = rolled(ankle, yaw, pitch);
    return {at, yaw, pitch, true, contact};
  }
  const double m = moving_share(track, t), s_swing = (u - g.stance) / (1 - g.stance);
  const auto [next, next_yaw] = plant(k + 1);
  const V3 off = rolled(ankle, yaw, -kToeRock).first, on = rolled(next, next_yaw, kHeelRock).first;
  const double w = smooth(s_swing);
  V3 at = (1 - w) * off + w * on;
  const double ground = (1 - w) * ankle.z() + w * next.z();
  at.z() = ground + m * (at.z() - ground) + m * g.clearance * std::sin(kPi * s_swing);
  foot.ankle_world = at;
  foot.yaw = yaw + wrapped_angle(next_yaw - yaw) * w;
  foot.pitch = m * ((1 - s_swing) * -kToeRock + s_swing * kHeelRock);
  return foot;
}

BoneTrack walking(const PersonModel& person, std::shared_ptr<const Track> track, Gait g) {
  const Skeleton s = person.skeleton;
  return [s, track, g](double t) {
    const Pose actor = track->pose(t), to_actor = actor.inverse();
    const double actor_yaw = yaw_of(actor), m = moving_share(*track, t);
    const double cycle = 2 * kPi * (track->distance_at(t) / (2 * g.step) + g.phase);
    V3 ankle[2];
    M3 foot[2];
    for (int i = 0; i < 2; ++i) {
      const FootState f = foot_state(s, g, *track, i == 0 ? 1 : -1, t);
      ankle[i] = to_actor * f.ankle_world;
      foot[i] = about_z(wrapped_angle(f.yaw - actor_yaw)) * about_y(-f.pitch);
    }
    const double rest = s.joints[kPelvis].z();
    const double idle = (1 - m) * 0.006 * s.height * std::sin(2 * kPi * t / 3.7 + g.look_phase);
    const V3 root(0, 0.012 * s.height * m * std::sin(cycle - 0.3) + idle,
                  hip_height(s, ankle, rest - 0.01 * s.height * m) - rest);
    const double yaw = -0.07 * m * std::cos(cycle), lean = 0.04 * m;
    std::array<M3, kBones> local;
    local.fill(M3::Identity());
    local[kPelvis] = about_z(yaw) * about_y(lean);
    const Pose pelvis = Pose(Eigen::Translation3d(root)) * pivot(s.joints[kPelvis], local[kPelvis]);
    legs(s, pelvis, ankle, foot, pelvis.linear() * V3::UnitX(), local);
    local[kSpine] = about_z(-0.5 * yaw), local[kChest] = about_z(-0.6 * yaw);
    const double look = g.look_amplitude * std::sin(2 * kPi * t / g.look_period + g.look_phase);
    local[kNeck] = about_z(0.3 * look) * about_y(0.04), local[kHead] = about_z(0.7 * look);
    for (int side : {1, -1}) {
      const int o = side > 0 ? 0 : 3;
      const double swing = side * -g.arm_swing * m * std::cos(cycle);  // against the same leg
      local[std::size_t(kUpperArmL + o)] = about_y(-swing);
      local[std::size_t(kForearmL + o)] = about_y(-(0.15 + 0.25 * m + 0.3 * std::max(0.0, swing)));
    }
    if (g.umbrella) {  // the right forearm up, the hand turning the stick upright
      local[kUpperArmR] = about_y(-0.45), local[kForearmR] = about_y(-1.5);
      local[kHandR] = about_y(kPi / 2 - 1.95);
    }
    return forward_kinematics(s, local, root);
  };
}

double rider_height(const VehicleModel& bike) {
  const V3 hip = bike.saddle + V3(0, 0, 0.06);
  const V3 low = bike.cranks ? V3(bike.bottom_bracket + V3(-0.05, 0, 0.07 - bike.crank_length))
                             : V3(bike.pegs + V3(-0.05, 0, 0.07));
  return std::clamp((hip - low).norm() / (0.97 * 0.48), 1.55, 1.95);
}

BoneTrack riding(const PersonModel& person, const VehicleModel& bike,
                 std::shared_ptr<const Track> track) {
  const Skeleton s = person.skeleton;
  const bool pedals = bike.cranks != nullptr;
  const double wheel = bike.wheel_radius.front(), lean = pedals ? 0.55 : 0.35;
  return [s, bike, track, pedals, wheel, lean](double t) {
    std::array<M3, kBones> local;
    local.fill(M3::Identity());
    local[kPelvis] = about_y(lean);
    const V3 root = bike.saddle + V3(-0.02, 0, 0.06) - s.joints[kPelvis];
    const Pose pelvis = Pose(Eigen::Translation3d(root)) * pivot(s.joints[kPelvis], local[kPelvis]);
    const double crank = track->distance_at(t) / (wheel * bike.gear);
    V3 ankle[2];
    M3 foot[2];
    for (int i = 0; i < 2; ++i) {
      const int side = i == 0 ? 1 : -1;
      if (pedals) {  // the left pedal leads the crank's +x arm, the right one the other
        const V3 pedal = bike.bottom_bracket + about_y(crank) * V3(side * bike.crank_length, 0, 0) +
                         V3(0, side * 0.13, 0);
        ankle[i] = pedal + V3(-0.05, 0, 0.07);
      } else {
        ankle[i] = bike.pegs + V3(-0.03, side * bike.peg_spread, 0.07);
      }
      foot[i] = about_y(-0.15);
    }
    legs(s, pelvis, ankle, foot, V3::UnitX(), local);
    local[kChest] = about_y(0.1);
    local[kNeck] = about_y(-0.4 * lean), local[kHead] = about_y(-0.5 * lean);
    std::vector<Pose> bones = forward_kinematics(s, local, root);
    for (int side : {1, -1}) {  // hands on the grips
      const int o = side > 0 ? 0 : 3;
      const V3 shoulder = bones[kChest] * s.joints[std::size_t(kUpperArmL + o)];
      const V3 grip = bike.grips + V3(-0.06, side * bike.grip_spread, 0.0);
      const V3 rest_upper =
          s.joints[std::size_t(kForearmL + o)] - s.joints[std::size_t(kUpperArmL + o)];
      const V3 rest_fore = s.joints[std::size_t(kHandL + o)] - s.joints[std::size_t(kForearmL + o)];
      const auto [upper, fore] =
          two_bone(shoulder, grip, s.upper_arm, s.forearm, V3(-0.4, side * 0.8, -1), rest_upper,
                   rest_fore, V3(-0.4, side * 0.8, -1));
      local[std::size_t(kUpperArmL + o)] = world_of(bones, kChest).transpose() * upper;
      local[std::size_t(kForearmL + o)] = upper.transpose() * fore;
    }
    return forward_kinematics(s, local, root);
  };
}

}  // namespace flowscape::assets
