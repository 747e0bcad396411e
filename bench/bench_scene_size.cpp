// bench_scene_size [frame = 0]: per map, how big a release's scene is with the detailed actors and
// with the legacy ones (the same config and seed as a release's first sequence of the map):
// triangles of the static world, triangles the actors show (every part counted), triangles of the
// distinct meshes behind them (what the BVHs hold: shared meshes once), skinned triangles (refitted
// per posed time), and the memory the renderer's scene takes (resident set growth while the city
// is built and its BVHs made, measured in a child process of its own).
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>

#include "flowscape/release/config.h"
#include "flowscape/release/sequence.h"

using namespace flowscape;

namespace {

double resident_mib() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return double(resident) * 4096 / (1 << 20);
}

struct Size {
  std::size_t world = 0, shown = 0, distinct = 0, skinned = 0;
  int actors = 0;
  double mib = 0, seconds = 0;  // the memory and the time building the scene and its BVHs take
};

Size measure_here(const SequenceSpec& spec) {
  const double before = resident_mib();
  const auto start = std::chrono::steady_clock::now();
  const Sequence sequence = make_sequence(spec);
  const Renderer renderer(sequence.city.scene);
  Size s;
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  s.mib = resident_mib() - before;
  s.world = sequence.city.scene.world.triangles.size();
  std::set<const Mesh*> meshes;
  for (const Actor& actor : sequence.city.scene.actors) {
    if (actor.color_only) continue;
    ++s.actors;
    for (const Part& part : actor.parts) {
      s.shown += part.mesh->triangles.size();
      if (part.bones) s.skinned += part.mesh->triangles.size();
      if (meshes.insert(part.mesh.get()).second) s.distinct += part.mesh->triangles.size();
    }
  }
  return s;
}

// In a child process, so each scene's memory is counted from the same start.
Size measure(const SequenceSpec& spec) {
  int channel[2];
  if (pipe(channel) != 0) std::abort();
  const pid_t child = fork();
  if (child == 0) {
    const Size s = measure_here(spec);
    if (write(channel[1], &s, sizeof s) != sizeof s) _exit(1);
    _exit(0);
  }
  Size s;
  if (read(channel[0], &s, sizeof s) != sizeof s) std::abort();
  waitpid(child, nullptr, 0);
  close(channel[0]), close(channel[1]);
  return s;
}

}  // namespace

int main() {
  ReleaseConfig config;
  config.maps = kMapCount, config.sequences_per_map = 1, config.frames = 3;
  std::printf("bench_scene_size: the first sequence of each map, %d vehicles, %d pedestrians\n",
              config.vehicles, config.pedestrians);
  std::printf("%-11s %-8s %7s %6s %10s %10s %9s %6s %8s\n", "map", "actors", "world", "count",
              "shown", "distinct", "skinned", "MiB", "build s");
  for (const SequencePlan& plan : plan_sequences(config))
    for (const char* style : {"legacy", "detailed"}) {
      ReleaseConfig c = config;
      c.actors = style;
      const Size s = measure(sequence_spec(c, plan));
      std::printf("%-11s %-8s %7zu %6d %10zu %10zu %9zu %6.0f %8.2f\n", map_name(plan.map).c_str(),
                  style, s.world, s.actors, s.shown, s.distinct, s.skinned, s.mib, s.seconds);
      std::fflush(stdout);
    }
  return 0;
}
