#include "flowscape/release/sequence.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <utility>

#include "flowscape/core/files.h"
#include "flowscape/core/profile.h"
#include "flowscape/core/random.h"
#include "flowscape/layout/classes.h"
#include "flowscape/release/adaptive_sampling.h"
#include "flowscape/release/manifest.h"
#include "flowscape/release/scenario.h"
#include "flowscape/renderer/denoise.h"
#include "flowscape/renderer/neural_denoise.h"
#include "flowscape/renderer/ray_kernels.h"
#include "flowscape/scenes/actors.h"
#include "flowscape/scenes/model_io.h"

namespace flowscape {

SequenceSpec sequence_spec(const ReleaseConfig& config, const SequencePlan& plan) {
  return sequence_spec(config, scenario_of(config, plan), plan.scenario_file);
}

SequenceSpec sequence_spec(const ReleaseConfig& config, const Scenario& s,
                           const std::filesystem::path& source) {
  SequenceSpec spec;
  CityConfig& city = spec.city;
  const StreetLife people = people_on_foot(s.map, s.vehicles, s.pedestrians, s.standing);
  city.map = s.map, city.seed = s.seed, city.vehicles = s.vehicles;
  city.pedestrians = people.walking, city.standing = people.standing;
  city.ego_start = int(s.seed % 100), city.ego_route = route_from_name(s.route);
  city.lane_change_at = s.lane_change_at;
  city.models = config.models;
  for (const auto& [kind, file] : s.models) city.models[kind] = file;  // over the release's
  city.world = s.world_file, city.scripted = s.actors;
  set_actors(spec, config);
  spec.weather = s.weather, spec.time_of_day = s.time_of_day, spec.sky = s.sky;
  spec.weather_parameters = s.weather_parameters;
  spec.frames = config.frames, spec.frame_rate = s.frame_rate;
  if (s.path) {
    try {
      spec.rig_path = rig_path_track(s, release_rig(config));
    } catch (const std::invalid_argument& e) {
      throw FileError(source, e.what());
    }
    spec.city.draw_ego = false;  // a handheld camera or a drone: no car under it
  }
  return spec;
}

void set_actors(SequenceSpec& spec, const ReleaseConfig& config) {
  CityConfig& city = spec.city;
  city.actors = style_from_name(config.actors);
  city.asset_packs = config.asset_packs;
  const Rig rig = release_rig(config);
  // FlowScape's views float where CARLA mounted them, with no car drawn under them
  city.draw_ego = config.ego == "on" || (config.ego == "auto" && !rig.flowscape);
  city.ego_cameras = rig.optical_centres();
}

FramePair Sequence::frame_pair(int frame) const {
  const double t = time(frame), next = t + 1 / spec.frame_rate;
  return {t, next, city.rig(t), city.rig(next)};
}

Moment Sequence::moment(int frame) const { return {time(frame), city.rig(time(frame))}; }

TruthPlan truth_plan(const Sequence& sequence, const ReleaseLayout& layout, int frame, int frames) {
  TruthPlan plan{{sequence.frame_pair(frame)}, {}};
  for (int step : layout.flow_steps(frame, frames))
    if (step != 1) {
      plan.request.more.push_back(sequence.moment(frame + step));
      plan.steps.push_back(step);
    }
  plan.request.scene_flow = layout.has("scene_flow");
  plan.request.normal = layout.has("normal");
  plan.request.shading_normal = layout.has("normal_shading");
  plan.request.camera_on_rig = true;
  plan.request.track = [&sequence](double t) { return sequence.city.rig(t); };
  return plan;
}

std::uint64_t Sequence::color_seed(int frame) const {
  return derived_seed(spec.city.seed, frame, 1);
}

RenderOptions Sequence::color_options(const ColorSection& color_settings, int frame) const {
  RenderOptions options{color_settings.spp, color_settings.max_bounces, color_seed(frame)};
  options.indirect_samples = indirect_samples(color_settings);
  options.edge_samples = color_settings.edge_spp;
  return options;
}

std::unique_ptr<const Denoiser> release_denoiser(const ColorSection& color_settings) {
  return make_denoiser(color_settings.denoise, color_settings.denoise_model,
                       color_settings.temporal > 0);
}

Image<float> denoised_cube_color(const ColorSection& color_settings, const ColorLayers& color,
                                 const GroundTruth& truth) {
  const ScopedPhase phase("denoising");
  return release_denoiser(color_settings)->cube(color, truth);
}

ColorLayers release_cube_layers(const ColorSection& color_settings, int face_size,
                                const Sequence& sequence, Renderer& renderer,
                                const GroundTruth& truth, int frame) {
  return adaptive_color_layers(
      [&](const RenderOptions& options) {
        return cube_color_layers(renderer, face_size, sequence.frame_pair(frame), options);
      },
      [&](const ColorLayers& color) { return denoised_cube_color(color_settings, color, truth); },
      sequence.color_options(color_settings, frame), color_settings.adaptive);
}

Image<float> denoised_color(const ColorSection& color_settings, const ColorLayers& layers,
                            const Projection& camera, ImageView<const float> depth,
                            ImageView<const std::uint16_t> instance) {
  const ScopedPhase phase("denoising");
  return release_denoiser(color_settings)->view(layers, camera, depth, instance);
}

Image<float> release_color(const ColorSection& color_settings, const Sequence& sequence,
                           Renderer& renderer, const Projection& camera, int frame,
                           const GroundTruth& truth) {
  return release_color(color_settings, sequence, renderer, camera,
                       TruthRequest{sequence.frame_pair(frame)}, frame, truth);
}

Image<float> release_color(const ColorSection& color_settings, const Sequence& sequence,
                           Renderer& renderer, const Projection& camera, const TruthRequest& view,
                           int frame, const GroundTruth& truth) {
  return denoised_color(
      color_settings,
      release_layers(color_settings, sequence, renderer, camera, view, frame, truth), camera,
      truth.depth.view(), truth.instance.view());
}

ColorLayers traced_layers(Renderer& renderer, const Projection& camera, const TruthRequest& view,
                          const RenderOptions& options) {
  const ScopedPhase phase("path tracing");
  return view.readout.global()
             ? renderer.color_layers(camera, view.pair, options)
             : renderer.color_layers(camera, view.pair.time, view.track, view.readout, options);
}

ColorLayers release_layers(const ColorSection& color_settings, const Sequence& sequence,
                           Renderer& renderer, const Projection& camera, const TruthRequest& view,
                           int frame, const GroundTruth& truth) {
  return adaptive_color_layers(
      [&](const RenderOptions& options) { return traced_layers(renderer, camera, view, options); },
      [&](const ColorLayers& layers) {
        return denoised_color(color_settings, layers, camera, truth.depth.view(),
                              truth.instance.view());
      },
      sequence.color_options(color_settings, frame), color_settings.adaptive);
}

Sequence make_sequence(const SequenceSpec& spec) {
  const std::uint64_t seed = spec.city.seed;
  Weather weather = under_sky(
      at_time_of_day(randomized(weather_preset(spec.weather), seed), spec.time_of_day, seed),
      spec.sky, seed);
  if (!spec.weather_parameters.empty()) weather = with_parameters(weather, spec.weather_parameters);
  CityConfig city_config = spec.city;
  city_config.duration = (spec.frames + 1) / spec.frame_rate;
  city_config.wet = weather.precipitation > 0;
  Sequence s{spec, make_city(city_config), weather};
  s.city.rig_path = spec.rig_path;
  apply_weather(s.weather, seed, s.city.rig_track(), s.city.scene);
  return s;
}

namespace {

// Each view's camera -> rig, by its meta.json key.
std::vector<std::pair<std::string, Pose>> view_mounts(const Rig& rig) {
  std::vector<std::pair<std::string, Pose>> mounts;
  for (const RigCamera& camera : rig.cameras)
    mounts.emplace_back(view_dir(view_of(rig, camera)).generic_string(), camera.mount());
  return mounts;
}

nlohmann::json matrix_rows(const Mat3& m) {
  return {{m(0, 0), m(0, 1), m(0, 2)}, {m(1, 0), m(1, 1), m(1, 2)}, {m(2, 0), m(2, 1), m(2, 2)}};
}

// The views of another rig than flowscape: each camera's model, parameters (as its lens states
// them: OpenCV's K and D for Kannala-Brandt), image and mount.
nlohmann::json rig_views_json(const Rig& rig) {
  nlohmann::json views = nlohmann::json::object();
  for (const RigCamera& camera : rig.cameras) {
    const Projection& p = camera.projection;
    views[view_dir(View::of_camera(camera.name)).generic_string()] = {
        {"model", p.model()},
        {"parameters", p.parameters()},
        {"width", p.width},
        {"height", p.height},
        {"camera_to_rig", matrix_rows(p.camera_to_rig())},
        {"translation_in_rig", {camera.position.x(), camera.position.y(), camera.position.z()}}};
    if (!camera.readout.global())  // poses are the frame time's (the middle line's)
      views[view_dir(View::of_camera(camera.name)).generic_string()]["rolling_shutter"] = {
          {"readout_s", camera.readout.seconds},
          {"lines", camera.readout.columns ? "columns" : "rows"},
          {"line_time", "frame time + readout_s x (line + 0.5 - lines / 2) / lines"}};
  }
  return views;
}

}  // namespace

void check_user_files(const ReleaseConfig& config) {
  std::set<std::string> read;
  const auto check = [&](const std::string& file, const auto& load) {
    if (!file.empty() && read.insert(file).second) load();
  };
  bool maps_checked = false;  // the maps' sequences share the release's models
  for (const SequencePlan& plan : shard_plans(config)) {
    if (plan.scenario_file.empty() && std::exchange(maps_checked, true)) continue;
    const SequenceSpec spec = sequence_spec(config, plan);
    Scene scratch;
    if (spec.city.world)
      check(spec.city.world->path, [&] { load_world(*spec.city.world, scratch); });
    std::vector<std::string> models;
    for (const auto& [kind, file] : spec.city.models) models.push_back(file);
    for (const ScriptedActor& actor : spec.city.scripted) models.push_back(actor.model);
    for (const std::string& file : models)
      check(file, [&] { load_model(file, SemanticClass::Vehicles, 4, scratch); });
  }
}

SequenceMeta sequence_meta(const Sequence& s, const SequencePlan& plan,
                           const ReleaseConfig& config) {
  SequenceMeta meta;
  meta.scene = plan.name, meta.map = plan.map, meta.sequence = plan.index;
  meta.map_name = map_name(plan.map), meta.seed = plan.seed;
  meta.weather = to_json(s.weather);
  meta.weather["exposure"] = s.city.scene.environment.exposure;  // the sky's, applied to all light
  meta.frames = config.frames, meta.fps = s.spec.frame_rate;
  meta.camera_height = s.city.mount.height;
  meta.camera_pitch_sway = s.city.mount.pitch_amplitude * 180 / kPi;
  meta.camera_roll_sway = s.city.mount.roll_amplitude * 180 / kPi;
  for (int f = 0; f < config.frames; ++f) meta.poses.push_back(s.city.rig(s.time(f)));
  meta.city = to_json(s.city);
  const Rig rig = release_rig(config);
  meta.erp_height = rig.flowscape ? config.height : 0;  // another rig has no ERP
  meta.face_size = rig.has_cube_faces() ? config.face_size : 0;
  meta.views = rig.flowscape ? views_json(config.height, meta.face_size) : rig_views_json(rig);
  if (!rig.flowscape) meta.rig = to_json(rig);
  for (const auto& [view, mount] : view_mounts(rig)) {
    nlohmann::json poses = nlohmann::json::array();
    for (const Pose& pose : meta.poses) poses.push_back(pose_row_major(pose * mount));
    meta.views[view]["poses"] = poses;
  }
  meta.actors = actor_records(s, config.frames, config.classes);
  meta.scenario = to_json(scenario_of(config, plan));
  const RayKernels kernels = ray_kernels();
  meta.generator = {{"flowscape", kGeneratorVersion},
                    {"embree", kernels.embree},
                    {"kernels", kernels.family},
                    {"embree_config", kernels.config}};
  return meta;
}

namespace {

// Micrometres and microradians: far below what the scene's float vertices hold, and short JSON.
double rounded(double value) { return std::round(value * 1e6) / 1e6; }

nlohmann::json vector_json(const Vec3& v) {
  return {rounded(v.x()), rounded(v.y()), rounded(v.z())};
}

// Appends a box pose's centre, heading (the yaw of its x axis) and rotation (a unit quaternion w,
// x, y, z) to the actor's columns, for a box pose in the world or (suffix "_rig") in the rig.
void add_box_pose(nlohmann::json& columns, const Pose& pose, const std::string& suffix) {
  const Eigen::Quaterniond q(pose.linear());
  columns["centre" + suffix].push_back(vector_json(pose.translation()));
  columns["heading" + suffix].push_back(rounded(yaw_of(pose)));
  columns["rotation" + suffix].push_back(
      {rounded(q.w()), rounded(q.x()), rounded(q.y()), rounded(q.z())});
}

// The licence of an asset pack's model ("pack/name").
std::string pack_licence(const CityConfig& city, const std::string& model) {
  for (const std::string& pack : city.asset_packs)
    for (const PackModel& m : asset_pack(pack))
      if (model_id(m) == model) return m.licence;
  return "";
}

// The box (in the actor's frame: pose = its centre there) holding every per-frame box.
Box3 extent_box(const Sequence& s, const Actor& actor, const std::vector<Box3>& boxes, int frames) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int f = 0; f < frames; ++f) {
    const Box3& box = boxes[std::size_t(f)];
    const Pose in_actor = actor.pose(s.time(f)).inverse() * box.pose;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 local((corner & 1 ? 0.5 : -0.5) * box.size.x(),
                       (corner & 2 ? 0.5 : -0.5) * box.size.y(),
                       (corner & 4 ? 0.5 : -0.5) * box.size.z());
      const Vec3 p = in_actor * local;
      lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    }
  }
  Box3 out;
  out.pose = Pose(Eigen::Translation3d((lo + hi) / 2)), out.size = hi - lo;
  return out;
}

}  // namespace

nlohmann::json actor_records(const Sequence& s, int frames, const std::string& classes) {
  const ClassTable& table = class_table(classes);
  const bool detailed = s.city.config.actors == ActorStyle::Detailed;
  nlohmann::json actors = nlohmann::json::array();
  for (std::size_t a = 0; a < s.city.actors.size(); ++a) {
    const Actor& actor = s.city.scene.actors[a];
    const ActorRecord& of = s.city.actors[a];
    nlohmann::json record = {{"instance", actor.instance},
                             {"kind", kind_name(of.kind)},
                             {"class", int(table.of_scene[std::size_t(actor_class(actor))])}};
    std::vector<Box3> boxes;
    for (int f = 0; f < frames; ++f) boxes.push_back(actor_box(actor, s.time(f)));
    const Box3 fixed = extent_box(s, actor, boxes, frames);
    if (detailed) {
      if (of.parked) record["parked"] = true;
      if (of.ego) record["ego"] = true;
      if (of.scripted) record["scripted"] = true;
      if (of.standing) record["standing"] = true;
      if (!of.family.empty()) record["family"] = of.family;
      if (!of.model.empty()) {
        record["model"] = of.model;
        record["licence"] = pack_licence(s.city.config, of.model);
      }
      record["fixed_box"] = {{"centre_in_actor", vector_json(fixed.pose.translation())},
                             {"size", vector_json(fixed.size)}};
    }
    for (int f = 0; f < frames; ++f) {  // one entry per frame in each column
      const double t = s.time(f);
      const Box3& box = boxes[std::size_t(f)];
      const Motion motion =
          actor_motion(actor, t, actor.pose(t).inverse() * box.pose.translation());
      add_box_pose(record, box.pose, "");
      add_box_pose(record, s.city.rig(t).inverse() * box.pose, "_rig");
      if (detailed)
        record["centre_fixed"].push_back(vector_json(actor.pose(t) * fixed.pose.translation()));
      record["size"].push_back(vector_json(box.size));
      record["velocity"].push_back(vector_json(motion.linear));
      record["angular_velocity"].push_back(vector_json(motion.angular));
    }
    actors.push_back(record);
  }
  return actors;
}

}  // namespace flowscape
