// gen_flowscape: renders a FlowScape release (design.md's layout): per map its sequences in their
// weathers, every modality in ERP and on the six cube faces, meta.json per sequence, manifest.json
// with sha256 of every file and a dataset card. Killed at any moment, the same command resumes and
// finishes with the same bytes.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <CLI/CLI.hpp>
#include <charconv>
#include <cstdio>
#include <optional>
#include <sstream>

#include "cli.h"
#include "flowscape/core/files.h"
#include "flowscape/release/manifest.h"
#include "flowscape/release/meta.h"
#include "flowscape/release/scenario.h"
#include "flowscape/release/sequence.h"
#include "flowscape/release/statistics.h"
#include "flowscape/release/writer.h"
#include "flowscape/renderer/calibration_file.h"
#include "tracing_cli.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> comma_list(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');) items.push_back(item);
  return items;
}

// The whole number `text` is, all of it; nullopt for anything else (empty text too).
std::optional<int> whole_number(const std::string& text) {
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
  return value;
}

// "1.5,0,-0.3,0,-10,0" -> the six numbers of --rig-mount; other text is a usage error.
std::vector<double> parse_mount(const std::string& text) {
  std::vector<double> numbers;
  for (const std::string& item : comma_list(text)) {
    double value = 0;
    const auto [end, error] = std::from_chars(item.data(), item.data() + item.size(), value);
    if (error != std::errc() || end != item.data() + item.size() || item.empty()) break;
    numbers.push_back(value);
  }
  if (numbers.size() != 6 || comma_list(text).size() != 6)
    throw CLI::ValidationError("--rig-mount wants x,y,z,yaw,pitch,roll: six numbers (got \"" +
                               text + "\")");
  return numbers;
}

// "1,2,4" -> {1, 2, 4}; other text is an option error.
std::vector<int> parse_gaps(const std::string& text) {
  std::vector<int> gaps;
  for (const std::string& item : comma_list(text)) {
    const std::optional<int> gap = whole_number(item);
    if (!gap)
      throw std::invalid_argument(
          "--flow-gaps wants whole numbers separated by commas, e.g. 1,2,4 "
          "(got \"" +
          text + "\")");
    gaps.push_back(*gap);
  }
  return gaps;
}

// A whole number >= 0 of an option, else a usage error naming it.
int parse_count(const std::string& text, const char* option) {
  const std::optional<int> value = whole_number(text);
  if (!value || *value < 0)
    throw CLI::ValidationError(std::string(option) + ": \"" + text +
                               "\" is not a whole number >= 0");
  return *value;
}

// Options a rig other than the flowscape one cannot use: a usage error, not silently ignored.
void refuse_rig_options(const nlohmann::json& given, const std::string& rig) {
  if (rig == kFlowscapeRig) return;
  if (given.contains("face_size") || given.contains("cube"))
    throw std::invalid_argument(
        std::string(given.contains("face_size") ? "--face-size" : "--no-cube") +
        ": only the flowscape rig has cube faces (the rig is \"" + rig + "\")");
  const bool file = rig.ends_with(".json") || is_calibration_file(rig);
  if (file && given.contains("resolution"))
    throw std::invalid_argument("--resolution: " + rig +
                                " sets its cameras' image sizes (--scale scales them)");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Render a FlowScape release: ERP and cube-face colour, 360-degree flow, semantics, "
      "instances, depth and validity for every frame of every sequence, with a manifest. "
      "Rerun the same command to resume an interrupted run."};
  const ReleaseConfig defaults;  // the paper's FlowScape
  ConfigSources sources;
  nlohmann::json& given = sources.command_line;
  std::string out = "dataset", config_file, shard, weathers, times, skies;
  int threads = 0;
  const auto option = [&](const char* flags, const char* key, auto default_value,
                          const char* help) {
    return app
        .add_option_function<decltype(default_value)>(
            flags, [&given, key](const auto& value) { given[key] = value; }, help)
        ->default_str((std::ostringstream() << default_value).str());
  };
  auto* out_option = app.add_option("-o,--out", out, "release folder");
  app.add_option("--config", config_file,
                 "JSON with any of the options below; options given here win over the file, and "
                 "the file over --demo");
  app.add_option_function<std::string>(
         "--maps",
         [&given](const std::string& text) {
           if (text.find(',') == std::string::npos) {
             given["maps"] = parse_count(text, "--maps");
             return;
           }
           std::vector<int> maps;
           for (const std::string& map : comma_list(text))
             if (!map.empty()) maps.push_back(parse_count(map, "--maps"));
           given["map_list"] = maps;
         },
         "city maps: a count N (maps 0..N-1, 1-8), or the chosen map numbers (0-7) separated by "
         "commas (3,7; one map: 5,)")
      ->default_str(std::to_string(defaults.maps));
  option("--sequences-per-map", "sequences_per_map", defaults.sequences_per_map,
         "sequences per map");
  option("--frames", "frames", defaults.frames, "frames per sequence (30 Hz)");
  app.add_option_function<std::string>(
         "--resolution",
         [&given](const std::string& text) {
           try {
             given["resolution"] = parse_resolution(text);
           } catch (const std::invalid_argument& e) {
             throw CLI::ValidationError(e.what());
           }
         },
         "ERP size: the height (512) or height x width (512x1024; the width is twice the height)")
      ->default_str(std::to_string(defaults.height));
  option("--face-size", "face_size", defaults.face_size, "cube face size in pixels");
  option("--spp", "spp", defaults.spp, "path-traced samples per pixel");
  option("--indirect-spp", "indirect_spp", defaults.indirect_spp,
         "of those, how many gather indirect light (more than --spp: all; 0: 4 when denoised, "
         "all when not)");
  option("--adaptive", "adaptive", defaults.adaptive,
         "share of the pixels (0-1) that take half of --spp where the denoised colour is "
         "estimated worst, the others the first half only; 0: every pixel --spp");
  option("--denoise", "denoise", defaults.denoise,
         "atrous: the colour denoised with its feature layers; oidn: by OIDN's trained U-Net "
         "(weights from scripts/install_deps.sh); none: the raw path tracer");
  option("--denoise-model", "denoise_model", defaults.denoise_model,
         "the U-Net of --denoise oidn: default or small (half the work)");
  app.add_option("--weather", weathers,
                 "comma-separated weather presets cycled over each map's sequences (default "
                 "sunny x5,cloud,fog,rain)");
  app.add_option(
      "--time-of-day", times,
      "comma-separated times of day cycled over the release's sequences: day, dawn, "
      "dusk, night or a sun elevation in degrees (-90..90; default day x3,dawn,dusk,night)");
  app.add_option("--sky", skies,
                 "comma-separated skies cycled over the release's sequences: physical (default), "
                 "or a real HDR sky map (sky, park, sunrise, dawn, venice; its sun sets the time "
                 "of day; scripts/fetch_sky_maps.sh fetches them, the physical sky stands in for "
                 "a map not fetched)");
  option("--vehicles", "vehicles", defaults.vehicles, "vehicles per map");
  option("--pedestrians", "pedestrians", defaults.pedestrians, "pedestrians per map");
  option("--turn-share", "turn_share", defaults.turn_share,
         "share of sequences whose ego turns at a junction within its frames (0-1; the others "
         "drive on, their lane ahead kept clear at spawn)");
  option("--ego-routes", "ego_routes", defaults.ego_routes,
         "mix: --turn-share of the sequences turn, the others drive; free: every ego drives as "
         "traffic lets it from where its seed starts it (releases of flowscape 0.8 and before)");
  option("--seed", "seed", defaults.seed, "release seed")
      ->check(CLI::Validator(
          [](const std::string& text) {
            return text.find('-') == std::string::npos ? "" : "must be a whole number >= 0";
          },
          "UINT64"));
  std::string outputs, gaps;
  app.add_option("--outputs", outputs,
                 "comma-separated output kinds besides the six every release has (color flow "
                 "semantic instance depth valid): flow_backward (brings valid_backward), "
                 "valid_backward, scene_flow, normal, normal_shading, final (the final pass: "
                 "motion blur, exposure, noise, lens; a second path trace); all; none")
      ->default_str("flow_backward,valid_backward,scene_flow,normal");
  app.add_option("--flow-gaps", gaps,
                 "comma-separated frame gaps of every flow kind (1 is the next frame; flow_gap<k> "
                 "and, with backward flow, flow_backward_gap<k> for the others)")
      ->default_str("1");
  option("--flow-format", "flow_format", defaults.flow_format,
         "how every flow kind is stored: flo (Middlebury float32; the PanoFlow tree's), kitti-png "
         "(16-bit PNG, 1/64 px steps within +-512 px) or half-exr (half floats: 1/4 px steps from "
         "256 px); flow beyond the range is marked unknown, never wrapped");
  option("--shutter-angle", "shutter_angle", defaults.shutter_angle,
         "the final pass (--outputs final): degrees of a frame the shutter is open, centred on "
         "the frame's time (1-360; the motion blur's length is the flow times angle / 360)");
  option("--pixel-pitch", "pixel_pitch", defaults.pixel_pitch,
         "the final pass's sensor pixel pitch in micrometres (smaller: more noise)");
  option("--lens-glare", "lens_glare", defaults.lens_glare,
         "the final pass: share of light the lens scatters round bright lights (0-0.5)");
  option("--chromatic-aberration", "chromatic_aberration", defaults.chromatic_aberration,
         "the final pass: lateral chromatic aberration of real lenses, red magnified and blue "
         "shrunk by this share of the radius (|k| <= 0.05)");
  option("--lens-drops", "lens_drops", defaults.lens_drops,
         "the final pass: water drops on real lenses (-1: in rain only, more in heavier rain; "
         "0-200: this many; output kind lens_mask marks what they hide)");
  option("--lens-dirt", "lens_dirt", defaults.lens_dirt,
         "the final pass: dirt on real lenses, the densest blotch's share of the light (0-1)");
  option("--jpeg-quality", "jpeg_quality", defaults.jpeg_quality,
         "the final pass through JPEG compression at this quality (1-100; 0: none)");
  bool no_noise = false, no_vignetting = false, bayer = false;
  app.add_flag("--bayer", bayer,
               "the final pass's sensor behind an RGGB Bayer filter, demosaicked");
  app.add_flag("--no-sensor-noise", no_noise, "the final pass without shot and read noise");
  app.add_flag(
      "--no-vignetting", no_vignetting,
      "the final pass without a real lens's vignetting (the ERP and cube faces have none)");
  option("--rig", "rig", defaults.rig,
         "the cameras: flowscape (the ERP and six cube faces), fisheye, woodscape, pal, "
         "dual-fisheye, or a rig file (.json, docs/cameras.md)");
  auto* rig_from = app.add_option_function<std::string>(
      "--rig-from", [&given](const std::string& file) { given["rig"] = file; },
      "a calibration as the rig: OpenCV's (cv::FileStorage .yaml/.xml) or Kalibr's camchain "
      "(.yaml); its first camera placed by --rig-mount (docs/cameras.md)");
  rig_from->excludes(app.get_option("--rig"));
  app.add_option_function<std::string>(
      "--rig-mount", [&given](const std::string& text) { given["rig_mount"] = parse_mount(text); },
      "X,Y,Z,YAW,PITCH,ROLL: the calibration's first camera on the rig (metres: x forward, y "
      "left, z up; degrees as a rig file's yaw_pitch_roll_degrees)");
  option("--scale", "scale", defaults.scale,
         "scale a rig file's or calibration's image sizes and intrinsics (0.25: a quick preview; "
         "K as docs/cameras.md says)");
  std::vector<std::string> scenarios;
  app.add_option("--scenario", scenarios,
                 "scenario files (.json, docs/scenarios.md), one sequence each, instead of the "
                 "maps' sequences; options given here override their rig, ego and frames");
  option("--actors", "actors", defaults.actors,
         "detailed: the built-in vehicle families and people, parked vehicles as actors, the ego "
         "vehicle drawn; legacy: flowscape 0.9's box models (reproduces its releases)");
  option("--classes", "classes", defaults.classes,
         "the semantic class table: carla-0.9.13 (FlowScape's 23 ids) or carla-0.9.14 (rider, car, "
         "truck, bus, motorcycle, bicycle apart, and the ego vehicle as 29)");
  std::vector<std::string> packs;
  app.add_option("--asset-pack", packs,
                 "opt in to an asset pack of Debian's game data: torcs (torcs-data's cars; GPL-2+ "
                 "and Free Art License models, recorded per actor and in the card); repeatable");
  std::vector<std::string> models;
  app.add_option("--model", models,
                 "KIND=FILE: a user model for an actor kind (car, truck, bus, bike, pedestrian), "
                 "glTF or anything assimp reads, textures included; repeat for several kinds "
                 "(replaces the config file's \"models\")");
  bool no_cube = false, check = false, force = false;
  option("--ego", "ego", defaults.ego,
         "the ego vehicle under the rig (detailed actors): on, off, or auto: drawn for every rig "
         "but flowscape (FlowScape's CARLA frames show no ego)");
  app.add_flag("--no-cube", no_cube, "ERP only: no cube faces (ERP colour rendered directly)");
  app.add_option("--shard", shard, "K/N: make only the sequences k with k % N == K");
  app.add_option("--threads", threads, "threads (0: all cores)")->check(CLI::Range(0, 1024));
  app.add_flag("--demo", sources.demo,
               "a small release in demo/ (1 map, 2 sequences of 4 frames, 128 x 256, 8 spp, sunny "
               "and rain) unless options say otherwise");
  app.add_flag("--force", force,
               "the folder holds a release made with another config: delete its files "
               "(sequences/, manifests, card, config.json, manifest.json) and start over");
  app.add_flag("--check", check,
               "only check the options and print the plan, and report what the --out folder holds "
               "that the release should not (temporary files, foreign files, files missing or "
               "changed since manifest.json); write nothing");
  finish_options(app, "gen_flowscape");
  version_with_kernels(app, "gen_flowscape");
  if (const auto status = parse_options(app, argc, argv)) return *status;
  try {
    embree_config();  // a bad FLOWSCAPE_EMBREE_CONFIG fails before anything is written
    if (!weathers.empty()) given["weathers"] = comma_list(weathers);
    if (!times.empty()) given["times_of_day"] = comma_list(times);
    if (!skies.empty()) given["skies"] = comma_list(skies);
    if (!outputs.empty())
      given["outputs"] = outputs == "none" ? std::vector<std::string>{} : comma_list(outputs);
    if (!gaps.empty()) given["flow_gaps"] = parse_gaps(gaps);
    if (no_cube) given["cube"] = false;
    if (no_noise) given["sensor_noise"] = false;
    if (no_vignetting) given["vignetting"] = false;
    if (bayer) given["bayer"] = true;
    if (!models.empty()) given["models"] = parse_models(models);
    if (!packs.empty()) given["asset_packs"] = packs;
    sources.file = config_file;
    sources.scenarios.assign(scenarios.begin(), scenarios.end());
    ReleaseConfig c = resolve_config(sources);
    try {
      refuse_rig_options(given, c.rig);
      if (!scenarios.empty() && (given.contains("maps") || given.contains("map_list") ||
                                 given.contains("sequences_per_map")))
        throw std::invalid_argument(
            std::string(given.contains("sequences_per_map") ? "--sequences-per-map" : "--maps") +
            ": the scenarios say which sequences the release holds");
    } catch (const std::invalid_argument& e) {
      std::fprintf(diagnostics(), "gen_flowscape: error: %s (see --help)\n", e.what());
      return kUsageError;
    }
    if (!scenarios.empty())  // each scenario's paths read and checked before anything is written
      for (const SequencePlan& plan : plan_sequences(c)) {
        const std::string file = plan.scenario_file.string();
        if (const std::string warning = version_warning(read_scenario(file)); !warning.empty())
          std::fprintf(diagnostics(), "gen_flowscape: %s: %s\n", file.c_str(), warning.c_str());
        sequence_spec(c, plan);
      }
    if (is_calibration_file(c.rig))  // a wide-angle calibration that sees only part of its image
      for (const std::string& warning : calibration_warnings(release_rig(c)))
        std::fprintf(diagnostics(), "gen_flowscape: %s: warning: %s\n", c.rig.c_str(),
                     warning.c_str());
    if (!shard.empty()) parse_shard(shard, c);
    if (sources.demo && !out_option->count()) out = kDemoOut;
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              threads > 0 ? threads : tbb::this_task_arena::max_concurrency());
    if (check) {
      check_user_files(c);
      std::printf("%zu sequences of %d frames; shard %d/%d makes %zu of them\n",
                  plan_sequences(c).size(), c.frames, c.shard, c.shards, shard_plans(c).size());
      const std::vector<ReleaseProblem> problems = release_problems(out, c);
      for (const ReleaseProblem& p : problems)
        std::fprintf(diagnostics(), "gen_flowscape: %s: %s\n", p.path.c_str(), p.problem.c_str());
      if (problems.empty()) return 0;
      std::fprintf(diagnostics(),
                   "gen_flowscape: error: %s: %zu file(s) not as the release has them\n",
                   out.c_str(), problems.size());
      return 1;
    }
    const ReleaseWritten written = write_release(c, out, force);
    std::printf("%s: %zu sequences, %zu frames, %zu files\n", written.manifest.c_str(),
                written.sequences, written.frames, written.files);
    if (c.shards == 1)
      std::fputs(
          statistics_summary(read_json(written.manifest).value("statistics", nlohmann::json()))
              .c_str(),
          stdout);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(diagnostics(), "gen_flowscape: error: %s\n", e.what());
    return 1;
  }
}
