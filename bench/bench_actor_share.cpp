// bench_actor_share RELEASE: how much of what the camera sees moves on its own. Per map of a
// release, the share of non-sky ERP pixels that show an actor (instance > 0: vehicles, cyclists,
// pedestrians), averaged over every frame of the map's sequences. Target (issue 18): at least 5 %.
#include <cmath>
#include <cstdio>
#include <map>

#include "flowscape/formats/image_io.h"
#include "flowscape/layout/layout.h"
#include "flowscape/layout/meta.h"
#include "flowscape/layout/split.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

// instance > 0 over non-sky (finite depth) pixels of one ERP frame
double actor_share(const fs::path& sequence, int frame) {
  const auto file = [&](const char* kind) { return erp_file(sequence, kind, frame); };
  const Image<std::uint16_t> instance = read_image<std::uint16_t>(file("instance"));
  const Image<float> depth = read_image<float>(file("depth"));
  std::size_t actors = 0, ground = 0;
  for (std::size_t i = 0; i < instance.data.size(); ++i) {
    if (std::isinf(depth.data[i])) continue;
    ++ground;
    actors += instance.data[i] > 0;
  }
  return ground ? double(actors) / double(ground) : 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: bench_actor_share RELEASE\n");
    return 2;
  }
  try {
    std::map<std::string, std::pair<double, int>> per_map;  // sum of shares, frames
    for (const SequenceInfo& s : read_release_sequences(argv[1])) {
      const fs::path dir = sequence_dir(argv[1], s.name);
      const std::string map = read_meta(dir).map_name;
      for (int f = 0; f < s.frames; ++f) {
        per_map[map].first += actor_share(dir, f);
        ++per_map[map].second;
      }
    }
    std::printf("%-12s %7s %18s\n", "map", "frames", "actor pixels");
    for (const auto& [map, sum] : per_map)
      std::printf("%-12s %7d %17.2f%%\n", map.c_str(), sum.second, 100 * sum.first / sum.second);
    std::printf("(target: at least 5 %% of non-sky pixels on every map)\n");
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_actor_share: error: %s\n", e.what());
    return 1;
  }
}
