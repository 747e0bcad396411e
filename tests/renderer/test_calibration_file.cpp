#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <opencv2/core.hpp>

#include "../temp_dir.h"
#include "flowscape/renderer/calibration_file.h"

using namespace flowscape;

namespace {

std::filesystem::path write(const TempDir& dir, const std::string& name, const std::string& text) {
  const std::filesystem::path path = dir.path / name;
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path) << text;
  return path;
}

std::string row(const Eigen::Matrix4d& m, int r) {
  char text[200];
  std::snprintf(text, sizeof text, "[%.17g, %.17g, %.17g, %.17g]", m(r, 0), m(r, 1), m(r, 2),
                m(r, 3));
  return text;
}

// Kalibr's camchain as PyYAML writes it: no %YAML header, the block sequence of T_cn_cnm1 at its
// key's indentation (both refused by OpenCV's own reader).
std::string kalibr_camchain(const Eigen::Matrix4d& t_c1_c0, const std::string& model0 = "pinhole") {
  std::string text =
      "cam0:\n"
      "  cam_overlaps: [1]\n"
      "  camera_model: " +
      model0 +
      "\n"
      "  distortion_coeffs: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]\n"
      "  distortion_model: radtan\n"
      "  intrinsics: [458.654, 457.296, 367.215, 248.375]\n"
      "  resolution: [752, 480]\n"
      "  rostopic: /cam0/image_raw\n"
      "cam1:\n"
      "  T_cn_cnm1:\n";
  for (int r = 0; r < 4; ++r) text += "  - " + row(t_c1_c0, r) + "\n";
  return text +
         "  cam_overlaps: [0]\n"
         "  camera_model: pinhole\n"
         "  distortion_coeffs: [0.01, -0.002, 0.0005, -0.0001]\n"
         "  distortion_model: equidistant\n"
         "  intrinsics: [190.97, 190.97, 254.93, 256.89]\n"
         "  resolution: [512, 512]\n"
         "  rostopic: /cam1/image_raw\n";
}

Eigen::Matrix4d camera1_from_camera0() {
  Pose t = Pose::Identity();
  t.linear() = Eigen::AngleAxisd(0.02, Vec3(0.1, 1, -0.2).normalized()).toRotationMatrix();
  t.translation() = Vec3(-0.110073808127187, 0.000399121547014, -0.000853702503357);
  return t.matrix();
}

// A point in a camera's own frame (x right, y down, z forward) from a point in the rig frame.
Vec3 in_camera(const RigCamera& camera, const Vec3& rig_point) {
  return camera.mount().inverse() * rig_point;
}

}  // namespace

TEST_CASE("a Kalibr camchain becomes a rig: lenses as Kalibr projects, cameras chained") {
  TempDir dir;
  const Eigen::Matrix4d t = camera1_from_camera0();
  const auto file = write(dir, "camchain.yaml", kalibr_camchain(t));
  const CameraMount mount{{1.5, 0.2, -0.3}, {10, -15, 2}};
  const Rig rig = rig_from_calibration(file, mount);
  CHECK(rig.name == "camchain");
  REQUIRE(rig.cameras.size() == 2);
  CHECK(rig.cameras[0].name == "cam0");
  CHECK(rig.cameras[1].name == "cam1");

  // cam0 sits where the mount says
  CHECK(rig.cameras[0].position.isApprox(mount.position));
  CHECK(rig.cameras[0].projection.camera_to_rig().isApprox(look(10, -15, 2), 1e-12));
  // cam1 sees every rig point where T_cn_cnm1 carries cam0's view of it
  for (const Vec3& p : {Vec3(5, 1, 0.3), Vec3(-2, 4, 1), Vec3(0.3, -0.2, 7)}) {
    const Vec3 x0 = in_camera(rig.cameras[0], p), x1 = in_camera(rig.cameras[1], p);
    CHECK((x1 - (t.topLeftCorner<3, 3>() * x0 + t.topRightCorner<3, 1>())).norm() < 1e-9);
  }

  // cam0: radtan, Kalibr's projection u = fu x' + pu (pixel centres at integers) + our 0.5
  const Lens& lens = *rig.cameras[0].projection.lens;
  CHECK(lens.model() == "pinhole");
  CHECK(lens.width() == 752);
  const double k1 = -0.28340811, k2 = 0.07395907, p1 = 0.00019359, p2 = 1.76187114e-05;
  const Vec3 d(0.3, -0.2, 1);
  const double x = d.x() / d.z(), y = d.y() / d.z(), r2 = x * x + y * y;
  const double radial = 1 + k1 * r2 + k2 * r2 * r2;
  const double xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x);
  const double yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y;
  const std::optional<Vec2> pixel = lens.project(d);
  REQUIRE(pixel);
  CHECK(pixel->x() == Approx(458.654 * xd + 367.215 + 0.5).epsilon(1e-12));
  CHECK(pixel->y() == Approx(457.296 * yd + 248.375 + 0.5).epsilon(1e-12));

  // cam1: pinhole-equi is Kannala-Brandt, reaching the image's corners
  const Lens& fisheye = *rig.cameras[1].projection.lens;
  CHECK(fisheye.model() == "kannala_brandt");
  CHECK(fisheye.ray(Vec2(0.01, 0.01)));
  CHECK(fisheye.ray(Vec2(511.99, 511.99)));
}

TEST_CASE("OpenCV's calibration files: pinhole and cv::fisheye, as its samples write them") {
  TempDir dir;
  const std::string common =
      "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\n"
      "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
      "   data: [ 500., 0., 319.5, 0., 510., 239.5, 0., 0., 1. ]\n";
  const auto pinhole_file =
      write(dir, "opencv.yml",
            common +
                "distortion_coefficients: !!opencv-matrix\n   rows: 5\n   cols: 1\n   dt: d\n"
                "   data: [ -0.1, 0.01, 0.001, -0.002, 0. ]\n");
  const Rig pinhole = rig_from_calibration(pinhole_file, CameraMount{});
  REQUIRE(pinhole.cameras.size() == 1);
  const nlohmann::json p = pinhole.cameras[0].projection.lens->parameters();
  CHECK(pinhole.cameras[0].projection.lens->model() == "pinhole");
  CHECK(p["K"] == nlohmann::json{{500., 0., 319.5}, {0., 510., 239.5}, {0., 0., 1.}});
  CHECK(p["D"] == nlohmann::json{-0.1, 0.01, 0.001, -0.002, 0.});
  // the principal point (319.5, 239.5) is the image's centre: our continuous (320, 240)
  CHECK(pinhole.cameras[0].projection.lens->project(Vec3(0, 0, 1))->isApprox(Vec2(320, 240)));

  const auto fisheye_file =
      write(dir, "fisheye.yaml",
            common +
                "distortion_coefficients: !!opencv-matrix\n   rows: 4\n   cols: 1\n   dt: d\n"
                "   data: [ 0.05, -0.01, 0.002, -0.0002 ]\nfisheye_model: 1\n");
  const Rig fisheye = rig_from_calibration(fisheye_file, CameraMount{});
  CHECK(fisheye.cameras[0].projection.lens->model() == "kannala_brandt");
  CHECK(fisheye.cameras[0].projection.lens->ray(Vec2(0.01, 0.01)));

  const auto xml =
      write(dir, "opencv.xml",
            "<?xml version=\"1.0\"?>\n<opencv_storage>\n<image_width>64</image_width>"
            "<image_height>48</image_height>\n<camera_matrix type_id=\"opencv-matrix\">"
            "<rows>3</rows><cols>3</cols><dt>d</dt><data>50. 0. 31.5 0. 50. 23.5 0. 0. "
            "1.</data></camera_matrix>\n<distortion_coefficients type_id=\"opencv-"
            "matrix\"><rows>1</rows><cols>4</cols><dt>d</dt><data>0. 0. 0. "
            "0.</data></distortion_coefficients>\n</opencv_storage>\n");
  CHECK(rig_from_calibration(xml, CameraMount{}).cameras[0].projection.lens->width() == 64);
}

TEST_CASE("a calibration's problems are named with the file") {
  TempDir dir;
  const auto camchain = write(dir, "camchain.yaml", kalibr_camchain(camera1_from_camera0()));
  const auto fails = [](const std::filesystem::path& file, std::optional<CameraMount> mount,
                        const std::string& says) {
    try {
      rig_from_calibration(file, mount);
      FAIL("no error for " << file);
    } catch (const std::exception& e) {
      const std::string message = e.what();
      CHECK_THAT(message, Catch::Contains(file.string()) && Catch::Contains(says));
    }
  };
  fails(camchain, std::nullopt, "--rig-mount");  // a calibration has no rig origin
  fails(write(dir, "omni.yaml", kalibr_camchain(camera1_from_camera0(), "omni")), CameraMount{},
        "cam0: camera model \"omni\" (Kalibr's unified omnidirectional (Mei) model)");
  Eigen::Matrix4d sheared = camera1_from_camera0();
  sheared(0, 1) += 0.01;
  fails(write(dir, "sheared.yaml", kalibr_camchain(sheared)), CameraMount{},
        "cam1: \"T_cn_cnm1\"'s rotation must be a rotation");
  fails(write(dir, "other.yaml", "%YAML:1.0\n---\nfoo: 1\n"), CameraMount{},
        "neither a Kalibr camchain");
  fails(write(dir, "broken.yaml", "cam0: [1, 2\n  : :\n"), CameraMount{}, "not YAML (line ");
  fails(dir.path / "missing.yaml", CameraMount{}, "missing.yaml");
}

TEST_CASE("a scaled camera sees every direction at the scaled place of its image") {
  TempDir dir;
  const Rig kalibr = rig_from_calibration(
      write(dir, "camchain.yaml", kalibr_camchain(camera1_from_camera0())), CameraMount{});
  std::vector<std::shared_ptr<const Lens>> lenses = {
      kalibr.cameras[0].projection.lens,
      kalibr.cameras[1].projection.lens,
      kannala_brandt_200(96),
      woodscape_190(120, 90),
      dual_fisheye_190(64),
      panoramic_annular(96),
      make_lens("double_sphere", {{"width", 100},
                                  {"height", 80},
                                  {"K", {{30, 0, 49.5}, {0, 31, 39.5}, {0, 0, 1}}},
                                  {"xi", -0.2},
                                  {"alpha", 0.6}})};
  for (const auto& lens : lenses)
    for (double scale : {0.5, 0.37, 2.0}) {
      const auto scaled = scaled_lens(*lens, scale);
      const double sx = double(scaled->width()) / lens->width();
      const double sy = double(scaled->height()) / lens->height();
      CHECK(scaled->model() == lens->model());
      CHECK(std::abs(scaled->width() - lens->width() * scale) <= 1);
      for (int i = 1; i < 16; ++i)
        for (int j = 1; j < 16; ++j) {
          const Vec2 pixel(lens->width() * i / 16.0, lens->height() * j / 16.0);
          const std::optional<Vec3> ray = lens->ray(pixel);
          if (!ray) continue;
          // (a dual fisheye's outer ring sees what the other lens owns: project() goes there)
          const Vec2 seen_before = *lens->project(*ray);
          const std::optional<Vec2> seen = scaled->project(*ray);
          INFO(lens->model() << " scale " << scale << " pixel " << pixel.transpose());
          REQUIRE(seen);
          CHECK((*seen - Vec2(seen_before.x() * sx, seen_before.y() * sy)).norm() < 1e-6);
        }
    }
  // K's rule in OpenCV's convention: 640 x 480 with its centre at (319.5, 239.5) halves to
  // 320 x 240 with its centre at (159.5, 119.5)
  const auto half = scaled_lens(
      *make_lens(
          "pinhole",
          {{"width", 640}, {"height", 480}, {"K", {{500, 0, 319.5}, {0, 500, 239.5}, {0, 0, 1}}}}),
      0.5);
  CHECK(half->parameters()["K"] ==
        nlohmann::json{{250., 0., 159.5}, {0., 250., 119.5}, {0., 0., 1.}});
  CHECK_THROWS_WITH(scaled_lens(*kannala_brandt_200(8), 0.1), Catch::Contains("under 2 pixels"));
  const Rig small = scaled_rig(kalibr, 0.25);
  CHECK(small.cameras[0].projection.lens->width() == 188);
  CHECK(small.cameras[1].position == kalibr.cameras[1].position);
}

namespace {

// The camera whose pinhole parameters are given, with distortion `d` (OpenCV's k1 k2 p1 p2 k3).
void check_pinhole(const RigCamera& camera, const std::vector<double>& k, int width, int height,
                   const std::vector<double>& d) {
  const nlohmann::json p = camera.projection.lens->parameters();
  CHECK(camera.projection.lens->model() == "pinhole");
  CHECK(p["width"] == width);
  CHECK(p["height"] == height);
  CHECK(p["K"] == nlohmann::json{{k[0], 0., k[2]}, {0., k[1], k[3]}, {0., 0., 1.}});
  CHECK(p["D"] == nlohmann::json(d));
}

Eigen::Matrix4d some_camera_from_imu(double angle, const Vec3& axis, const Vec3& t) {
  Pose pose = Pose::Identity();
  pose.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  pose.translation() = t;
  return pose.matrix();
}

}  // namespace

TEST_CASE("OpenCV's tutorial output, with its own key spellings, written by cv::FileStorage") {
  TempDir dir;
  for (const char* name : {"out_camera_data.yml", "out_camera_data.xml"}) {
    INFO(name);
    const std::filesystem::path file = dir.path / name;
    {  // the keys the calib3d tutorial (camera_calibration.cpp) writes
      cv::FileStorage fs(file.string(), cv::FileStorage::WRITE);
      fs << "calibration_time"
         << "Mon Dec  7 10:00:00 2026";
      fs << "nr_of_frames" << 25 << "image_Width" << 640 << "image_Height" << 480;
      fs << "board_Width" << 9 << "board_Height" << 6 << "square_Size" << 50.0;
      fs << "fix_aspect_ratio" << 1.0 << "flags" << 2;
      fs << "Camera_Matrix" << (cv::Mat_<double>(3, 3) << 600, 0, 319.5, 0, 600, 239.5, 0, 0, 1);
      fs << "Distortion_Coefficients" << (cv::Mat_<double>(5, 1) << -0.2, 0.05, 0.001, 0.002, 0);
      fs << "Avg_Reprojection_Error" << 0.3;
    }
    const Rig rig = rig_from_calibration(file, CameraMount{});
    REQUIRE(rig.cameras.size() == 1);
    check_pinhole(rig.cameras[0], {600, 600, 319.5, 239.5}, 640, 480,
                  {-0.2, 0.05, 0.001, 0.002, 0});
  }
}

TEST_CASE("ROS's camera_info, as a YAML file and as a message, and COLMAP's cameras.txt") {
  TempDir dir;
  // camera_calibration_parsers' file
  const Rig file = rig_from_calibration(
      write(dir, "narrow_stereo.yaml",
            "image_width: 640\nimage_height: 480\ncamera_name: narrow_stereo\n"
            "camera_matrix:\n  rows: 3\n  cols: 3\n  data: [430.1, 0, 320.4, 0, 431.2, 240.6, 0, "
            "0, 1]\n"
            "distortion_model: plumb_bob\ndistortion_coefficients:\n  rows: 1\n  cols: 5\n"
            "  data: [-0.3, 0.09, 0.0001, -0.0002, 0]\n"
            "rectification_matrix:\n  rows: 3\n  cols: 3\n  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]\n"
            "projection_matrix:\n  rows: 3\n  cols: 4\n  data: [400, 0, 320, 0, 0, 400, 240, 0, "
            "0, 0, 1, 0]\n"),
      CameraMount{});
  check_pinhole(file.cameras[0], {430.1, 431.2, 320.4, 240.6}, 640, 480,
                {-0.3, 0.09, 0.0001, -0.0002, 0});
  // `rostopic echo -n 1 /camera_info` of an equidistant (fisheye) camera
  const Rig message = rig_from_calibration(
      write(dir, "camera_info.yaml",
            "header:\n  seq: 7\n  stamp: {secs: 1, nsecs: 2}\n  frame_id: cam\nheight: 512\n"
            "width: 512\ndistortion_model: \"equidistant\"\nD: [0.01, -0.002, 0.0005, -0.0001]\n"
            "K: [190.9, 0.0, 254.9, 0.0, 190.9, 256.8, 0.0, 0.0, 1.0]\n"
            "R: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]\n"
            "P: [190.9, 0.0, 254.9, 0.0, 0.0, 190.9, 256.8, 0.0, 0.0, 0.0, 1.0, 0.0]\n"),
      CameraMount{});
  CHECK(message.cameras[0].projection.lens->model() == "kannala_brandt");
  CHECK(message.cameras[0].projection.lens->parameters()["D"] ==
        nlohmann::json{0.01, -0.002, 0.0005, -0.0001});
  // COLMAP: pixel centres at +0.5, so OpenCV's cx = COLMAP's cx - 0.5
  const Rig colmap = rig_from_calibration(
      write(dir, "cameras.txt",
            "# Camera list with one line of data per camera:\n"
            "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n# Number of cameras: 1\n"
            "3 OPENCV 1024 768 800.5 801.5 512.25 384.75 -0.1 0.02 0.001 -0.003\n"),
      CameraMount{});
  REQUIRE(colmap.cameras.size() == 1);
  CHECK(colmap.cameras[0].name == "cam3");
  check_pinhole(colmap.cameras[0], {800.5, 801.5, 511.75, 384.25}, 1024, 768,
                {-0.1, 0.02, 0.001, -0.003, 0});
  // the continuous pixel COLMAP projects the axis to is its (cx, cy)
  CHECK(colmap.cameras[0].projection.lens->project(Vec3(0, 0, 1))->isApprox(Vec2(512.25, 384.75)));
  const Rig simple = rig_from_calibration(
      write(dir, "simple/cameras.txt", "1 SIMPLE_RADIAL 640 480 500 320 240 0.05\n"),
      CameraMount{});
  check_pinhole(simple.cameras[0], {500, 500, 319.5, 239.5}, 640, 480, {0.05, 0, 0, 0, 0});
  const Rig fisheye = rig_from_calibration(
      write(dir, "fisheye/cameras.txt",
            "1 OPENCV_FISHEYE 640 640 200 200 320 320 0.01 -0.002 0.0005 -0.0001\n"),
      CameraMount{});
  CHECK(fisheye.cameras[0].projection.lens->model() == "kannala_brandt");
}

TEST_CASE("Kalibr camchain-imucam files place later cameras by their T_cam_imu") {
  TempDir dir;
  const Eigen::Matrix4d c0 = some_camera_from_imu(1.6, {0.1, 0.2, 1}, {0.05, -0.01, 0.02}),
                        c1 = some_camera_from_imu(1.5, {-0.1, 0.3, 1}, {-0.06, 0.0, 0.03});
  std::string text = "# TUM-VI's camchain-imucam, as Kalibr writes it\n";
  for (int n = 0; n < 2; ++n) {
    const Eigen::Matrix4d& t = n == 0 ? c0 : c1;
    text += "cam" + std::to_string(n) + ":\n  T_cam_imu:\n";
    for (int r = 0; r < 4; ++r) text += "  - " + row(t, r) + "\n";
    text +=
        "  camera_model: pinhole\n  distortion_coeffs: [0.0034, 0.0007, -0.0021, 0.0002]\n"
        "  distortion_model: equidistant\n  intrinsics: [190.9, 190.9, 254.9, 256.8]\n"
        "  resolution: [512, 512]\n  timeshift_cam_imu: 0.0\n";
  }
  const Rig rig = rig_from_calibration(write(dir, "camchain-imucam.yaml", text),
                                       CameraMount{{0.4, 0, 1.2}, {0, -5, 0}});
  REQUIRE(rig.cameras.size() == 2);
  // a point the IMU sees at q is at c0 q in cam0 and at c1 q in cam1
  for (const Vec3& q : {Vec3(1, 2, 3), Vec3(-4, 0.5, 2)}) {
    const Vec3 in0 = (c0 * q.homogeneous()).head<3>(), in1 = (c1 * q.homogeneous()).head<3>();
    const Vec3 rig_point = rig.cameras[0].mount() * in0;
    CHECK((in_camera(rig.cameras[1], rig_point) - in1).norm() < 1e-9);
  }
  // without T_cn_cnm1 and without cam0's T_cam_imu, cam1 cannot be placed
  text.erase(text.find("  T_cam_imu:"), text.find("  camera_model") - text.find("  T_cam_imu:"));
  CHECK_THROWS_WITH(rig_from_calibration(write(dir, "half.yaml", text), CameraMount{}),
                    Catch::Contains("half.yaml: cam1: needs \"T_cn_cnm1\" (or \"T_cam_imu\" here "
                                    "and in cam0)"));
}

TEST_CASE("YAML as YAML tools write it: anchors, flow maps, comments, quoted numbers") {
  TempDir dir;
  const Rig rig = rig_from_calibration(
      write(dir, "anchors.yaml",
            "# a camchain a script wrote with PyYAML's anchors\n"
            "cam0: &camera {camera_model: pinhole, distortion_model: radtan,\n"
            "  distortion_coeffs: [-0.1, 0.01, 0, 0], intrinsics: [400, 400, 319.5, 239.5],\n"
            "  resolution: [640, 480]}  # the left camera\n"
            "cam1:\n  <<: *camera\n  T_cn_cnm1: [[1, 0, 0, -0.1], [0, 1, 0, 0], [0, 0, 1, 0], "
            "[0, 0, 0, 1]]\n"),
      CameraMount{});
  REQUIRE(rig.cameras.size() == 2);
  CHECK((rig.cameras[1].position - Vec3(0, -0.1, 0)).norm() < 1e-12);  // 0.1 m to cam0's right
  CHECK_THROWS_WITH(rig_from_calibration(write(dir, "quoted.yaml",
                                               "cam0: {camera_model: pinhole, intrinsics: ['400', "
                                               "400, 319.5, 239.5], resolution: [640, 480]}\n"),
                                         CameraMount{}),
                    Catch::Contains("quoted.yaml: cam0: \"intrinsics\" must hold numbers"));
}

TEST_CASE("a glTF file's cameras become a rig, placed as the file places them") {
  TempDir dir;
  // two cameras: the first at the origin looking along glTF's -z, the second 2 m to its right
  // (glTF x), turned 90 degrees to the right about glTF's y (up)
  const double s = std::sqrt(0.5);
  const nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0, 1}}}}},
      {"nodes",
       {{{"name", "Front Cam"}, {"camera", 0}},
        {{"name", "side"},
         {"camera", 1},
         {"translation", {2, 0, 0}},
         {"rotation", {0, -s, 0, s}}}}},
      {"cameras",
       {{{"type", "perspective"},
         {"perspective", {{"yfov", 0.8}, {"aspectRatio", 1.5}, {"znear", 0.1}}}},
        {{"type", "perspective"}, {"perspective", {{"yfov", 1.2}, {"znear", 0.1}}}}}}};
  std::ofstream(dir.path / "cameras.gltf") << gltf.dump();
  const Rig rig =
      rig_from_calibration(dir.path / "cameras.gltf", CameraMount{{1, 0, 1.5}, Vec3::Zero()});
  REQUIRE(rig.cameras.size() == 2);
  CHECK(rig.cameras[0].name == "front_cam");
  CHECK(rig.cameras[1].name == "side");
  const nlohmann::json p0 = rig.cameras[0].projection.lens->parameters();
  CHECK(p0["height"] == 512);
  CHECK(p0["width"] == 768);  // 1.5 x 512
  CHECK(p0["K"][1][1].get<double>() == Approx(256 / std::tan(0.4)));
  CHECK(rig.cameras[1].projection.lens->parameters()["width"] == 512);  // square without one
  // the first camera where the mount says, looking forward; the second 2 m to its right (the
  // rig's -y), looking right
  CHECK(rig.cameras[0].position.isApprox(Vec3(1, 0, 1.5)));
  CHECK(rig.cameras[0].projection.camera_to_rig().isApprox(look(0, 0, 0), 1e-12));
  CHECK((rig.cameras[1].position - Vec3(1, -2, 1.5)).norm() < 1e-12);
  CHECK((rig.cameras[1].projection.camera_to_rig() * Vec3::UnitZ() - Vec3(0, -1, 0)).norm() <
        1e-12);
}

TEST_CASE("hostile calibrations: nesting, 100 cameras, wrong types, each one line with the file") {
  TempDir dir;
  const auto refused = [&](const std::string& name, const std::string& text,
                           const std::string& says) {
    try {
      rig_from_calibration(write(dir, name, text), CameraMount{});
      FAIL("no error for " << name);
    } catch (const std::exception& e) {
      CHECK_THAT(std::string(e.what()), Catch::Contains(name) && Catch::Contains(says));
    }
  };
  // would overflow yaml-cpp's and OpenCV's recursive parsers
  refused("deep.yaml", "cam0: " + std::string(60000, '[') + std::string(60000, ']') + "\n",
          "nested more than 64 levels deep");
  std::string xml = "<?xml version=\"1.0\"?>\n<opencv_storage>";
  for (int k = 0; k < 30000; ++k) xml += "<a>";
  refused("deep.xml", xml, "nested more than 64 levels deep");
  std::string many;
  for (int n = 0; n < 100; ++n)
    many += "cam" + std::to_string(n) +
            ": {camera_model: pinhole, intrinsics: [1, 1, 1, 1], "
            "resolution: [4, 4]}\n";
  refused("many.yaml", many, "holds 100 cameras; a rig takes at most 16");
  refused("width.yaml",
          "camera_matrix: [1, 0, 1, 0, 1, 1, 0, 0, 1]\ndistortion_coefficients: [0, 0, 0, 0]\n"
          "image_width: wide\nimage_height: 4\n",
          "needs \"image_width\" (a whole number of pixels)");
  refused("twice.yaml",
          "cam0: {camera_model: pinhole, intrinsics: [1, 1, 1, 1], resolution: [4, 4]}\n"
          "cam0: {camera_model: pinhole, intrinsics: [2, 2, 2, 2], resolution: [8, 8]}\n",
          "line 2: key \"cam0\" appears twice in one map");
  refused("cameras.txt", "1 PINHOLE 64 48 50 50 32 24\n2 PINHOLE 64 48 50 50 32 24\n",
          "holds 2 cameras");
  refused("fov/cameras.txt", "1 FOV 64 48 50 50 32 24 0.9\n", "camera model FOV is not one");
  refused("colmap/cameras.txt", "1 PINHOLE 64 48 50 nan 32 24\n", "\"nan\" is not a finite number");
  refused("far.yaml",
          "cam0: {camera_model: pinhole, intrinsics: [1, 1, 1, 1], resolution: [4, 4]}\n"
          "cam1: {camera_model: pinhole, intrinsics: [1, 1, 1, 1], resolution: [4, 4],\n"
          "  T_cn_cnm1: [[1, 0, 0, 1e308], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}\n",
          "cam1: \"T_cn_cnm1\"'s translation must lie within 1,000 km");
}

TEST_CASE("a wide-angle calibration that sees only part of its image is warned about") {
  TempDir dir;
  // k1 = -0.5 with a 90-degree-wide image: r_d(r) = r (1 - 0.5 r^2) stops growing at r = 0.816
  const Rig rig = rig_from_calibration(
      write(dir, "wide.yaml",
            "camera_matrix: [100, 0, 99.5, 0, 100, 99.5, 0, 0, 1]\n"
            "distortion_coefficients: [-0.5, 0, 0, 0, 0]\nimage_width: 200\nimage_height: 200\n"),
      CameraMount{});
  const std::vector<std::string> warnings = calibration_warnings(rig);
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0],
             Catch::StartsWith("cam0 sees only ") && Catch::Contains("degrees off the axis"));
  // where it stops: r (1 - 0.5 r^2) peaks at r = sqrt(2/3), atan of which is 39.2 degrees; the
  // outermost pixel centre that still sees lies within a pixel of it
  const std::size_t at = warnings[0].find("stops ") + 6;
  CHECK(std::stod(warnings[0].substr(at)) == Approx(39.2).margin(0.8));
  const Rig mild = rig_from_calibration(
      write(dir, "mild.yaml",
            "camera_matrix: [100, 0, 99.5, 0, 100, 99.5, 0, 0, 1]\n"
            "distortion_coefficients: [-0.05, 0, 0, 0, 0]\nimage_width: 200\nimage_height: 200\n"),
      CameraMount{});
  CHECK(calibration_warnings(mild).empty());
}
