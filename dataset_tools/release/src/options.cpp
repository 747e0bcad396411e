#include "flowscape/release/options.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "flowscape/scenes/city.h"
#include "json_integer.h"

namespace flowscape {
namespace {

using Section = OptionSection;
using Form = OptionForm;
using C = ReleaseConfig;

// The number (an int or a double) `text` is, all of it; nullopt for anything else (empty text too).
template <class Number>
std::optional<Number> number_of(const std::string& text) {
  Number value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
  return value;
}

template <class Number>
nlohmann::json json_number(const std::string& text) {  // null where it is none
  const std::optional<Number> number = number_of<Number>(text);
  return number ? nlohmann::json(*number) : nlohmann::json();
}

std::vector<std::string> comma_list(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');) items.push_back(item);
  return items;
}

// --maps: a count N (maps 0..N-1), or the chosen map numbers separated by commas ("5," is one).
nlohmann::json parse_maps(const std::string& text) {
  const auto count = [&](const std::string& item) {
    const std::optional<int> value = number_of<int>(item);
    if (!value || *value < 0)
      throw std::invalid_argument("--maps: \"" + item + "\" is not a whole number >= 0");
    return *value;
  };
  if (text.find(',') == std::string::npos) return {{"maps", count(text)}};
  std::vector<int> maps;
  for (const std::string& map : comma_list(text))
    if (!map.empty()) maps.push_back(count(map));
  return {{"map_list", maps}};
}

nlohmann::json parse_resolution_option(const std::string& text) {
  return {{"resolution", parse_resolution(text)}};
}

nlohmann::json parse_model(const std::string& text) { return nlohmann::json(parse_models({text})); }

std::string number_text(double value, bool integral) {
  if (integral) return std::to_string(static_cast<long long>(value));
  std::ostringstream text;
  text << value;
  return text.str();
}

bool integral(const OptionField& field) {
  return std::holds_alternative<int C::*>(field) ||
         std::holds_alternative<std::uint64_t C::*>(field);
}

// "1..65536 (0: as the denoiser wants)": a number option's range, empty for one without.
std::string range_text(const ReleaseOption& option) {
  if (!std::isfinite(option.min)) return "";
  return number_text(option.min, integral(option.field)) + ".." +
         number_text(option.max, integral(option.field)) +
         (*option.special ? " (" + std::string(option.special) + ")" : "");
}

// "a, b or c"
std::string alternatives(const std::vector<const char*>& choices) {
  std::string text;
  for (std::size_t k = 0; k < choices.size(); ++k)
    text += (k == 0 ? "" : k + 1 == choices.size() ? " or " : ", ") + std::string(choices[k]);
  return text;
}

}  // namespace

const std::vector<ReleaseOption>& release_options() {
  static const std::vector<ReleaseOption> options = {
      // plan: which sequences
      {.key = "maps",
       .field = &C::maps,
       .section = Section::Plan,
       .flag = "--maps",
       .form = Form::Parsed,
       .min = 1,
       .max = kMapCount,
       .help = "city maps: a count N (maps 0..N-1), or the chosen map numbers (0-7) separated by "
               "commas (3,7; one map: 5,), each map's sequences with the names and seeds the "
               "whole release gives them (config key map_list)",
       .parse = parse_maps},
      {.key = "map_list",
       .field = &C::map_list,
       .section = Section::Plan,
       .form = Form::None,
       .help = "the chosen maps (0-7) instead of the first `maps` (--maps 3,7)"},
      {.key = "sequences_per_map",
       .field = &C::sequences_per_map,
       .section = Section::Plan,
       .flag = "--sequences-per-map",
       .min = 1,
       .max = 99,
       .help = "sequences per map"},
      {.key = "frames",
       .field = &C::frames,
       .section = Section::Plan,
       .flag = "--frames",
       .min = 2,
       .max = 999999,
       .help = "frames per sequence (30 Hz)"},
      {.key = "seed",
       .field = &C::seed,
       .section = Section::Plan,
       .flag = "--seed",
       .help = "release seed: every sequence's derives from it, the map and the sequence"},
      {.key = "scenarios",
       .field = &C::scenarios,
       .section = Section::Plan,
       .form = Form::None,
       .help = "scenario files (docs/scenarios.md), one sequence each, instead of the maps' "
               "sequences (--scenario)"},
      // scene: the city, its traffic, weather and light
      {.key = "weathers",
       .field = &C::weathers,
       .section = Section::Scene,
       .flag = "--weather",
       .form = Form::List,
       .help = "weather presets cycled over each map's sequences (sunny, cloud, fog, rain, ...)",
       .list_wants = "weather presets separated by commas"},
      {.key = "times_of_day",
       .field = &C::times_of_day,
       .section = Section::Scene,
       .flag = "--time-of-day",
       .form = Form::List,
       .help = "times of day cycled over the release's sequences by their number: day, dawn, "
               "dusk, night or a sun elevation in degrees (-90..90; docs/weather.md)",
       .list_wants = "times of day separated by commas"},
      {.key = "skies",
       .field = &C::skies,
       .section = Section::Scene,
       .flag = "--sky",
       .form = Form::List,
       .help = "skies cycled over the release's sequences: physical, or a real HDR sky map (sky, "
               "park, sunrise, dawn, venice; its sun sets the time of day; "
               "scripts/fetch_sky_maps.sh fetches them)",
       .list_wants = "skies separated by commas"},
      {.key = "vehicles",
       .field = &C::vehicles,
       .section = Section::Scene,
       .flag = "--vehicles",
       .min = 0,
       .max = 200,
       .help = "vehicles per map (with people walking and standing at most 200)"},
      {.key = "pedestrians",
       .field = &C::pedestrians,
       .section = Section::Scene,
       .flag = "--pedestrians",
       .min = -1,
       .max = 200,
       .special = "-1: the map's own, 8 rural to 56 downtown",
       .help = "people walking per map (with vehicles and people standing at most 200)"},
      {.key = "standing",
       .field = &C::standing,
       .section = Section::Scene,
       .flag = "--standing",
       .min = -1,
       .max = 200,
       .special = "-1: the map's own, 3 rural to 24 downtown, or in its proportion to the "
                  "people walking given",
       .help = "people standing or waiting on the pavements per map, alone or in groups of up to "
               "four, where no walker passes (with vehicles and walkers at most 200)",
       .absent = 0},
      {.key = "turn_share",
       .field = &C::turn_share,
       .section = Section::Scene,
       .flag = "--turn-share",
       .min = 0,
       .max = 1,
       .help = "share of sequences whose ego turns at a junction within its frames: sequence n "
               "turns when floor((n + 1) x share) > floor(n x share); the others drive on, their "
               "lane ahead kept clear at spawn (docs/scenes.md)"},
      {.key = "ego_routes",
       .field = &C::ego_routes,
       .section = Section::Scene,
       .flag = "--ego-routes",
       .choices = {"mix", "free"},
       .help = "mix: --turn-share of the sequences turn, the others drive; free: every ego "
               "drives as traffic lets it from where its seed starts it (releases of flowscape "
               "0.8 and before, whose config.json lacks the key, are read so)",
       .absent = "free"},
      {.key = "actors",
       .field = &C::actors,
       .section = Section::Scene,
       .flag = "--actors",
       .choices = {"detailed", "legacy"},
       .help = "detailed: the built-in vehicle families and people, parked vehicles as actors; "
               "legacy: flowscape 0.9's box models (reproduces its releases)",
       .absent = "legacy"},
      {.key = "ego",
       .field = &C::ego,
       .section = Section::Scene,
       .flag = "--ego",
       .choices = {"auto", "on", "off"},
       .help = "the ego vehicle under the rig (detailed actors): on, off, or auto: drawn for every "
               "rig but flowscape (FlowScape's CARLA frames show no ego)"},
      {.key = "models",
       .field = &C::models,
       .section = Section::Scene,
       .flag = "--model",
       .form = Form::Each,
       .help = "KIND=FILE: a user model for an actor kind (car, truck, bus, bike, pedestrian), "
               "glTF or anything assimp reads, textures included; repeat for several kinds",
       .parse = parse_model},
      {.key = "asset_packs",
       .field = &C::asset_packs,
       .section = Section::Scene,
       .flag = "--asset-pack",
       .form = Form::Each,
       .help = "opt in to an asset pack of Debian's game data: torcs (torcs-data's cars; GPL-2+ "
               "and Free Art License models, recorded per actor and in the card); repeatable"},
      // render: images and samples
      {.key = "resolution",
       .field = &C::height,
       .section = Section::Render,
       .flag = "--resolution",
       .form = Form::Parsed,
       .min = 8,
       .max = 8192,
       .help = "ERP size: the height (512) or height x width (512x1024; the width is twice the "
               "height); presets' images are scaled to it",
       .parse = parse_resolution_option},
      {.key = "face_size",
       .field = &C::face_size,
       .section = Section::Render,
       .flag = "--face-size",
       .min = 4,
       .max = 8192,
       .help = "cube face size in pixels (256 matches a 512 x 1024 ERP at the equator)"},
      {.key = "spp",
       .field = &C::spp,
       .section = Section::Render,
       .flag = "--spp",
       .min = 1,
       .max = 65536,
       .help = "path-traced samples per pixel"},
      {.key = "indirect_spp",
       .field = &C::indirect_spp,
       .section = Section::Render,
       .flag = "--indirect-spp",
       .min = 0,
       .max = 65536,
       .special = "0: as the denoiser wants",
       .help = "of those, how many gather indirect light (weighted for all; more than --spp: "
               "all; 0: 4 when denoised, all when not)"},
      {.key = "edge_spp",
       .field = &C::edge_spp,
       .section = Section::Render,
       .flag = "--edge-spp",
       .min = 0,
       .max = 65536,
       .special = "0: none",
       .help = "where a pixel's samples disagree on the light met before any surface (a lit "
               "window's, a lamp's, the sky's edge), camera rays up to this many in all gather "
               "that light alone (at or below --spp: none; releases of flowscape 0.16 and "
               "before, whose config.json lacks the key, are read with 0)",
       .absent = 0},
      {.key = "max_bounces",
       .field = &C::max_bounces,
       .section = Section::Render,
       .form = Form::None,
       .min = 0,
       .max = 64,
       .help = "the longest path, in bounces"},
      {.key = "adaptive",
       .field = &C::adaptive,
       .section = Section::Render,
       .flag = "--adaptive",
       .min = 0,
       .max = 1,
       .special = "0: uniform sampling",
       .help = "share of the pixels (0-1) that take half of --spp where the denoised colour is "
               "estimated worst, the others the first half only; 0: every pixel --spp "
               "(docs/release.md, \"Adaptive sampling\")"},
      {.key = "temporal",
       .field = &C::temporal,
       .section = Section::Render,
       .flag = "--temporal",
       .min = 0,
       .max = 8,
       .special = "0: each frame alone",
       .help = "temporal reconstruction: each frame's colour layers averaged with those of the K "
               "frames before and after it along the exact flow, history rejected where the "
               "shading changed, before the denoiser (docs/renderer.md, \"Temporal "
               "reconstruction\"; not with --adaptive)"},
      {.key = "denoise",
       .field = &C::denoise,
       .section = Section::Render,
       .flag = "--denoise",
       .help = "atrous: the colour denoised with its feature layers; oidn: by OIDN's trained U-Net "
               "(weights from scripts/install_deps.sh); none: the raw path tracer"},
      {.key = "denoise_model",
       .field = &C::denoise_model,
       .section = Section::Render,
       .flag = "--denoise-model",
       .help = "the U-Net of --denoise oidn: default or small"},
      // outputs: what is written, and how
      {.key = "cube",
       .field = &C::cube,
       .section = Section::Outputs,
       .flag = "--no-cube",
       .form = Form::Off,
       .help = "the six cube faces too (the ERP colour stitched from them); --no-cube: the ERP "
               "only, its colour rendered directly"},
      {.key = "outputs",
       .field = &C::outputs,
       .section = Section::Outputs,
       .flag = "--outputs",
       .form = Form::List,
       .help = "output kinds besides the six every release has (color flow semantic instance "
               "depth valid): flow_backward (brings valid_backward), valid_backward, scene_flow, "
               "normal, normal_shading, final (the final pass: motion blur, exposure, noise, "
               "lens; a second path trace), lens_mask, time; all; none",
       .list_wants = "output kinds separated by commas",
       .absent = nlohmann::json::array()},
      {.key = "flow_gaps",
       .field = &C::flow_gaps,
       .section = Section::Outputs,
       .flag = "--flow-gaps",
       .form = Form::List,
       .help = "frame gaps of every flow kind (1 is the next frame and must be there; "
               "flow_gap<k> and, with backward flow, flow_backward_gap<k> for the others)",
       .list_wants = "whole numbers separated by commas, e.g. 1,2,4",
       .absent = nlohmann::json::array({1})},
      {.key = "flow_format",
       .field = &C::flow_format,
       .section = Section::Outputs,
       .flag = "--flow-format",
       .help = "how every flow kind is stored: flo (Middlebury float32; the PanoFlow tree's), "
               "kitti-png (16-bit PNG, 1/64 px steps within +-512 px) or half-exr (half floats: "
               "1/4 px steps from 256 px); flow beyond the range is marked unknown, never "
               "wrapped"},
      {.key = "classes",
       .field = &C::classes,
       .section = Section::Outputs,
       .flag = "--classes",
       .help = "the semantic class table: carla-0.9.13 (FlowScape's 23 ids) or carla-0.9.14 "
               "(rider, car, truck, bus, motorcycle, bicycle apart, and the ego vehicle as 29)"},
      // the final pass (output kind final)
      {.key = "shutter_angle",
       .field = &C::shutter_angle,
       .section = Section::FinalPass,
       .flag = "--shutter-angle",
       .min = 1,
       .max = 360,
       .help = "degrees of a frame the shutter is open, centred on the frame's time (the motion "
               "blur's length is the flow times angle / 360)"},
      {.key = "sensor_noise",
       .field = &C::sensor_noise,
       .section = Section::FinalPass,
       .flag = "--no-sensor-noise",
       .form = Form::Off,
       .help = "shot and read noise"},
      {.key = "pixel_pitch",
       .field = &C::pixel_pitch,
       .section = Section::FinalPass,
       .flag = "--pixel-pitch",
       .min = 0.5,
       .max = 50,
       .help = "the sensor's pixel pitch in micrometres (smaller: more noise)"},
      {.key = "lens_glare",
       .field = &C::lens_glare,
       .section = Section::FinalPass,
       .flag = "--lens-glare",
       .min = 0,
       .max = 0.5,
       .help = "share of light the lens scatters round bright lights"},
      {.key = "vignetting",
       .field = &C::vignetting,
       .section = Section::FinalPass,
       .flag = "--no-vignetting",
       .form = Form::Off,
       .help = "a real lens's vignetting (the ERP and cube faces have none)"},
      {.key = "chromatic_aberration",
       .field = &C::chromatic_aberration,
       .section = Section::FinalPass,
       .flag = "--chromatic-aberration",
       .min = -0.05,
       .max = 0.05,
       .help = "lateral chromatic aberration of real lenses: red magnified and blue shrunk by this "
               "share of the radius"},
      {.key = "bayer",
       .field = &C::bayer,
       .section = Section::FinalPass,
       .flag = "--bayer",
       .form = Form::On,
       .help = "the sensor behind an RGGB Bayer filter, demosaicked"},
      {.key = "jpeg_quality",
       .field = &C::jpeg_quality,
       .section = Section::FinalPass,
       .flag = "--jpeg-quality",
       .min = 0,
       .max = 100,
       .help = "JPEG compression at this quality (1-100; 0: none)"},
      {.key = "lens_drops",
       .field = &C::lens_drops,
       .section = Section::FinalPass,
       .flag = "--lens-drops",
       .min = -1,
       .max = 200,
       .special = "-1: in rain only",
       .help = "water drops on real lenses (-1: round(24 x precipitation) in rain, none in dry "
               "weather; 0-200: this many; output kind lens_mask marks what they hide)"},
      {.key = "lens_dirt",
       .field = &C::lens_dirt,
       .section = Section::FinalPass,
       .flag = "--lens-dirt",
       .min = 0,
       .max = 1,
       .help = "dirt on real lenses: the densest blotch's share of the light"},
      // rig: the cameras
      {.key = "rig",
       .field = &C::rig,
       .section = Section::Rig,
       .flag = "--rig",
       .help = "the cameras: flowscape (the ERP and six cube faces), fisheye, woodscape, pal, "
               "dual-fisheye, a rig file (.json) or a calibration (--rig-from; docs/cameras.md)"},
      {.key = "rig_mount",
       .field = &C::rig_mount,
       .section = Section::Rig,
       .flag = "--rig-mount",
       .form = Form::List,
       .help = "X,Y,Z,YAW,PITCH,ROLL: a calibration's first camera on the rig (metres: x forward, "
               "y left, z up; degrees as a rig file's yaw_pitch_roll_degrees)",
       .list_wants = "x,y,z,yaw,pitch,roll: six numbers",
       .list_size = 6},
      {.key = "scale",
       .field = &C::scale,
       .section = Section::Rig,
       .flag = "--scale",
       .help = "a rig file's or calibration's image sizes and intrinsics scaled by this, in (0, "
               "4] (0.25: a quick preview)"},
  };
  return options;
}

std::string section_name(OptionSection section) {
  constexpr const char* kNames[] = {"plan", "scene", "render", "outputs", "final pass", "rig"};
  return kNames[int(section)];
}

nlohmann::json option_value(const ReleaseOption& option, const ReleaseConfig& config) {
  return std::visit([&](auto member) { return nlohmann::json(config.*member); }, option.field);
}

void set_option(const ReleaseOption& option, const nlohmann::json& value, ReleaseConfig& config) {
  std::visit(
      [&](auto member) {
        using T = std::decay_t<decltype(config.*member)>;
        if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
          config.*member = json_integer<T>(value, option.key);
        } else if constexpr (std::is_same_v<T, std::vector<int>>) {
          if (!value.is_array())
            throw std::invalid_argument(std::string(1, '"') + option.key +
                                        "\" must be a list of integers");
          T numbers;
          for (const nlohmann::json& number : value)
            numbers.push_back(json_integer<int>(number, option.key));
          config.*member = numbers;
        } else {
          config.*member = value.get<T>();
        }
      },
      option.field);
}

void check_option(const ReleaseOption& option, const ReleaseConfig& config) {
  const nlohmann::json value = option_value(option, config);
  const auto refuse = [&](const std::string& what) {
    throw std::invalid_argument("release config: " + std::string(option.key) + " must be " + what);
  };
  if (value.is_number() &&
      !(value.get<double>() >= option.min && value.get<double>() <= option.max))
    refuse("in " + range_text(option));
  if (!option.choices.empty() && std::none_of(option.choices.begin(), option.choices.end(),
                                              [&](const char* choice) { return value == choice; }))
    refuse(alternatives(option.choices));
}

nlohmann::json with_absent_keys(nlohmann::json recorded) {
  if (!recorded.is_object()) return recorded;
  const ReleaseConfig defaults;
  for (const ReleaseOption& option : release_options())
    if (!recorded.contains(option.key))
      recorded[option.key] =
          option.absent.is_null() ? option_value(option, defaults) : option.absent;
  return recorded;
}

nlohmann::json parse_list(const ReleaseOption& option, const std::string& text) {
  if (text == "none") return nlohmann::json::array();
  // an item as the list's member holds it: null where it is not a number the list wants
  const auto item_value = [&](const std::string& item) -> nlohmann::json {
    if (std::holds_alternative<std::vector<int> C::*>(option.field)) return json_number<int>(item);
    if (std::holds_alternative<std::vector<double> C::*>(option.field))
      return json_number<double>(item);
    return item;
  };
  nlohmann::json list = nlohmann::json::array();
  for (const std::string& item : comma_list(text)) list.push_back(item_value(item));
  const bool numbers_read =
      std::none_of(list.begin(), list.end(), [](const nlohmann::json& v) { return v.is_null(); });
  if (!numbers_read || (option.list_size > 0 && list.size() != option.list_size))
    throw std::invalid_argument(std::string(option.flag) + " wants " + option.list_wants +
                                " (got \"" + text + "\")");
  return list;
}

nlohmann::json parse_each(const ReleaseOption& option, const std::vector<std::string>& values) {
  if (!option.parse) return values;
  nlohmann::json all = nlohmann::json::object();
  for (const std::string& value : values) all.update(option.parse(value));
  return all;
}

std::string options_markdown() {
  const ReleaseConfig defaults;
  std::string text =
      "# Release options\n\n"
      "Every option of a release: its key in a config file (`--config`, and the release's\n"
      "`config.json`), its flag on gen_flowscape's command line, its default and its range. "
      "Written\n"
      "by `gen_flowscape --options-markdown` from the table in "
      "dataset_tools/release/src/options.cpp;\n"
      "a test fails when this page and the table differ. The options that run the program rather\n"
      "than describe the release (`--out`, `--config`, `--scenario`, `--rig-from`, `--shard`,\n"
      "`--threads`, `--demo`, `--check`, `--force`) are in docs/release.md.\n";
  for (int s = 0; s <= int(OptionSection::Rig); ++s) {
    text += "\n## " + section_name(OptionSection(s)) + "\n\n| key | flag | default | values | |\n" +
            "| --- | --- | --- | --- | --- |\n";
    for (const ReleaseOption& option : release_options()) {
      if (int(option.section) != s) continue;
      const std::string values =
          option.choices.empty() ? range_text(option) : alternatives(option.choices);
      const std::string flag = *option.flag ? "`" + std::string(option.flag) + "`" : "";
      text += "| `" + std::string(option.key) + "` | " + flag + " | `" +
              option_value(option, defaults).dump() + "` | " + values + " | " + option.help +
              " |\n";
    }
  }
  return text;
}

}  // namespace flowscape
