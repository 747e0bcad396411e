#pragma once
// Internal: where pedestrians walk: loops along the sidewalks round the blocks, some crossing the
// road between two blocks on the crosswalks.
#include <vector>

#include "city_layout.h"
#include "path.h"

namespace flowscape {

// Where a walking loop crosses a road: on a crosswalk between s_in and s_out.
struct LoopCrossing {
  double s_in, s_out;
  int crosswalk;  // index into Layout::crosswalks
};

struct SidewalkLoop {
  Path path;  // closed
  std::vector<LoopCrossing> crossings;
  // The ground lift of a walker at s: the kerb's height on the sidewalk, stepping down to the road
  // over the last 0.5 m before a crossing (and up after it).
  double lift(double s) const;
};

// Two loops per block, one each way along its sidewalks; blocks above one another pair up their
// counter-clockwise loops into one round both, crossing the road between them at the crosswalks
// on either end.
std::vector<SidewalkLoop> sidewalk_loops(const Layout& layout);

}  // namespace flowscape
