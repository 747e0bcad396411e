// bench_street_life [SEEDS]: how busy each map's pavements are round the ego, with the maps' own
// street life (city.h's street_life: walking and standing per map) against flowscape 0.19's 80
// walkers on every map in the same run: people on foot within 30 m of the ego at the first frame,
// the pavement there (square metres, sampled every 0.5 m), people per 100 m^2 of it, and how many
// stand. 120 vehicles, detailed actors, the release's driving route.
#include <cstdio>
#include <cstdlib>

#include "flowscape/core/types.h"
#include "flowscape/scenes/city.h"

using namespace flowscape;
using V2 = Eigen::Vector2d;

namespace {

constexpr double kNear = 30, kCell = 0.5;

struct Tally {
  double people = 0, standing = 0, pavement = 0;
  Tally& operator+=(const Tally& o) {
    people += o.people, standing += o.standing, pavement += o.pavement;
    return *this;
  }
};

Tally round_the_ego(int map, std::uint64_t seed, StreetLife life) {
  CityConfig config;
  config.map = map, config.seed = seed, config.vehicles = 120;
  config.pedestrians = life.walking, config.standing = life.standing;
  config.ego_start = int(seed % 100), config.ego_route = EgoRoute::Drive;
  config.duration = 101 / kFrameRate;
  const City city = make_city(config);
  const V2 ego = city.ego(0).translation().head<2>();
  Tally tally;
  for (std::size_t a = 0; a < city.actors.size(); ++a) {
    const bool near = (city.scene.actors[a].pose(0).translation().head<2>() - ego).norm() < kNear;
    if (city.actors[a].kind != ActorKind::Pedestrian || !near) continue;
    tally.people += 1, tally.standing += city.actors[a].standing;
  }
  for (double x = -kNear; x <= kNear; x += kCell)
    for (double y = -kNear; y <= kNear; y += kCell)
      if (x * x + y * y < kNear * kNear && city.area_at(ego + V2(x, y)) == Area::SideWalk)
        tally.pavement += kCell * kCell;
  return tally;
}

void print_row(const char* name, const char* life, const Tally& sum, int seeds) {
  std::printf("%-11s %-10s %7.1f %9.1f %10.0f %9.2f\n", name, life, sum.people / seeds,
              sum.standing / seeds, sum.pavement / seeds, 100 * sum.people / sum.pavement);
}

}  // namespace

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 4;
  if (seeds < 1) {
    std::fprintf(stderr, "bench_street_life: SEEDS must be a whole number >= 1\n");
    return 1;
  }
  std::printf("%d sequences per map, people on foot within %.0f m of the ego at frame 0\n", seeds,
              kNear);
  std::printf("%-11s %-10s %7s %9s %10s %9s\n", "map", "life", "people", "standing", "pavement",
              "/100 m^2");
  for (int map = 0; map < kMapCount; ++map) {
    Tally old_life, own_life;
    for (int s = 0; s < seeds; ++s) {
      const std::uint64_t seed = std::uint64_t(1000 * map + s);
      old_life += round_the_ego(map, seed, {80, 0});
      own_life += round_the_ego(map, seed, street_life(map));
    }
    const std::string name = map_name(map);
    print_row(name.c_str(), "80 walk", old_life, seeds);
    print_row("", "map's own", own_life, seeds);
  }
  return 0;
}
