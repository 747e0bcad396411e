#include "flowscape/release/config.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "flowscape/core/files.h"
#include "flowscape/core/names.h"
#include "flowscape/core/random.h"
#include "flowscape/layout/classes.h"
#include "flowscape/layout/layout.h"
#include "flowscape/layout/meta.h"
#include "flowscape/release/options.h"
#include "flowscape/release/scenario.h"
#include "flowscape/renderer/calibration_file.h"
#include "flowscape/renderer/denoiser.h"
#include "flowscape/scenes/city.h"
#include "flowscape/weather/weather.h"

namespace flowscape {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("release config: " + what);
}

// A rig the user's file describes (a rig file or a calibration), not a preset.
bool is_rig_file(const std::string& rig) {
  return rig.ends_with(".json") || is_calibration_file(rig);
}

}  // namespace

void validate(const ReleaseConfig& c) {
  for (const ReleaseOption& option : release_options()) check_option(option, c);
  for (std::size_t k = 0; k < c.map_list.size(); ++k)
    require(c.map_list[k] >= 0 && c.map_list[k] < kMapCount &&
                std::find(c.map_list.begin(), c.map_list.begin() + long(k), c.map_list[k]) ==
                    c.map_list.begin() + long(k),
            "map_list must hold different map numbers in 0.." + std::to_string(kMapCount - 1));
  try {  // an unknown one, or oidn where the build left the U-Net out
    make_denoiser(c.denoise, c.denoise_model);
  } catch (const std::invalid_argument& e) {
    require(false, e.what());
  }
  require(!c.weathers.empty(), "weathers must not be empty");
  for (const std::string& w : c.weathers) weather_preset(w);
  require(!c.times_of_day.empty(), "times_of_day must not be empty");
  for (const std::string& t : c.times_of_day) validate_time_of_day(t);
  require(!c.skies.empty(), "skies must not be empty");
  try {
    flow_format_from_name(c.flow_format);
  } catch (const std::invalid_argument& e) {
    require(false, e.what());
  }
  require(c.scale > 0 && c.scale <= 4, "scale must be in (0, 4]");
  require(c.scale == 1 || is_rig_file(c.rig),
          "scale is for a rig file or calibration: the " + c.rig + " rig is sized by resolution");
  require(c.rig_mount.empty() || (c.rig_mount.size() == 6 && is_calibration_file(c.rig)),
          "rig_mount is x, y, z, yaw, pitch, roll for a calibration file's first camera (the "
          "rig is " +
              c.rig + ")");
  for (double v : c.rig_mount) require(std::isfinite(v), "rig_mount must be finite");
  if (c.rig_mount.size() == 6)
    require(within_world({c.rig_mount[0], c.rig_mount[1], c.rig_mount[2]}),
            "rig_mount's x, y, z must lie within 1,000 km (metres)");
  for (const std::string& sky : c.skies) validate_sky(sky);
  require(c.vehicles + std::max(c.pedestrians, 0) + std::max(c.standing, 0) <= 200,
          "vehicles + pedestrians + standing must be in 0..200");
  require(c.asset_packs.empty() || c.actors == "detailed", "asset_packs need detailed actors");
  require(c.temporal == 0 || c.adaptive == 0,
          "temporal and adaptive do not go together (adaptive sampling picks pixels per frame)");
  for (const std::string& pack : c.asset_packs) asset_pack(pack);
  class_table(c.classes);
  for (const auto& [kind, path] : c.models) {
    kind_from_name(kind);
    if (!std::filesystem::is_regular_file(path)) throw FileError(path, "no such model file");
  }
  try {
    release_layout(c);
  } catch (const std::invalid_argument& e) {
    require(false, e.what());
  }
  for (int gap : c.flow_gaps)
    require(gap < c.frames, "flow gap " + std::to_string(gap) + " needs more than " +
                                std::to_string(gap) + " frames (the release has " +
                                std::to_string(c.frames) + ")");
  require(c.shards >= 1 && c.shard >= 0 && c.shard < c.shards, "shard K/N needs 0 <= K < N (got " +
                                                                   std::to_string(c.shard) + "/" +
                                                                   std::to_string(c.shards) + ")");
}

ColorSection color_section(const ReleaseConfig& c) {
  return {c.spp,      c.indirect_spp, c.edge_spp, c.max_bounces,
          c.adaptive, c.temporal,     c.denoise,  c.denoise_model};
}

FinalPassSection final_pass_section(const ReleaseConfig& c) {
  return {c.shutter_angle,        c.sensor_noise, c.pixel_pitch,  c.lens_glare, c.vignetting,
          c.chromatic_aberration, c.bayer,        c.jpeg_quality, c.lens_drops, c.lens_dirt};
}

int indirect_samples(const ColorSection& c) {
  if (c.indirect_spp > 0) return std::min(c.indirect_spp, c.spp);
  return make_denoiser(c.denoise, c.denoise_model)->filters()
             ? std::min(kDenoisedIndirectSpp, c.spp)
             : c.spp;
}

Rig release_rig(const ReleaseConfig& c) {
  if (c.rig == kFlowscapeRig) return flowscape_rig(c.height, c.cube ? c.face_size : 0);
  if (!is_rig_file(c.rig)) return rig_preset(c.rig, c.height);
  std::optional<CameraMount> mount;
  if (c.rig_mount.size() == 6)
    mount = CameraMount{{c.rig_mount[0], c.rig_mount[1], c.rig_mount[2]},
                        {c.rig_mount[3], c.rig_mount[4], c.rig_mount[5]}};
  try {
    const Rig rig = c.rig.ends_with(".json") ? rig_from_json(read_json(c.rig))
                                             : rig_from_calibration(c.rig, mount);
    return c.scale == 1 ? rig : scaled_rig(rig, c.scale);
  } catch (const std::invalid_argument& e) {
    throw FileError(c.rig, e.what());
  }
}

View view_of(const Rig& rig, const RigCamera& camera) {
  if (!rig.flowscape) return View::of_camera(camera.name);
  const auto index = std::size_t(&camera - rig.cameras.data());
  return index == 0 ? View() : View(kFaces[index - 1]);
}

ReleaseLayout release_layout(const ReleaseConfig& c) {
  ReleaseLayout layout =
      ReleaseLayout::of(c.outputs, c.flow_gaps, c.cube, flow_format_from_name(c.flow_format));
  const Rig rig = release_rig(c);
  if (!rig.flowscape)  // its views are the ERP's and the faces' (ReleaseLayout::of)
    for (const RigCamera& camera : rig.cameras)
      layout.cameras.push_back({camera.name, camera.projection.wraps_around()});
  return layout;
}

std::string config_differences(const nlohmann::json& first, const std::string& first_name,
                               const nlohmann::json& second, const std::string& second_name) {
  std::string text;
  const auto add = [&](const std::string& key, const std::string& difference) {
    text += (text.empty() ? "" : "; ") + key + ": " + difference;
  };
  for (const auto& [key, value] : second.items()) {
    const nlohmann::json before = first.value(key, nlohmann::json());
    if (before != value)
      add(key, before.dump() + " " + first_name + ", " + value.dump() + " " + second_name);
  }
  for (const auto& [key, value] : first.items())
    if (!second.contains(key)) add(key, "unknown " + second_name);
  return text;
}

nlohmann::json to_json(const ReleaseConfig& c) {
  nlohmann::json j = nlohmann::json::object();
  for (const ReleaseOption& option : release_options()) j[option.key] = option_value(option, c);
  return j;
}

ReleaseConfig release_config_from_json(const nlohmann::json& j, ReleaseConfig c) {
  if (!j.is_object()) throw std::invalid_argument("release config: expected a JSON object");
  nlohmann::json merged = to_json(c);
  std::vector<std::string> known;
  for (const auto& [key, value] : merged.items()) known.push_back(key);
  for (const auto& [key, value] : j.items()) {
    if (!merged.contains(key))
      throw std::invalid_argument("release config: unknown key \"" + key + "\"" +
                                  did_you_mean(key, known, {{"weather", "weathers"}}));
    merged[key] = value;
  }
  try {
    for (const ReleaseOption& option : release_options())
      set_option(option, merged.at(option.key), c);
  } catch (const std::exception& e) {  // json's type errors and json_integer's
    throw std::invalid_argument(std::string("release config: ") + e.what());
  }
  validate(c);
  return c;
}

nlohmann::json demo_config() {
  return {{"maps", 1},
          {"sequences_per_map", 2},
          {"frames", 4},
          {"resolution", 128},
          {"face_size", 64},
          {"spp", 8},
          {"weathers", {"sunny", "rain"}}};
}

ReleaseConfig resolve_config(const ConfigSources& sources) {
  ReleaseConfig config = sources.demo ? release_config_from_json(demo_config()) : ReleaseConfig{};
  if (!sources.file.empty()) {
    try {
      config = release_config_from_json(read_json(sources.file), config);
    } catch (const std::invalid_argument& e) {
      throw FileError(sources.file, e.what());
    }
  }
  if (!sources.scenarios.empty()) {
    nlohmann::json keys = release_keys(sources.scenarios, sources.command_line);
    for (const std::filesystem::path& file : sources.scenarios)
      keys["scenarios"].push_back(file.string());
    config = release_config_from_json(keys, config);
  }
  if (sources.command_line.is_null()) return config;
  return release_config_from_json(sources.command_line, config);
}

int parse_resolution(const std::string& text) {
  const char* end = text.data() + text.size();
  int height = 0, width = 0;
  const std::from_chars_result h_read = std::from_chars(text.data(), end, height);
  bool whole = h_read.ec == std::errc() && height > 0;
  if (whole && h_read.ptr != end) {
    whole = *h_read.ptr == 'x';
    const std::from_chars_result w_read = std::from_chars(h_read.ptr + 1, end, width);
    whole = whole && w_read.ec == std::errc() && w_read.ptr == end;
    if (whole && std::int64_t(width) != 2 * std::int64_t(height))
      throw std::invalid_argument("--resolution " + text +
                                  ": an equirectangular frame is twice as wide as high (" +
                                  std::to_string(height) + "x" + std::to_string(2 * height) + ")");
  }
  if (!whole)
    throw std::invalid_argument(
        "--resolution wants the height or HEIGHTxWIDTH, e.g. 512 or "
        "512x1024 (got \"" +
        text + "\")");
  return height;
}

void parse_shard(const std::string& text, ReleaseConfig& config) {
  int k = -1, n = -1;
  const char* end = text.data() + text.size();
  const std::from_chars_result k_read = std::from_chars(text.data(), end, k);
  bool whole = k_read.ec == std::errc() && k_read.ptr < end && *k_read.ptr == '/';
  if (whole) {
    const std::from_chars_result n_read = std::from_chars(k_read.ptr + 1, end, n);
    whole = n_read.ec == std::errc() && n_read.ptr == end;
  }
  if (!whole)
    throw std::invalid_argument("--shard wants K/N with whole numbers, e.g. 0/4 (got \"" + text +
                                "\")");
  config.shard = k, config.shards = n;
  validate(config);
}

std::map<std::string, std::string> parse_models(const std::vector<std::string>& options) {
  std::map<std::string, std::string> models;
  for (const std::string& option : options) {
    const std::size_t equals = option.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == option.size())
      throw std::invalid_argument("--model wants KIND=FILE, e.g. car=models/car.glb (got \"" +
                                  option + "\")");
    models[option.substr(0, equals)] = option.substr(equals + 1);
  }
  return models;
}

void check_sky_resolution(const ReleaseConfig& c) {
  const double erp = c.height / kPi, faces = c.cube ? c.face_size / 2.0 : 0;
  for (const std::string& sky : c.skies) check_sky_resolution(sky, std::max(erp, faces));
}

std::vector<int> release_maps(const ReleaseConfig& c) {
  if (!c.map_list.empty()) return c.map_list;
  std::vector<int> maps;
  for (int m = 0; m < c.maps; ++m) maps.push_back(m);
  return maps;
}

// One plan per scenario file, named after its map (map<MM>_seq<SS>, numbered within the map).
std::vector<SequencePlan> scenario_plans(const ReleaseConfig& c) {
  std::vector<SequencePlan> plans;
  std::map<int, int> per_map;
  for (const std::string& file : c.scenarios) {
    const Scenario s = read_scenario(file);
    const int index = per_map[s.map]++;
    plans.push_back({sequence_name(s.map, index), s.map, index, int(plans.size()), s.weather,
                     s.time_of_day, s.sky, s.seed, s.route == "turn", file});
  }
  return plans;
}

std::vector<SequencePlan> plan_sequences(const ReleaseConfig& c) {
  if (!c.scenarios.empty()) return scenario_plans(c);
  std::vector<SequencePlan> plans;
  for (int m : release_maps(c))
    for (int s = 0; s < c.sequences_per_map; ++s) {
      const int number = int(plans.size());
      const bool turns = c.ego_routes == "mix" && std::floor((number + 1) * c.turn_share) >
                                                      std::floor(number * c.turn_share);
      plans.push_back({sequence_name(m, s), m, s, number, c.weathers[s % c.weathers.size()],
                       c.times_of_day[number % c.times_of_day.size()],
                       c.skies[number % c.skies.size()], derived_seed(c.seed, m, s), turns});
    }
  return plans;
}

std::vector<std::string> sequence_names(const ReleaseConfig& config) {
  std::vector<std::string> names;
  for (const SequencePlan& plan : plan_sequences(config)) names.push_back(plan.name);
  return names;
}

bool in_shard(const SequencePlan& plan, const ReleaseConfig& c) {
  return plan.number % c.shards == c.shard;
}

std::vector<SequencePlan> shard_plans(const ReleaseConfig& config) {
  std::vector<SequencePlan> mine;
  for (const SequencePlan& plan : plan_sequences(config))
    if (in_shard(plan, config)) mine.push_back(plan);
  return mine;
}

}  // namespace flowscape
