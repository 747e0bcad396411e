#include "standing.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "flowscape/core/random.h"

namespace flowscape {
namespace {

using V2 = Eigen::Vector2d;

// Clear of the kerb's poles (street lights 0.25 m in, signals and signs 0.3 m in from both
// kerbs) and of the facades (frames stand 0.3 m out): a person's middle keeps this far from both.
constexpr double kFromEdges = 0.7;

// A pavement along one side of a block: its kerb, the way into the block, its length, and how
// near the ego's way comes.
struct Pavement {
  V2 start, along, inward;
  double length, width;
  double from_way = 0;
};

// How near p comes to the ego's way (its track sampled every quarter second).
double distance_to_way(const Track& ego, const V2& p) {
  double nearest = 1e18;
  for (std::size_t k = 0; k < ego.poses.size(); k += 15)
    nearest = std::min(nearest, (ego.poses[k].translation().head<2>() - p).norm());
  return nearest;
}

// The pavements of the map's blocks, each with how near it comes to the ego's way.
std::vector<Pavement> pavements(const Layout& layout, const Track& ego) {
  std::vector<Pavement> out;
  const double w = layout.style.sidewalk;
  for (const Block& b : layout.blocks) {
    if (b.diagonal >= 0) continue;  // a plaza: paving, no pavement along a kerb
    const V2 size = b.hi - b.lo;
    const Pavement sides[4] = {{b.lo, V2(0, 1), V2(1, 0), size.y(), w},
                               {V2(b.hi.x(), b.lo.y()), V2(0, 1), V2(-1, 0), size.y(), w},
                               {b.lo, V2(1, 0), V2(0, 1), size.x(), w},
                               {V2(b.lo.x(), b.hi.y()), V2(1, 0), V2(0, -1), size.x(), w}};
    for (int k = 0; k < 4; ++k)
      if (b.road_beside[k] && w > 2 * kFromEdges) out.push_back(sides[k]);
  }
  for (Pavement& p : out) {
    p.from_way = 1e18;
    for (double s = 0; s <= p.length; s += 2)
      p.from_way = std::min(p.from_way, distance_to_way(ego, p.start + s * p.along));
  }
  return out;
}

// Whether a person may stand at p: on the pavement, kFromEdges from the road, the lot and the
// plazas, off the curved pavements round the map's corners.
bool on_pavement(const Layout& layout, const V2& p) {
  if (layout.bend_at(p) >= 0) return false;
  for (const V2& d : {V2(1, 0), V2(-1, 0), V2(0, 1), V2(0, -1)})
    if (layout.area(p + kFromEdges * d) != Area::SideWalk) return false;
  return layout.area(p) == Area::SideWalk;
}

// A walker's track and the box round everything it passes.
struct WalkerSpan {
  const Track* track;
  V2 lo, hi;
};

std::vector<WalkerSpan> walker_spans(const std::vector<Track>& tracks) {
  std::vector<WalkerSpan> spans;
  for (const Track& track : tracks) {
    WalkerSpan span{&track, V2::Constant(1e18), V2::Constant(-1e18)};
    for (const Pose& pose : track.poses)
      span.lo = span.lo.cwiseMin(pose.translation().head<2>()),
      span.hi = span.hi.cwiseMax(pose.translation().head<2>());
    spans.push_back(span);
  }
  return spans;
}

bool clear_of_walkers(const std::vector<WalkerSpan>& walkers, const V2& p, double clear) {
  for (const WalkerSpan& w : walkers) {
    if ((p.array() < w.lo.array() - clear).any() || (p.array() > w.hi.array() + clear).any())
      continue;
    for (const Pose& pose : w.track->poses)
      if ((pose.translation().head<2>() - p).norm() < clear) return false;
  }
  return true;
}

// The pavements that come within `reach` of the ego's way.
std::vector<const Pavement*> near_the_way(const std::vector<Pavement>& all, double reach) {
  std::vector<const Pavement*> near;
  for (const Pavement& p : all)
    if (p.from_way < reach) near.push_back(&p);
  return near;
}

// People in a group of one to four: 55 % alone, 25 % two, 12 % three, 8 % four.
int group_size(Random& random) {
  const double u = random.uniform();
  return u < 0.55 ? 1 : u < 0.8 ? 2 : u < 0.92 ? 3 : 4;
}

// Where one alone looks: at the road (waiting), at the shop fronts, or along the pavement.
double lone_yaw(const Pavement& pavement, Random& random) {
  const double u = random.uniform();
  const V2 look = u < 0.5              ? V2(-pavement.inward)
                  : u < 0.7            ? pavement.inward
                  : random.chance(0.5) ? pavement.along
                                       : V2(-pavement.along);
  return std::atan2(look.y(), look.x()) + random.uniform(-0.4, 0.4);
}

// `size` people round `middle` on `pavement`, `apart` from their neighbours, facing the middle (one
// alone: lone_yaw), a quarter of the others children.
std::vector<StandingPerson> group_round(const Layout& layout, const Pavement& pavement,
                                        const V2& middle, int size, double apart, Random& random) {
  const double radius = size == 1 ? 0 : apart / (2 * std::sin(kPi / size));
  const double turn = random.uniform(0, 2 * kPi);
  std::vector<StandingPerson> members;
  for (int k = 0; k < size; ++k) {
    const double angle = turn + 2 * kPi * k / size;
    const V2 at = middle + radius * V2(std::cos(angle), std::sin(angle));
    const double yaw =
        size == 1 ? lone_yaw(pavement, random) : angle + kPi + random.uniform(-0.3, 0.3);
    const PathPoint point{at, V2(std::cos(yaw), std::sin(yaw))};
    members.push_back({ground_pose(layout, point, kCurb), k > 0 && random.chance(0.25)});
  }
  return members;
}

}  // namespace

std::vector<StandingPerson> place_standing(const Layout& layout, const TrafficTracks& tracks,
                                           int count, std::uint64_t seed, bool wet) {
  std::vector<StandingPerson> people;
  if (count == 0) return people;
  const std::vector<Pavement> ways = pavements(layout, tracks.vehicles[0]);
  const std::vector<WalkerSpan> walkers = walker_spans(tracks.walkers);
  // apart by this much, middle to middle: people of a group, and anyone from a walker (open
  // umbrellas of 0.5 m radius need more)
  const double apart = wet ? 1.3 : 0.9, from_walkers = wet ? 1.5 : 0.85;
  Random random(derived_seed(seed, 0, 0x7374616e64ull));  // "stand"
  while (int(people.size()) < count) {
    bool placed = false;
    // round the ego's way: within 20 m, 5 m more each 50 tries that found no room
    for (int attempt = 0; attempt < 1000 && !placed; ++attempt) {
      const double reach = 20 + 5 * (attempt / 50);
      const std::vector<const Pavement*> near = near_the_way(ways, reach);
      if (near.empty()) continue;
      const Pavement& pavement = *near[random.below(int(near.size()))];
      const V2 middle = pavement.start + random.uniform(0, pavement.length) * pavement.along +
                        random.uniform(kFromEdges, pavement.width - kFromEdges) * pavement.inward;
      if (distance_to_way(tracks.vehicles[0], middle) > reach) continue;
      const int size = std::min(group_size(random), count - int(people.size()));
      const std::vector<StandingPerson> members =
          group_round(layout, pavement, middle, size, apart, random);
      placed = std::all_of(members.begin(), members.end(), [&](const StandingPerson& m) {
        const V2 at = m.pose.translation().head<2>();
        return on_pavement(layout, at) && clear_of_walkers(walkers, at, from_walkers) &&
               std::none_of(people.begin(), people.end(), [&](const StandingPerson& o) {
                 return (o.pose.translation().head<2>() - at).norm() < apart + 0.3;
               });
      });
      if (placed) people.insert(people.end(), members.begin(), members.end());
    }
    if (!placed)
      throw std::invalid_argument("map " + layout.style.name + " has no room for " +
                                  std::to_string(count) + " people standing on its pavements");
  }
  return people;
}

}  // namespace flowscape
