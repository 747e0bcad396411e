// Every camera model against hand-derived or independent expectations: round trips over the whole
// image, Kannala-Brandt against OpenCV's cv::fisheye::projectPoints, the closed-form flow of a
// rotation about the optical axis, and the image-circle and annulus masks at their stated angles.
#include <catch2/catch.hpp>
#include <cmath>
#include <opencv2/calib3d.hpp>

#include "flowscape/renderer/lens.h"
#include "flowscape/renderer/renderer.h"

using namespace flowscape;

namespace {

constexpr double kDegree = 3.14159265358979323846 / 180;

struct Sample {
  const char* name;
  std::shared_ptr<const Lens> lens;
};

std::vector<Sample> lenses() {
  return {
      {"pinhole", make_lens("pinhole", {{"width", 64},
                                        {"height", 48},
                                        {"K", {{50, 0, 31.2}, {0, 52, 24.1}, {0, 0, 1}}},
                                        {"D", {-0.28, 0.07, 0.001, -0.002, 0.0}}})},
      {"equidistant", make_lens("equidistant", {{"width", 60},
                                                {"height", 60},
                                                {"K", {{17, 0, 29.5}, {0, 17, 29.5}, {0, 0, 1}}},
                                                {"max_angle_degrees", 100}})},
      {"kannala_brandt", kannala_brandt_200(64)},
      {"double_sphere",
       make_lens("double_sphere", {{"width", 64},
                                   {"height", 64},
                                   {"K", {{16, 0, 31.5}, {0, 16, 31.5}, {0, 0, 1}}},
                                   {"xi", -0.2},
                                   {"alpha", 0.6},
                                   {"max_angle_degrees", 100}})},
      {"woodscape", woodscape_190(80, 60)},
      {"dual_fisheye", dual_fisheye_190(32)},
      {"panoramic_annular", panoramic_annular(64, 60)},
  };
}

double angle_from_axis(const Vec3& ray) { return std::acos(std::clamp(ray.z(), -1.0, 1.0)); }

// Where the optical axis meets the image, from the parameters as each model states them
// (continuous coordinates: OpenCV's K and OCamCalib's centre put the top-left pixel at 0, 0).
Vec2 principal_point(const Lens& lens) {
  const nlohmann::json p = lens.parameters();
  if (p.contains("K")) return {p["K"][0][2].get<double>() + 0.5, p["K"][1][2].get<double>() + 0.5};
  if (p.contains("centre"))
    return {p["centre"][0].get<double>() + 0.5, p["centre"][1].get<double>() + 0.5};
  return {lens.width() / 2.0 + p.value("cx_offset", 0.0),
          lens.height() / 2.0 + p.value("cy_offset", 0.0)};
}

}  // namespace

TEST_CASE("every camera model's project(ray(p)) is p over its whole image") {
  for (const Sample& s : lenses()) {
    INFO(s.name);
    const Lens& lens = *s.lens;
    int covered = 0;
    double worst = 0;
    for (int j = 0; j < 4 * lens.height(); ++j)
      for (int i = 0; i < 4 * lens.width(); ++i) {
        const Vec2 p((i + 0.5) / 4, (j + 0.5) / 4);  // a quarter-pixel grid
        const std::optional<Vec3> ray = lens.ray(p);
        if (!ray) continue;
        ++covered;
        REQUIRE(std::abs(ray->norm() - 1) < 1e-12);
        const std::optional<Vec2> back = lens.project(*ray);
        REQUIRE(back);
        const bool rear = s.lens->model() == "dual_fisheye" && p.x() >= lens.height();
        const Vec3 own = rear ? Vec3(-ray->x(), ray->y(), -ray->z()) : *ray;  // its lens's frame
        if (s.lens->model() == "dual_fisheye" && angle_from_axis(own) > 90 * kDegree) {
          // the ring beyond 90 degrees sees what the other lens owns: the same direction there
          CHECK((*lens.ray(*back) - *ray).norm() < 1e-9);
          CHECK((back->x() >= lens.height()) != rear);  // in the other half
          continue;
        }
        worst = std::max(worst, (*back - p).norm());
      }
    CHECK(covered > lens.width() * lens.height());  // a quarter of the 16 samples per pixel
    CHECK(worst < 1e-6);
    // and the parameters build the same lens again
    const auto again = make_lens(lens.model(), lens.parameters());
    CHECK(again->parameters() == lens.parameters());
  }
}

TEST_CASE("Kannala-Brandt projects as OpenCV's cv::fisheye::projectPoints does") {
  const std::vector<double> D{0.05, -0.01, 0.002, -0.0002};
  const double fx = 300, fy = 310, cx = 319.5, cy = 241.0;
  const auto lens = make_lens("kannala_brandt", {{"width", 640},
                                                 {"height", 480},
                                                 {"K", {{fx, 0, cx}, {0, fy, cy}, {0, 0, 1}}},
                                                 {"D", D},
                                                 {"max_angle_degrees", 100}});
  std::vector<cv::Point3d> points;
  for (double theta = 0.5; theta < 89.5; theta += 3.7)  // OpenCV works with z > 0 only
    for (double phi = -180; phi < 180; phi += 11.3)
      points.emplace_back(std::sin(theta * kDegree) * std::cos(phi * kDegree),
                          std::sin(theta * kDegree) * std::sin(phi * kDegree),
                          std::cos(theta * kDegree));
  std::vector<cv::Point2d> projected;
  const cv::Matx33d K(fx, 0, cx, 0, fy, cy, 0, 0, 1);
  cv::fisheye::projectPoints(points, projected, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K,
                             cv::Vec4d(D[0], D[1], D[2], D[3]));
  for (std::size_t k = 0; k < points.size(); ++k) {
    const std::optional<Vec2> ours = lens->project({points[k].x, points[k].y, points[k].z});
    REQUIRE(ours);
    // OpenCV puts the centre of the top-left pixel at (0, 0), we at (0.5, 0.5)
    CHECK(ours->x() - 0.5 == Approx(projected[k].x).margin(1e-9));
    CHECK(ours->y() - 0.5 == Approx(projected[k].y).margin(1e-9));
  }
}

TEST_CASE("a rotation about a lens's optical axis turns its image about the principal point") {
  // an empty scene: every ray sees the sky, so the flow is the rotation's alone. The rig turns by
  // psi about the camera's z; a fixed direction then sits turned by -psi in the camera's (x right,
  // y down) image plane, at the same angle from the axis: p' = c + R(-psi) (p - c) for every
  // radially symmetric model (the rear lens of a dual fisheye, its x mirrored, turns by +psi)
  Scene empty;
  Renderer renderer(empty);
  const double psi = 3 * kDegree;
  Mat3 forward;  // the front face's frame: camera z = rig x (forward), x = rig -y, y = rig -z
  forward << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  const auto turned = [&](Vec2 p, Vec2 c, double a) {
    const Vec2 d = p - c;
    return Vec2(c.x() + std::cos(a) * d.x() - std::sin(a) * d.y(),
                c.y() + std::sin(a) * d.x() + std::cos(a) * d.y());
  };
  std::vector<Sample> radial = lenses();
  radial.erase(radial.begin());  // the pinhole's tangential terms are not symmetric
  radial.push_back(
      {"radial pinhole", make_lens("pinhole", {{"width", 48},
                                               {"height", 48},
                                               {"K", {{40, 0, 23.5}, {0, 40, 23.5}, {0, 0, 1}}},
                                               {"D", {-0.2, 0.05, 0, 0, 0.01}}})});
  for (const Sample& s : radial) {
    INFO(s.name);
    const Projection camera = Projection::of_lens(s.lens, forward);
    FramePair pair;
    pair.rig = Pose::Identity();
    pair.next_rig = Pose(Eigen::AngleAxisd(psi, Vec3::UnitX()));  // about the camera's z
    const GroundTruth gt = renderer.ground_truth(camera, pair);
    int checked = 0;
    for (int y = 0; y < camera.height; ++y)
      for (int x = 0; x < camera.width; ++x) {
        const Vec2 pixel(x + 0.5, y + 0.5);
        const std::optional<Vec3> ray = s.lens->ray(pixel);
        if (!ray) {
          CHECK(*gt.valid.pixel(x, y) == 0);
          continue;
        }
        Vec2 centre = principal_point(*s.lens);
        double angle = -psi;
        if (s.lens->model() == "dual_fisheye") {
          const bool rear = x >= camera.height;
          centre = Vec2((rear ? 1.5 : 0.5) * camera.height, 0.5 * camera.height);
          if (angle_from_axis(rear ? Vec3(-ray->x(), ray->y(), -ray->z()) : *ray) > 88 * kDegree)
            continue;  // may cross to the other lens
          if (rear) angle = psi;
        }
        const Vec2 expected = turned(pixel, centre, angle);
        const float* f = gt.flow.pixel(x, y);
        if (!s.lens->project(s.lens->ray(expected).value_or(Vec3::Zero())).has_value()) continue;
        CHECK(pixel.x() + f[0] == Approx(expected.x()).margin(1e-4));
        CHECK(pixel.y() + f[1] == Approx(expected.y()).margin(1e-4));
        ++checked;
      }
    CHECK(checked > camera.width * camera.height / 3);
  }
}

TEST_CASE(
    "image circles and the annulus end at their stated angles, and nothing is seen past them") {
  // along each azimuth, the radius where a lens stops seeing: its ray there is at the stated angle
  struct Edge {
    std::shared_ptr<const Lens> lens;
    Vec2 centre;
    double inner_degrees, outer_degrees;  // 0: no inner edge
  };
  const std::vector<Edge> edges{
      {kannala_brandt_200(64), {32, 32}, 0, 100},
      {dual_fisheye_190(32), {16, 16}, 0, 95},
      {panoramic_annular(64, 60), {32, 32}, 60, 120},
  };
  for (const Edge& e : edges) {
    INFO(e.lens->model());
    const bool dual = e.lens->model() == "dual_fisheye";
    for (double phi = 0; phi < 360; phi += 17) {
      const Vec2 along(std::cos(phi * kDegree), std::sin(phi * kDegree));
      if (dual && along.x() > 0.5) continue;  // towards the rear lens's half
      const auto sees = [&](double r) { return e.lens->ray(e.centre + r * along).has_value(); };
      const auto edge_at = [&](double inside, double outside) {  // bisection of the mask
        for (int i = 0; i < 60; ++i) {
          const double mid = 0.5 * (inside + outside);
          (sees(mid) ? inside : outside) = mid;
        }
        return inside;
      };
      const double outer = edge_at(e.inner_degrees > 0 ? 20 : 1, dual ? 16.4 : 60);
      CHECK(angle_from_axis(*e.lens->ray(e.centre + outer * along)) / kDegree ==
            Approx(e.outer_degrees).margin(1e-6));
      CHECK_FALSE(sees(outer + 1e-3));
      if (e.inner_degrees > 0) {
        const double inner = edge_at(20, 0);
        CHECK(angle_from_axis(*e.lens->ray(e.centre + inner * along)) / kDegree ==
              Approx(e.inner_degrees).margin(1e-6));
        CHECK_FALSE(sees(inner - 1e-3));
        CHECK_FALSE(sees(0));
      }
    }
    // directions beyond the stated angles are not seen either
    const double beyond = (e.outer_degrees + 0.5) * kDegree;
    if (e.lens->model() != "dual_fisheye")  // there the other lens sees it
      CHECK_FALSE(e.lens->project({std::sin(beyond), 0, std::cos(beyond)}));
  }
}

TEST_CASE("bad lens parameters are named") {
  CHECK_THROWS_WITH(make_lens("fishey", {}), Catch::Contains("unknown camera model \"fishey\""));
  CHECK_THROWS_WITH(make_lens("kannala_brandt", {{"width", 64}, {"height", 64}}),
                    Catch::Contains("\"K\" must be 3 rows of 3"));
  const nlohmann::json K = {{30, 0, 31.5}, {0, 30, 31.5}, {0, 0, 1}};
  CHECK_THROWS_WITH(make_lens("kannala_brandt", {{"width", 64},
                                                 {"height", 64},
                                                 {"K", K},
                                                 {"D", {-0.5, 0, 0, 0}},
                                                 {"max_angle_degrees", 100}}),
                    Catch::Contains("folds back before max_angle_degrees"));
  CHECK_THROWS_WITH(make_lens("woodscape", {{"width", 64}, {"height", 1e9}, {"k", {1, 0, 0, 0}}}),
                    Catch::Contains("\"height\" must be a whole number"));
  CHECK_THROWS_WITH(make_lens("double_sphere",
                              {{"width", 64}, {"height", 64}, {"K", K}, {"xi", 0.5}, {"alpha", 2}}),
                    Catch::Contains("\"alpha\" must be in [0, 1]"));
  CHECK_THROWS_WITH(panoramic_annular(64, 200), Catch::Contains("band must be in (0, 180)"));
}
