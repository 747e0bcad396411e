#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>

#include "../temp_dir.h"
#include "flowscape/renderer/calibration_file.h"

using namespace flowscape;

namespace {

std::filesystem::path write(const TempDir& dir, const std::string& name, const std::string& text) {
  const std::filesystem::path path = dir.path / name;
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
  fails(write(dir, "broken.yaml", "cam0: [1, 2\n  : :\n"), CameraMount{}, "not a calibration");
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
