#include "city_world.h"

#include <algorithm>
#include <cmath>

#include "city_materials.h"
#include "flowscape/core/random.h"
#include "flowscape/scenes/shapes.h"

namespace flowscape {
namespace {

using V2 = Eigen::Vector2d;
using V3 = Eigen::Vector3d;
using C = SemanticClass;
using Footprint = std::array<V2, 4>;

struct Palette {
  std::uint16_t asphalt, white, yellow, pavement, curb, grass, dirt, concrete, water, glass, bark,
      metal, sign, signal_stop, signal_go, timber, rail, tank, lamp, lit_shop;
  std::vector<std::uint16_t> lit_windows;  // warm, cool and dim rooms
  std::vector<std::uint16_t> leaves;       // a few tree species
};

Palette make_palette(Scene& scene, std::uint64_t seed, const Style& style) {
  namespace cm = city_materials;
  Random random(seed);
  const auto add = [&](const Material& m) { return add_material(scene, m); };
  const auto next = [&] { return random.bits(); };
  Palette p;
  p.asphalt = add(cm::asphalt(next()));
  p.white = add(cm::road_paint(next(), {0.75f, 0.75f, 0.72f}));
  p.yellow = add(cm::road_paint(next(), {0.7f, 0.55f, 0.1f}));
  p.pavement = add(cm::paving(next(), style.buildings == Style::Buildings::Towers ? 0.6 : 0.4));
  p.curb = add(cm::kerb(next()));
  p.grass = add(cm::grass(next()));
  p.dirt = add(cm::soil(next()));
  p.concrete = add(cm::concrete(next()));
  p.water = add(cm::water());
  const std::uint64_t glass_seed = next();
  p.glass = add(cm::window_glass(glass_seed));
  p.bark = add(cm::bark(next()));
  p.metal = add(cm::painted_metal(next(), {0.3f, 0.32f, 0.3f}));
  p.sign = add(cm::sign_face(next()));
  p.signal_stop = add(cm::signal_head(0)), p.signal_go = add(cm::signal_head(2));
  p.timber = add(cm::timber(next()));
  p.rail = add(cm::painted_metal(next(), {0.4f, 0.33f, 0.27f}));
  p.tank = add(cm::painted_metal(next(), {0.75f, 0.75f, 0.72f}));
  for (int k = 0; k < 3; ++k) p.leaves.push_back(add(cm::leaves(next())));
  p.lamp = add(cm::street_lamp());
  const Eigen::Vector3f rooms[] = {Eigen::Vector3f(1.0f, 0.78f, 0.52f) * 4e-4f,
                                   Eigen::Vector3f(0.85f, 0.92f, 1.0f) * 3e-4f,
                                   Eigen::Vector3f(1.0f, 0.7f, 0.4f) * 1.5e-4f};
  for (const Eigen::Vector3f& glow : rooms)
    p.lit_windows.push_back(add(cm::lit_window(glass_seed, glow)));
  p.lit_shop = add(cm::lit_window(glass_seed, Eigen::Vector3f(1.0f, 0.9f, 0.75f) * 1.2e-3f));
  return p;
}

// How a building's facades are dressed.
struct Dress {
  std::uint16_t facade, frame, roof;
  bool sills, ledges, cornice;
};

constexpr double kFacadeDepth = 0.3;  // the most that frames, sills, ledges and cornices stand out

// `r` less `cut`, a box over one of its corners: two rectangles (one where `cut` does not meet it).
std::vector<Rect> minus_corner(const Rect& r, const Rect& cut) {
  if (!r.meets(cut)) return {r};
  const bool left = cut.lo.x() <= r.lo.x(), below = cut.lo.y() <= r.lo.y();
  const Rect beside{V2(left ? cut.hi.x() : r.lo.x(), r.lo.y()),
                    V2(left ? r.hi.x() : cut.lo.x(), r.hi.y())};
  const Rect rest{
      V2(left ? r.lo.x() : std::max(r.lo.x(), cut.lo.x()), below ? cut.hi.y() : r.lo.y()),
      V2(left ? std::min(r.hi.x(), cut.hi.x()) : r.hi.x(), below ? r.hi.y() : cut.lo.y())};
  std::vector<Rect> out;
  for (const Rect& part : {beside, rest})
    if (part.hi.x() > part.lo.x() && part.hi.y() > part.lo.y()) out.push_back(part);
  return out;
}

class WorldBuilder {
 public:
  WorldBuilder(const Layout& layout, std::uint64_t seed, Scene& scene)
      : layout_(layout),
        random_(seed ^ 0x5deece66dull),
        mesh_(scene.world),
        scene_(scene),
        palette_(make_palette(scene, random_.bits(), layout.style)) {
    flat_ = std::all_of(layout.node_height.begin(), layout.node_height.end(),
                        [](double h) { return h == 0; });
  }

  std::vector<Footprint> build() {
    terrain();
    roads();
    for (const Block& block : layout_.blocks) this->block(block);
    return solids_;
  }

 private:
  V3 at(const V2& p, double lift) const { return {p.x(), p.y(), layout_.height(p) + lift}; }

  // A horizontal rectangle following the ground, split into cells of at most `cell` metres; uv
  // is (x, y) unless a frame is given.
  void patch(V2 lo, V2 hi, double lift, Paint paint, double cell = 6,
             const UvFrame& frame = UvFrame{}) {
    if (flat_) cell = 1e9;
    const int nx = std::max(1, int(std::ceil((hi.x() - lo.x()) / cell)));
    const int ny = std::max(1, int(std::ceil((hi.y() - lo.y()) / cell)));
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const auto corner = [&](int di, int dj) {
          return V2(lo.x() + (hi.x() - lo.x()) * (i + di) / nx,
                    lo.y() + (hi.y() - lo.y()) * (j + dj) / ny);
        };
        add_quad(mesh_, at(corner(0, 0), lift), at(corner(1, 0), lift), at(corner(1, 1), lift),
                 at(corner(0, 1), lift), paint, frame);
      }
  }

  // A strip along a straight line from a to b, `width` wide, lying on the ground.
  void strip(const V2& a, const V2& b, double width, double lift, Paint paint) {
    const V2 along = b - a, side = V2(-along.y(), along.x()).normalized() * (width / 2);
    const int n = flat_ ? 1 : std::max(1, int(std::ceil(along.norm() / 6)));
    for (int k = 0; k < n; ++k) {
      const V2 p = a + along * double(k) / n, q = a + along * double(k + 1) / n;
      add_quad(mesh_, at(p - side, lift), at(q - side, lift), at(q + side, lift),
               at(p + side, lift), paint);
    }
  }

  // A vertical face along the ground from a to b, from lift0 to lift1 above it.
  void wall(const V2& a, const V2& b, double lift0, double lift1, Paint paint) {
    const int n = flat_ ? 1 : std::max(1, int(std::ceil((b - a).norm() / 6)));
    for (int k = 0; k < n; ++k) {
      const V2 p = a + (b - a) * double(k) / n, q = a + (b - a) * double(k + 1) / n;
      add_quad(mesh_, at(p, lift0), at(q, lift0), at(q, lift1), at(p, lift1), paint);
    }
  }

  void terrain() {
    const V2 lo = layout_.lo(), hi = layout_.hi();
    const double far = 1500;
    const double z = -0.3;
    // a wide plain around the map (four quads around the map's rectangle)
    const V2 corners[4] = {V2(-far, -far), V2(far, -far), V2(far, far), V2(-far, far)};
    const V2 inner[4] = {lo, V2(hi.x(), lo.y()), hi, V2(lo.x(), hi.y())};
    const Paint ground{layout_.style.water ? C::Water : C::Terrain,
                       layout_.style.water ? palette_.water : palette_.grass};
    for (int k = 0; k < 4; ++k) {
      const V2 &a = corners[k], &b = corners[(k + 1) % 4], &c = inner[(k + 1) % 4], &d = inner[k];
      add_quad(mesh_, V3(a.x(), a.y(), z), V3(b.x(), b.y(), z), V3(c.x(), c.y(), z),
               V3(d.x(), d.y(), z), ground);
    }
  }

  // Roads map u along the road and v across it from the centre line (asphalt's tyre tracks).
  void roads() {
    const Paint road{C::Road, palette_.asphalt};
    for (int j = 0; j < layout_.ny(); ++j)  // runs of segments along x, junctions included
      for (int i = 0, end = 0; i + 1 < layout_.nx(); i = std::max(i + 1, end)) {
        for (end = i; end + 1 < layout_.nx() && layout_.x_segment(end, j);) ++end;
        if (end == i) continue;
        const double x0 = is_bend(i, j) ? layout_.xs[i] + bend_cut(i, j)
                                        : layout_.xs[i] - layout_.half_width_y(i);
        const double x1 = is_bend(end, j) ? layout_.xs[end] - bend_cut(end, j)
                                          : layout_.xs[end] + layout_.half_width_y(end);
        patch(V2(x0, layout_.ys[j] - layout_.half_width_x(j)),
              V2(x1, layout_.ys[j] + layout_.half_width_x(j)), 0, road, 4,
              {V3(0, layout_.ys[j], 0), V3::UnitX(), V3::UnitY()});
      }
    for (int i = 0; i < layout_.nx(); ++i)
      for (int j = 0; j + 1 < layout_.ny(); ++j)
        if (layout_.y_segment(i, j))
          patch(V2(layout_.xs[i] - layout_.half_width_y(i),
                   layout_.ys[j] + (is_bend(i, j) ? bend_cut(i, j) : layout_.half_width_x(j))),
                V2(layout_.xs[i] + layout_.half_width_y(i),
                   layout_.ys[j + 1] -
                       (is_bend(i, j + 1) ? bend_cut(i, j + 1) : layout_.half_width_x(j + 1))),
                0, road, 4, {V3(layout_.xs[i], 0, 0), V3::UnitY(), -V3::UnitX()});
    margin_ends();
    for (const Lane& lane : layout_.lanes) markings(lane);
    for (int n = 0; n < int(layout_.node_height.size()); ++n) junction(n);
    for (int j = 0; j < layout_.ny(); ++j)
      if (layout_.median(layout_.lanes_along_x[j]) > 0) barriers(j);
  }

  // Where a road line would run on into the margin beyond the outermost road: a sidewalk along
  // that road and ground (the blocks there stop at the road line's edges).
  void margin_ends() {
    const V2 low = layout_.lo(), high = layout_.hi();
    const double w = layout_.style.sidewalk;
    const Paint walk{C::SideWalk, palette_.pavement}, curb{C::SideWalk, palette_.curb},
        ground{C::Terrain, palette_.grass};
    const auto end = [&](const V2& kerb_a, const V2& kerb_b, const V2& outward, double depth) {
      const V2 walk_end_a = kerb_a + outward * w, walk_end_b = kerb_b + outward * w;
      const V2 far_b = kerb_b + outward * depth;
      patch(kerb_a.cwiseMin(walk_end_b), kerb_a.cwiseMax(walk_end_b), kCurb, walk);
      wall(kerb_a, kerb_b, 0, kCurb, curb);
      if (layout_.style.water && outward.y() < 0)  // the quay and the water, as the blocks beside
        return waterfront(walk_end_a.cwiseMin(far_b), walk_end_a.cwiseMax(far_b));
      patch(walk_end_a.cwiseMin(far_b), walk_end_a.cwiseMax(far_b), kCurb, ground);
    };
    const double left = layout_.xs.front() - layout_.half_width_y(0),
                 right = layout_.xs.back() + layout_.half_width_y(layout_.nx() - 1),
                 bottom = layout_.ys.front() - layout_.half_width_x(0),
                 top = layout_.ys.back() + layout_.half_width_x(layout_.ny() - 1);
    for (int j = 0; j < layout_.ny(); ++j) {
      const double y0 = layout_.ys[j] - layout_.half_width_x(j),
                   y1 = layout_.ys[j] + layout_.half_width_x(j);
      end(V2(left, y1), V2(left, y0), V2(-1, 0), left - low.x());
      end(V2(right, y0), V2(right, y1), V2(1, 0), high.x() - right);
    }
    for (int i = 0; i < layout_.nx(); ++i) {
      const double x0 = layout_.xs[i] - layout_.half_width_y(i),
                   x1 = layout_.xs[i] + layout_.half_width_y(i);
      end(V2(x0, bottom), V2(x1, bottom), V2(0, -1), bottom - low.y());
      end(V2(x1, top), V2(x0, top), V2(0, 1), high.y() - top);
    }
  }

  // A median barrier and guard rails along road j (a highway) between its junctions.
  void barriers(int j) {
    const Paint rail{C::GuardRail, palette_.metal};
    const double half = layout_.half_width_x(j) - 0.4;
    for (int i = 0; i + 1 < layout_.nx(); ++i) {
      const double x0 = layout_.xs[i] + layout_.junction_reach(layout_.node(i, j)).x(),
                   x1 = layout_.xs[i + 1] - layout_.junction_reach(layout_.node(i + 1, j)).x();
      for (double y : {layout_.ys[j] - half, layout_.ys[j], layout_.ys[j] + half}) {
        const V3 centre = at(V2((x0 + x1) / 2, y), 0.45);
        add_oriented_box(mesh_, Pose(Eigen::Translation3d(centre)), V3((x1 - x0) / 2, 0.2, 0.45),
                         rail);
      }
    }
  }

  void markings(const Lane& lane) {
    const PathPoint a = lane.path.at(0), b = lane.path.at(lane.path.length());
    const V2 left(-a.direction.y(), a.direction.x());
    const Paint white{C::RoadLine, palette_.white}, yellow{C::RoadLine, palette_.yellow};
    // the line on this lane's left: dashed white between lanes, solid yellow at the centre
    const V2 shift = left * (kLaneWidth / 2);
    if (lane.index == 0) {
      strip(a.position + shift - left * 0.12, b.position + shift - left * 0.12, 0.12, 0.02, yellow);
    } else {
      const double length = lane.path.length();
      for (double s = 1; s + 3 < length; s += 9)
        strip(lane.path.at(s).position + shift, lane.path.at(s + 3).position + shift, 0.15, 0.02,
              white);
    }
    if (layout_.is_bend(lane.to)) return;  // no stop line before a bend
    // stop line across the lane at its end
    strip(b.position - a.direction * 0.3 - left * (kLaneWidth / 2),
          b.position - a.direction * 0.3 + left * (kLaneWidth / 2), 0.4, 0.02, white);
  }

  bool is_bend(int i, int j) const { return layout_.is_bend(layout_.node(i, j)); }
  double bend_cut(int i, int j) const { return layout_.bend_cut(layout_.node(i, j)); }

  // The road round a bend: straight from where the lanes stop to the circle's tangent points, a
  // quarter annulus between them; its centre and lane lines; a kerb, a curved sidewalk and ground
  // inside it; ground outside it. (u, v) are distances from the node along the bend's two roads.
  void bend(int n) {
    const auto arms = layout_.bend_arms(n);
    const V2 node = layout_.node_position(n);
    const double half = layout_.half_width_x(n / layout_.nx()), cut = layout_.bend_cut(n),
                 walk = layout_.style.sidewalk, r = kBendRadius;
    const auto at_uv = [&](double u, double v) { return node + u * arms[0] + v * arms[1]; };
    // the point `off` inside the centre line at share t of the way (0: where the first road's
    // lanes stop, 1: the second's), and the direction of travel there
    const double straight = cut - r, arc = r * kPi / 2, total = 2 * straight + arc;
    const auto along = [&](double t, double off) -> std::pair<V2, V2> {
      const double s = t * total;
      if (s <= straight) return {at_uv(cut - s, off), -arms[0]};
      if (s >= straight + arc) return {at_uv(off, r + s - straight - arc), arms[1]};
      const double theta = (s - straight) / r;  // from (r, 0) round (r, r) to (0, r)
      const V2 centre = at_uv(r, r), out = -std::cos(theta) * arms[1] - std::sin(theta) * arms[0];
      return {centre + (r - off) * out, std::cos(theta) * -arms[0] + std::sin(theta) * arms[1]};
    };
    const int steps = 48;
    const Paint road{C::Road, palette_.asphalt}, yellow{C::RoadLine, palette_.yellow},
        white{C::RoadLine, palette_.white}, walkway{C::SideWalk, palette_.pavement},
        kerb{C::SideWalk, palette_.curb}, grass{C::Terrain, palette_.grass};
    const auto band = [&](double off0, double off1, double lift, Paint paint, bool uv) {
      for (int k = 0; k < steps; ++k) {
        const auto [a, da] = along(double(k) / steps, off0);
        const V2 b = along(double(k + 1) / steps, off0).first;
        const V2 c = along(double(k + 1) / steps, off1).first,
                 d = along(double(k) / steps, off1).first;
        const V2 left(-da.y(), da.x());
        const UvFrame frame{V3(a.x(), a.y(), 0) - V3(da.x(), da.y(), 0) * (k * total / steps) +
                                V3(left.x(), left.y(), 0) * off0,
                            V3(da.x(), da.y(), 0), V3(left.x(), left.y(), 0)};
        if (uv)
          add_quad(mesh_, at(a, lift), at(b, lift), at(c, lift), at(d, lift), paint, frame);
        else
          add_quad(mesh_, at(a, lift), at(b, lift), at(c, lift), at(d, lift), paint);
      }
    };
    const int lanes = layout_.lanes_along_x[n / layout_.nx()];
    band(-half, half, 0, road, true);
    for (const double off : {-0.18, 0.06}) band(off, off + 0.12, 0.02, yellow, false);
    for (int k = 1; k < lanes; ++k)
      for (const double side : {-1.0, 1.0})
        band(side * k * kLaneWidth - 0.075, side * k * kLaneWidth + 0.075, 0.02, white, false);
    band(half, half + walk, kCurb, walkway, false);
    for (int k = 0; k < steps; ++k)  // the kerb's face, seen from the road
      wall(along(double(k) / steps, half).first, along(double(k + 1) / steps, half).first, 0, kCurb,
           kerb);
    // ground inside the sidewalk (fanned from the square's far corner) and outside the road
    // (from its near corner): both regions are convex
    const auto fan = [&](const V2& from, double off) {
      for (int k = 0; k < steps; ++k)
        add_quad(mesh_, at(from, kCurb), at(along(double(k) / steps, off).first, kCurb),
                 at(along(double(k + 1) / steps, off).first, kCurb), at(from, kCurb), grass);
    };
    fan(at_uv(cut, cut), half + walk);
    fan(at_uv(-half, -half), -half);
  }

  void junction(int n) {
    if (layout_.is_bend(n)) return bend(n);
    const V2 centre = layout_.node_position(n), reach = layout_.junction_reach(n);
    const double hx = layout_.half_width_y(n % layout_.nx()),
                 hy = layout_.half_width_x(n / layout_.nx());
    const Paint zebra{C::RoadLine, palette_.white};
    // crossings on its arms, stripes along the road
    for (int side : {-1, 1}) {
      for (double y = -hy + 0.5; y < hy - 0.4 && layout_.has_arm(n, side > 0); y += 1.2)
        strip(centre + V2(side * (hx + 0.5), y), centre + V2(side * (reach.x() - 0.5), y), 0.6,
              0.02, zebra);
      for (double x = -hx + 0.5; x < hx - 0.4 && layout_.has_arm(n, 2 + (side > 0)); x += 1.2)
        strip(centre + V2(x, side * (hy + 0.5)), centre + V2(x, side * (reach.y() - 0.5)), 0.6,
              0.02, zebra);
    }
    if (layout_.is_roundabout(n)) {
      const double z = layout_.height(centre);
      add_cylinder(mesh_, Pose(Eigen::Translation3d(centre.x(), centre.y(), z - 0.2)), 3.0, 0.5,
                   {C::Terrain, palette_.grass}, 16);
      tree(centre, 0.5);
    }
    const int i = n % layout_.nx(), j = n / layout_.nx();
    const bool lights =
        !layout_.is_roundabout(n) && i > 0 && j > 0 && i + 1 < layout_.nx() && j + 1 < layout_.ny();
    for (int corner = 0; corner < 4; ++corner) {
      const V2 sign(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1);
      const V2 spot = centre + V2(sign.x() * (hx + 0.3), sign.y() * (hy + 0.3));
      if (lights)
        traffic_light(spot, sign, n % 2 == 0);
      else if (random_.chance(0.5))
        traffic_sign(spot);
    }
  }

  Pose upright(const V2& p, double lift, double yaw = 0) const {
    return Pose(Eigen::Translation3d(at(p, lift)) * Eigen::AngleAxisd(yaw, V3::UnitZ()));
  }

  // At night the heads facing the road along x show green when `x_goes`, the others red.
  void traffic_light(const V2& spot, const V2& sign, bool x_goes) {
    add_cylinder(mesh_, upright(spot, kCurb), 0.09, 4.2, {C::Pole, palette_.metal}, 8);
    for (int k = 0; k < 2; ++k) {  // one head facing each road at this corner
      const V2 face = k == 0 ? V2(sign.x(), 0) : V2(0, sign.y());
      const bool go = (k == 0) == x_goes;
      add_oriented_box(mesh_, upright(spot + 0.3 * face, kCurb + 3.7), V3(0.15, 0.15, 0.45),
                       {C::TrafficLight, go ? palette_.signal_go : palette_.signal_stop});
    }
  }

  void traffic_sign(const V2& spot) {
    add_cylinder(mesh_, upright(spot, kCurb), 0.05, 2.6, {C::Pole, palette_.metal}, 6);
    add_oriented_box(mesh_, upright(spot, kCurb + 2.4, random_.uniform(0, 3.14)),
                     V3(0.02, 0.35, 0.35), {C::TrafficSign, palette_.sign});
  }

  void street_light(const V2& spot, const V2& toward_road) {
    add_cylinder(mesh_, upright(spot, kCurb), 0.08, 6.5, {C::Pole, palette_.metal}, 8);
    const double yaw = std::atan2(toward_road.y(), toward_road.x());
    add_oriented_box(mesh_, upright(spot + toward_road * 0.8, kCurb + 6.4, yaw),
                     V3(0.9, 0.08, 0.06), {C::Pole, palette_.metal});
    add_oriented_box(mesh_, upright(spot + toward_road * 1.6, kCurb + 6.3, yaw),
                     V3(0.3, 0.14, 0.06), {C::Pole, palette_.lamp});  // the lamp head
    scene_.lamps.push_back(street_lamp_light(at(spot + toward_road * 1.6, kCurb + 6.22)));
  }

  // A trunk and a crown of irregular leaf clusters around it.
  void tree(const V2& p, double lift) {
    const double height = random_.uniform(2.0, 3.5), crown = random_.uniform(1.5, 2.8);
    add_cylinder(mesh_, upright(p, lift), 0.18, height + 0.6 * crown,
                 {C::Vegetation, palette_.bark}, 7);
    const Paint leaves{C::Vegetation, palette_.leaves[random_.below(int(palette_.leaves.size()))]};
    const int clusters = 4 + random_.below(4);
    for (int k = 0; k < clusters; ++k) {
      const double a = 2 * kPi * (k + random_.uniform(0, 0.6)) / clusters;
      const double r = k == 0 ? 0 : crown * random_.uniform(0.35, 0.6);
      const V3 centre = at(p, lift + height + crown * random_.uniform(0.5, 1.1)) +
                        V3(r * std::cos(a), r * std::sin(a), 0);
      const double size = crown * (k == 0 ? 0.75 : random_.uniform(0.45, 0.65));
      add_lumpy_ball(mesh_, centre, V3(size, size, size * random_.uniform(0.7, 0.95)), leaves,
                     random_);
    }
  }

  bool free_of_solids(const V2& lo, const V2& hi) const {
    for (const Footprint& f : solids_) {
      V2 flo = f[0], fhi = f[0];
      for (const V2& c : f) flo = flo.cwiseMin(c), fhi = fhi.cwiseMax(c);
      if (lo.x() < fhi.x() && hi.x() > flo.x() && lo.y() < fhi.y() && hi.y() > flo.y())
        return false;
    }
    return true;
  }

  void sidewalks(const Block& b) {
    const double w = layout_.style.sidewalk;
    const Paint walk{C::SideWalk, palette_.pavement}, curb{C::SideWalk, palette_.curb};
    const V2 lo = b.lo, hi = b.hi;
    const std::array<std::pair<V2, V2>, 4> bands = {
        std::pair{lo, V2(lo.x() + w, hi.y())}, std::pair{V2(hi.x() - w, lo.y()), hi},
        std::pair{lo, V2(hi.x(), lo.y() + w)}, std::pair{V2(lo.x(), hi.y() - w), hi}};
    const std::array<std::pair<V2, V2>, 4> edges = {
        // curb faces, seen from the road
        std::pair{V2(lo.x(), hi.y()), lo}, std::pair{V2(hi.x(), lo.y()), hi},
        std::pair{lo, V2(hi.x(), lo.y())}, std::pair{hi, V2(lo.x(), hi.y())}};
    for (int k = 0; k < 4; ++k) {
      if (!b.road_beside[k]) continue;
      for (const Rect& part : without_bends({bands[k].first, bands[k].second}))
        patch(part.lo, part.hi, kCurb, walk);
      // the kerb, shortened where a bend's own kerb takes over
      V2 from = edges[k].first, to = edges[k].second;
      for (const Rect& bend : bend_squares_) {
        const Rect edge{from.cwiseMin(to), from.cwiseMax(to)};
        if (!Rect{edge.lo - V2::Constant(0.01), edge.hi + V2::Constant(0.01)}.meets(bend)) continue;
        const V2 along = (to - from).normalized();
        const double extent = std::abs((bend.hi - bend.lo).dot(along));
        if (bend.contains(from, 0.01)) from += along * extent;
        if (bend.contains(to, 0.01)) to -= along * extent;
      }
      wall(from, to, 0, kCurb, curb);
      const V2 along = (to - from).normalized();
      const V2 inward(-along.y(), along.x());
      for (double s = 12; s < (to - from).norm() - 12; s += 30)
        street_light(from + along * s + inward * 0.25, -inward);
    }
  }

  // Every building its own facade, frames and roof (materials seeded per building).
  Dress dress(bool houses) {
    namespace cm = city_materials;
    const auto seed = random_.bits();
    return {add_material(scene_, cm::facade(seed, houses)),
            add_material(scene_, cm::window_frame(seed + 1)),
            add_material(scene_, cm::roof_tiles(seed + 2)),
            random_.chance(0.7),
            !houses && random_.chance(0.5),
            !houses && random_.chance(0.5)};
  }

  void building(const V2& lo, const V2& hi, double height, const Dress& d, bool roof) {
    const V2 corners[4] = {lo, V2(hi.x(), lo.y()), hi, V2(lo.x(), hi.y())};
    double base = 1e9;
    for (const V2& c : corners) base = std::min(base, layout_.height(c));
    const V3 lo3(lo.x(), lo.y(), base - 0.5), hi3(hi.x(), hi.y(), base + kCurb + height);
    Mesh box;
    add_box(box, lo3.cast<float>(), hi3.cast<float>(), C::Building);
    box.materials.assign(box.triangles.size(), d.facade);
    append_mesh(mesh_, box);
    const V2 grow(kFacadeDepth, kFacadeDepth);  // frames, sills and ledges stand out this far
    solids_.push_back({lo - grow, V2(hi.x() + grow.x(), lo.y() - grow.y()), hi + grow,
                       V2(lo.x() - grow.x(), hi.y() + grow.y())});
    for (int k = 0; k < 4; ++k) facade(corners[k], corners[(k + 1) % 4], base + kCurb, height, d);
    if (roof) gable(lo3, hi3, d.roof);
  }

  // A box on a facade from a to b (outside on the right of a -> b): `along` from a, `out` from
  // the wall, `z` above the ground; half extents (along, out, up).
  void on_wall(const V2& a, const V2& b, double along, double out, double z, const V3& half,
               Paint paint) {
    const V2 dir = (b - a).normalized(), normal(dir.y(), -dir.x());
    const V2 p = a + dir * along + normal * out;
    add_oriented_box(mesh_,
                     Pose(Eigen::Translation3d(p.x(), p.y(), z) *
                          Eigen::AngleAxisd(std::atan2(dir.y(), dir.x()), V3::UnitZ())),
                     half, paint);
  }

  // Windows in framed openings with sills, storey ledges and a cornice, per the building's dress.
  void facade(const V2& a, const V2& b, double base, double height, const Dress& d) {
    const Paint frame{C::Building, d.frame};
    const double length = (b - a).norm();
    const int columns = int(length / 3.2);
    const V2 dir = (b - a) / length, out(dir.y(), -dir.x());
    for (double z = base + 1.2; z + 2.2 < base + height; z += 3.3) {
      for (int c = 0; c < columns; ++c) {
        const double s = length * (c + 0.5) / columns;
        on_wall(a, b, s, 0.03, z + 0.9, V3(0.78, 0.03, 0.98), frame);
        const V2 p = a + dir * s + out * 0.065;
        const V3 p0(p.x() - dir.x() * 0.68, p.y() - dir.y() * 0.68, z + 0.02),
            p1(p.x() + dir.x() * 0.68, p.y() + dir.y() * 0.68, z + 0.02);
        add_quad(mesh_, p0, p1, p1 + V3(0, 0, 1.76), p0 + V3(0, 0, 1.76), window(p0, z - base));
        if (d.sills) on_wall(a, b, s, 0.1, z - 0.1, V3(0.85, 0.1, 0.03), frame);
      }
      if (d.ledges) on_wall(a, b, length / 2, 0.06, z - 0.35, V3(length / 2, 0.06, 0.08), frame);
    }
    if (d.cornice)
      on_wall(a, b, length / 2, 0.15, base + height - 0.2, V3(length / 2 + 0.15, 0.15, 0.2), frame);
  }

  // A window's glass: a third of the windows (two thirds of the shop fronts on the ground floor)
  // lit at night, picked by a hash of the window's place, so the world's random stream and
  // geometry stay as they were.
  Paint window(const V3& corner, double storey_height) const {
    const bool shop = storey_height < 2;
    const double pick =
        tex::hash01(std::int64_t(std::floor(corner.x() * 10)),
                    std::int64_t(std::floor(corner.y() * 10 + corner.z() * 7)), 0x11);
    if (shop && pick < 0.65) return {C::Building, palette_.lit_shop};
    if (!shop && pick < 0.33) return {C::Building, palette_.lit_windows[int(pick / 0.11)]};
    return {C::Building, palette_.glass};
  }

  void gable(const V3& lo, const V3& hi, std::uint16_t material) {
    const Paint roof{C::Building, material};
    const double ridge = hi.z() + 0.4 * (hi.y() - lo.y()), my = (lo.y() + hi.y()) / 2;
    const V3 a(lo.x(), lo.y(), hi.z()), b(hi.x(), lo.y(), hi.z()), c(hi.x(), hi.y(), hi.z()),
        d(lo.x(), hi.y(), hi.z()), r0(lo.x(), my, ridge), r1(hi.x(), my, ridge);
    // u along the eaves, v up the slope from them
    add_quad(mesh_, a, b, r1, r0, roof, {a, V3::UnitX(), (r0 - a).normalized()});
    add_quad(mesh_, c, d, r0, r1, roof, {c, -V3::UnitX(), (r1 - c).normalized()});
    add_quad(mesh_, b, c, r1, r1, roof);
    add_quad(mesh_, d, a, r0, r0, roof);
  }

  void fence(const V2& a, const V2& b) {
    const Paint paint{C::Fence, palette_.timber};
    const V2 along = (b - a).normalized();
    for (double s = 0; s <= (b - a).norm(); s += 2.5)
      add_oriented_box(mesh_, upright(a + along * s, kCurb + 0.6), V3(0.05, 0.05, 0.6), paint);
    const double yaw = std::atan2(along.y(), along.x());
    add_oriented_box(mesh_, upright((a + b) / 2, kCurb + 1.0, yaw),
                     V3((b - a).norm() / 2, 0.03, 0.06), paint);
  }

  // Parts of `r` outside the squares that bends take from the block being built.
  std::vector<Rect> without_bends(const Rect& r) const {
    std::vector<Rect> parts{r};
    for (const Rect& bend : bend_squares_) {
      std::vector<Rect> next;
      for (const Rect& part : parts)
        for (const Rect& piece : minus_corner(part, bend)) next.push_back(piece);
      parts = std::move(next);
    }
    return parts;
  }

  // The squares of bends at the block's corners (from its corner to where the lanes stop).
  void find_bend_squares(const Block& b) {
    bend_squares_.clear();
    if (!b.inner) return;
    for (const V2& corner : {b.lo, V2(b.hi.x(), b.lo.y()), b.hi, V2(b.lo.x(), b.hi.y())}) {
      const int n = layout_.bend_at(corner);
      if (n < 0) continue;
      const auto arms = layout_.bend_arms(n);
      const V2 far = layout_.node_position(n) + layout_.bend_cut(n) * (arms[0] + arms[1]);
      bend_squares_.push_back({corner.cwiseMin(far), corner.cwiseMax(far)});
    }
  }

  bool clear_of_bends(const V2& lo, const V2& hi) const {
    return std::none_of(bend_squares_.begin(), bend_squares_.end(), [&](const Rect& r) {
      return Rect{lo, hi}.meets(r);
    });
  }

  // A paved plaza with a diagonal street across it: the road, paving either side of it (the block
  // cut by the road's band: two convex polygons), kerbs along the road and round the block where
  // the road does not cross, and trees along the road.
  void plaza(const Block& b, const Diagonal& d) {
    const V2 normal(-d.direction.y(), d.direction.x());
    const Paint road{C::Road, palette_.asphalt}, walk{C::SideWalk, palette_.pavement},
        kerb{C::SideWalk, palette_.curb};
    // the road from where it leaves one junction's box to where it enters the other's
    const auto box_exit = [&](int node) {
      const V2 half(layout_.half_width_y(node % layout_.nx()),
                    layout_.half_width_x(node / layout_.nx()));
      return std::min(half.x() / std::abs(d.direction.x()), half.y() / std::abs(d.direction.y()));
    };
    const V2 a = layout_.node_position(d.from), c = layout_.node_position(d.to);
    const V2 from = a + d.direction * box_exit(d.from), to = c - d.direction * box_exit(d.to);
    const int pieces = std::max(1, int(std::ceil((to - from).norm() / 6)));
    for (int k = 0; k < pieces; ++k) {
      const V2 p = from + (to - from) * double(k) / pieces,
               q = from + (to - from) * double(k + 1) / pieces;
      const V2 side = normal * d.half_width;
      add_quad(mesh_, at(p - side, 0), at(q - side, 0), at(q + side, 0), at(p + side, 0), road,
               {V3(a.x(), a.y(), 0), V3(d.direction.x(), d.direction.y(), 0),
                V3(normal.x(), normal.y(), 0)});
    }
    const std::array<V2, 4> corners{b.lo, V2(b.hi.x(), b.lo.y()), b.hi, V2(b.lo.x(), b.hi.y())};
    for (const double side : {-1.0, 1.0}) {
      // the block's corners beyond the road's edge on this side, and where its edges meet that edge
      std::vector<V2> paving;
      for (int k = 0; k < 4; ++k) {
        const V2 &p = corners[k], &q = corners[(k + 1) % 4];
        const double fp = side * d.offset(p) - d.half_width, fq = side * d.offset(q) - d.half_width;
        if (fp >= 0) paving.push_back(p);
        if ((fp < 0) != (fq < 0)) paving.push_back(p + (q - p) * (fp / (fp - fq)));
      }
      for (std::size_t k = 1; k + 1 < paving.size(); ++k)
        add_quad(mesh_, at(paving[0], kCurb), at(paving[k], kCurb), at(paving[k + 1], kCurb),
                 at(paving[0], kCurb), walk);
      // the kerb along the road: the chord of the paving polygon on the road's edge
      std::vector<V2> edge;
      for (const V2& p : paving)
        if (std::abs(side * d.offset(p) - d.half_width) < 1e-9) edge.push_back(p);
      if (edge.size() == 2) wall(edge[0], edge[1], 0, kCurb, kerb);
      for (std::size_t k = 0; k < paving.size(); ++k) {  // and round the block
        const V2 &p = paving[k], &q = paving[(k + 1) % paving.size()];
        const bool on_road_edge = std::abs(side * d.offset(p) - d.half_width) < 1e-9 &&
                                  std::abs(side * d.offset(q) - d.half_width) < 1e-9;
        if (!on_road_edge) wall(p, q, 0, kCurb, kerb);
      }
      const double length = (c - a).norm();
      for (double s = 12; s < length - 12; s += 15) {
        const V2 spot = a + d.direction * s + normal * side * (d.half_width + 2.5);
        if (spot.x() > b.lo.x() + 2 && spot.x() < b.hi.x() - 2 && spot.y() > b.lo.y() + 2 &&
            spot.y() < b.hi.y() - 2)
          tree(spot, kCurb);
      }
    }
  }

  void block(const Block& b) {
    if (b.diagonal >= 0) return plaza(b, layout_.diagonals[b.diagonal]);
    const Style& style = layout_.style;
    find_bend_squares(b);
    sidewalks(b);
    const double w = style.sidewalk;
    const V2 lo = b.lo + V2(b.road_beside[0] ? w : 0, b.road_beside[2] ? w : 0);
    const V2 hi = b.hi - V2(b.road_beside[1] ? w : 0, b.road_beside[3] ? w : 0);
    if (hi.x() - lo.x() < 4 || hi.y() - lo.y() < 4) return;
    const bool park = random_.chance(style.parks);
    const bool green = park || style.buildings == Style::Buildings::Houses ||
                       style.buildings == Style::Buildings::Farms;
    if (style.water && !b.road_beside[2] && b.road_beside[3]) return waterfront(lo, hi);
    for (const Rect& part : without_bends({lo, hi}))
      patch(part.lo, part.hi, kCurb,
            green ? Paint{C::Terrain, palette_.grass}
                  : Paint{C::Ground, style.buildings == Style::Buildings::Warehouses
                                         ? palette_.dirt
                                         : palette_.concrete});
    if (!park)
      lots(lo, hi, b);
    else if (clear_of_bends(V2(lo.x(), lo.y()), V2(hi.x(), lo.y() + 2)))
      fence(V2(lo.x() + 1, lo.y() + 1), V2(hi.x() - 1, lo.y() + 1));
    if (style.rails && !b.road_beside[3]) rails(lo, hi);
    const double spacing = 100 / std::max(0.1, style.trees + (park ? 6 : 0));
    for (double x = lo.x() + 2; x < hi.x() - 2; x += spacing)
      for (double y : {lo.y() + 1.5, hi.y() - 1.5})
        if (free_of_solids(V2(x, y) - V2(2, 2), V2(x, y) + V2(2, 2)) &&
            clear_of_bends(V2(x, y) - V2(2, 2), V2(x, y) + V2(2, 2)))
          tree(V2(x, y), kCurb);
    if (park)
      for (int k = 0; k < 6; ++k) {
        const V2 p(random_.uniform(lo.x() + 4, hi.x() - 4),
                   random_.uniform(lo.y() + 4, hi.y() - 4));
        if (clear_of_bends(p - V2(2, 2), p + V2(2, 2))) tree(p, kCurb);
      }
  }

  // Buildings along the block's two sides that run along x, front at the block's edge.
  void lots(const V2& lo, const V2& hi, const Block& b) {
    const Style& style = layout_.style;
    using Kind = Style::Buildings;
    const bool houses = style.buildings == Kind::Houses || style.buildings == Kind::Farms;
    const double setback = houses ? 5 : (style.buildings == Kind::Warehouses ? 3 : 0.5);
    const double max_depth = std::min(houses ? 12.0 : 30.0, (hi.y() - lo.y()) / 2 - setback - 1);
    if (max_depth < 5) return;
    for (int side = 0; side < 2; ++side) {
      if (!b.road_beside[2 + side] && b.inner) continue;
      double x = lo.x() + 1;
      while (x < hi.x() - 6) {
        const double width =
            std::min(hi.x() - 1 - x, random_.uniform(houses ? 9 : 12, houses ? 14 : 30));
        if (width < 6) break;
        const double depth = random_.uniform(std::min(8.0, max_depth), max_depth);
        const double y0 = side == 0 ? lo.y() + setback : hi.y() - setback - depth;
        const V2 blo(x, y0), bhi(x + width, y0 + depth);
        if (random_.chance(style.fill) && clear_of_bends(blo - V2(1, 1), bhi + V2(1, 1))) {
          building(blo, bhi, random_.uniform(style.height_min, style.height_max), dress(houses),
                   houses);
          if (houses) {
            const double front = side == 0 ? lo.y() + 1 : hi.y() - 1;
            fence(V2(x, front), V2(x + width - 2.5, front));
          }
          if (style.buildings == Kind::Warehouses && random_.chance(0.4)) tank(blo, bhi, side);
        }
        x += width + random_.uniform(1, houses ? 8 : 4);
      }
    }
  }

  void tank(const V2& lo, const V2& hi, int side) {
    const double y = side == 0 ? hi.y() + 4 : lo.y() - 4, x = (lo.x() + hi.x()) / 2;
    if (!free_of_solids(V2(x - 3.5, y - 3.5), V2(x + 3.5, y + 3.5)) ||
        !clear_of_bends(V2(x - 3.5, y - 3.5), V2(x + 3.5, y + 3.5)))
      return;
    add_cylinder(mesh_, upright(V2(x, y), kCurb - 0.3), 3, random_.uniform(4, 9),
                 {C::Static, palette_.tank}, 16);
    solids_.push_back({V2(x - 3, y - 3), V2(x + 3, y - 3), V2(x + 3, y + 3), V2(x - 3, y + 3)});
  }

  void rails(const V2& lo, const V2& hi) {
    const double y = (lo.y() + hi.y()) / 2;
    strip(V2(lo.x(), y), V2(hi.x(), y), 3.0, kCurb + 0.05, {C::RailTrack, palette_.dirt});
    for (double offset : {-0.72, 0.72})
      strip(V2(lo.x(), y + offset), V2(hi.x(), y + offset), 0.08, kCurb + 0.2,
            {C::RailTrack, palette_.rail});
  }

  // A promenade along the road, a quay wall, water below and piers on posts.
  void waterfront(const V2& lo, const V2& hi) {
    const double quay = hi.y() - 8;
    patch(V2(lo.x(), quay), hi, kCurb, {C::Ground, palette_.concrete});
    patch(lo, V2(hi.x(), quay), -1.5, {C::Water, palette_.water}, 50);
    wall(V2(hi.x(), quay), V2(lo.x(), quay), -1.5, kCurb, {C::Wall, palette_.concrete});
    for (double x = lo.x() + 20; x < hi.x() - 10; x += 60) {
      const V3 p = at(V2(x, quay - 15), kCurb);
      add_oriented_box(mesh_, Pose(Eigen::Translation3d(p - V3(0, 0, 0.15))), V3(3, 15, 0.15),
                       {C::Bridge, palette_.timber});
      for (double dy : {-12.0, 0.0, 12.0})
        for (double dx : {-2.5, 2.5})
          add_cylinder(mesh_, Pose(Eigen::Translation3d(p + V3(dx, dy, -2.5))), 0.2, 2.3,
                       {C::Bridge, palette_.timber}, 6);
    }
    for (double x = lo.x() + 5; x < hi.x() - 5; x += 14) tree(V2(x, hi.y() - 3), kCurb);
  }

  const Layout& layout_;
  Random random_;
  Mesh& mesh_;
  Scene& scene_;
  Palette palette_;
  bool flat_;
  std::vector<Footprint> solids_;
  std::vector<Rect> bend_squares_;  // of the block being built
};

}  // namespace

std::vector<Footprint> build_world(const Layout& layout, std::uint64_t seed, Scene& scene) {
  return WorldBuilder(layout, seed, scene).build();
}

Lamp street_lamp_light(const Vec3& position) {
  Lamp light;
  light.position = position;
  light.cos_inner = std::cos(50 * kPi / 180), light.cos_outer = std::cos(72 * kPi / 180);
  light.intensity = Eigen::Vector3f(1.0f, 0.86f, 0.68f) * 0.015f;
  return light;
}

}  // namespace flowscape
