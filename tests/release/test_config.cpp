#include <algorithm>
#include <catch2/catch.hpp>
#include <map>
#include <string>

#include "flowscape/core/files.h"
#include "flowscape/layout/meta.h"
#include "flowscape/layout/split.h"
#include "flowscape/release/config.h"
#include "flowscape/release/options.h"
#include "flowscape/release/sequence.h"
#include "flowscape/release/writer.h"
#include "temp_dir.h"

using namespace flowscape;
namespace fs = std::filesystem;

TEST_CASE("shards share out the sequences exactly once") {
  ReleaseConfig config;
  config.shards = 3;
  std::vector<int> owners(64, 0);
  for (config.shard = 0; config.shard < 3; ++config.shard)
    for (const SequencePlan& plan : plan_sequences(config))
      if (in_shard(plan, config)) ++owners[plan.number];
  CHECK(std::all_of(owners.begin(), owners.end(), [](int n) { return n == 1; }));
}

TEST_CASE("release configs round-trip through JSON and bad values are named") {
  ReleaseConfig config;
  config.maps = 3, config.frames = 7, config.weathers = {"rain", "fog"}, config.cube = false;
  CHECK(to_json(release_config_from_json(to_json(config))) == to_json(config));
  CHECK_THROWS_WITH(release_config_from_json({{"maps", 9}}),
                    Catch::Contains("maps must be in 1..8"));
  CHECK_THROWS_WITH(release_config_from_json({{"frames", 1}}), Catch::Contains("frames"));
  CHECK_THROWS_WITH(release_config_from_json({{"spp", "many"}}), Catch::Contains("release config"));
  CHECK_THROWS_WITH(release_config_from_json({{"weathers", {"hail"}}}),
                    Catch::Contains("unknown weather preset \"hail\""));
  CHECK_THROWS_WITH(release_config_from_json({{"vehicles", 150}, {"pedestrians", 60}}),
                    Catch::Contains("vehicles + pedestrians"));
  CHECK_THROWS_WITH(
      release_config_from_json({{"vehicles", 120}, {"pedestrians", 60}, {"standing", 21}}),
      Catch::Contains("vehicles + pedestrians + standing must be in 0..200"));
  CHECK_THROWS_WITH(release_config_from_json({{"standing", -2}}), Catch::Contains("standing"));
  CHECK((ReleaseConfig{}.pedestrians == -1 && ReleaseConfig{}.standing == -1));  // the map's own
  // a release from before people stood had none
  CHECK(release_config_from_json(with_absent_keys({{"pedestrians", 80}})).standing == 0);
}

TEST_CASE("config sources: defaults, then --demo, then the config file, then the command line") {
  TempDir dir;
  const fs::path file = dir.path / "config.json";
  write_text(file, R"({"frames": 7, "spp": 3, "weathers": ["fog"]})");
  CHECK(to_json(resolve_config({})) == to_json(ReleaseConfig{}));
  const ReleaseConfig demo = resolve_config({true, {}, {}});
  CHECK((demo.maps == 1 && demo.sequences_per_map == 2 && demo.frames == 4 && demo.height == 128));
  CHECK(demo.weathers == std::vector<std::string>{"sunny", "rain"});
  const ReleaseConfig layered = resolve_config({true, file, {{"spp", 5}}});
  CHECK(layered.maps == 1);    // demo
  CHECK(layered.frames == 7);  // the file over the demo
  CHECK(layered.spp == 5);     // the command line over the file
  CHECK(layered.weathers == std::vector<std::string>{"fog"});
  CHECK(resolve_config({false, file, {}}).maps == 8);  // the defaults under the file
  write_text(file, R"({"frams": 3})");
  CHECK_THROWS_WITH(resolve_config({false, file, {}}),
                    Catch::Contains("config.json: release config: unknown key \"frams\" (did you "
                                    "mean \"frames\"?)"));
  write_text(file, R"({"weather": ["fog"]})");  // the flag is --weather, the key weathers
  CHECK_THROWS_WITH(resolve_config({false, file, {}}),
                    Catch::Contains("unknown key \"weather\" (did you mean \"weathers\"?)"));
  CHECK_THROWS_WITH(resolve_config({false, dir.path / "none.json", {}}),
                    Catch::Contains("none.json: file not found"));
  CHECK_THROWS_WITH(resolve_config({false, dir.path, {}}),
                    Catch::Contains(": is a folder, expected a file"));
  CHECK_THROWS_WITH(resolve_config({false, {}, {{"maps", 0}}}),
                    Catch::Contains("maps must be in 1..8"));
}

TEST_CASE("config numbers stay what they say: no wrapping, no truncation") {
  const auto refused = [](const char* json) {
    try {
      release_config_from_json(nlohmann::json::parse(json));
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK(refused(R"({"maps": 4294967297})") ==
        "release config: \"maps\" 4294967297 is out of range (-2147483648..2147483647)");
  CHECK(refused(R"({"frames": 4.7})") == "release config: \"frames\" must be an integer (got 4.7)");
  CHECK(refused(R"({"frames": 4.0})") == "release config: \"frames\" must be an integer (got 4.0)");
  CHECK(refused(R"({"seed": -1})") ==
        "release config: \"seed\" -1 is out of range (0..18446744073709551615)");
  CHECK(refused(R"({"spp": 2147483648})") ==
        "release config: \"spp\" 2147483648 is out of range (-2147483648..2147483647)");
  CHECK(refused(R"({"spp": -2147483649})") ==
        "release config: \"spp\" -2147483649 is out of range (-2147483648..2147483647)");
  CHECK(refused(R"({"seed": 18446744073709551615})") == "accepted");
  CHECK(refused(R"({"cube": 1})").find("type must be boolean") != std::string::npos);
  CHECK(refused(R"([1, 2])") == "release config: expected a JSON object");
}

TEST_CASE("shards given as K/N are parsed and checked") {
  ReleaseConfig config;
  parse_shard("2/5", config);
  CHECK((config.shard == 2 && config.shards == 5));
  CHECK(shard_plans(config).size() == 13);  // sequences 2, 7, ..., 62 of 64
  CHECK_THROWS_WITH(parse_shard("5/5", config), Catch::Contains("shard K/N needs 0 <= K < N"));
  CHECK_THROWS_WITH(parse_shard("two", config), Catch::Contains("--shard wants K/N"));
}

TEST_CASE("the resolution option takes the height or HEIGHTxWIDTH") {
  CHECK(parse_resolution("512") == 512);
  CHECK(parse_resolution("512x1024") == 512);
  CHECK_THROWS_WITH(parse_resolution("512x1000"),
                    Catch::Contains("twice as wide as high (512x1024)"));
  for (const char* bad : {"", "x", "abc", "64x", "x128", "64x128x", "-5x-10", "99999999999"})
    CHECK_THROWS_WITH(parse_resolution(bad), Catch::Contains("--resolution wants the height"));
}

TEST_CASE("outputs and flow gaps are checked like every other key") {
  const auto refused = [](const char* json, const char* message) {
    CHECK_THROWS_WITH(release_config_from_json(nlohmann::json::parse(json)),
                      Catch::Contains(message));
  };
  refused(R"({"outputs": ["normals"]})", "unknown output kind \"normals\" (pick from: all,");
  refused(R"({"outputs": ["depth"]})", "unknown output kind \"depth\"");
  refused(R"({"flow_gaps": [1, 2.5]})", "\"flow_gaps\" must be an integer (got 2.5)");
  refused(R"({"flow_gaps": 2})", "\"flow_gaps\" must be a list of integers");
  refused(R"({"flow_gaps": [2]})", "flow gaps must include 1");
  refused(R"({"flow_gaps": [1, 100], "frames": 100})", "flow gap 100 needs more than 100 frames");
  const ReleaseConfig c = release_config_from_json(
      nlohmann::json::parse(R"({"outputs": ["all"], "flow_gaps": [1, 3]})"));
  CHECK(release_layout(c).kinds.size() ==
        kOutputKinds.size() + 4);  // flow, valid and backward at 3
  CHECK(to_json(c)["flow_gaps"] == nlohmann::json{1, 3});
  CHECK(release_layout(ReleaseConfig{}).has("flow_backward"));
}

TEST_CASE("the rig is a preset or a rig file, named when it is neither") {
  CHECK_THROWS_WITH(release_config_from_json(nlohmann::json::parse(R"({"rig": "gopro"})")),
                    Catch::Contains("unknown rig \"gopro\" (flowscape, fisheye, woodscape"));
  CHECK_THROWS_WITH(release_config_from_json(nlohmann::json::parse(R"({"rig": "/nowhere.json"})")),
                    Catch::Contains("/nowhere.json: file not found"));
  const ReleaseConfig pal = release_config_from_json(nlohmann::json::parse(R"({"rig": "pal"})"));
  CHECK(release_layout(pal).cameras == std::vector<LayoutCamera>{{"pal", false}});
  CHECK(release_layout(ReleaseConfig{}).has_erp());
}

TEST_CASE("the flowscape rig's cameras are written as the ERP and the faces, others by name") {
  ReleaseConfig config;
  const Rig flowscape = release_rig(config);
  REQUIRE(flowscape.cameras.size() == 7);
  CHECK(view_of(flowscape, flowscape.cameras[0]).is_erp());
  CHECK(view_of(flowscape, flowscape.cameras[3]).face == Face::Back);
  config.cube = false;
  CHECK(release_rig(config).cameras.size() == 1);
  config.rig = "woodscape";
  const Rig woodscape = release_rig(config);
  CHECK(view_of(woodscape, woodscape.cameras[1]).camera == "rear");
}

TEST_CASE("the options table holds every key of config.json once, each read, written and checked") {
  std::vector<std::string> keys;
  for (const ReleaseOption& option : release_options()) keys.push_back(option.key);
  std::sort(keys.begin(), keys.end());
  CHECK(std::adjacent_find(keys.begin(), keys.end()) == keys.end());
  // a config.json flowscape 0.15 wrote before the table existed: every key read, and written back
  // as it was
  const nlohmann::json written =
      read_json(fs::path(FLOWSCAPE_SOURCE_DIR) / "tests/release/data/config_0.15.json");
  for (const auto& [key, value] : written.items())
    CHECK(std::binary_search(keys.begin(), keys.end(), key));
  nlohmann::json expected = written;  // and the keys added since, at their defaults
  for (const char* added : {"temporal", "edge_spp", "standing"})
    expected[added] = to_json(ReleaseConfig{})[added];
  CHECK(to_json(release_config_from_json(written)) == expected);
  for (const ReleaseOption& option : release_options()) {
    INFO(option.key);
    if (std::isfinite(option.max)) {  // one step past the top of its range is refused by name
      const bool whole = option_value(option, ReleaseConfig{}).is_number_integer();
      const nlohmann::json past = {{option.key, whole ? nlohmann::json(std::int64_t(option.max) + 1)
                                                      : nlohmann::json(option.max + 0.25)}};
      CHECK_THROWS_WITH(release_config_from_json(past),
                        Catch::Contains(std::string(option.key) + " must be in"));
    }
    if (!option.choices.empty())
      CHECK_THROWS_WITH(release_config_from_json({{option.key, "neither"}}),
                        Catch::Contains(std::string(option.key) + " must be "));
    CHECK((*option.flag != 0) == (option.form != OptionForm::None));
    CHECK(!std::string(option.help).empty());
  }
  // a list option's command-line text, and the errors that name its flag
  const auto option = [](const char* key) {
    return *std::find_if(release_options().begin(), release_options().end(),
                         [&](const ReleaseOption& o) { return o.key == std::string(key); });
  };
  CHECK(parse_list(option("flow_gaps"), "1,2,4") == nlohmann::json{1, 2, 4});
  CHECK(parse_list(option("outputs"), "none") == nlohmann::json::array());
  CHECK(parse_list(option("rig_mount"), "1,0,1.5,0,-10,0") ==
        nlohmann::json{1.0, 0.0, 1.5, 0.0, -10.0, 0.0});
  CHECK_THROWS_WITH(parse_list(option("rig_mount"), "1,2,3"),
                    Catch::Contains("--rig-mount wants x,y,z,yaw,pitch,roll"));
  CHECK_THROWS_WITH(parse_list(option("flow_gaps"), "1,b"), Catch::Contains("--flow-gaps wants"));
}

TEST_CASE("the sequence mix: every third turns, the others drive; free as before 0.9") {
  ReleaseConfig config;
  config.maps = 2, config.sequences_per_map = 4;
  std::vector<EgoRoute> routes;
  for (const SequencePlan& plan : plan_sequences(config))
    routes.push_back(sequence_spec(config, plan).city.ego_route);
  // numbers 2, 5: floor((n + 1) / 3) > floor(n / 3)
  const EgoRoute D = EgoRoute::Drive, T = EgoRoute::Turn;
  CHECK(routes == std::vector<EgoRoute>{D, D, T, D, D, T, D, D});
  config.ego_routes = "free";
  for (const SequencePlan& plan : plan_sequences(config)) {
    CHECK_FALSE(plan.turns);
    CHECK(sequence_spec(config, plan).city.ego_route == EgoRoute::Free);
  }
  CHECK_THROWS_WITH(release_config_from_json({{"ego_routes", "loop"}}),
                    Catch::Contains("ego_routes must be mix or free"));
  CHECK_THROWS_WITH(release_config_from_json({{"turn_share", 1.5}}),
                    Catch::Contains("turn_share must be in 0..1"));
}

namespace {

// A release whose config.json was written by `then` without `keys` (an older flowscape's) resumes
// with `then`, and a rerun with `now` is refused naming `changed`.
void check_resumes_as_before(ReleaseConfig then, const std::vector<std::string>& keys,
                             ReleaseConfig now, const std::string& changed) {
  TempDir dir;
  then.maps = now.maps = 1, then.sequences_per_map = now.sequences_per_map = 1;
  then.frames = now.frames = 2;
  nlohmann::json old = to_json(then);
  for (const std::string& key : keys) old.erase(key);
  write_text(dir.path / "config.json", old.dump());
  CHECK_NOTHROW(claim_release(then, dir.path, false));
  CHECK_THROWS_WITH(claim_release(now, dir.path, false), Catch::Contains(changed));
}

}  // namespace

TEST_CASE("a release of flowscape 0.8 (no ego_routes in config.json) resumes as free") {
  ReleaseConfig free;
  free.ego_routes = "free";
  check_resumes_as_before(free, {"ego_routes", "turn_share"}, ReleaseConfig{},
                          "ego_routes: \"free\" recorded, \"mix\" now");
}

TEST_CASE("a release of flowscape 0.16 (no edge_spp in config.json) resumes without edge samples") {
  CHECK(ReleaseConfig{}.edge_spp == 32);
  ReleaseConfig none;
  none.edge_spp = 0;
  check_resumes_as_before(none, {"edge_spp"}, ReleaseConfig{}, "edge_spp: 0 recorded, 32 now");
}

TEST_CASE("adaptive sampling's share is checked, and a release of 0.12 resumes as uniform") {
  CHECK(ReleaseConfig{}.adaptive == 0);
  for (const nlohmann::json& share : {nlohmann::json(1.5), nlohmann::json(-0.1)})
    CHECK_THROWS_WITH(release_config_from_json({{"adaptive", share}}),
                      Catch::Contains("adaptive must be in 0..1"));
  CHECK(release_config_from_json({{"adaptive", 0}}).adaptive == 0);
  ReleaseConfig adaptive;
  adaptive.adaptive = 0.25;
  check_resumes_as_before(ReleaseConfig{}, {"adaptive"}, adaptive,
                          "adaptive: 0.0 recorded, 0.25 now");
}
