#pragma once
// Internal: people standing or waiting on the pavements near the ego, alone or in groups, each
// where no walker passes during the sequence (placed after the traffic is simulated) and clear of
// the kerb's poles and the facades.
#include <vector>

#include "city_layout.h"
#include "traffic.h"

namespace flowscape {

struct StandingPerson {
  Pose pose;  // on the pavement, facing where the person looks (a group: its middle)
  bool child = false;
};

// `count` people round the ego's way (its track), in groups of one to four, drawn from their own
// stream of `seed`; `wet`: far enough apart for open umbrellas. Throws std::invalid_argument when
// the map has no room for them.
std::vector<StandingPerson> place_standing(const Layout& layout, const TrafficTracks& tracks,
                                           int count, std::uint64_t seed, bool wet);

}  // namespace flowscape
