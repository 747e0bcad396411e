#include "flowscape/release.h"

#include <tbb/parallel_for.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <stdexcept>

#include "flowscape/city.h"
#include "flowscape/color.h"
#include "flowscape/contact_sheet.h"
#include "flowscape/cubemap_io.h"
#include "flowscape/flow_io.h"
#include "flowscape/flow_viz.h"
#include "flowscape/io.h"
#include "flowscape/random.h"
#include "flowscape/renderer.h"
#include "flowscape/semantic_viz.h"
#include "flowscape/sha256.h"
#include "flowscape/stitch.h"
#include "flowscape/weather.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

constexpr double kFps = 30;

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("release config: " + what);
}

std::string numbered(const char* format, int value) {
  char text[32];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

std::uint64_t mixed_seed(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
  Random random(seed ^ (a << 32) ^ (b << 8) ^ 0x632be59bd9b4e019ull);
  return random.bits();
}

struct Sequence {
  City city;
  Weather weather;
};

Sequence make_sequence(const ReleaseConfig& config, const SequencePlan& plan) {
  CityConfig city_config;
  city_config.map = plan.map, city_config.seed = plan.seed;
  city_config.vehicles = config.vehicles, city_config.pedestrians = config.pedestrians;
  city_config.ego_start = int(plan.seed % 100);
  city_config.duration = (config.frames + 1) / kFps;
  Sequence s{make_city(city_config), randomized(weather_preset(plan.weather), plan.seed)};
  const City& city = s.city;
  apply_weather(
      s.weather, plan.seed, [&city](double t) { return city.rig(t); }, s.city.scene);
  return s;
}

nlohmann::json meta_json(const ReleaseConfig& config, const SequencePlan& plan, const Sequence& s) {
  nlohmann::json poses = nlohmann::json::array();
  for (int f = 0; f < config.frames; ++f) {
    const Eigen::Matrix4d m = s.city.rig(f / kFps).matrix();
    std::vector<double> row_major;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) row_major.push_back(m(r, c));
    poses.push_back(row_major);
  }
  nlohmann::json meta = {
      {"scene", plan.name},
      {"map", plan.map},
      {"map_name", map_name(plan.map)},
      {"sequence", plan.index},
      {"seed", plan.seed},
      {"weather", to_json(s.weather)},
      {"frames", config.frames},
      {"fps", kFps},
      {"erp", {{"width", 2 * config.height}, {"height", config.height}, {"flow", "360-degree"}}},
      {"camera",
       {{"height_above_ego", s.city.camera_height},
        {"frame", "x forward, y left, z up; rig pose = rig -> world, 3x4 row-major"}}},
      {"poses", poses},
      {"city", to_json(s.city)}};
  if (config.cube)
    meta["cube"] = {{"face_size", config.face_size},
                    {"focal", config.face_size / 2.0},
                    {"faces", {"front", "right", "back", "left", "up", "down"}}};
  return meta;
}

bool all_exist(const fs::path& dir, const std::vector<std::string>& files) {
  return std::all_of(files.begin(), files.end(),
                     [&](const std::string& f) { return fs::exists(dir / f); });
}

void write_truth(const fs::path& dir, const std::string& name, const GroundTruth& gt,
                 bool with_flow) {
  write_image(dir / "semantic" / (name + ".png"), gt.semantic);
  write_image(dir / "instance" / (name + ".png"), gt.instance);
  write_image(dir / "depth" / (name + ".exr"), gt.depth);
  if (!with_flow) return;
  write_flo(dir / "flow" / (name + ".flo"), gt.flow.view());
  write_image(dir / "valid" / (name + ".png"), gt.valid);
}

void write_cube_truth(const fs::path& dir, const std::string& name, const CubeFrame& cube,
                      bool with_flow) {
  const GroundTruth& gt = cube.truth;
  const Image<std::uint8_t> color = linear_to_srgb8(cube.color.view());
  write_cube_image(dir, "color", name + ".png", color.view());
  write_cube_image(dir, "semantic", name + ".png", gt.semantic.view());
  write_cube_image(dir, "instance", name + ".png", gt.instance.view());
  write_cube_image(dir, "depth", name + ".exr", gt.depth.view());
  if (!with_flow) return;
  write_cube_flow(dir, name + ".flo", gt.flow.view());
  write_cube_image(dir, "valid", name + ".png", gt.valid.view());
}

void write_frame(const ReleaseConfig& config, const SequencePlan& plan, Renderer& renderer,
                 const City& city, const CubeToErp* map, const fs::path& dir, int frame) {
  const double t = frame / kFps;
  const FramePair pair{t, t + 1 / kFps, city.rig(t), city.rig(t + 1 / kFps)};
  const RenderOptions options{config.spp, config.max_bounces, mixed_seed(plan.seed, frame, 1)};
  const Projection erp = Projection::equirectangular(config.height);
  const std::string name = frame_name(frame);
  const bool with_flow = frame + 1 < config.frames;
  Image<float> erp_color;
  if (map) {
    const CubeFrame cube = render_cube(renderer, config.face_size, pair, &options);
    write_cube_truth(dir / "cube", name, cube, with_flow);
    erp_color = resample_bilinear(map->sampling, cube.color);
  } else {
    erp_color = renderer.color(erp, pair, options);
  }
  write_truth(dir / "erp", name, renderer.ground_truth(erp, pair), with_flow);
  write_image(dir / "erp" / "color" / (name + ".png"), linear_to_srgb8(erp_color.view()));
}

}  // namespace

void validate(const ReleaseConfig& c) {
  require(c.maps >= 1 && c.maps <= kMapCount, "maps must be in 1.." + std::to_string(kMapCount));
  require(c.sequences_per_map >= 1 && c.sequences_per_map <= 99,
          "sequences_per_map must be in 1..99");
  require(c.frames >= 2 && c.frames <= 999999, "frames must be in 2..999999");
  require(c.height >= 8 && c.height <= 8192, "resolution (ERP height) must be in 8..8192");
  require(c.face_size >= 4 && c.face_size <= 8192, "face_size must be in 4..8192");
  require(c.spp >= 1 && c.spp <= 65536, "spp must be in 1..65536");
  require(c.max_bounces >= 0 && c.max_bounces <= 64, "max_bounces must be in 0..64");
  require(!c.weathers.empty(), "weathers must not be empty");
  for (const std::string& w : c.weathers) weather_preset(w);
  require(c.vehicles >= 0 && c.pedestrians >= 0 && c.vehicles + c.pedestrians <= 200,
          "vehicles + pedestrians must be in 0..200");
  require(c.shards >= 1 && c.shard >= 0 && c.shard < c.shards, "shard K/N needs 0 <= K < N (got " +
                                                                   std::to_string(c.shard) + "/" +
                                                                   std::to_string(c.shards) + ")");
}

namespace {

// The JSON keys of a ReleaseConfig and the members they hold, written and read from this one list.
template <class Config, class Visit>
void for_each_field(Config& c, Visit&& visit) {
  visit("maps", c.maps), visit("sequences_per_map", c.sequences_per_map);
  visit("frames", c.frames), visit("resolution", c.height), visit("face_size", c.face_size);
  visit("spp", c.spp), visit("max_bounces", c.max_bounces), visit("weathers", c.weathers);
  visit("vehicles", c.vehicles), visit("pedestrians", c.pedestrians), visit("seed", c.seed);
  visit("cube", c.cube);
}

}  // namespace

nlohmann::json to_json(const ReleaseConfig& c) {
  nlohmann::json j = nlohmann::json::object();
  for_each_field(c, [&](const char* key, const auto& value) { j[key] = value; });
  return j;
}

ReleaseConfig release_config_from_json(const nlohmann::json& j, ReleaseConfig c) {
  if (!j.is_object()) throw std::invalid_argument("release config: expected a JSON object");
  nlohmann::json merged = to_json(c);
  for (const auto& [key, value] : j.items()) {
    if (!merged.contains(key))
      throw std::invalid_argument("release config: unknown key \"" + key + "\"");
    merged[key] = value;
  }
  try {
    for_each_field(c, [&](const char* key, auto& field) {
      field = merged.at(key).get<std::decay_t<decltype(field)>>();
    });
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("release config: ") + e.what());
  }
  validate(c);
  return c;
}

std::vector<SequencePlan> plan_sequences(const ReleaseConfig& c) {
  std::vector<SequencePlan> plans;
  for (int m = 0; m < c.maps; ++m)
    for (int s = 0; s < c.sequences_per_map; ++s) {
      const int number = int(plans.size());
      plans.push_back({numbered("map%02d", m) + numbered("_seq%02d", s), m, s, number,
                       c.weathers[s % c.weathers.size()], mixed_seed(c.seed, m, s)});
    }
  return plans;
}

bool in_shard(const SequencePlan& plan, const ReleaseConfig& c) {
  return plan.number % c.shards == c.shard;
}

fs::path sequence_dir(const fs::path& out, const SequencePlan& plan) {
  return out / "sequences" / plan.name;
}

std::string frame_name(int frame) { return numbered("%06d", frame); }

std::vector<std::string> frame_files(const ReleaseConfig& c, int frame) {
  const std::string name = frame_name(frame);
  const bool with_flow = frame + 1 < c.frames;
  std::vector<std::string> files;
  const auto add_set = [&](const std::string& prefix) {
    for (const char* m : {"color", "semantic", "instance"})
      files.push_back(prefix + m + "/" + name + ".png");
    files.push_back(prefix + "depth/" + name + ".exr");
    if (with_flow) {
      files.push_back(prefix + "flow/" + name + ".flo");
      files.push_back(prefix + "valid/" + name + ".png");
    }
  };
  add_set("erp/");
  if (c.cube)
    for (Face face : kFaces) add_set("cube/" + std::string(face_name(face)) + "/");
  return files;
}

void remove_partial_files(const fs::path& dir) {
  if (!fs::exists(dir)) return;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().filename().string().rfind(".partial-", 0) == 0)
      fs::remove(entry.path());
}

void write_sequence(const ReleaseConfig& config, const SequencePlan& plan, const fs::path& out,
                    const SequenceProgress& progress) {
  const fs::path dir = sequence_dir(out, plan);
  fs::create_directories(dir);
  remove_partial_files(dir);
  std::vector<int> frames_to_render;
  for (int f = 0; f < config.frames; ++f) {
    if (all_exist(dir, frame_files(config, f)))
      progress.frame_skipped();
    else
      frames_to_render.push_back(f);
  }
  if (frames_to_render.empty() && fs::exists(dir / "meta.json")) return;
  Sequence s = make_sequence(config, plan);
  if (!fs::exists(dir / "meta.json"))
    write_text(dir / "meta.json", meta_json(config, plan, s).dump(1) + "\n");
  Renderer renderer(s.city.scene);
  const CubeToErp map =
      config.cube ? make_cube_to_erp(config.face_size, config.height) : CubeToErp{};
  for (int f : frames_to_render) {
    write_frame(config, plan, renderer, s.city, config.cube ? &map : nullptr, dir, f);
    progress.frame_done();
  }
}

nlohmann::json file_hashes(const fs::path& out, const std::vector<SequencePlan>& plans) {
  std::vector<fs::path> files;
  for (const SequencePlan& plan : plans) {
    const fs::path dir = sequence_dir(out, plan);
    if (!fs::exists(dir)) throw FileError(dir, "sequence folder missing");
    for (const auto& entry : fs::recursive_directory_iterator(dir))
      if (entry.is_regular_file()) files.push_back(fs::relative(entry.path(), out));
  }
  std::sort(files.begin(), files.end());
  std::vector<nlohmann::json> entries(files.size());
  tbb::parallel_for(std::size_t(0), files.size(), [&](std::size_t k) {
    entries[k] = {{"sha256", sha256_file(out / files[k])},
                  {"bytes", fs::file_size(out / files[k])}};
  });
  nlohmann::json hashes = nlohmann::json::object();
  for (std::size_t k = 0; k < files.size(); ++k) hashes[files[k].generic_string()] = entries[k];
  return hashes;
}

void write_manifest(const fs::path& out, const ReleaseConfig& config, const nlohmann::json& files) {
  nlohmann::json all = files;
  for (const fs::path& extra : {fs::path("README.md"), fs::path("card")}) {
    if (!fs::exists(out / extra)) continue;
    std::vector<fs::path> found;
    if (fs::is_directory(out / extra)) {
      for (const auto& e : fs::recursive_directory_iterator(out / extra))
        if (e.is_regular_file()) found.push_back(fs::relative(e.path(), out));
    } else {
      found.push_back(extra);
    }
    for (const fs::path& f : found)
      all[f.generic_string()] = {{"sha256", sha256_file(out / f)},
                                 {"bytes", fs::file_size(out / f)}};
  }
  std::map<std::string, int> per_weather, per_map;
  int sequences = 0;
  for (const SequencePlan& plan : plan_sequences(config))
    ++per_weather[plan.weather], ++per_map[map_name(plan.map)], ++sequences;
  const nlohmann::json manifest = {{"generator", kGeneratorVersion},
                                   {"config", to_json(config)},
                                   {"counts",
                                    {{"sequences", sequences},
                                     {"frames", sequences * config.frames},
                                     {"flow_pairs", sequences * (config.frames - 1)},
                                     {"sequences_per_weather", per_weather},
                                     {"sequences_per_map", per_map}}},
                                   {"files", all}};
  write_text(out / "manifest.json", manifest.dump(1) + "\n");
}

namespace {

std::vector<nlohmann::json> read_shard_manifests(const fs::path& out) {
  const fs::path dir = out / "manifests";
  if (!fs::is_directory(dir)) throw FileError(dir, "no shard manifests (did the shards run?)");
  std::vector<nlohmann::json> shards;
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::ifstream in(entry.path());
    try {
      shards.push_back(nlohmann::json::parse(in));
    } catch (const nlohmann::json::exception& e) {
      throw FileError(entry.path(), std::string("not a shard manifest: ") + e.what());
    }
  }
  if (shards.empty()) throw FileError(dir, "no shard manifests (did the shards run?)");
  return shards;
}

void check_sequence_complete(const fs::path& out, const ReleaseConfig& config,
                             const SequencePlan& plan) {
  const fs::path dir = sequence_dir(out, plan);
  const int shard = plan.number % config.shards;
  const std::string rerun = " (rerun shard " + std::to_string(shard) + ")";
  if (!fs::exists(dir / "meta.json")) throw FileError(dir, "sequence missing" + rerun);
  for (int f = 0; f < config.frames; ++f)
    for (const std::string& file : frame_files(config, f))
      if (!fs::exists(dir / file)) throw FileError(dir / file, "missing" + rerun);
}

}  // namespace

ReleaseConfig merge_shards(const fs::path& out, bool verify) {
  const std::vector<nlohmann::json> shards = read_shard_manifests(out);
  ReleaseConfig config;
  try {
    config = release_config_from_json(shards.front().at("config"));
    config.shards = shards.front().at("shards").get<int>();
  } catch (const nlohmann::json::exception& e) {
    throw FileError(out / "manifests", std::string("bad shard manifest: ") + e.what());
  }
  std::vector<bool> seen(std::size_t(std::max(1, config.shards)), false);
  nlohmann::json files = nlohmann::json::object();
  for (const nlohmann::json& shard : shards) {
    if (shard.at("config") != shards.front().at("config") || shard.at("shards") != config.shards)
      throw FileError(out / "manifests", "shards made with different configs");
    seen.at(shard.at("shard").get<std::size_t>()) = true;
    files.update(shard.at("files"));
  }
  std::string missing;
  for (std::size_t k = 0; k < seen.size(); ++k)
    if (!seen[k]) missing += (missing.empty() ? "" : ", ") + std::to_string(k);
  if (!missing.empty())
    throw FileError(out / "manifests", "no manifest from shard(s) " + missing + " of " +
                                           std::to_string(config.shards) + ": rerun them");
  const std::vector<SequencePlan> plans = plan_sequences(config);
  for (const SequencePlan& plan : plans) check_sequence_complete(out, config, plan);
  const nlohmann::json on_disk = verify ? file_hashes(out, plans) : nlohmann::json();
  for (const auto& [path, entry] : files.items()) {
    if (!fs::exists(out / path)) throw FileError(out / path, "listed by a shard but missing");
    if (fs::file_size(out / path) != entry.at("bytes").get<std::uintmax_t>())
      throw FileError(out / path, "size differs from its shard manifest");
    if (verify && on_disk.value(path, nlohmann::json()) != entry)
      throw FileError(out / path, "sha256 differs from its shard manifest");
  }
  config.shard = 0, config.shards = 1;
  write_dataset_card(out, config);
  write_manifest(out, config, files);
  fs::remove_all(out / "manifests");
  return config;
}

std::vector<Image<std::uint8_t>> frame_preview_row(const fs::path& dir, int frame, int width) {
  const std::string name = frame_name(frame);
  const Image<std::uint8_t> color =
      read_image<std::uint8_t>(dir / "erp" / "color" / (name + ".png"));
  Image<std::uint8_t> flow(color.width, color.height, 3);
  if (fs::exists(dir / "erp" / "flow" / (name + ".flo"))) {
    const Flow uv = read_flow(dir / "erp" / "flow" / (name + ".flo"));
    const Image<std::uint8_t> valid =
        read_image<std::uint8_t>(dir / "erp" / "valid" / (name + ".png"));
    flow = flow_to_color(uv.uv.view(), valid.view(), {});
  }
  const Image<std::uint8_t> semantic =
      read_image<std::uint8_t>(dir / "erp" / "semantic" / (name + ".png"));
  return {shrink_to_width(color, width), shrink_to_width(flow, width),
          shrink_to_width(semantic_to_color(semantic.view()), width)};
}

}  // namespace flowscape
