#include "flowscape/scenes/actors.h"

#include <array>
#include <limits>

#include "flowscape/scenes/skinning.h"

namespace flowscape {

Box3 actor_box(const Actor& actor, double t) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Part& part : actor.parts)
    for (const Vec3& p : part_vertices_at(part, t)) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if (!(lo.array() <= hi.array()).all()) return {actor.pose(t), Vec3::Zero()};  // no vertices
  Box3 box;
  box.pose = actor.pose(t) * Eigen::Translation3d((lo + hi) / 2);
  box.size = hi - lo;
  return box;
}

Motion actor_motion(const Actor& actor, double t, const Vec3& local) {
  constexpr double h = 5e-4;
  const Pose before = actor.pose(t - h), after = actor.pose(t + h);
  const Eigen::AngleAxisd turn(after.linear() * before.linear().transpose());
  return {(after * local - before * local) / (2 * h), turn.axis() * turn.angle() / (2 * h)};
}

SemanticClass actor_class(const Actor& actor) {
  std::array<std::size_t, 256> counts{};
  for (const Part& part : actor.parts)
    for (SemanticClass c : part.mesh->classes) ++counts[std::size_t(c)];
  std::size_t best = 0;
  for (std::size_t c = 1; c < counts.size(); ++c)
    if (counts[c] > counts[best]) best = c;
  return SemanticClass(best);
}

}  // namespace flowscape
