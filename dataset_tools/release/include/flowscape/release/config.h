#pragma once
// What a release is made of (ReleaseConfig), where its values come from (defaults, --demo, a config
// file, the command line), and which sequences that is (plan_sequences).
#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flowscape/layout/layout.h"
#include "flowscape/renderer/rig.h"

namespace flowscape {

struct ReleaseConfig {
  int maps = 8, sequences_per_map = 8, frames = 100;
  // Chosen maps (0-7) instead of the first `maps`: each map's sequences as the whole release has
  // them (names, seeds), so one map of a release can be rendered on its own.
  std::vector<int> map_list{};
  int height = 512;     // ERP height; width = 2 x height
  int face_size = 256;  // cube faces: 256 matches a 512 x 1024 ERP at the equator
  // Samples per pixel, and how many of them (at most spp) go on from the first surface to gather
  // indirect light; chosen by bench_image_quality: denoised, as clean as 16 raw samples in half
  // the time.
  // indirect_spp 0: chosen by the denoiser (kDenoisedIndirectSpp when denoised, every sample
  // when not: a converged reference, --spp 1024 --denoise none, gathers on every sample).
  int spp = 8, indirect_spp = 0, max_bounces = 4;
  // Edge samples: where a pixel's samples disagree on the light they meet before any surface (a
  // lit window's, a lamp's or the sky's edge), camera rays up to edge_spp in all gather that light
  // alone (RenderOptions::edge_samples); at or below spp: none. 32 brings the night's relative
  // error at 512 x 1024 from 2.5x the day's to 1.5x (docs/renderer.md, "Edge samples").
  int edge_spp = 32;
  // Adaptive sampling (release/adaptive_sampling.h): the share of the pixels (0-1) that take half
  // of spp where the denoised colour is estimated worst, the others only the first half; 0 (the
  // default): every pixel spp. Needs spp >= 4 (fewer: uniform). At equal samples 0.25 gains
  // 0.5-1.5 dB and costs 40 % more colour time (docs/release.md, "Adaptive sampling").
  double adaptive = 0;
  // Temporal reconstruction (renderer/temporal.h): the colour layers of the `temporal` frames
  // before and after each frame reprojected along the exact flow and averaged into its own before
  // the denoiser, where their shading agrees; 0: every frame alone.
  int temporal = 0;
  // The colour's denoiser: "atrous" (renderer/denoise.h), "oidn" (OIDN's U-Net,
  // renderer/neural_denoise.h, of size denoise_model: default or small), or "none": raw.
  std::string denoise = "atrous", denoise_model = "default";
  // Weather presets, cycled over the sequences of a map (FlowScape: 5 sunny, cloud, fog, rain).
  std::vector<std::string> weathers{"sunny", "sunny", "sunny", "sunny",
                                    "sunny", "cloud", "fog",   "rain"};
  // Times of day (weather.h's at_time_of_day: day, dawn, dusk or a sun elevation), cycled over the
  // release's sequences by their number, so they fall across maps and weathers.
  std::vector<std::string> times_of_day{"day", "day", "day", "dawn", "dusk", "night"};
  // Skies (weather.h's under_sky: "physical", or a real HDR sky map whose sun replaces the time of
  // day), cycled over the release's sequences by their number.
  std::vector<std::string> skies{"physical"};
  // People on foot per map, walking and standing (scenes/city.h's CityConfig): -1, the map's own
  // (street_life: downtown busy, rural sparse).
  int vehicles = 120, pedestrians = -1, standing = -1;
  // The share of sequences whose ego turns left or right at a junction within its frames (city.h's
  // EgoRoute::Turn; the others drive on as traffic lets them, EgoRoute::Drive): sequence number n
  // of the release turns when floor((n + 1) x share) > floor(n x share), so 1/3: every third.
  double turn_share = 1.0 / 3;
  // "mix": turn_share of the sequences turn, the others drive (both Turn and Drive keep the lane
  // ahead clear at spawn); "free": every ego starts where its seed says and drives as traffic
  // lets it (EgoRoute::Free: the releases of flowscape 0.8 and before, whose config.json lacks
  // the key and is read so).
  std::string ego_routes = "mix";
  // User models replacing the built-in ones, by actor kind (car, truck, bus, bike, pedestrian):
  // glTF through tinygltf, OBJ/FBX/... through assimp, with their textures.
  std::map<std::string, std::string> models;
  // "detailed": the built-in vehicle families and people, parked vehicles as actors, the ego
  // vehicle as `ego` says; "legacy": flowscape 0.9's box models (a config.json without the key,
  // from 0.9 and before, is read so).
  std::string actors = "detailed";
  // The ego vehicle under the rig: "on" (drawn, in every camera that sees it), "off", or "auto":
  // drawn for every rig but the flowscape preset, whose release reproduces FlowScape's CARLA
  // frames (the car a roof rig stands on would fill the lower hemisphere with still pixels).
  std::string ego = "auto";
  // The semantic class table the files are written in (release/classes.h): "carla-0.9.13" (the
  // default, FlowScape's) or "carla-0.9.14" (with riders, cars, trucks, buses, motorcycles,
  // bicycles and the ego vehicle apart).
  std::string classes = "carla-0.9.13";
  // Opt-in asset packs of Debian's game data ("torcs"): a quarter of the cars show their models;
  // each model's licence is recorded per actor in meta.json and in the card (GPL or share-alike
  // terms travel with the images that show them).
  std::vector<std::string> asset_packs{};
  std::uint64_t seed = 0;
  bool cube = true;  // also write the six faces (the ERP colour is stitched from them)
  // Output kinds written besides the six every release has (layout.h's pickable rows, or "all"),
  // and the frame gaps of every flow kind (1 = the flow to the next frame; must be there). The
  // default is what bench_outputs found cheap next to the colour (docs/release.md): 11 % of a
  // frame's colour time together; normal_shading (23 %) and more gaps are asked for.
  std::vector<std::string> outputs{"flow_backward", "valid_backward", "scene_flow", "normal"};
  // The final pass (output kind "final", release/final_pass.h): the shutter's angle (degrees of a
  // frame, 1-360), shot and read noise on or off, the sensor's pixel pitch (micrometres: smaller
  // pixels, more noise), the share of light the lens scatters into glare, vignetting on real
  // lenses.
  double shutter_angle = 180;
  bool sensor_noise = true;
  double pixel_pitch = 3;
  double lens_glare = 0.02;
  bool vignetting = true;
  // More of the final pass's camera: lateral chromatic aberration on real lenses (share of the
  // radius, |k| <= 0.05), a Bayer mosaic demosaicked, JPEG compression at a quality (0: none).
  double chromatic_aberration = 0;
  bool bayer = false;
  int jpeg_quality = 0;
  // What lies on real lenses in the final pass (renderer/lens_cover.h): water drops (-1: in rain
  // only, round(24 x precipitation), at least 1; else this many, 0..200) and dirt (the densest
  // blotch's share of the light, 0..1; 0: clean).
  int lens_drops = -1;
  double lens_dirt = 0;
  std::vector<int> flow_gaps{1};
  // How the flow kinds are stored (formats/flow_io.h, FlowFormat): "flo" (Middlebury float32, the
  // PanoFlow tree's), "kitti-png" (16-bit, 1/64 px within +-512 px), "half-exr" (half floats).
  std::string flow_format = "flo";
  // The cameras: "flowscape" (the ERP and, with `cube`, the six faces at the rig's origin), a
  // preset of renderer/rig.h (fisheye, woodscape, pal, dual-fisheye: images scaled to `height`),
  // a rig file (.json, docs/cameras.md), or a calibration file (.yaml, .yml, .xml: OpenCV's or
  // Kalibr's, renderer/calibration_file.h) mounted by `rig_mount`.
  std::string rig = "flowscape";
  // A calibration's first camera on the rig: x, y, z (metres), yaw, pitch, roll (degrees); empty
  // for every other rig.
  std::vector<double> rig_mount;
  // A rig file's or calibration's image sizes and intrinsics scaled by this (previews; 1: as
  // given). Presets and the flowscape rig are sized by `height`.
  double scale = 1;
  // Scenario files (release/scenario.h), one sequence each, instead of the maps' sequences
  // (maps, map_list and sequences_per_map then unused).
  std::vector<std::string> scenarios;
  int shard = 0, shards = 1;  // this process makes the sequences k with k % shards == shard
};
void validate(const ReleaseConfig& config);  // throws std::invalid_argument naming the value
// Throws std::invalid_argument when a fetched sky map of the config is too small for its images
// (the ERP's and the cube faces' pixels per radian; weather.h's check_sky_resolution).
void check_sky_resolution(const ReleaseConfig& config);

// The sections of a release the frame pipeline's stages take instead of the whole config (their
// members as ReleaseConfig describes them).
// How a view's colour is path traced and denoised.
struct ColorSection {
  int spp, indirect_spp, edge_spp, max_bounces;
  double adaptive;
  int temporal;
  std::string denoise, denoise_model;
};
ColorSection color_section(const ReleaseConfig& config);
// The final pass's shutter, sensor and lens (final_pass.h).
struct FinalPassSection {
  double shutter_angle;
  bool sensor_noise;
  double pixel_pitch, lens_glare;
  bool vignetting;
  double chromatic_aberration;
  bool bayer;
  int jpeg_quality, lens_drops;
  double lens_dirt;
};
FinalPassSection final_pass_section(const ReleaseConfig& config);

inline constexpr int kDenoisedIndirectSpp = 4;
// How many of a pixel's samples gather indirect light (see ReleaseConfig::indirect_spp).
int indirect_samples(const ColorSection& color);
// The kinds and views a release made with `config` holds (its outputs, flow gaps, rig, faces).
ReleaseLayout release_layout(const ReleaseConfig& config);
// The release's rig (renderer/rig.h): for flowscape the ERP and, with `cube`, the six faces; a rig
// file's errors are FileErrors naming it.
Rig release_rig(const ReleaseConfig& config);
// The view a camera of the rig is written as: the flowscape rig's ERP and faces, or cameras/<name>.
View view_of(const Rig& rig, const RigCamera& camera);
nlohmann::json to_json(const ReleaseConfig& config);
// "spp: 8 recorded, 4 now; seed: ..." for the keys whose values differ between two configs as JSON,
// each value followed by the name of the config it comes from.
std::string config_differences(const nlohmann::json& first, const std::string& first_name,
                               const nlohmann::json& second, const std::string& second_name);
// `base` with the values the JSON gives; unknown keys are an error (a typo would go unnoticed).
ReleaseConfig release_config_from_json(const nlohmann::json& json, ReleaseConfig base = {});

// --demo: a small release of the built-in city (1 map, 2 sequences of 4 frames, 128 x 256, 8 spp,
// sunny and rain) in demo/.
nlohmann::json demo_config();
inline constexpr const char* kDemoOut = "demo";

// Where a config comes from, weakest first: the defaults (the paper's FlowScape), the demo's,
// a config file, the options given on the command line (as config keys, e.g. {"spp": 4}).
struct ConfigSources {
  bool demo = false;
  std::filesystem::path file;  // empty: none
  nlohmann::json command_line = nlohmann::json::object();
  // Scenario files: their release-wide keys (scenario.h's release_keys) between the file and the
  // command line, and the release's sequences.
  std::vector<std::filesystem::path> scenarios = {};
};
// Errors name the config file where it is the file's value that is wrong.
ReleaseConfig resolve_config(const ConfigSources& sources);

// "512" or "512x1024" -> the ERP height 512; throws std::invalid_argument for other text or a width
// that is not twice the height.
int parse_resolution(const std::string& text);
// "K/N" -> config.shard = K, config.shards = N; throws std::invalid_argument for other text.
void parse_shard(const std::string& text, ReleaseConfig& config);
// "KIND=FILE" options (--model) -> a models map; throws std::invalid_argument for other text.
std::map<std::string, std::string> parse_models(const std::vector<std::string>& options);

struct SequencePlan {
  std::string name;        // map<MM>_seq<SS>
  int map, index, number;  // number: position in the whole release
  std::string weather, time_of_day, sky;
  std::uint64_t seed;
  bool turns;  // its ego turns at a junction (ReleaseConfig::turn_share of ego_routes "mix")
  std::filesystem::path scenario_file = {};  // the scenario it renders; empty: a map's sequence
};
// The maps a release renders: map_list, else 0 .. maps - 1.
std::vector<int> release_maps(const ReleaseConfig& c);
std::vector<SequencePlan> plan_sequences(const ReleaseConfig& config);  // every shard's
std::vector<std::string> sequence_names(const ReleaseConfig& config);   // theirs, in that order
bool in_shard(const SequencePlan& plan, const ReleaseConfig& config);
std::vector<SequencePlan> shard_plans(const ReleaseConfig& config);  // this shard's

}  // namespace flowscape
