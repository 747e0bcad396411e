// city_preview: one ERP frame of each city map (colour, flow, semantics side by side) in a
// contact-sheet PNG, rendered as a release renders it (the same Sequence: the weather preset varied
// by the seed); optionally each map as glTF with its scene record, to inspect in any viewer.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "cli.h"
#include "flowscape/core/files.h"
#include "flowscape/formats/contact_sheet.h"
#include "flowscape/formats/flow_viz.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/formats/semantic_viz.h"
#include "flowscape/formats/srgb.h"
#include "flowscape/layout/meta.h"
#include "flowscape/release/gallery.h"
#include "flowscape/release/scenario.h"
#include "flowscape/release/sequence.h"
#include "flowscape/renderer/calibration_file.h"
#include "flowscape/renderer/denoiser.h"
#include "flowscape/scenes/model_io.h"
#include "tracing_cli.h"

using namespace flowscape;

namespace {

struct Options {
  std::string out = "city_maps.png", gltf_dir;
  int height = 160, vehicles = 120, pedestrians = -1, standing = -1, ego_start = 37;
  ReleaseConfig color;  // spp, indirect_spp, denoise: as a release renders colour
  std::uint64_t seed = 0;
  double time = 1.0;
  std::vector<int> maps{0, 1, 2, 3, 4, 5, 6, 7};
  std::vector<std::string> weathers;      // when given: one row per weather, of the first map
  std::vector<std::string> times_of_day;  // when given: one row per weather and time of day
  std::vector<std::string> skies;         // when given: and one per sky
  std::map<std::string, std::string> models;
  std::vector<std::string> rigs;  // when given: one row per camera of each rig, of the first map
  bool plan = false;              // seen from above instead of from the ego
  bool actors = false;            // the gallery of the built-in actor models instead
  std::vector<std::string> actor_models;
  std::string scenario, from_release;  // one sequence's scenario file, or a release's sequence
};

// A pinhole 40 degrees wide looking straight down on the middle of the map's roads, north up,
// high enough to see all of them.
FramePair plan_view(const City& city, double time) {
  Eigen::Vector2d lo = city.start_points.front().pose.translation().head<2>(), hi = lo;
  for (const StartPoint& p : city.start_points)
    lo = lo.cwiseMin(p.pose.translation().head<2>()),
    hi = hi.cwiseMax(p.pose.translation().head<2>());
  const Eigen::Vector2d centre = (lo + hi) / 2;
  const double half_size = 0.6 * (hi - lo).maxCoeff(), fov = 40 * kPi / 180;
  Pose rig = Pose::Identity();
  rig.linear() << 0, -1, 0, 0, 0, 1, -1, 0, 0;  // columns: forward = down, left = west, up = north
  rig.translation() << centre.x(), centre.y(), half_size / std::tan(fov / 2);
  return {time, time + 1 / kFrameRate, rig, rig};
}

// A preview's sequence of map `map`: the options' traffic and ego start, the ego driving free,
// `frames` frames, the actors and ego as `config` says.
SequenceSpec preview_spec(const Options& o, const ReleaseConfig& config, int map,
                          const std::string& weather, int frames) {
  SequenceSpec spec;
  CityConfig& city = spec.city;
  const StreetLife people = people_on_foot(map, o.vehicles, o.pedestrians, o.standing);
  city.map = map, city.seed = o.seed, city.vehicles = o.vehicles;
  city.pedestrians = people.walking, city.standing = people.standing;
  city.ego_start = o.ego_start, city.ego_route = EgoRoute::Free, city.models = o.models;
  set_actors(spec, config);
  spec.weather = weather, spec.frames = frames;
  return spec;
}

// One row of the plan sheet: colour and semantics of map `map` seen from above.
std::vector<Image<std::uint8_t>> render_plan(const Options& o, int map) {
  const int frame = int(std::lround(o.time * kFrameRate));
  const SequenceSpec spec = preview_spec(o, o.color, map, "sunny", frame + 2);
  const Sequence sequence = make_sequence(spec);
  Renderer renderer(sequence.city.scene);
  const FramePair frames = plan_view(sequence.city, frame / kFrameRate);
  const Projection camera = Projection::pinhole(o.height, o.height, 40);
  const GroundTruth gt = renderer.ground_truth(camera, frames);
  const Image<float> color = release_color(color_section(o.color), sequence, renderer, camera,
                                           TruthRequest{frames}, frame, gt);
  return {linear_to_srgb8(color.view()), semantic_to_color(gt.semantic.view())};
}

struct Row {
  int map;
  std::string weather, time_of_day, sky;
};

// One row per map (sunny, by day), or per weather and time of day of the first map.
std::vector<Row> planned_rows(const Options& o) {
  std::vector<Row> rows;
  if (o.weathers.empty() && o.times_of_day.empty() && o.skies.empty()) {
    for (int map : o.maps) rows.push_back({map, "sunny", "day", "physical"});
    return rows;
  }
  const auto or_else = [](const std::vector<std::string>& given, const char* otherwise) {
    return given.empty() ? std::vector<std::string>{otherwise} : given;
  };
  for (const std::string& weather : or_else(o.weathers, "sunny"))
    for (const std::string& time : or_else(o.times_of_day, "day"))
      for (const std::string& sky : or_else(o.skies, "physical"))
        rows.push_back({o.maps[0], weather, time, sky});
  return rows;
}

// Colour | flow | semantics of a sequence's ERP at `frame`, colour as a release made with `config`
// renders it; with --gltf, the scene at that time and its scene record as <name>.gltf and
// <name>.json.
std::vector<Image<std::uint8_t>> erp_row(const Options& o, const ReleaseConfig& config,
                                         const Sequence& sequence, int frame,
                                         const std::string& name) {
  Renderer renderer(sequence.city.scene);
  // the last frame has no next one: its flow goes back to the frame before
  const bool last = frame + 1 >= sequence.spec.frames;
  const Moment now = sequence.moment(frame), before = sequence.moment(frame - last);
  const FramePair frames =
      last ? FramePair{now.time, before.time, now.rig, before.rig} : sequence.frame_pair(frame);
  const Projection erp = Projection::equirectangular(o.height);
  const GroundTruth gt = renderer.ground_truth(erp, frames);
  const Image<float> color =
      release_color(color_section(config), sequence, renderer, erp, frame, gt);
  if (!o.gltf_dir.empty()) {
    std::filesystem::create_directories(o.gltf_dir);
    const std::filesystem::path base = std::filesystem::path(o.gltf_dir) / name;
    export_gltf(sequence.city.scene, frames.time, base.string() + ".gltf");
    write_text(base.string() + ".json", to_json(sequence.city).dump(2) + "\n");
  }
  return {linear_to_srgb8(color.view()), flow_to_color(gt.flow.view(), gt.valid.view(), {}),
          semantic_to_color(gt.semantic.view())};
}

// One row of the sheet: colour | flow | semantics of map `map` in a weather preset at a time of
// day under a sky, at the frame nearest the options' time.
std::vector<Image<std::uint8_t>> render_row(const Options& o, int map, const std::string& weather,
                                            const std::string& time_of_day = "day",
                                            const std::string& sky = "physical") {
  const int frame = int(std::lround(o.time * kFrameRate));
  SequenceSpec spec = preview_spec(o, o.color, map, weather, frame + 2);
  spec.time_of_day = time_of_day, spec.sky = sky;
  std::vector<Image<std::uint8_t>> row =
      erp_row(o, o.color, make_sequence(spec), frame, map_name(map));
  cv::Mat canvas(row[0].height, row[0].width, CV_8UC3, row[0].data.data());
  cv::putText(canvas, std::to_string(map) + " " + map_name(map) + " " + weather, cv::Point(6, 18),
              cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  return row;
}

// The scenario of --scenario FILE or --from-release SEQUENCE_FOLDER, with the config of the
// release it renders in: the defaults with the scenario's release-wide keys, or the release's own.
std::pair<ReleaseConfig, Scenario> chosen_scenario(const Options& o) {
  if (!o.scenario.empty()) {
    ConfigSources sources;
    sources.scenarios = {o.scenario};
    return {resolve_config(sources), read_scenario(o.scenario)};
  }
  const std::filesystem::path sequence = o.from_release,
                              release = sequence.parent_path().parent_path();
  const SequenceMeta meta = read_meta(sequence);
  if (meta.scenario.is_null())
    throw FileError(sequence / "meta.json", "records no scenario (made before flowscape 0.10)");
  ReleaseConfig config = release_config_from_json(read_json(release / "config.json"));
  config.scenarios.clear();  // the recorded scenario stands for its file
  const Scenario scenario = scenario_from_json(meta.scenario);
  if (const std::string warning = version_warning(scenario); !warning.empty())
    std::fprintf(diagnostics(), "city_preview: %s: %s\n", o.from_release.c_str(), warning.c_str());
  return {config, scenario};
}

// One row (erp_row) of the chosen scenario's sequence at the frame nearest the options' time,
// built as its release builds it; --gltf names its files after the scenario or the sequence.
std::vector<Image<std::uint8_t>> render_scenario(const Options& o) {
  const auto [config, scenario] = chosen_scenario(o);
  const int frame = int(std::lround(o.time * scenario.frame_rate));
  if (frame < 0 || frame >= config.frames)
    throw std::invalid_argument("--time " + std::to_string(o.time) +
                                ": the sequence's frames are from 0 to " +
                                std::to_string((config.frames - 1) / scenario.frame_rate) + " s");
  const std::string name = o.scenario.empty()
                               ? std::filesystem::path(o.from_release).filename().string()
                               : std::filesystem::path(o.scenario).stem().string();
  return erp_row(o, config, make_sequence(sequence_spec(config, scenario, o.scenario)), frame,
                 name);
}

// One row per camera of a rig (the flowscape rig: its ERP), colour | flow | semantics of map
// `map`, each camera at its own mount, as a release renders them; labelled "<rig> <camera>".
std::vector<std::vector<Image<std::uint8_t>>> render_rig(const Options& o, int map,
                                                         const std::string& rig_name) {
  ReleaseConfig config = o.color;
  config.rig = rig_name, config.height = o.height;
  const Rig rig = release_rig(config);
  if (is_calibration_file(config.rig))
    for (const std::string& warning : calibration_warnings(rig))
      std::fprintf(diagnostics(), "city_preview: %s: warning: %s\n", config.rig.c_str(),
                   warning.c_str());
  if (rig.flowscape) {
    std::vector<std::vector<Image<std::uint8_t>>> rows{render_row(o, map, "sunny")};
    label_tile(rows[0][0], rig_name + " erp, " + map_name(map) + " sunny");
    return rows;
  }
  const int frame = int(std::lround(o.time * kFrameRate));
  const SequenceSpec spec = preview_spec(o, config, map, "sunny", frame + 2);
  const Sequence sequence = make_sequence(spec);
  Renderer renderer(sequence.city.scene);
  std::vector<std::vector<Image<std::uint8_t>>> rows;
  for (const RigCamera& camera : rig.cameras) {
    TruthRequest rig_request{sequence.frame_pair(frame)};
    rig_request.track = [&sequence](double t) { return sequence.city.rig(t); };
    const TruthRequest request = at_camera(rig_request, camera);
    const GroundTruth gt = renderer.ground_truth(camera.projection, request);
    const Image<float> color = release_color(color_section(config), sequence, renderer,
                                             camera.projection, request, frame, gt);
    rows.push_back({linear_to_srgb8(color.view()),
                    flow_to_color(gt.flow.view(), gt.valid.view(), {}),
                    semantic_to_color(gt.semantic.view())});
    label_tile(rows.back()[0], rig.name + " " + camera.name);
  }
  return rows;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Render one ERP frame of each procedural city map into a contact sheet: colour, "
      "ground-truth flow (PanoFlow wheel) and semantics (CARLA palette) per row, as a release "
      "renders them."};
  Options o;
  app.add_option("-o,--out", o.out, "contact sheet PNG");
  app.add_option("--height", o.height, "ERP height in pixels (width = 2 x height)")
      ->check(CLI::Range(16, 2048));
  app.add_option("--spp", o.color.spp, "path-traced samples per pixel")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  app.add_option("--indirect-spp", o.color.indirect_spp,
                 "of those, how many gather indirect light (more than --spp: all; 0: 4 when "
                 "denoised, all when not)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  app.add_option("--denoise", o.color.denoise,
                 "atrous (as a release), oidn (OIDN's U-Net) or none: the raw path tracer")
      ->check(CLI::IsMember(kDenoiserNames))
      ->capture_default_str();
  app.add_option("--seed", o.seed, "sequence seed (city, traffic, weather variant, noise)");
  app.add_option("--vehicles", o.vehicles, "vehicles per map")->check(CLI::Range(0, 200));
  app.add_option("--pedestrians", o.pedestrians, "people walking per map (-1: the map's own)")
      ->check(CLI::Range(-1, 200));
  app.add_option("--standing", o.standing, "people standing per map (-1: the map's own)")
      ->check(CLI::Range(-1, 200));
  app.add_option("--ego-start", o.ego_start, "start point of the ego vehicle (0-99)")
      ->check(CLI::Range(0, 99));
  app.add_option("--time", o.time, "seconds into the sequence (rounded to a frame)")
      ->check(CLI::Range(0.0, 600.0));
  app.add_option("--maps", o.maps, "map numbers (0-7)")->check(CLI::Range(0, kMapCount - 1));
  app.add_option("--weathers", o.weathers,
                 "one row per weather preset (sunny cloud fog rain wet wet_cloudy soft_rain "
                 "hard_rain clear_sunset foggy_rain) of the first map; default: sunny");
  app.add_option("--times-of-day", o.times_of_day,
                 "with or without --weathers: one row per weather and time of day (day, dawn, "
                 "dusk, night or a sun elevation in degrees) of the first map");
  app.add_option("--skies", o.skies,
                 "with or without the two above: one row per sky as well (physical, or a sky map "
                 "that scripts/fetch_sky_maps.sh fetched: sky, park, sunrise, dawn, venice)");
  std::vector<std::string> models;
  app.add_option("--model", models,
                 "KIND=FILE: a user model for an actor kind (car, truck, bus, bike, pedestrian)");
  app.add_option("--gltf", o.gltf_dir,
                 "also write <map>.gltf and its scene record <map>.json here");
  app.add_option("--rigs", o.rigs,
                 "one row per camera of each rig (flowscape, fisheye, woodscape, pal, "
                 "dual-fisheye, or a rig file .json) of the first map, each camera's image "
                 "scaled by --height as a release scales it");
  app.add_flag("--plan", o.plan,
               "each map seen from above (colour and semantics, --height pixels square) instead "
               "of from the ego");
  app.add_option("--actor-style", o.color.actors,
                 "detailed (the built-in vehicle families and people) or legacy (flowscape 0.9's "
                 "boxes), as gen_flowscape --actors")
      ->check(CLI::IsMember({"detailed", "legacy"}))
      ->capture_default_str();
  app.add_option("--ego", o.color.ego, "the ego vehicle: auto, on or off, as gen_flowscape --ego")
      ->check(CLI::IsMember({"auto", "on", "off"}))
      ->capture_default_str();
  app.add_flag("--actors", o.actors,
               "the gallery of built-in actor models instead: one row per model seen from the "
               "front, side, back and three-quarters, and its semantics, --height pixels high; "
               "with --times-of-day, one row per model and time under the physical sky, a street "
               "lamp beside it and its lamps on when the release's are");
  app.add_option("--actor-models", o.actor_models,
                 "with --actors: these models only (hatchback saloon estate suv pickup van taxi "
                 "police delivery_van city_bus box_truck lorry motorbike bicycle man woman child "
                 "umbrella jogger)");
  app.add_option("--scenario", o.scenario,
                 "one row of a scenario file's sequence (docs/scenarios.md) at --time; with "
                 "--gltf its scene there");
  auto* from_release =
      app.add_option("--from-release", o.from_release,
                     "SEQUENCE_FOLDER (release/sequences/map00_seq03): one row of a release's "
                     "sequence, rebuilt from its recorded scenario and the release's config; with "
                     "--gltf its scene, as the release rendered it");
  from_release->excludes(app.get_option("--scenario"));
  finish_options(app, "city_preview");
  version_with_kernels(app, "city_preview");
  if (const auto status = parse_options(app, argc, argv)) return *status;
  try {
    embree_config();  // fail before rendering
    for (const std::string& name : o.weathers) weather_preset(name);
    for (const std::string& time : o.times_of_day) validate_time_of_day(time);
    for (const std::string& sky : o.skies) check_sky_resolution(sky, o.height / kPi);
    o.models = parse_models(models);
    std::vector<std::vector<Image<std::uint8_t>>> sheet;
    if (o.actors) {
      sheet = actor_gallery({o.height, o.color, o.actor_models, 0, o.times_of_day});
      write_image(o.out, contact_sheet(sheet));
      std::printf("%s: %zu rows\n", o.out.c_str(), sheet.size());
      return 0;
    }
    if (!o.scenario.empty() || !o.from_release.empty()) {
      sheet.push_back(render_scenario(o));
      write_image(o.out, contact_sheet(sheet));
      std::printf("%s\n", o.out.c_str());
      return 0;
    }
    for (const std::string& rig : o.rigs) {
      const auto rows = render_rig(o, o.maps[0], rig);
      sheet.insert(sheet.end(), rows.begin(), rows.end());
      std::printf("rig %s: %zu camera(s)\n", rig.c_str(), rows.size());
      std::fflush(stdout);
    }
    const std::vector<Row> rows = o.rigs.empty() ? planned_rows(o) : std::vector<Row>{};
    for (std::size_t row = 0; row < rows.size(); ++row) {
      const auto start = std::chrono::steady_clock::now();
      const auto& [map, weather, time, sky] = rows[row];
      sheet.push_back(o.plan ? render_plan(o, map) : render_row(o, map, weather, time, sky));
      const std::string look = (time == "day" ? weather : weather + " at " + time) +
                               (sky == "physical" ? "" : ", sky map " + sky);
      label_tile(sheet.back().front(), map_name(map) + (o.plan ? ", from above" : ", " + look));
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf("row %zu/%zu (%s %s) in %.1f s\n", row + 1, rows.size(), map_name(map).c_str(),
                  look.c_str(), seconds);
      std::fflush(stdout);
    }
    write_image(o.out, contact_sheet(sheet));
    std::printf("%s\n", o.out.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(diagnostics(), "city_preview: error: %s\n", e.what());
    return 1;
  }
}
