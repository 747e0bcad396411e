#include "vehicle_body.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "flowscape/scenes/shapes.h"

namespace flowscape::assets {
namespace {

using C = SemanticClass;

// Section heights as shares of the flank (sill to belt) and of the glass (belt to roof).
constexpr double kFlankShares[] = {0, 0.03, 0.09, 0.18, 0.32, 0.5, 0.68, 0.84, 0.94, 1};
constexpr double kGlassShares[] = {0, 0.06, 0.25, 0.5, 0.75, 0.92, 1};
constexpr int kBottomPoints = 3, kTopPoints = 4;
constexpr int kFlankPoints = int(std::size(kFlankShares)),
              kGlassPoints = int(std::size(kGlassShares));
constexpr int kFirstFlank = kBottomPoints, kFirstGlass = kFirstFlank + kFlankPoints,
              kFirstTop = kFirstGlass + kGlassPoints, kHalfRing = kFirstTop + kTopPoints;

bool between(double x, double a, double b) { return x >= std::min(a, b) && x <= std::max(a, b); }

// The stations: even in the plan's angle (dense round the nose and tail), dense over the wheel
// arches, and one at every window edge.
std::vector<double> stations(const BodyShape& s) {
  const double a = s.length / 2;
  std::vector<double> x;
  constexpr int kPlan = 36;
  for (int k = 0; k <= kPlan; ++k) {
    const double c = std::cos(kPi * k / kPlan);
    x.push_back(-a * std::copysign(std::pow(std::abs(c), 2 / s.plan_exponent), c));
  }
  const double arch = s.wheel_radius + s.arch_clearance;
  for (double axle : s.axles)
    for (int k = -7; k <= 7; ++k) x.push_back(axle + arch * std::sin(kPi / 2 * k / 7.0));
  const Glazing& g = s.glazing;
  for (double e : {g.windscreen_front, g.windscreen_back, g.rear_front, g.rear_back, g.side_front,
                   g.side_back})
    x.push_back(e);
  for (const auto& [p0, p1] : g.pillars) x.push_back(p0), x.push_back(p1);
  for (double& v : x) v = std::clamp(v, -a, a);
  std::sort(x.begin(), x.end());
  std::vector<double> kept;
  for (double v : x)
    if (kept.empty() || v - kept.back() > 0.004) kept.push_back(v);
  if (kept.back() < a) kept.back() = a;
  return kept;
}

// The left half of the section at station x, from the bottom's centre to the roof's centre.
std::vector<V2> half_section(const BodyShape& s, const BodyFrame& f, double x) {
  std::vector<V2> points;
  const double zb = f.bottom(x), zl = std::max(f.belt(x), zb), zt = std::max(f.top(x), zl);
  const double yb = f.half_width(x, zb);
  for (int k = 0; k < kBottomPoints; ++k) points.emplace_back(yb * k / kBottomPoints, zb);
  for (double share : kFlankShares) {
    const double z = zb + (zl - zb) * share;
    points.emplace_back(f.half_width(x, std::min(z, zl)), z);
  }
  for (double share : kGlassShares) {
    const double z = zl + (zt - zl) * share;
    points.emplace_back(share == 0 ? f.half_width(x, zl + 1e-9) : f.half_width(x, z), z);
  }
  const double yt = points.back().x();
  for (int k = 1; k <= kTopPoints; ++k) {
    const double y = yt * (1 - double(k) / kTopPoints);
    points.emplace_back(y, zt + (yt > 0 ? s.crown * (1 - (y / yt) * (y / yt)) : 0));
  }
  return points;
}

int half_index(int column) { return column < kHalfRing ? column : 2 * (kHalfRing - 1) - column; }

// What a quad of the shell is: by the section segment its upper (or outer) edge lies in, where it
// is along the body and which way it faces.
QuadPaint shell_paint(const BodyShape& s, const BodyFrame& f, const Grid& grid, int r, int c) {
  const int j = std::max(half_index(c), half_index((c + 1) % grid.columns));
  const V3 p00 = grid.points[std::size_t(r) * grid.columns + c],
           p11 = grid.points[std::size_t(r + 1) * grid.columns + (c + 1) % grid.columns],
           p01 = grid.points[std::size_t(r) * grid.columns + (c + 1) % grid.columns],
           p10 = grid.points[std::size_t(r + 1) * grid.columns + c];
  const V3 centre = (p00 + p11 + p01 + p10) / 4;
  const double x = centre.x(), z = centre.z();
  const Glazing& g = s.glazing;
  const auto paint = [](Slot slot) { return QuadPaint{C::Vehicles, slot}; };
  if (j <= kFirstFlank) return paint(kUnderbody);
  const double ends = s.axles.empty()
                          ? s.length / 2
                          : std::max(std::abs(s.axles.front()), std::abs(s.axles.back()));
  if (j < kFirstGlass)  // the flank: black trim low down at the bumpers
    return paint(z < s.bottom(x) + s.trim_height && std::abs(x) > ends ? kTrim : kPaint);
  if (j == kFirstGlass) return paint(kPaint);  // the shoulder
  const double glass_height = f.top(x) - f.belt(x);
  if (j < kFirstTop) {
    if (glass_height < 0.08) return paint(kPaint);
    V3 n = (p11 - p00).cross(p01 - p10);
    n = n.norm() > 0 ? V3(n.normalized()) : V3::UnitY();
    if (std::abs(n.x()) > 0.75)
      return paint((n.x() > 0 ? g.front_face : g.rear_face) ? kGlass : kTrim);
    if (!between(x, g.side_back, g.side_front)) return paint(kPaint);
    for (const auto& [p0, p1] : g.pillars)
      if (between(x, p0, p1)) return paint(kTrim);
    const bool framed = z < f.belt(x) + g.frame || z > f.top(x) - g.frame ||
                        std::abs(x - g.side_back) < g.frame || std::abs(x - g.side_front) < g.frame;
    return paint(framed ? kTrim : kGlass);
  }
  const bool windscreen = between(x, g.windscreen_front, g.windscreen_back),
             rear = between(x, g.rear_front, g.rear_back);
  if (!windscreen && !rear) return paint(kPaint);
  return paint(j == kFirstTop + 1 ? kTrim : kGlass);  // a black frit along the glass's edge
}

void add_shell(Mesh& mesh, const BodyShape& s, const BodyFrame& f) {
  const std::vector<double> xs = stations(s);
  Grid grid{int(xs.size()), 2 * (kHalfRing - 1), true, {}};
  for (double x : xs) {
    const std::vector<V2> half = half_section(s, f, x);
    for (int c = 0; c < grid.columns; ++c) {
      const V2& p = half[std::size_t(half_index(c))];
      grid.points.emplace_back(x, c < kHalfRing ? p.x() : -p.x(), p.y());
    }
  }
  add_grid(mesh, grid, [&](int r, int c) { return shell_paint(s, f, grid, r, c); });
}

// A patch on the front (end +1) or rear (-1) face, 4 mm proud of it; a point beyond the body's
// outline there (a lamp wrapping round a corner) is drawn in towards the patch's centre.
void add_face_decal(Mesh& mesh, const BodyFrame& f, const Decal& d, int end) {
  constexpr int n = 5;
  const double centre = f.face_x(d.y, d.z, end);
  if (!std::isfinite(centre)) return;  // off the body: no decal
  // a point on the face near the centre's (not on the bonnet or boot lid far behind it)
  const auto near_face = [&](double x) { return std::isfinite(x) && std::abs(x - centre) < 0.12; };
  Grid grid{n, n, false, {}};
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      const double dy = d.half_width * (2.0 * i / (n - 1) - 1) * -end,
                   dz = d.half_height * (2.0 * k / (n - 1) - 1);
      double x = std::numeric_limits<double>::quiet_NaN(), y = d.y, z = d.z;
      for (double share = 1; share > 0 && !near_face(x); share -= 0.1)
        y = d.y + share * dy, z = d.z + share * dz, x = f.face_x(y, z, end);
      if (!near_face(x)) x = centre, y = d.y, z = d.z;
      grid.points.emplace_back(x + end * 0.004, y, z);
    }
  add_grid(mesh, grid, [&](int, int) { return QuadPaint{C::Vehicles, d.slot}; });
}

// A strip on a flank at x (a door seam), from the sill to the belt.
void add_seam(Mesh& mesh, const BodyFrame& f, double x, int side) {
  constexpr int n = 8;
  Grid grid{2, n, false, {}};
  const double z0 = f.bottom(x) + 0.08, z1 = f.belt(x) - 0.02;
  for (double dx : {-0.003, 0.003})
    for (int k = 0; k < n; ++k) {
      const double z = z0 + (z1 - z0) * k / (n - 1);
      grid.points.emplace_back(x + dx * side, side * (f.half_width(x + dx, z) + 0.0015), z);
    }
  add_grid(mesh, grid, [&](int, int) { return QuadPaint{C::Vehicles, kTrim}; });
}

// A panel on a flank, 3 mm proud of it (and clipped to the flank's heights at each x).
void add_panel(Mesh& mesh, const BodyFrame& f, const Panel& p, int side) {
  constexpr int n = 10, m = 6;
  Grid grid{n, m, false, {}};
  for (int i = 0; i < n; ++i) {
    const double x = p.x0 + (p.x1 - p.x0) * i / (n - 1);
    const double z0 = std::max(p.z0, f.bottom(x) + 0.02), z1 = std::min(p.z1, f.top(x) - 0.02);
    for (int k = 0; k < m; ++k) {
      const double z = z0 + (z1 - z0) * k / (m - 1);
      grid.points.emplace_back(x, side * (f.half_width(x, z) + 0.003), z);
    }
  }
  add_grid(mesh, grid, [&](int, int) { return QuadPaint{C::Vehicles, p.slot}; });
}

void add_mirrors_and_handles(Mesh& mesh, const BodyShape& s, const BodyFrame& f) {
  for (int side : {-1, 1}) {
    for (double x : s.handles) {
      const double z = f.belt(x) - 0.09;
      add_rounded_box(mesh, Pose(Eigen::Translation3d(x, side * (f.half_width(x, z) + 0.008), z)),
                      V3(0.065, 0.012, 0.014), 0.01, C::Vehicles, kChrome, 2);
    }
    if (!s.mirrors) continue;
    const double x = std::max(s.glazing.windscreen_front, s.glazing.windscreen_back) - 0.06,
                 z = f.belt(x) + 0.09, y = f.half_width(x, f.belt(x));
    add_rounded_box(mesh, Pose(Eigen::Translation3d(x - 0.03, side * (y + 0.12), z)),
                    V3(0.055, 0.1, 0.065), 0.03, C::Vehicles, kTrim, 2);
    add_rounded_box(mesh, Pose(Eigen::Translation3d(x, side * (y + 0.02), z - 0.03)),
                    V3(0.04, 0.04, 0.02), 0.01, C::Vehicles, kTrim, 1);
  }
}

// Floor, door linings and dash, seats and a steering wheel: what the glass shows inside, clear of
// the wheel arches and below the shoulders.
void add_cabin(Mesh& mesh, const BodyShape& s, const BodyFrame& f) {
  const Glazing& g = s.glazing;
  const double arch = s.wheel_radius + s.arch_clearance + 0.05;
  double front = std::max(g.windscreen_front, g.windscreen_back) - 0.05;
  double back = std::min(g.side_back, g.side_front) + 0.1;
  for (double axle : s.axles) {
    if (axle > 0) front = std::min(front, axle - arch);
    if (axle < 0) back = std::max(back, axle + arch);
  }
  if (front - back < 0.8) return;
  const double floor = f.bottom(0) + 0.12, sill = f.belt(0) - 0.04;
  const double half = f.half_width(0, sill) - 0.05;
  const Paint lining{C::Vehicles, kInterior};
  const V3 a(back, -half, floor), b(front, -half, floor), c(front, half, floor),
      d(back, half, floor);
  const V3 up(0, 0, sill - floor);
  add_quad(mesh, a, d, c, b, lining);            // floor, facing up
  add_quad(mesh, a, b, b + up, a + up, lining);  // right lining, facing in
  add_quad(mesh, c, d, d + up, c + up, lining);  // left lining
  add_quad(mesh, d, a, a + up, d + up, lining);  // behind the rear seats
  add_rounded_box(mesh, Pose(Eigen::Translation3d(front - 0.2, 0, sill - 0.07)),
                  V3(0.18, half, 0.08), 0.05, C::Vehicles, kInterior, 2);
  const double driver = s.left_hand_drive ? 0.37 : -0.37;
  std::vector<V3> ring;
  for (int k = 0; k <= 16; ++k) {
    const double t = 2 * kPi * k / 16;
    ring.push_back(V3(front - 0.5 + 0.06 * std::sin(t), driver + 0.17 * std::cos(t),
                      sill + 0.1 + 0.16 * std::sin(t)));
  }
  add_tube(mesh, ring, std::vector<double>(ring.size(), 0.015), 6, C::Vehicles, kInterior);
  const auto seat = [&](double x, double y, double w) {
    add_rounded_box(mesh, Pose(Eigen::Translation3d(x, y, floor + 0.28)), V3(0.24, w, 0.06), 0.04,
                    C::Vehicles, kInterior, 2);
    add_rounded_box(mesh,
                    Pose(Eigen::Translation3d(x - 0.24, y, floor + 0.58) *
                         Eigen::AngleAxisd(-0.25, V3::UnitY())),
                    V3(0.06, w, 0.28), 0.04, C::Vehicles, kInterior, 2);
  };
  const double row = front - 1.0;
  seat(row, 0.37, 0.23), seat(row, -0.37, 0.23);
  if (row - 0.9 > back + 0.3) seat(row - 0.9, 0, half - 0.08);
}

}  // namespace

double BodyFrame::plan_half_width(double x) const {
  const double a = shape.length / 2, b = shape.width / 2, u = std::abs(x) / a;
  if (u >= 1) return 0;
  return b * std::pow(1 - std::pow(u, shape.plan_exponent), 1 / shape.plan_exponent);
}

double BodyFrame::bottom(double x) const {
  double z = shape.bottom(x);
  const double arch = shape.wheel_radius + shape.arch_clearance;
  for (double axle : shape.axles) {
    const double dx = x - axle;
    if (std::abs(dx) < arch) z = std::max(z, shape.wheel_radius + std::sqrt(arch * arch - dx * dx));
  }
  return std::min(z, belt(x) - 0.02);
}

double BodyFrame::belt(double x) const { return std::min(shape.belt(x), top(x)); }
double BodyFrame::top(double x) const { return shape.top(x); }

// The section is the mid-body's shape scaled to the plan's width at x, so the nose and the tail
// close smoothly.
double BodyFrame::half_width(double x, double z) const {
  const double b = shape.width / 2, scale = plan_half_width(x) / b, zl = belt(x), zt = top(x);
  const double zb = std::min(shape.bottom(x), zl);  // (the arch does not change the flank's shape)
  if (scale <= 0 || z < zb - 1e-9 || z > zt + 1e-9) return 0;
  const double flank = b * (1 - shape.bulge);
  if (z <= zl) {
    const double h = zl - zb, q = h > 0 ? 2 * (z - zb) / h - 1 : 0;
    double y = b * (1 - shape.bulge * q * q);
    const double rs = std::min({shape.sill_radius, h / 2, b});
    const double lowest = bottom(x);
    if (z < lowest + rs) {
      const double d = std::min(lowest + rs - z, rs);
      y -= rs - std::sqrt(rs * rs - d * d);
    }
    return scale * std::max(y, 0.0);
  }
  const double h = zt - zl, share = h > 0 ? (z - zl) / h : 1;
  double y = flank - shape.shoulder - shape.tumblehome * share;
  const double rr = std::min(shape.roof_radius, h);
  if (z > zt - rr && rr > 0) {
    const double d = std::min(z - (zt - rr), rr);
    y -= rr - std::sqrt(rr * rr - d * d);
  }
  return scale * std::max(y, 0.0);
}

double BodyFrame::face_x(double y, double z, int end) const {
  const auto inside = [&](double x) { return std::abs(y) < half_width(x, z) && z >= bottom(x); };
  // walk in from the end (a wheel arch makes the inside no interval), then bisect the step
  const double a = shape.length / 2, step = 0.01;
  double outside = end * a, in = outside;
  while (!inside(in)) {
    outside = in, in -= end * step;
    if (std::abs(in) < a / 2) return std::numeric_limits<double>::quiet_NaN();
  }
  for (int k = 0; k < 30; ++k) {
    const double mid = (in + outside) / 2;
    (inside(mid) ? in : outside) = mid;
  }
  return in;
}

Mesh vehicle_body(const BodyShape& shape) {
  Mesh mesh;
  const BodyFrame frame{shape};
  add_shell(mesh, shape, frame);
  for (const Decal& d : shape.front) add_face_decal(mesh, frame, d, 1);
  for (const Decal& d : shape.rear) add_face_decal(mesh, frame, d, -1);
  for (double x : shape.seams)
    for (int side : {-1, 1}) add_seam(mesh, frame, x, side);
  for (const Panel& p : shape.panels)
    for (int side : {-1, 1})
      if (p.side == 0 || p.side == side) add_panel(mesh, frame, p, side);
  add_mirrors_and_handles(mesh, shape, frame);
  if (shape.cabin) add_cabin(mesh, shape, frame);
  return mesh;
}

Mesh road_wheel(double radius, double width, double rim_share, int outward) {
  Mesh mesh;
  const double w = width / 2, rim = rim_share * radius, side = 0.8 * (radius - rim);
  // tyre: the inner bead, the sidewalls bulging out, the rounded tread (radius, y)
  const std::vector<V2> tyre = {{rim, -w * 0.85},
                                {rim + 0.3 * side, -w},
                                {rim + 0.8 * side, -w * 1.02},
                                {radius - 0.03, -w * 0.96},
                                {radius - 0.005, -w * 0.75},
                                {radius, -w * 0.4},
                                {radius, w * 0.4},
                                {radius - 0.005, w * 0.75},
                                {radius - 0.03, w * 0.96},
                                {rim + 0.8 * side, w * 1.02},
                                {rim + 0.3 * side, w},
                                {rim, w * 0.85}};
  constexpr int kAround = 24;
  Grid grid{int(tyre.size()), kAround, true, {}};
  for (const V2& p : tyre)
    for (int k = 0; k < kAround; ++k) {
      const double a = 2 * kPi * k / kAround;
      grid.points.emplace_back(p.x() * std::cos(a), p.y(), p.x() * std::sin(a));
    }
  // the tyre's inner face (toward the axle) closes it as a ring of rubber
  grid.rows += 1;
  for (int k = 0; k < kAround; ++k) grid.points.push_back(grid.points[std::size_t(k)]);
  add_grid(mesh, grid, [](int, int) { return QuadPaint{C::Vehicles, kTyre}; });
  // the rim: a dished face a little inside the outer sidewall, and the hub
  const double face = outward * w * 0.55;
  add_lathe(mesh,
            {{0, face - outward * 0.03},
             {0.15 * rim, face + outward * 0.01},
             {0.5 * rim, face},
             {rim * 1.02, face + outward * 0.02},
             {rim * 1.02, -face},
             {0, -face}},
            24, C::Vehicles, kRim);
  return mesh;
}

}  // namespace flowscape::assets
