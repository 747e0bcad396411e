#pragma once
// A release small enough to render in a test: one map, tiny images, a few actors.
#include "flowscape/release/config.h"

inline flowscape::ReleaseConfig tiny_release_config(int sequences = 1, int frames = 3) {
  flowscape::ReleaseConfig config;
  config.maps = 1, config.sequences_per_map = sequences, config.frames = frames;
  config.height = 16, config.face_size = 8, config.spp = 1;
  config.vehicles = 4, config.pedestrians = 2, config.seed = 11;
  config.weathers = {"sunny", "rain"};
  return config;
}
