#pragma once
// One sequence as a release renders it: a city map with its traffic, the weather preset varied by
// the sequence's seed, and the frame pairs at the release's frame rate. Built here once, for the
// release writer and city_preview alike.
#include <cstdint>
#include <string>

#include "flowscape/layout/meta.h"
#include "flowscape/release/config.h"
#include "flowscape/renderer/denoiser.h"
#include "flowscape/renderer/renderer.h"
#include "flowscape/scenes/city.h"
#include "flowscape/weather/weather.h"

namespace flowscape {

struct SequenceSpec {
  // The map or world, its traffic, actors and ego (scenes/city.h); city.seed is the sequence's
  // seed: the city, traffic, weather variant and colour noise. Its duration follows from the
  // frames, its wetness from the weather (make_sequence).
  CityConfig city{.vehicles = 120, .pedestrians = 80, .ego_route = EgoRoute::Drive};
  std::string weather = "sunny";                                 // a preset name
  std::string time_of_day = "day";                               // weather.h's at_time_of_day
  std::string sky = "physical";                                  // weather.h's under_sky
  nlohmann::json weather_parameters = nlohmann::json::object();  // set over it (scenario.h)
  int frames = 100;
  double frame_rate = kFrameRate;  // frames per second
  PoseTrack rig_path{};  // the rig's own path (a scenario's waypoints or pose file), or empty
};
// The spec of a planned sequence of a release: its scenario's (scenario.h's scenario_of: its ego
// start follows from its seed, its route from the plan's `turns` or the scenario file).
SequenceSpec sequence_spec(const ReleaseConfig& config, const SequencePlan& plan);
// Reads every user file this shard's sequences load when they are made (scenario worlds, actor
// models, scripted actors' models) into a scratch scene, each once, so that a bad one is named
// (a FileError) before a release writes anything.
void check_user_files(const ReleaseConfig& config);
// The spec of a scenario (scenario.h) in a release made with `config` (its rig, frames, models,
// actors); `source` names the scenario's file in errors.
struct Scenario;
SequenceSpec sequence_spec(const ReleaseConfig& config, const Scenario& scenario,
                           const std::filesystem::path& source = {});
// The release's actors and ego vehicle in a spec: the actor style, whether the ego is drawn
// (ReleaseConfig::ego) and the cameras it must keep clear of (the release's rig).
void set_actors(SequenceSpec& spec, const ReleaseConfig& config);

struct Sequence {
  SequenceSpec spec;
  City city;
  Weather weather;  // randomized(preset, seed): what the sequence's meta.json records

  double time(int frame) const { return frame / spec.frame_rate; }
  FramePair frame_pair(int frame) const;      // frame -> frame + 1
  Moment moment(int frame) const;             // the frame's time and rig
  std::uint64_t color_seed(int frame) const;  // the path tracer's seed for this frame
  // The path tracer's settings for this frame: config.spp samples, indirect_spp of them (at most
  // all) gathering indirect light, color_seed(frame).
  RenderOptions color_options(const ColorSection& color_settings, int frame) const;
};
// The city is built and the weather applied (sky, fog, wet materials, rain streaks, puddles).
// A Renderer keeps a reference to sequence.city.scene: do not move the Sequence while one lives.
Sequence make_sequence(const SequenceSpec& spec);

// The denoiser the release's denoise and denoise_model name (renderer/denoiser.h).
std::unique_ptr<const Denoiser> release_denoiser(const ColorSection& color_settings);
// A view's colour layers as the release's denoiser leaves them (the guides for a-trous).
Image<float> denoised_color(const ColorSection& color_settings, const ColorLayers& layers,
                            const Projection& camera, ImageView<const float> depth,
                            ImageView<const std::uint16_t> instance);
// The colour of a cube frame's faces (stacked layers, and the faces' ground truth for a-trous) as
// the release's denoiser leaves them.
Image<float> denoised_cube_color(const ColorSection& color_settings, const ColorLayers& color,
                                 const GroundTruth& truth);
// The cube faces' colour layers of a frame as a release renders them (before denoised_cube_color):
// path traced with color_options (and config.adaptive's adaptive sampling, which denoises with the
// faces' ground truth `truth`).
ColorLayers release_cube_layers(const ColorSection& color_settings, int face_size,
                                const Sequence& sequence, Renderer& renderer,
                                const GroundTruth& truth, int frame);
// The colour of one camera's view of a frame as a release renders it without cube faces: path
// traced with color_options (and config.adaptive's adaptive sampling) and denoised with the view's
// ground truth (unless config.denoise is "none").
Image<float> release_color(const ColorSection& color_settings, const Sequence& sequence,
                           Renderer& renderer, const Projection& camera, int frame,
                           const GroundTruth& truth);
// The same as `view` sees it (a rig camera's request: its viewpoint, its rolling shutter).
Image<float> release_color(const ColorSection& color_settings, const Sequence& sequence,
                           Renderer& renderer, const Projection& camera, const TruthRequest& view,
                           int frame, const GroundTruth& truth);
// A view's colour layers path traced as `view` says (its pair, or its rolling shutter's lines).
ColorLayers traced_layers(Renderer& renderer, const Projection& camera, const TruthRequest& view,
                          const RenderOptions& options);
// Its colour layers, before denoised_color.
ColorLayers release_layers(const ColorSection& color_settings, const Sequence& sequence,
                           Renderer& renderer, const Projection& camera, const TruthRequest& view,
                           int frame, const GroundTruth& truth);

// meta.json of a planned sequence of a release: all but the 2-D boxes, which come from its
// instance images (meta.h's instance_boxes).
SequenceMeta sequence_meta(const Sequence& sequence, const SequencePlan& plan,
                           const ReleaseConfig& config);
// Every actor (traffic, riders, parked vehicles, the ego) per frame: instance, kind, class (in the
// class table `classes`), 3-D box in the world and the rig, velocities; detailed actors also
// their fixed box (the extent of their deforming parts over the frames, in the actor's frame)
// and flags for parked and ego (docs/release.md, "meta.json").
nlohmann::json actor_records(const Sequence& sequence, int frames,
                             const std::string& classes = "carla-0.9.13");
// What a frame's ground truth needs for the layout's kinds: the pair to the next frame, a target in
// `more` for every other flow step the frame has (layout.h's flow_steps), the vector kinds.
struct TruthPlan {
  TruthRequest request;
  std::vector<int> steps;  // of request.more: its k-th target is frame + steps[k]
};
TruthPlan truth_plan(const Sequence& sequence, const ReleaseLayout& layout, int frame, int frames);

}  // namespace flowscape
