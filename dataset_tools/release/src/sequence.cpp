#include "flowscape/release/sequence.h"

#include <algorithm>

#include "flowscape/core/random.h"
#include "flowscape/renderer/denoise.h"

namespace flowscape {

SequenceSpec sequence_spec(const ReleaseConfig& config, const SequencePlan& plan) {
  return {plan.map,           plan.weather,         plan.seed,     config.vehicles,
          config.pedestrians, int(plan.seed % 100), config.frames, config.models};
}

FramePair Sequence::frame_pair(int frame) const {
  const double t = time(frame), next = t + 1 / kFrameRate;
  return {t, next, city.rig(t), city.rig(next)};
}

std::uint64_t Sequence::color_seed(int frame) const { return derived_seed(spec.seed, frame, 1); }

RenderOptions Sequence::color_options(const ReleaseConfig& config, int frame) const {
  RenderOptions options{config.spp, config.max_bounces, color_seed(frame)};
  options.indirect_samples = std::min(config.indirect_spp, config.spp);
  return options;
}

Image<float> release_color(const ReleaseConfig& config, const Sequence& sequence,
                           Renderer& renderer, const Projection& camera, int frame,
                           const GroundTruth& truth) {
  return release_color(config, sequence, renderer, camera, sequence.frame_pair(frame), frame,
                       truth);
}

Image<float> release_color(const ReleaseConfig& config, const Sequence& sequence,
                           Renderer& renderer, const Projection& camera, const FramePair& pair,
                           int frame, const GroundTruth& truth) {
  const ColorLayers layers =
      renderer.color_layers(camera, pair, sequence.color_options(config, frame));
  if (config.denoise == "none") return raw_color(layers);
  return denoise(layers, {&camera, truth.depth.view(), truth.instance.view()});
}

Sequence make_sequence(const SequenceSpec& spec) {
  CityConfig city_config;
  city_config.map = spec.map, city_config.seed = spec.seed;
  city_config.vehicles = spec.vehicles, city_config.pedestrians = spec.pedestrians;
  city_config.ego_start = spec.ego_start;
  city_config.duration = (spec.frames + 1) / kFrameRate;
  city_config.models = spec.models;
  Sequence s{spec, make_city(city_config), randomized(weather_preset(spec.weather), spec.seed)};
  apply_weather(s.weather, spec.seed, s.city.rig_track(), s.city.scene);
  return s;
}

SequenceMeta sequence_meta(const Sequence& s, const SequencePlan& plan,
                           const ReleaseConfig& config) {
  SequenceMeta meta;
  meta.scene = plan.name, meta.map = plan.map, meta.sequence = plan.index;
  meta.map_name = map_name(plan.map), meta.seed = plan.seed;
  meta.weather = to_json(s.weather);
  meta.frames = config.frames, meta.fps = kFrameRate;
  meta.erp_height = config.height;
  meta.camera_height = s.city.mount.height;
  meta.camera_pitch_sway = s.city.mount.pitch_amplitude * 180 / kPi;
  meta.camera_roll_sway = s.city.mount.roll_amplitude * 180 / kPi;
  for (int f = 0; f < config.frames; ++f) meta.poses.push_back(s.city.rig(Sequence::time(f)));
  meta.city = to_json(s.city);
  meta.face_size = config.cube ? config.face_size : 0;
  return meta;
}

}  // namespace flowscape
