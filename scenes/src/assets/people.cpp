#include "people.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "flowscape/scenes/shapes.h"

namespace flowscape::assets {
namespace {

// Body measures, metres (anthropometric shares of the height, scaled by the build).
struct Measures {
  double H;
  double ankle, knee, crotch, hip, waist, chest, shoulder, neck_base, chin, crown;
  double hip_y, shoulder_y;
  double hip_w, hip_d, waist_w, waist_d, chest_w, chest_d, shoulder_w;
  double thigh_r, knee_r, calf_r, ankle_r, upper_arm_r, elbow_r, forearm_r, wrist_r, neck_r;
  double head_w, head_d, head_h;
  double upper_arm, forearm, hand, foot, foot_w;
};

Measures measures(const Look& look) {
  const double H = look.height, b = look.build, f = look.female ? 1 : 0;
  Measures m{};
  m.H = H;
  const double head = look.child ? 0.165 : 0.13;  // children have larger heads
  m.crown = H, m.chin = H * (1 - head), m.head_h = H * head;
  m.neck_base = m.chin - H * (look.child ? 0.03 : 0.04);
  m.shoulder = m.neck_base - H * 0.018;
  const double legs = look.child ? 0.47 : 0.52;  // hip joint height share
  m.hip = H * legs, m.crotch = m.hip - H * 0.045, m.knee = H * (legs * 0.55), m.ankle = H * 0.04;
  m.waist = m.hip + (m.shoulder - m.hip) * 0.32, m.chest = m.hip + (m.shoulder - m.hip) * 0.66;
  const double w = H * (look.child ? 1.08 : 1.0);  // children are a little stockier for their size
  m.hip_y = w * (0.048 + 0.004 * f) * b, m.shoulder_y = w * (0.112 - 0.007 * f) * std::sqrt(b);
  m.hip_w = w * (0.097 + 0.008 * f) * b, m.hip_d = w * (0.062 + 0.004 * f) * b;
  m.waist_w = w * (0.086 - 0.01 * f) * b, m.waist_d = w * (0.057 - 0.004 * f) * b;
  m.chest_w = w * (0.099 - 0.006 * f) * b, m.chest_d = w * (0.06 + 0.003 * f) * b;
  m.shoulder_w = m.shoulder_y + w * 0.02;
  const double limb = w * std::sqrt(b) * (1 - 0.06 * f);
  m.thigh_r = limb * 0.047, m.knee_r = limb * 0.029, m.calf_r = limb * 0.033,
  m.ankle_r = limb * 0.019;
  m.upper_arm_r = limb * 0.025, m.elbow_r = limb * 0.018, m.forearm_r = limb * 0.02;
  m.wrist_r = limb * 0.014, m.neck_r = limb * 0.033;
  m.head_w = H * (look.child ? 0.058 : 0.044), m.head_d = H * (look.child ? 0.07 : 0.056);
  m.upper_arm = H * 0.186, m.forearm = H * 0.146, m.hand = H * 0.105;
  m.foot = H * 0.152, m.foot_w = H * 0.03;
  return m;
}

// Up to four bones and their weights, summing to 1.
struct Weights {
  std::array<std::uint8_t, 4> bones{0, 0, 0, 0};
  Eigen::Vector4f weights{1, 0, 0, 0};
};
Weights only(int bone) { return {{std::uint8_t(bone), 0, 0, 0}, {1, 0, 0, 0}}; }
Weights blend(int a, int b, double s) {
  s = std::clamp(s, 0.0, 1.0);
  return {{std::uint8_t(a), std::uint8_t(b), 0, 0}, {float(1 - s), float(s), 0, 0}};
}
double ramp(double x, double centre, double half) {  // 0 below centre - half, 1 above centre + half
  const double s = std::clamp((x - centre + half) / (2 * half), 0.0, 1.0);
  return s * s * (3 - 2 * s);
}

using WeightFn = std::function<Weights(const V3&)>;

// Adds a component, each vertex skinned by `weights` of its rest position.
void add_skinned(Mesh& body, Mesh component, const WeightFn& weights) {
  component.bones.clear(), component.weights.clear();
  for (const Eigen::Vector3f& v : component.vertices) {
    const Weights w = weights(v.cast<double>());
    component.bones.push_back(w.bones), component.weights.push_back(w.weights);
  }
  append_with_skin(body, component);
}

// A tube through sections along a polyline: rows (point, half width along `side`, half depth
// along x), superelliptic sections (exponent `power`), closed by cap points at both ends.
struct Ring {
  V3 centre;
  double width, depth;
};
Mesh tube_through(const std::vector<Ring>& rings, double power, SemanticClass cls,
                  const std::function<std::uint16_t(const V3&)>& slot, bool caps = true,
                  int sides = 12) {
  Grid grid{int(rings.size()) + (caps ? 2 : 0), sides, true, {}};
  const auto ring_points = [&](const Ring& r) {
    for (int k = 0; k < sides; ++k) {
      const double a = 2 * kPi * k / sides, c = std::cos(a), s = std::sin(a);
      const double e = 2 / power;
      grid.points.push_back(r.centre + V3(r.depth * std::copysign(std::pow(std::abs(c), e), c),
                                          r.width * std::copysign(std::pow(std::abs(s), e), s), 0));
    }
  };
  if (caps) grid.points.insert(grid.points.end(), sides, rings.front().centre);
  for (const Ring& r : rings) ring_points(r);
  if (caps) grid.points.insert(grid.points.end(), sides, rings.back().centre);
  Mesh mesh;
  add_grid(mesh, grid, [&](int r, int c) {
    const V3 centre = (grid.at(r, c) + grid.at(r + 1, (c + 1) % sides)) / 2;
    return QuadPaint{cls, slot(centre)};
  });
  return mesh;
}

// A limb along a chain of joints, its sections perpendicular to each segment (rings given by the
// share along the chain and radius), skinned along the chain.
Mesh limb(const std::vector<V3>& joints, const std::vector<std::pair<double, double>>& radii,
          SemanticClass cls, const std::function<std::uint16_t(double)>& slot, int sides = 10) {
  std::vector<double> length{0};
  for (std::size_t k = 1; k < joints.size(); ++k)
    length.push_back(length.back() + (joints[k] - joints[k - 1]).norm());
  const auto point_at = [&](double share) {
    const double s = share * length.back();
    std::size_t k = 1;
    while (k + 1 < joints.size() && length[k] < s) ++k;
    const double t = (s - length[k - 1]) / (length[k] - length[k - 1]);
    return V3(joints[k - 1] + t * (joints[k] - joints[k - 1]));
  };
  Grid grid{int(radii.size()) + 2, sides, true, {}};
  std::vector<double> shares;
  const auto ring = [&](double share, double radius) {
    const double h = 0.01;
    const V3 axis =
        (point_at(std::min(share + h, 1.0)) - point_at(std::max(share - h, 0.0))).normalized();
    const V3 u = (V3::UnitX() - V3::UnitX().dot(axis) * axis).normalized(), v = axis.cross(u);
    const V3 centre = point_at(share);
    for (int k = 0; k < sides; ++k) {
      const double a = 2 * kPi * k / sides;
      grid.points.push_back(centre + radius * (std::cos(a) * u + std::sin(a) * v));
    }
  };
  grid.points.insert(grid.points.end(), sides, point_at(radii.front().first));
  for (const auto& [share, radius] : radii) ring(share, radius), shares.push_back(share);
  grid.points.insert(grid.points.end(), sides, point_at(radii.back().first));
  Mesh mesh;
  add_grid(mesh, grid, [&](int r, int) {
    const double share = shares[std::size_t(std::clamp(r - 1, 0, int(shares.size()) - 1))];
    return QuadPaint{cls, slot(share)};
  });
  return mesh;
}

std::uint16_t fixed(PersonSlot slot) { return slot; }

struct Builder {
  const Look& look;
  const Measures m;
  SemanticClass cls;
  Skeleton skeleton{};
  Mesh mesh;

  V3 shoulder(int side) const { return {0, side * m.shoulder_y, m.shoulder}; }
  V3 elbow(int side) const {
    return shoulder(side) + m.upper_arm * V3(0.0, side * 0.09, -1).normalized();
  }
  V3 wrist(int side) const {
    return elbow(side) + m.forearm * V3(0.12, side * 0.06, -1).normalized();
  }

  void make_skeleton() {
    Skeleton& s = skeleton;
    s.height = m.H;
    s.parent = {-1,         kPelvis,   kSpine,  kChest,     kNeck,     kChest,
                kUpperArmL, kForearmL, kChest,  kUpperArmR, kForearmR, kPelvis,
                kThighL,    kShinL,    kPelvis, kThighR,    kShinR};
    s.joints[kPelvis] = {0, 0, m.hip};
    s.joints[kSpine] = {0, 0, m.waist};
    s.joints[kChest] = {0, 0, m.chest - 0.04 * m.H};
    s.joints[kNeck] = {0, 0, m.neck_base};
    s.joints[kHead] = {0.005 * m.H, 0, m.chin + 0.01 * m.H};
    for (int side : {1, -1}) {
      const int o = side > 0 ? 0 : 3, l = side > 0 ? 0 : 3;
      s.joints[kUpperArmL + o] = shoulder(side);
      s.joints[kForearmL + o] = elbow(side);
      s.joints[kHandL + o] = wrist(side);
      s.joints[kThighL + l] = {0, side * m.hip_y, m.hip};
      s.joints[kShinL + l] = {0, side * m.hip_y, m.knee};
      s.joints[kFootL + l] = {0, side * m.hip_y, m.ankle};
    }
    s.thigh = m.hip - m.knee, s.shin = m.knee - m.ankle;
    s.upper_arm = m.upper_arm, s.forearm = m.forearm;
    s.ankle = m.ankle, s.hip_y = m.hip_y, s.foot = m.foot;
  }

  // the torso's bones by height; low at the sides it follows the thighs a little
  Weights torso_weights(const V3& p) const {
    const double z = p.z(), H = m.H;
    if (z < m.hip + 0.02 * H && std::abs(p.y()) > 0.25 * m.hip_y) {
      const int thigh = p.y() > 0 ? kThighL : kThighR;
      return blend(kPelvis, thigh, 0.55 * ramp(-z, -(m.hip - 0.03 * H), 0.035 * H));
    }
    if (z < m.waist) return blend(kPelvis, kSpine, ramp(z, m.waist, 0.035 * H));
    if (z < m.chest - 0.04 * H)
      return blend(kSpine, kChest, ramp(z, m.chest - 0.04 * H, 0.035 * H));
    return blend(kChest, kNeck, ramp(z, m.neck_base + 0.005 * H, 0.008 * H));
  }

  Weights leg_weights(const V3& p, int side) const {
    const int o = side > 0 ? 0 : 3;
    const double z = p.z();
    if (z > m.knee)
      return blend(kThighL + o, kPelvis, 0.4 * ramp(z, m.hip + 0.01 * m.H, 0.02 * m.H));
    if (z > m.ankle + 0.02 * m.H)
      return blend(kShinL + o, kThighL + o, ramp(z, m.knee, 0.03 * m.H));
    return blend(kShinL + o, kFootL + o, 1 - ramp(z, m.ankle, 0.012 * m.H));
  }

  Weights arm_weights(const V3& p, int side) const {
    const int o = side > 0 ? 0 : 3;
    const V3 s = shoulder(side), e = elbow(side), w = wrist(side);
    const double along_upper = (p - s).dot((e - s).normalized());
    const double along_fore = (p - e).dot((w - e).normalized());
    if (along_upper < 0.5 * m.upper_arm)
      return blend(kChest, kUpperArmL + o, ramp(along_upper, 0.02 * m.H, 0.03 * m.H));
    if (along_fore < 0.5 * m.forearm)
      return blend(kUpperArmL + o, kForearmL + o, ramp(along_fore, 0, 0.025 * m.H));
    return blend(kForearmL + o, kHandL + o, ramp(along_fore, m.forearm, 0.012 * m.H));
  }

  bool long_sleeves() const { return look.top != Look::Top::TShirt; }
  double hem() const {  // where the bottom garment's legs end
    switch (look.bottom) {
      case Look::Bottom::Shorts:
        return m.knee + 0.05 * m.H;
      case Look::Bottom::Trousers:
        return -1;
      default:
        return m.H;  // skirt / dress: bare legs (tights look like skin at this scale)
    }
  }

  void add_torso() {
    const double H = m.H, jacket = look.top == Look::Top::Jacket ? 1.04 : 1.0;
    const std::vector<std::pair<double, Ring>> rows = {
        {m.crotch - 0.012 * H, {V3(-0.004 * H, 0, 0), 0.45 * m.hip_w, 0.6 * m.hip_d}},
        {m.crotch, {V3(-0.006 * H, 0, 0), 0.82 * m.hip_w, 0.92 * m.hip_d}},
        {m.hip, {V3(-0.008 * H, 0, 0), m.hip_w, m.hip_d}},
        {m.waist, {V3(0, 0, 0), m.waist_w * jacket, m.waist_d * jacket}},
        {m.chest - 0.05 * H,
         {V3(0.003 * H, 0, 0), (m.waist_w + m.chest_w) / 2 * jacket,
          (m.waist_d + m.chest_d) / 2 * jacket}},
        {m.chest, {V3(0.006 * H, 0, 0), m.chest_w * jacket, m.chest_d * jacket}},
        {m.shoulder - 0.03 * H, {V3(0, 0, 0), 1.04 * m.chest_w * jacket, 0.9 * m.chest_d * jacket}},
        {m.shoulder, {V3(-0.004 * H, 0, 0), m.shoulder_w * jacket, 0.72 * m.chest_d * jacket}},
        {m.neck_base - 0.006 * H, {V3(-0.006 * H, 0, 0), 0.55 * m.shoulder_w, 0.6 * m.chest_d}},
        {m.neck_base + 0.004 * H, {V3(-0.006 * H, 0, 0), 1.2 * m.neck_r, 1.15 * m.neck_r}}};
    std::vector<Ring> rings;
    for (const auto& [z, ring] : rows)
      rings.push_back({ring.centre + V3(0, 0, z), ring.width, ring.depth});
    const double waist = m.waist - 0.01 * H;
    add_skinned(
        mesh,
        tube_through(rings, 2.6, cls,
                     [&](const V3& p) { return p.z() < waist ? fixed(kBottom) : fixed(kTop); }),
        [&](const V3& p) { return torso_weights(p); });
  }

  void add_legs() {
    for (int side : {1, -1}) {
      const V3 hip(0, side * m.hip_y, m.hip), ankle(0, side * m.hip_y, m.ankle);
      const double span = m.hip - m.ankle + 0.03 * m.H;
      const auto share = [&](double z) { return (m.hip + 0.03 * m.H - z) / span; };
      const double trouser = look.bottom == Look::Bottom::Trousers ? 0.032 * m.H : 0;
      const std::vector<std::pair<double, double>> radii = {
          {share(m.hip + 0.03 * m.H), 0.8 * m.thigh_r},
          {share(m.hip - 0.03 * m.H), m.thigh_r},
          {share(m.hip - 0.12 * m.H), 0.88 * m.thigh_r},
          {share(m.knee + 0.05 * m.H), std::max(0.66 * m.thigh_r, trouser)},
          {share(m.knee), std::max(m.knee_r, trouser)},
          {share(m.knee - 0.06 * m.H), std::max(m.calf_r, trouser)},
          {share(m.ankle + 0.06 * m.H), std::max(0.75 * m.calf_r, trouser)},
          {share(m.ankle + 0.01 * m.H), std::max(m.ankle_r, trouser * 0.95)},
          {1, 0.9 * m.ankle_r}};
      const double hem = this->hem();
      add_skinned(mesh,
                  limb({hip + V3(0, 0, 0.03 * m.H), ankle}, radii, cls,
                       [&](double s) {
                         const double z = m.hip + 0.03 * m.H - s * span;
                         return z > hem ? fixed(kBottom) : fixed(kSkinTone);
                       }),
                  [&](const V3& p) { return leg_weights(p, side); });
      add_shoe(side);
    }
  }

  void add_shoe(int side) {
    const double H = m.H, f = m.foot, y0 = side * m.hip_y;
    std::vector<Ring> rings;
    const double xs[] = {-0.24, -0.2, -0.1, 0.1, 0.35, 0.55, 0.7, 0.76};
    const double heights[] = {0.5, 0.75, 0.95, 0.9, 0.55, 0.42, 0.3, 0.15};
    const double widths[] = {0.5, 0.75, 0.85, 0.9, 1.0, 0.95, 0.7, 0.3};
    const double top = m.ankle + 0.012 * H;
    for (int k = 0; k < 8; ++k) {
      const double h = top * heights[k];
      rings.push_back({V3(xs[k] * f, y0 + side * 0.004 * H, h / 2), m.foot_w * widths[k], h / 2});
    }
    add_skinned(mesh, along_x(rings), [&](const V3& p) {
      const int o = side > 0 ? 0 : 3;
      return blend(kFootL + o, kShinL + o, 0.5 * ramp(p.z(), top, 0.008 * H));
    });
  }

  // a tube along x through rings (centre, half width, half height): a shoe
  Mesh along_x(const std::vector<Ring>& rings) const {
    constexpr int sides = 12;
    Grid grid{int(rings.size()) + 2, sides, true, {}};
    grid.points.insert(grid.points.end(), sides, rings.front().centre);
    for (const Ring& r : rings)
      for (int k = 0; k < sides; ++k) {
        const double a = 2 * kPi * k / sides, c = std::cos(a), s = std::sin(a);
        grid.points.push_back(r.centre +
                              V3(0, r.width * std::copysign(std::pow(std::abs(c), 0.6), c),
                                 r.depth * std::copysign(std::pow(std::abs(s), 0.6), s)));
      }
    grid.points.insert(grid.points.end(), sides, rings.back().centre);
    Mesh out;
    add_grid(out, grid, [&](int, int) { return QuadPaint{cls, kShoes}; });
    return out;
  }

  void add_arms() {
    for (int side : {1, -1}) {
      const V3 s = shoulder(side), e = elbow(side), w = wrist(side);
      const V3 top = s + V3(0, -side * 0.012 * m.H, 0.01 * m.H);
      const double l0 = (s - top).norm(), l1 = m.upper_arm, l2 = m.forearm, total = l0 + l1 + l2;
      const auto share = [&](double d) { return d / total; };
      const std::vector<std::pair<double, double>> radii = {
          {0, 0.75 * m.upper_arm_r},
          {share(l0), 1.1 * m.upper_arm_r},
          {share(l0 + 0.4 * l1), m.upper_arm_r},
          {share(l0 + l1), m.elbow_r},
          {share(l0 + l1 + 0.35 * l2), m.forearm_r},
          {share(total - 0.01), m.wrist_r},
          {1, 0.9 * m.wrist_r}};
      const double sleeve = long_sleeves() ? share(total - 0.02) : share(l0 + 0.45 * l1);
      add_skinned(mesh,
                  limb({top, s, e, w}, radii, cls,
                       [&](double t) { return t < sleeve ? fixed(kTop) : fixed(kSkinTone); }),
                  [&](const V3& p) { return arm_weights(p, side); });
      // the hand: a flattened mitten along the forearm's line, and a thumb
      const V3 dir = (w - e).normalized();
      Mesh hand;
      add_ellipsoid(hand, V3::Zero(), V3(0.012 * m.H, 0.025 * m.H, 0.05 * m.H), cls, kSkinTone, 6,
                    10);
      add_ellipsoid(hand, V3(0.012 * m.H, -side * 0.012 * m.H, 0.01 * m.H),
                    V3(0.008 * m.H, 0.008 * m.H, 0.022 * m.H), cls, kSkinTone, 4, 8);
      const Eigen::Quaterniond turn = Eigen::Quaterniond::FromTwoVectors(V3(0, 0, -1), dir);
      Mesh placed;
      append_mesh(placed, hand, Pose(Eigen::Translation3d(w + dir * 0.045 * m.H) * turn));
      add_skinned(mesh, placed, [&](const V3&) { return only(side > 0 ? kHandL : kHandR); });
    }
  }

  // the head as a loft from the chin to the crown, with a nose, ears and eyes
  V3 head_centre() const { return {0.006 * m.H, 0, m.chin}; }
  std::vector<Ring> head_rings(double grow) const {
    const double shares[] = {0, 0.08, 0.22, 0.38, 0.55, 0.7, 0.83, 0.93, 0.99};
    const double widths[] = {0.45, 0.72, 0.84, 0.93, 1.0, 1.0, 0.92, 0.68, 0.25};
    const double depths[] = {0.5, 0.78, 0.9, 0.97, 1.0, 1.0, 0.94, 0.72, 0.28};
    const double forward[] = {0.35, 0.2, 0.1, 0.05, 0.0, -0.02, -0.05, -0.06, -0.05};
    std::vector<Ring> rings;
    for (int k = 0; k < 9; ++k)
      rings.push_back({head_centre() + V3(forward[k] * m.head_d, 0, shares[k] * m.head_h),
                       widths[k] * m.head_w * grow + (grow > 1 ? 0.004 * m.H : 0),
                       depths[k] * m.head_d * grow + (grow > 1 ? 0.004 * m.H : 0)});
    return rings;
  }

  void add_head() {
    const auto head = [](const V3&) { return only(kHead); };
    add_skinned(mesh,
                tube_through(head_rings(1), 2.2, cls, [](const V3&) { return fixed(kSkinTone); }),
                head);
    const V3 c = head_centre();
    Mesh parts;
    add_ellipsoid(parts, c + V3(0.97 * m.head_d, 0, 0.42 * m.head_h),
                  V3(0.012 * m.H, 0.008 * m.H, 0.016 * m.H), cls, kSkinTone, 5, 8);
    for (int side : {1, -1}) {
      add_ellipsoid(parts, c + V3(-0.05 * m.head_d, side * 0.98 * m.head_w, 0.5 * m.head_h),
                    V3(0.011 * m.H, 0.005 * m.H, 0.018 * m.H), cls, kSkinTone, 4, 8);
      add_ellipsoid(parts, c + V3(0.86 * m.head_d, side * 0.36 * m.head_w, 0.57 * m.head_h),
                    V3(0.004 * m.H, 0.008 * m.H, 0.004 * m.H), cls, kEyes, 4, 8);
    }
    add_skinned(mesh, parts, head);
    std::vector<Ring> neck;
    for (double z : {m.neck_base - 0.02 * m.H, m.chin + 0.02 * m.H})
      neck.push_back({V3(0, 0, z), m.neck_r, m.neck_r});
    add_skinned(mesh,
                tube_through(
                    neck, 2, cls, [](const V3&) { return fixed(kSkinTone); }, true, 10),
                [&](const V3& p) {
                  return blend(kNeck, kHead, ramp(p.z(), m.chin + 0.005 * m.H, 0.01 * m.H));
                });
  }

  void add_hair() {
    using Hair = Look::Hair;
    if (look.hair == Hair::Bald) return;
    const bool cap = look.hair == Hair::Cap;
    const double grow = look.hair == Hair::Bob || look.hair == Hair::Long ? 1.12 : 1.06;
    const std::vector<Ring> rings = head_rings(cap ? 1.08 : grow);
    // the hair line: low at the back, above the ears at the sides, the forehead at the front
    const double front = cap ? 0.72 : 0.8, back = look.hair == Hair::Short || cap ? 0.3 : 0.12;
    Mesh hair = tube_through(rings, 2.2, cls, [&](const V3&) { return fixed(cap ? kBag : kHair); });
    const V3 c = head_centre();
    // keep the triangles above the hair line (an open shell); `facing`: +1 front, -1 back
    std::vector<Eigen::Vector3i> triangles;
    std::vector<SemanticClass> classes;
    std::vector<std::uint16_t> materials;
    for (std::size_t t = 0; t < hair.triangles.size(); ++t) {
      V3 centre = V3::Zero();
      for (int k = 0; k < 3; ++k) centre += hair.vertices[hair.triangles[t][k]].cast<double>() / 3;
      const double share = (centre.z() - c.z()) / m.head_h;
      const double facing = (centre.x() - c.x()) / m.head_d;
      const double line =
          facing > 0.3 ? front : back + (front - back) * std::max(0.0, facing + 0.3) / 0.6;
      if (share < line) continue;
      triangles.push_back(hair.triangles[t]), classes.push_back(hair.classes[t]);
      materials.push_back(hair.materials[t]);
    }
    hair.triangles = triangles, hair.classes = classes, hair.materials = materials;
    add_skinned(mesh, hair, [](const V3&) { return only(kHead); });
    Mesh extra;
    if (cap)
      add_ellipsoid(extra, c + V3(0.95 * m.head_d, 0, 0.8 * m.head_h),
                    V3(0.06 * m.H, 0.06 * m.H, 0.006 * m.H), cls, kBag, 4, 12);
    if (look.hair == Hair::Ponytail)
      add_tube(
          extra,
          {c + V3(-0.95 * m.head_d, 0, 0.6 * m.head_h), c + V3(-1.2 * m.head_d, 0, 0.2 * m.head_h),
           c + V3(-1.1 * m.head_d, 0, -0.3 * m.head_h)},
          {0.02 * m.H, 0.018 * m.H, 0.008 * m.H}, 8, cls, kHair);
    if (!extra.vertices.empty()) add_skinned(mesh, extra, [](const V3&) { return only(kHead); });
    if (look.hair == Hair::Long) {  // down the back to the shoulder blades
      std::vector<Ring> curtain;
      for (double z : {c.z() + 0.5 * m.head_h, c.z(), m.shoulder - 0.07 * m.H})
        curtain.push_back({V3(-0.75 * m.head_d, 0, z), 1.05 * m.head_w, 0.35 * m.head_d});
      add_skinned(
          mesh, tube_through(curtain, 2.4, cls, [](const V3&) { return fixed(kHair); }),
          [&](const V3& p) { return blend(kChest, kHead, ramp(p.z(), m.chin, 0.03 * m.H)); });
    }
  }

  void add_garments() {
    const double H = m.H;
    const bool skirt = look.bottom == Look::Bottom::Skirt || look.bottom == Look::Bottom::Dress;
    const bool coat = look.top == Look::Top::Coat;
    if (!skirt && !coat) return;
    const double top = coat ? m.shoulder - 0.01 * H : m.waist,
                 bottom = coat ? m.hip - 0.17 * H : m.knee + 0.06 * H;
    std::vector<Ring> rings;
    const int n = 6;
    for (int k = 0; k < n; ++k) {
      const double s = double(k) / (n - 1), z = bottom + (top - bottom) * s;
      double w, d;
      if (z > m.chest)
        w = m.chest_w * 1.08, d = m.chest_d * 1.12;
      else if (z > m.waist)
        w = m.waist_w * 1.1, d = m.waist_d * 1.15;
      else {
        const double flare = (m.waist - z) / (m.waist - bottom);
        w = m.hip_w * (1.08 + 0.2 * flare), d = m.hip_d * (1.15 + 0.35 * flare);
      }
      rings.push_back({V3(-0.004 * H, 0, z), w, d});
    }
    const std::uint16_t slot = coat ? kTop : kBottom;
    Mesh garment = tube_through(
        rings, 2.4, cls, [&](const V3&) { return slot; }, false, 16);
    add_skinned(mesh, garment, [&](const V3& p) {
      if (p.z() > m.hip) return torso_weights(p);
      const double s = std::clamp((m.hip - p.z()) / (m.hip - bottom), 0.0, 1.0);
      const int thigh = p.y() > 0 ? kThighL : kThighR;
      return blend(kPelvis, thigh, 0.45 * s * std::min(1.0, std::abs(p.y()) / m.hip_y));
    });
  }

  void add_accessories() {
    const double H = m.H;
    if (look.bag == Look::Bag::Backpack) {
      Mesh bag;
      add_rounded_box(bag,
                      Pose(Eigen::Translation3d(-m.chest_d - 0.045 * H, 0, m.chest - 0.03 * H)),
                      V3(0.04 * H, 0.085 * H, 0.115 * H), 0.025 * H, cls, kBag, 2);
      add_skinned(mesh, bag, [](const V3&) { return only(kChest); });
    } else if (look.bag == Look::Bag::Shoulder) {
      Mesh bag;
      add_rounded_box(bag, Pose(Eigen::Translation3d(0, -(m.hip_w + 0.025 * H), m.hip + 0.01 * H)),
                      V3(0.045 * H, 0.018 * H, 0.055 * H), 0.01 * H, cls, kBag, 2);
      add_skinned(mesh, bag, [](const V3&) { return only(kPelvis); });
    }
    if (!look.umbrella) return;
    // held in the right hand: rest-pose stick along the hand's +x, upright once the forearm is
    // raised to the horizontal (gait.cpp's holding pose)
    const V3 hand = wrist(-1) + (wrist(-1) - elbow(-1)).normalized() * 0.045 * H;
    Mesh umbrella;
    const double stick = 0.5 * H, radius = 0.5;
    add_tube(umbrella, {hand - V3(0.05 * H, 0, 0), hand + V3(stick, 0, 0)}, {0.006 * H, 0.006 * H},
             6, cls, kUmbrella);
    Mesh canopy;
    std::vector<V2> dome;
    for (int k = 0; k <= 6; ++k) {
      const double a = kPi / 2 * k / 6;
      dome.emplace_back(radius * std::sin(a), 0.3 * radius * std::cos(a));
    }
    dome.emplace_back(radius * 0.98, -0.01);
    dome.emplace_back(0, -0.01);
    add_lathe(canopy, dome, 16, cls, kUmbrella);
    // the lathe's axis is y: turn it onto +x, the dome's top to the stick's end
    append_mesh(umbrella, canopy,
                Pose(Eigen::Translation3d(hand + V3(stick - 0.3 * radius, 0, 0)) *
                     Eigen::AngleAxisd(-kPi / 2, V3::UnitZ())));
    add_skinned(mesh, umbrella, [](const V3&) { return only(kHandR); });
  }
};

}  // namespace

Look random_look(Random& random, bool child, bool rain) {
  Look look;
  look.child = child;
  look.female = random.chance(0.5);
  look.height = child         ? random.uniform(1.0, 1.45)
                : look.female ? random.uniform(1.52, 1.78)
                              : random.uniform(1.64, 1.94);
  look.build = child ? random.uniform(0.9, 1.05) : random.uniform(0.85, 1.25);
  const double u = random.uniform();
  look.top = rain && u < 0.5 ? Look::Top::Coat
             : u < 0.4       ? Look::Top::TShirt
             : u < 0.65      ? Look::Top::LongSleeves
             : u < 0.88      ? Look::Top::Jacket
                             : Look::Top::Coat;
  const double v = random.uniform();
  look.bottom = look.female && v < 0.22   ? Look::Bottom::Skirt
                : look.female && v < 0.35 ? Look::Bottom::Dress
                : v < 0.85                ? Look::Bottom::Trousers
                                          : Look::Bottom::Shorts;
  const double w = random.uniform();
  look.hair = look.female ? (w < 0.3    ? Look::Hair::Long
                             : w < 0.6  ? Look::Hair::Bob
                             : w < 0.85 ? Look::Hair::Ponytail
                                        : Look::Hair::Short)
                          : (w < 0.65   ? Look::Hair::Short
                             : w < 0.8  ? Look::Hair::Bald
                             : w < 0.92 ? Look::Hair::Cap
                                        : Look::Hair::Bob);
  const double b = random.uniform();
  look.bag = b < 0.2              ? Look::Bag::Backpack
             : b < 0.35 && !child ? Look::Bag::Shoulder
                                  : Look::Bag::None;
  look.umbrella = rain && !child && random.chance(0.6);
  return look;
}

PersonModel build_person(const Look& look, SemanticClass cls) {
  Builder b{look, measures(look), cls, {}, {}};
  b.make_skeleton();
  b.add_torso();
  b.add_legs();
  b.add_arms();
  b.add_head();
  b.add_hair();
  b.add_garments();
  b.add_accessories();
  return {std::make_shared<const Mesh>(std::move(b.mesh)), b.skeleton, look};
}

std::vector<Pose> forward_kinematics(const Skeleton& skeleton,
                                     const std::array<Eigen::Matrix3d, kBones>& local,
                                     const V3& root) {
  std::vector<Pose> bones(kBones);
  for (int b = 0; b < kBones; ++b) {
    const V3& joint = skeleton.joints[std::size_t(b)];
    const Pose about = Pose(Eigen::Translation3d(joint)) * Pose(local[std::size_t(b)]) *
                       Pose(Eigen::Translation3d(-joint));
    const int parent = skeleton.parent[std::size_t(b)];
    bones[std::size_t(b)] =
        parent < 0 ? Pose(Eigen::Translation3d(root)) * about : bones[std::size_t(parent)] * about;
  }
  return bones;
}

}  // namespace flowscape::assets
