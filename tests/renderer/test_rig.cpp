#include <catch2/catch.hpp>

#include "flowscape/renderer/rig.h"

using namespace flowscape;

TEST_CASE("look turns the forward camera by yaw, pitch and roll") {
  // camera axes as columns: x right, y down, z forward, in the rig (x forward, y left, z up)
  const Mat3 ahead = look(0, 0, 0);
  CHECK(ahead.col(2).isApprox(Vec3::UnitX()));
  CHECK(ahead.col(0).isApprox(-Vec3::UnitY()));
  CHECK(ahead.col(1).isApprox(-Vec3::UnitZ()));
  CHECK(look(90, 0, 0).col(2).isApprox(Vec3::UnitY(), 1e-12));  // yaw left
  CHECK(look(0, 90, 0).col(2).isApprox(Vec3::UnitZ(), 1e-12));  // pitch up
  CHECK(look(0, -30, 0).col(2).isApprox(Vec3(std::cos(kPi / 6), 0, -0.5), 1e-12));
  CHECK(look(0, 0, 90).col(0).isApprox(-Vec3::UnitZ(), 1e-12));  // roll: right turns down
  for (const Mat3& m : {look(12, -34, 56), look(-170, 80, -5)}) {
    CHECK((m.transpose() * m - Mat3::Identity()).norm() < 1e-12);
    CHECK(m.determinant() == Approx(1));
  }
}

TEST_CASE("a rig file reads back what it says and names what is wrong") {
  const nlohmann::json file = {
      {"name", "test rig"},
      {"cameras",
       {{{"name", "left_fisheye"},
         {"model", "equidistant"},
         {"parameters",
          {{"width", 64},
           {"height", 64},
           {"K", {{18, 0, 31.5}, {0, 18, 31.5}, {0, 0, 1}}},
           {"max_angle_degrees", 95}}},
         {"mount", {{"position", {0.5, 1, -0.2}}, {"yaw_pitch_roll_degrees", {90, -10, 0}}}}},
        {{"name", "pano"},
         {"model", "equirectangular"},
         {"parameters", {{"height", 16}}},
         {"mount", {{"position", {0, 0, 1}}}}}}}};
  const Rig rig = rig_from_json(file);
  REQUIRE(rig.cameras.size() == 2);
  CHECK(rig.cameras[0].position == Vec3(0.5, 1, -0.2));
  CHECK(rig.cameras[0].projection.rotation.isApprox(look(90, -10, 0)));
  CHECK(rig.cameras[1].projection.kind == Projection::Kind::Equirectangular);
  CHECK(rig.cameras[1].projection.width == 32);
  const Rig again = rig_from_json(to_json(rig));  // camera_to_rig rows instead of the angles
  CHECK(to_json(again) == to_json(rig));
  CHECK(rig.cameras[0].readout.global());
  CHECK_FALSE(to_json(rig)["cameras"][0].contains("rolling_shutter"));
  nlohmann::json rolling = file;
  rolling["cameras"][0]["rolling_shutter"] = {{"readout_ms", 25}, {"lines", "columns"}};
  const Rig read = rig_from_json(rolling);
  CHECK(read.cameras[0].readout.seconds == Approx(0.025));
  CHECK(read.cameras[0].readout.columns);
  CHECK(rig_from_json(to_json(read)).cameras[0].readout.seconds == read.cameras[0].readout.seconds);
  CHECK(again.cameras[0].mount().matrix().isApprox(rig.cameras[0].mount().matrix()));

  const auto refused = [&](const std::function<void(nlohmann::json&)>& change,
                           const std::string& message) {
    nlohmann::json bad = file;
    change(bad);
    CHECK_THROWS_WITH(rig_from_json(bad), Catch::Contains(message));
  };
  refused([](nlohmann::json& j) { j["cameras"][1]["name"] = "left_fisheye"; },
          "two cameras are named \"left_fisheye\"");
  refused([](nlohmann::json& j) { j["cameras"][0]["name"] = "Left Fisheye"; },
          "camera names are lower-case letters");
  refused([](nlohmann::json& j) { j["cameras"][0]["model"] = "fishey"; },
          "camera \"left_fisheye\": unknown camera model \"fishey\"");
  refused([](nlohmann::json& j) { j["cameras"][0]["model"] = "omni"; },
          "camera model \"omni\" (Kalibr's unified omnidirectional (Mei) model) is not one");
  refused([](nlohmann::json& j) { j["cameras"][0]["parameters"].erase("K"); },
          "camera \"left_fisheye\": lens parameter \"K\"");
  refused(
      [](nlohmann::json& j) {
        j["cameras"][0]["mount"] = {{"position", {0, 0, 0}},
                                    {"camera_to_rig", {{1, 0, 0}, {0, 1, 0}, {0, 0, 2}}}};
      },
      "camera_to_rig must be a rotation");
  refused(
      [](nlohmann::json& j) {
        j["cameras"][1]["mount"]["yaw_pitch_roll_degrees"] = {1, 0, 0};
      },
      "an equirectangular camera keeps the rig's axes");
  refused(
      [](nlohmann::json& j) {
        j["cameras"][1]["rolling_shutter"] = {{"readout_ms", 20}};
      },
      "an equirectangular camera has no rolling shutter");
  refused(
      [](nlohmann::json& j) {
        j["cameras"][0]["rolling_shutter"] = {{"readout_ms", 0}};
      },
      "\"readout_ms\" must be a number in (0, 1000]");
  refused(
      [](nlohmann::json& j) {
        j["cameras"][0]["rolling_shutter"] = {{"readout_ms", 20}, {"lines", "diagonal"}};
      },
      "\"lines\" must be \"rows\" or \"columns\"");
  refused(
      [](nlohmann::json& j) {
        j["cameras"][0]["rolling_shutter"] = {{"readout", 20}};
      },
      "rolling_shutter: unknown key \"readout\"");
  // a new user's slips (issue 35, point 1): each refused by name, the intended key suggested
  refused(
      [](nlohmann::json& j) {
        j["cameras"][0]["mount"] = {{"positon", {0.5, 1, -0.2}},
                                    {"yaw_pitch_roll_degrees", {90, -10, 0}}};
      },
      "camera \"left_fisheye\": mount: unknown key \"positon\" (did you mean \"position\"?)");
  refused(
      [](nlohmann::json& j) {
        j["cameras"][0]["mount"] = {{"position", {0.5, 1, -0.2}},
                                    {"yaw_pitch_roll_deg", {90, -10, 0}}};
      },
      "unknown key \"yaw_pitch_roll_deg\" (did you mean \"yaw_pitch_roll_degrees\"?)");
  refused(
      [](nlohmann::json& j) {
        j["cameras"][0]["parameters"]["dist_coeffs"] = {0, 0, 0, 0};
      },
      "lens parameters: unknown key \"dist_coeffs\" (did you mean \"D\"?)");
  refused([](nlohmann::json& j) { j["cameras"][0]["parameters"]["max_angle_degree"] = 95; },
          "unknown key \"max_angle_degree\" (did you mean \"max_angle_degrees\"?)");
  refused([](nlohmann::json& j) { j["cameras"][0].erase("mount"); },
          "camera \"left_fisheye\": needs a \"mount\"");
  refused([](nlohmann::json& j) { j["cameras"][0]["mount"].erase("yaw_pitch_roll_degrees"); },
          "mount needs a rotation");
  refused([](nlohmann::json& j) { j["cameras"][0]["mount"].erase("position"); },
          "mount needs a \"position\"");
  refused([](nlohmann::json& j) { j["cameras"][0]["modle"] = "equidistant"; },
          "unknown key \"modle\" (did you mean \"model\"?)");
  refused([](nlohmann::json& j) { j["camera"] = j["cameras"]; },
          "rig: unknown key \"camera\" (did you mean \"cameras\"?)");
  refused([](nlohmann::json& j) { j["cameras"] = nlohmann::json::array(); },
          "\"cameras\" must list 1 to 16 cameras");
  CHECK_THROWS_WITH(rig_preset("gopro", 64), Catch::Contains("unknown rig \"gopro\""));
}

TEST_CASE("a calibration's own names: OpenCV's fisheye model, a flat K as FileStorage writes it") {
  // issue 35, point 2: both were refused
  const nlohmann::json rows = {{18, 0, 31.5}, {0, 18, 31.5}, {0, 0, 1}};
  const nlohmann::json flat = {18, 0, 31.5, 0, 18, 31.5, 0, 0, 1};
  const auto camera = [](const std::string& model, const nlohmann::json& k) {
    return nlohmann::json{
        {"name", "front"},
        {"model", model},
        {"parameters",
         {{"width", 64},
          {"height", 64},
          {"K", k},
          {"D", {0.01, 0, 0, 0}},
          {"max_angle_degrees", 95}}},
        {"mount", {{"position", {0, 0, 0}}, {"yaw_pitch_roll_degrees", {0, 0, 0}}}}};
  };
  const Rig opencv = rig_from_json({{"cameras", {camera("fisheye", flat)}}});
  const Rig ours = rig_from_json({{"cameras", {camera("kannala_brandt", rows)}}});
  CHECK(opencv.cameras[0].projection.lens->model() == "kannala_brandt");
  CHECK(to_json(opencv) == to_json(ours));  // read back in our names: the same camera
  const Vec2 pixel(10.25, 40.5);
  CHECK(opencv.cameras[0].projection.ray(pixel).isApprox(ours.cameras[0].projection.ray(pixel)));
  nlohmann::json radtan = camera("plumb_bob", flat);  // Kalibr's four coefficients: k3 = 0
  radtan["parameters"].erase("max_angle_degrees");
  const Rig pinhole = rig_from_json({{"cameras", {radtan}}});
  CHECK(pinhole.cameras[0].projection.lens->model() == "pinhole");
  CHECK(to_json(pinhole)["cameras"][0]["parameters"]["D"] ==
        nlohmann::json{0.01, 0.0, 0.0, 0.0, 0.0});
}

TEST_CASE("the presets hold the cameras and image sizes they say") {
  CHECK(rig_preset("fisheye", 64).cameras.size() == 1);
  CHECK(rig_preset("fisheye", 64).cameras[0].projection.lens->model() == "kannala_brandt");
  const Rig wood = rig_preset("woodscape", 64);
  REQUIRE(wood.cameras.size() == 4);
  CHECK((wood.cameras[0].projection.width == 80 && wood.cameras[0].projection.height == 60));
  CHECK(wood.cameras[1].projection.rotation.col(2).x() < -0.9);  // the rear one looks back
  const Rig pal = rig_preset("pal", 64);
  CHECK(pal.cameras[0].projection.rotation.col(2).isApprox(Vec3::UnitZ(), 1e-12));  // axis up
  CHECK(pal.cameras[0].position.z() > 0);                                           // on a mast
  const Rig dual = rig_preset("dual-fisheye", 32);
  CHECK((dual.cameras[0].projection.width == 64 && dual.cameras[0].projection.height == 32));
}

TEST_CASE("a camera off the rig's origin moves with the rig's rotation (its lever arm)") {
  const RigCamera camera{"side", Projection::of_lens(kannala_brandt_200(16), look(0, 0, 0)),
                         Vec3(2, 0, 0)};
  TruthRequest request;
  request.pair.rig = Pose(Eigen::Translation3d(10, 0, 0));
  request.pair.next_rig =
      Pose(Eigen::Translation3d(10, 0, 0) * Eigen::AngleAxisd(kPi / 2, Vec3::UnitZ()));
  request.more = {{0.5, Pose(Eigen::AngleAxisd(kPi, Vec3::UnitZ()))}};
  const TruthRequest moved = at_camera(request, camera);
  CHECK(moved.pair.rig.translation().isApprox(Vec3(12, 0, 0)));
  CHECK(moved.pair.next_rig.translation().isApprox(Vec3(10, 2, 0)));  // turned left: now at +y
  CHECK(moved.more[0].rig.translation().isApprox(Vec3(-2, 0, 0)));
  CHECK(moved.pair.next_rig.linear().isApprox(request.pair.next_rig.linear()));
  CHECK_FALSE(moved.track);
  // a track moves the same way, and the camera's readout comes with it
  RigCamera rolling = camera;
  rolling.readout = {0.02, true};
  request.track = [](double t) { return Pose(Eigen::AngleAxisd(kPi / 2 * t, Vec3::UnitZ())); };
  const TruthRequest on_track = at_camera(request, rolling);
  CHECK(on_track.track(1).translation().isApprox(Vec3(0, 2, 0)));
  CHECK(on_track.readout.seconds == 0.02);
  CHECK(on_track.readout.columns);
}

TEST_CASE("the flowscape rig is seven cameras at the origin: the ERP and the cube's faces") {
  const Rig rig = flowscape_rig(16, 8);
  REQUIRE(rig.cameras.size() == 7);
  CHECK(rig.flowscape);
  CHECK(rig.has_cube_faces());
  CHECK(rig.cameras[0].name == "erp");
  CHECK(rig.cameras[0].projection.wraps_around());
  CHECK((rig.cameras[0].projection.width == 32 && rig.cameras[0].projection.height == 16));
  // the ERP's centre column looks forward; each face's centre looks along its axis (design.md)
  CHECK(rig.cameras[0].projection.ray(Vec2(16, 8)).normalized().isApprox(Vec3::UnitX(), 1e-12));
  const std::pair<const char*, Vec3> faces[] = {{"front", Vec3::UnitX()}, {"right", -Vec3::UnitY()},
                                                {"back", -Vec3::UnitX()}, {"left", Vec3::UnitY()},
                                                {"up", Vec3::UnitZ()},    {"down", -Vec3::UnitZ()}};
  for (int f = 0; f < 6; ++f) {
    const RigCamera& face = rig.cameras[std::size_t(f + 1)];
    CHECK(face.name == faces[f].first);
    CHECK((face.projection.width == 8 && face.projection.height == 8));
    CHECK(face.projection.ray(Vec2(4, 4)).normalized().isApprox(faces[f].second, 1e-12));
    // 90 degrees: the middle of the right edge is 45 degrees off the axis
    CHECK(face.projection.ray(Vec2(8, 4)).normalized().dot(faces[f].second) ==
          Approx(std::sqrt(0.5)));
    CHECK(face.position == Vec3::Zero());
  }
  CHECK(rig.optical_centres() == std::vector<Vec3>{Vec3::Zero()});
  const Rig erp_only = flowscape_rig(16, 0);
  CHECK(erp_only.cameras.size() == 1);
  CHECK_FALSE(erp_only.has_cube_faces());
  CHECK_FALSE(rig_preset("woodscape", 16).flowscape);
  CHECK(rig_preset("woodscape", 16).optical_centres().size() == 4);
}
