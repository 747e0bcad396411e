#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <set>

#include "../temp_dir.h"
#include "flowscape/core/files.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/layout/layout.h"
#include "flowscape/layout/meta.h"
#include "flowscape/release/manifest.h"
#include "flowscape/release/scenario.h"
#include "flowscape/release/sequence.h"
#include "flowscape/release/writer.h"
#include "tiny_release.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

fs::path write_json(const fs::path& path, const nlohmann::json& json) {
  std::ofstream(path) << json.dump(1);
  return path;
}

// A release of the scenario files with the tiny release's sizes.
ReleaseConfig scenario_release(const std::vector<fs::path>& files) {
  ConfigSources sources;
  sources.scenarios = files;
  sources.command_line = {{"resolution", 16}, {"face_size", 8}, {"spp", 1}};
  return resolve_config(sources);
}

std::map<fs::path, std::string> files_under(const fs::path& dir) {
  std::map<fs::path, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().filename() != "meta.json")
      files[fs::relative(entry.path(), dir)] = file_bytes(entry.path());
  return files;
}

Pose from_row_major(const nlohmann::json& values) {
  Pose pose = Pose::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c)
      pose.matrix()(r, c) = values.at(std::size_t(4 * r + c)).get<double>();
  return pose;
}

double angle_between(const Mat3& a, const Mat3& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

}  // namespace

TEST_CASE("a scenario round-trips through JSON and names what is wrong") {
  TempDir dir;
  std::ofstream(dir.path / "walk.txt") << "0 0 0 1.6 0 0 0 1\n1 1 0 1.6 0 0 0 1\n";
  const nlohmann::json drone = {{"flowscape_scenario", 1},
                                {"name", "drone"},
                                {"world", {{"map", "downtown"}, {"seed", 7}}},
                                {"rig", "dual-fisheye"},
                                {"motion",
                                 {{"waypoints",
                                   {{{"position", {0, 0, 20}}, {"time", 0}},
                                    {{"position", {30, 5, 20}}, {"speed", 8}},
                                    {{"position", {60, 0, 22}}, {"time", 9}}}}}},
                                {"traffic", {{"vehicles", 30}, {"pedestrians", 10}}},
                                {"weather", "rain"},
                                {"time_of_day", "dusk"},
                                {"frames", 20}};
  const Scenario s = scenario_from_json(drone);
  CHECK(s.map == 0);
  REQUIRE(s.path);
  CHECK(s.path->waypoints.size() == 3);
  CHECK(to_json(scenario_from_json(to_json(s))) == to_json(s));
  const nlohmann::json walk = {
      {"flowscape_scenario", 1},
      {"world", {{"map", 4}}},
      {"motion",
       {{"pose_file", "walk.txt"},
        {"format", "tum"},
        {"origin", {{"position", {1, 2, 0}}, {"yaw_pitch_roll_degrees", {90, 0, 0}}}}}}};
  const Scenario replay = scenario_from_json(walk, dir.path);
  CHECK(replay.path->pose_file == dir.path / "walk.txt");
  CHECK(to_json(scenario_from_json(to_json(replay))) == to_json(replay));
  CHECK(replay.path->origin().linear().col(0).isApprox(Vec3::UnitY(), 1e-12));  // turned 90 left

  // a scenario another version recorded warns that a re-render may differ in bytes
  nlohmann::json old = drone;
  old["generator"] = "flowscape 0.9";
  CHECK_THAT(version_warning(scenario_from_json(old)),
             Catch::Contains("recorded by flowscape 0.9; this is flowscape 0.15") &&
                 Catch::Contains("may differ in bytes"));
  old["generator"] = kGeneratorVersion;
  CHECK(version_warning(scenario_from_json(old)).empty());
  CHECK(version_warning(s).empty());  // written by hand

  const auto fails = [&](nlohmann::json j, const std::string& says) {
    CHECK_THROWS_WITH(scenario_from_json(j, dir.path), Catch::Contains(says));
  };
  nlohmann::json bad = drone;
  bad["wether"] = "fog";
  fails(bad, "unknown key \"wether\" (did you mean \"weather\"?)");
  bad = drone;
  bad["motion"]["waypoints"] = {{{"position", {0, 0, 0}}, {"time", 0}}};
  fails(bad, "a path needs at least 2 waypoints");
  bad = drone;
  bad["motion"]["waypoints"][2]["time"] = 1;
  fails(bad, "waypoint 2: times must increase");
  bad = drone;
  bad["world"]["map"] = "downton";
  fails(bad, "no map \"downton\" (did you mean \"downtown\"?)");
  bad = drone;
  bad["frame_rate"] = 0;
  fails(bad, "\"frame_rate\" must be in 1..240");
  bad = drone;
  bad["motion"] = {{"route", "drive"}, {"lane_change_at", 2}};
  fails(bad, "\"lane_change_at\" is for the lane_change route");
  bad = drone;
  bad.erase("flowscape_scenario");
  fails(bad, "must say the schema version");
  bad = drone;
  bad["ego"] = "on";
  fails(bad, "has no ego vehicle under it");
  bad = walk;
  bad["motion"]["pose_file"] = "missing.txt";
  fails(bad, "missing.txt: no such pose file");
  bad = drone;
  bad["motion"]["route"] = "turn";
  fails(bad, "motion: give one of");
  bad = drone;
  bad["models"] = {{"car", "no_such_car.glb"}};
  fails(bad, "no_such_car.glb: no such model file");
  bad["models"] = {{"tram", "walk.txt"}};
  fails(bad, "models: ");
  nlohmann::json with_model = drone;
  with_model["models"] = {
      {"car", "walk.txt"}};  // found beside the scenario (a file is enough here)
  CHECK(scenario_from_json(with_model, dir.path).models.at("car") ==
        (dir.path / "walk.txt").string());
}

TEST_CASE("weather by parameters: set exactly over the seed's preset, named when wrong") {
  const nlohmann::json foggy_dusk = {
      {"flowscape_scenario", 1},
      {"world", {{"map", "rural"}, {"seed", 9}}},
      {"weather",
       {{"preset", "cloud"}, {"fog_density", 0.03}, {"sun_elevation", 4.5}, {"wind", 0.2}}},
      {"traffic", {{"vehicles", 2}, {"pedestrians", 2}}},
      {"frames", 2}};
  const Scenario s = scenario_from_json(foggy_dusk);
  CHECK(s.weather == "cloud");
  CHECK(to_json(scenario_from_json(to_json(s))) == to_json(s));
  ReleaseConfig config = tiny_release_config(1, 2);
  const Sequence sequence = make_sequence(sequence_spec(config, s));
  CHECK(sequence.weather.preset == "cloud");
  CHECK(sequence.weather.fog_density == 0.03);
  CHECK(sequence.weather.sun_elevation == 4.5);
  CHECK(sequence.weather.wind == 0.2);
  // what the parameters leave alone is the seed's variant of the preset, as without them
  nlohmann::json plain = foggy_dusk;
  plain["weather"] = "cloud";
  const Weather varied = make_sequence(sequence_spec(config, scenario_from_json(plain))).weather;
  CHECK(sequence.weather.cloudiness == varied.cloudiness);
  CHECK(sequence.weather.sun_azimuth == varied.sun_azimuth);
  nlohmann::json bad = foggy_dusk;
  bad["weather"]["fog_densty"] = 0.1;
  CHECK_THROWS_WITH(
      scenario_from_json(bad),
      Catch::Contains("weather: unknown parameter \"fog_densty\" (did you mean \"fog_density\"?)"));
  bad = foggy_dusk;
  bad["weather"]["fog_density"] = 7;
  CHECK_THROWS_WITH(scenario_from_json(bad),
                    Catch::Contains("scenario: weather: ") && Catch::Contains("fog_density"));
}

TEST_CASE("a scenario's people on foot: the map's own unless given, none where recorded before") {
  const ReleaseConfig config;
  const auto city_of = [&](const nlohmann::json& traffic, const char* generator = nullptr) {
    nlohmann::json j = {{"flowscape_scenario", 1}, {"world", {{"map", "rural"}, {"seed", 1}}}};
    if (!traffic.is_null()) j["traffic"] = traffic;
    if (generator) j["generator"] = generator;
    return sequence_spec(config, scenario_from_json(j)).city;
  };
  const StreetLife rural = street_life(3);
  CHECK(city_of(nullptr).pedestrians == rural.walking);
  CHECK(city_of(nullptr).standing == rural.standing);
  // standing in the map's proportion to the walkers given: 16 x 3 / 8
  CHECK(city_of({{"pedestrians", 16}}).standing == 6);
  CHECK(city_of({{"pedestrians", 16}, {"standing", 2}}).standing == 2);
  CHECK(city_of({{"vehicles", 120}, {"pedestrians", 80}}, "flowscape 0.19.0").standing == 0);
  CHECK_THROWS_WITH(scenario_from_json({{"flowscape_scenario", 1},
                                        {"traffic", {{"pedestrians", 60}, {"standing", 30}}}}),
                    Catch::Contains("vehicles + pedestrians + standing"));
}

TEST_CASE("a built-in map's sequence rendered from its recorded scenario has the same bytes") {
  TempDir dir;
  ReleaseConfig config = tiny_release_config(2, 2);
  config.ego_routes = "mix", config.turn_share = 0.5;  // one drives, one turns
  write_release(config, dir.path / "maps", false);
  std::vector<fs::path> files;
  for (const char* scene : {"map00_seq00", "map00_seq01"}) {
    const nlohmann::json scenario = read_meta(sequence_dir(dir.path / "maps", scene)).scenario;
    REQUIRE(scenario.is_object());
    files.push_back(write_json(dir.path / (std::string(scene) + ".json"), scenario));
  }
  CHECK(read_json(files[1])["motion"]["route"] == "turn");
  ReleaseConfig from_scenarios = scenario_release(files);
  from_scenarios.vehicles = config.vehicles, from_scenarios.pedestrians = config.pedestrians;
  from_scenarios.weathers = config.weathers, from_scenarios.seed = config.seed;
  write_release(from_scenarios, dir.path / "scenarios", false);
  for (const char* scene : {"map00_seq00", "map00_seq01"}) {
    const auto before = files_under(sequence_dir(dir.path / "maps", scene));
    const auto after = files_under(sequence_dir(dir.path / "scenarios", scene));
    CHECK(before.size() >= 20);  // colour, flow both ways, masks, ids, depth... of 2 frames
    CHECK(before.size() == after.size());
    CHECK(before == after);  // every image, flow and mask byte
  }
}

TEST_CASE(
    "a rig's own path: waypoints flown, TUM, KITTI and COLMAP files replayed, as meta.json "
    "records") {
  TempDir dir;
  const nlohmann::json drone = {{"flowscape_scenario", 1},
                                {"world", {{"map", "downtown"}, {"seed", 3}}},
                                {"rig", "fisheye"},
                                {"motion",
                                 {{"waypoints",
                                   {{{"position", {0, 0, 20}}, {"time", 0}},
                                    {{"position", {1, 0.5, 20.2}}, {"time", 0.05}},
                                    {{"position", {2, 0, 20}}, {"time", 0.1}}}}}},
                                {"traffic", {{"vehicles", 4}, {"pedestrians", 2}}},
                                {"frames", 3}};
  const fs::path drone_file = write_json(dir.path / "drone.json", drone);
  // a handheld camera's TUM file, its poses at the frame times, given for the fisheye's own frame
  // the same as KITTI's 3 x 4 camera -> world rows at 30 Hz, and COLMAP's world -> camera
  // quaternion (w first) and translation, ordered by image name
  std::ofstream tum(dir.path / "walk.txt"), kitti(dir.path / "kitti.txt"),
      colmap(dir.path / "images.txt");
  std::vector<Pose> camera_poses;
  char line[300];
  for (int k = 0; k < 4; ++k) {
    Pose pose = Pose::Identity();
    pose.linear() = Eigen::AngleAxisd(0.1 * k, Vec3(0, 1, 0.2).normalized()).toRotationMatrix() *
                    look(10, 0, 0);
    pose.translation() = Vec3(0.4 * k, 0.05 * k, 1.6);
    camera_poses.push_back(pose);
    const Eigen::Quaterniond q(pose.linear());
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", k / 30.0,
                  pose.translation().x(), pose.translation().y(), pose.translation().z(), q.x(),
                  q.y(), q.z(), q.w());
    tum << line;
    for (int i = 0; i < 12; ++i)
      kitti << (i ? " " : "") << std::setprecision(17) << pose.matrix()(i / 4, i % 4);
    kitti << "\n";
    const Pose inverse = pose.inverse();
    const Eigen::Quaterniond w(inverse.linear());
    std::snprintf(line, sizeof line,
                  "%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g 1 img_%d.png\n\n", k + 1, w.w(),
                  w.x(), w.y(), w.z(), inverse.translation().x(), inverse.translation().y(),
                  inverse.translation().z(), k);
    colmap << line;
  }
  tum.close(), kitti.close(), colmap.close();
  nlohmann::json walk = drone;
  walk["motion"] = {{"pose_file", "walk.txt"}, {"poses_of", "front"}};
  walk["world"]["map"] = "suburb";
  const fs::path walk_file = write_json(dir.path / "walk.json", walk);
  std::vector<fs::path> files = {drone_file, walk_file};
  for (const char* format : {"kitti", "colmap"}) {
    walk["motion"] = {{"pose_file", format == std::string("kitti") ? "kitti.txt" : "images.txt"},
                      {"format", format},
                      {"rate", 30},
                      {"poses_of", "front"},
                      {"world_frame", "z_up"}};  // the file's world as ours, whatever the format
    files.push_back(write_json(dir.path / (std::string(format) + ".json"), walk));
  }

  ReleaseConfig config = scenario_release(files);
  config.vehicles = 4, config.pedestrians = 2;
  write_release(config, dir.path / "out", false);
  const SequenceMeta flown = read_meta(sequence_dir(dir.path / "out", "map00_seq00"));
  const PoseTrack path = waypoint_track(scenario_from_json(drone).path->waypoints);
  REQUIRE(flown.poses.size() == 3);
  for (int f = 0; f < 3; ++f) {
    CHECK((flown.poses[f].translation() - path(f / 30.0).translation()).norm() < 1e-9);
    CHECK(angle_between(flown.poses[f].linear(), path(f / 30.0).linear()) < 1e-9);
  }
  CHECK((flown.poses[0].translation() - Vec3(0, 0, 20)).norm() < 1e-3);  // waypoint 0 at t = 0
  // the fisheye's poses in meta.json are the file's, in all three formats
  for (const char* sequence : {"map01_seq00", "map01_seq01", "map01_seq02"}) {
    INFO(sequence);
    const SequenceMeta walked = read_meta(sequence_dir(dir.path / "out", sequence));
    const nlohmann::json& view = walked.views.at("cameras/front");
    for (int f = 0; f < 3; ++f) {
      const Pose recorded = from_row_major(view.at("poses")[f]);
      CHECK((recorded.translation() - camera_poses[f].translation()).norm() < 1e-9);
      CHECK(angle_between(recorded.linear(), camera_poses[f].linear()) < 1e-9);
    }
    CHECK(walked.scenario.at("motion").at("poses_of") == "front");
  }
  // a path shorter than the sequence is named
  ReleaseConfig longer = config;
  longer.frames = 60;
  CHECK_THROWS_WITH(write_release(longer, dir.path / "long", false),
                    Catch::Contains("drone.json: scenario: the waypoints end at 0.1"));
}

TEST_CASE("a user's world with its classes, scripted actors and a frame rate of the scenario's") {
  TempDir dir;
  const fs::path square = fs::path(FLOWSCAPE_SOURCE_DIR) / "examples/worlds/square.gltf";
  const nlohmann::json user = {
      {"flowscape_scenario", 1},
      {"name", "square"},
      {"world",
       {{"file", square.string()},
        {"units", "metres"},
        {"up", "y"},
        {"seed", 3},
        {"classes", nlohmann::json::array({nlohmann::json::array({"road*", "Road"}),
                                           nlohmann::json::array({"sidewalk*", "SideWalk"}),
                                           nlohmann::json::array({"building*", "Building"}),
                                           nlohmann::json::array({"tree*", "vegetation"}),
                                           nlohmann::json::array({"*", "Terrain"})})}}},
      {"motion",
       {{"waypoints",
         {{{"position", {-6, 9, 1.6}}, {"time", 0}}, {{"position", {0, 7.5, 1.6}}, {"time", 4}}}}}},
      {"actors",
       {{{"kind", "car"},
         {"waypoints", {{{"position", {-30, -2, 0}}}, {{"position", {30, -2, 0}}, {"speed", 10}}}}},
        {{"kind", "pedestrian"},
         {"waypoints",
          {{{"position", {8, 6, 0.12}}}, {{"position", {-6, 6, 0.12}}, {"speed", 1.4}}}}}}},
      {"frame_rate", 10},
      {"frames", 3}};
  const Scenario s = scenario_from_json(user);
  CHECK(s.map == kUserWorldMap);
  CHECK(to_json(scenario_from_json(to_json(s))) == to_json(s));
  ReleaseConfig config = scenario_release({write_json(dir.path / "square.json", user)});
  config.height = 32, config.cube = false;
  write_release(config, dir.path / "out", false);
  const fs::path seq = sequence_dir(dir.path / "out", "map08_seq00");
  const SequenceMeta meta = read_meta(seq);
  CHECK(meta.map_name == "user_world");
  CHECK(meta.fps == 10);
  // two waypoints: a straight line at constant speed, frame f at f / 10 s
  for (int f = 0; f < 3; ++f)
    CHECK((meta.poses[f].translation() - Vec3(-6 + 6 * f / 40.0, 9 - 1.5 * f / 40.0, 1.6)).norm() <
          1e-9);
  // the car covers 10 m/s x 0.1 s between frames, the walker 0.14 m
  std::map<std::string, nlohmann::json> scripted;
  for (const nlohmann::json& actor : meta.actors)
    if (actor.value("scripted", false)) scripted[actor.at("kind")] = actor;
  REQUIRE(scripted.size() == 2);
  for (const auto& [kind, step] :
       {std::pair<std::string, double>{"car", 1.0}, {"pedestrian", -0.14}})
    for (int f = 0; f < 2; ++f) {
      const nlohmann::json& centre = scripted[kind].at("centre_fixed");
      CHECK(centre[f + 1][0].get<double>() - centre[f][0].get<double>() ==
            Approx(step).margin(1e-5));
      CHECK(centre[f + 1][1].get<double>() == Approx(centre[f][1].get<double>()).margin(1e-5));
    }
  // the world's classes, as the patterns give them, in the ERP's semantics
  std::set<int> seen;
  const Image<std::uint8_t> semantic =
      read_image<std::uint8_t>(seq / frame_file(output_kind("semantic"), std::nullopt, 0));
  for (std::uint8_t id : semantic.data) seen.insert(id);
  for (const SemanticClass cls :
       {SemanticClass::Road, SemanticClass::SideWalk, SemanticClass::Building,
        SemanticClass::Vegetation, SemanticClass::Sky, SemanticClass::Vehicles})
    CHECK(seen.count(int(cls)) == 1);

  // what a user world refuses, one line each
  const auto fails = [&](nlohmann::json j, const std::string& says) {
    CHECK_THROWS_WITH(scenario_from_json(j), Catch::Contains(says));
  };
  nlohmann::json bad = user;
  bad["world"].erase("units");
  fails(bad, "a world file needs its \"units\"");
  bad = user;
  bad["world"]["units"] = "metre";
  fails(bad, "\"metre\" is not metres, centimetres");
  bad = user;
  bad["world"]["classes"] = nlohmann::json::array({nlohmann::json::array({"road*", "Rood"})});
  fails(bad, "world classes 0: unknown class \"Rood\"");
  bad = user;
  bad["traffic"] = {{"vehicles", 4}};
  fails(bad, "a world file has no roads or sidewalks for traffic");
  bad = user;
  bad["motion"] = {{"route", "drive"}};
  fails(bad, "a world file has no roads for an ego vehicle");
  bad = user;
  bad["actors"][0]["model"] = "missing.glb";
  fails(bad, "missing.glb: no such model file");
  bad = user;
  bad["actors"][1]["kind"] = "rider";
  fails(bad, "actor 1: a rider comes with its bike");
  bad = user;
  bad["actors"][0]["waypoints"] = {{{"position", {0, 0, 0}}}};
  fails(bad, "actor 0: a path needs at least 2 waypoints");
  bad = user;
  bad["frame_rate"] = 500;
  fails(bad, "\"frame_rate\" must be in 1..240");
}

TEST_CASE("a KITTI pose file drives the rig along its camera's view with the format's preset") {
  TempDir dir;
  // a KITTI camera (x right, y down, z forward) in its y-down world driving a left curve: its
  // heading turns about the world's up, -y
  std::ofstream kitti(dir.path / "00.txt");
  std::vector<Pose> file_poses;
  for (int k = 0; k < 12; ++k) {
    const double heading = 0.05 * k;
    Pose pose = Pose::Identity();
    pose.linear() = Eigen::AngleAxisd(-heading, Vec3::UnitY()).toRotationMatrix();  // left turn
    pose.translation() = Vec3(-std::sin(heading) * 4 * k, 0.02 * k, std::cos(heading) * 4 * k);
    file_poses.push_back(pose);
    for (int i = 0; i < 12; ++i)
      kitti << (i ? " " : "") << std::setprecision(17) << pose.matrix()(i / 4, i % 4);
    kitti << "\n";
  }
  kitti.close();
  const nlohmann::json scenario = {{"flowscape_scenario", 1},
                                   {"world", {{"map", 0}}},
                                   {"motion", {{"pose_file", "00.txt"}, {"format", "kitti"}}},
                                   {"frames", 20}};
  const Scenario s = scenario_from_json(scenario, dir.path);
  CHECK(s.path->poses_of == "camera_frame");
  CHECK(s.path->world.frame == "y_down");
  CHECK(to_json(scenario_from_json(to_json(s))) == to_json(s));  // recorded with its presets
  const PoseTrack rig = rig_path_track(s, Rig{});
  for (int k = 0; k < 12; ++k) {
    INFO(k);
    // the file's z (the camera's view) in our world, by the y-down world's axes: our x = its z,
    // our y = -its x, our z = -its y
    const Vec3 view = file_poses[k].linear().col(2), place = file_poses[k].translation();
    const Vec3 expected_forward(view.z(), -view.x(), -view.y()),
        expected_place(place.z(), -place.x(), -place.y());
    const Pose at = rig(k / 10.0);                                 // KITTI's 10 Hz
    CHECK((at.linear().col(0) - expected_forward).norm() < 1e-9);  // the rig's forward axis
    CHECK((at.linear().col(2) - Vec3::UnitZ()).norm() < 1e-9);     // upright
    CHECK((at.translation() - expected_place).norm() < 1e-9);
  }
  // the road turns left in our world: the heading grows counter-clockwise seen from above
  CHECK(rig(1.1).linear().col(0).y() > 0);
}

TEST_CASE("a scenario's paths are its folder's, recorded absolute; its numbers exactly as given") {
  TempDir dir;
  fs::create_directories(dir.path / "scenarios" / "rigs");
  std::ofstream(dir.path / "scenarios" / "rigs" / "front.json")
      << R"({"name": "front", "cameras": [{"name": "front", "model": "pinhole",
            "parameters": {"width": 32, "height": 24, "K": [[16, 0, 15.5], [0, 16, 11.5], [0, 0, 1]]},
            "mount": {"position": [1, 0, 0], "yaw_pitch_roll_degrees": [0, 0, 0]}}]})";
  const nlohmann::json scenario = {{"flowscape_scenario", 1},
                                   {"world", {{"map", 1}, {"seed", 3}}},
                                   {"rig", "rigs/front.json"},
                                   {"frames", 4}};
  const fs::path file = write_json(dir.path / "scenarios" / "s.json", scenario);
  const fs::path elsewhere = fs::current_path();
  fs::current_path(dir.path);  // run from another folder than the scenario's
  const Scenario s = read_scenario(file);
  fs::current_path(elsewhere);
  CHECK(s.rig == (dir.path / "scenarios" / "rigs" / "front.json").string());
  CHECK(fs::path(to_json(s).at("rig").get<std::string>()).is_absolute());

  const auto refused = [&](const char* key, const nlohmann::json& value, const std::string& says) {
    nlohmann::json bad = scenario;
    bad.erase("rig");
    if (std::string(key) == "seed")
      bad["world"]["seed"] = value;
    else if (std::string(key) == "vehicles")
      bad["traffic"] = {{"vehicles", value}};
    else if (std::string(key) == "units")
      bad["world"] = {
          {"file", "s.json"}, {"units", value}, {"up", "y"}, {"classes", {{"*", "Road"}}}};
    else
      bad[key] = value;
    CHECK_THROWS_WITH(read_scenario(write_json(dir.path / "scenarios" / "bad.json", bad)),
                      Catch::Contains("bad.json: scenario: ") && Catch::Contains(says));
  };
  refused("frames", 4294967298.0, "\"frames\" must be an integer (got 4294967298.0)");
  refused("frames", 4294967298u, "\"frames\" 4294967298 is out of range (2..999999)");
  refused("frames", 2.9, "\"frames\" must be an integer (got 2.9)");
  refused("vehicles", 4294967297u, "traffic: \"vehicles\" 4294967297 is out of range (0..200)");
  refused("seed", -1, "world: \"seed\" -1 is out of range");
  refused("units", 1e-300, "world \"units\" must be 1e-6..1e6 metres per unit");
  nlohmann::json far = scenario;
  far["rig"] = "rigs/missing.json";
  CHECK_THROWS_WITH(read_scenario(write_json(dir.path / "scenarios" / "far.json", far)),
                    Catch::Contains("rigs/missing.json: no such rig file"));
}
