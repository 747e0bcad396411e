#include <stdexcept>

#include "lens_math.h"

namespace flowscape {
namespace lens {

std::shared_ptr<const Lens> make_pinhole(const nlohmann::json& p);
std::shared_ptr<const Lens> make_kannala_brandt(const nlohmann::json& p, bool equidistant);
std::shared_ptr<const Lens> make_double_sphere(const nlohmann::json& p);
std::shared_ptr<const Lens> make_woodscape(const nlohmann::json& p);
std::shared_ptr<const Lens> make_dual_fisheye(const nlohmann::json& p);
std::shared_ptr<const Lens> make_panoramic_annular(const nlohmann::json& p);
std::shared_ptr<const Lens> panoramic_annular(int size, double band_degrees);

}  // namespace lens

std::shared_ptr<const Lens> make_lens(const std::string& model, const nlohmann::json& p) {
  // OpenCV's and Kalibr's names for the same models
  if (model == "pinhole" || model == "plumb_bob" || model == "radtan") return lens::make_pinhole(p);
  if (model == "fisheye") return lens::make_kannala_brandt(p, false);  // cv::fisheye
  if (model == "equidistant") return lens::make_kannala_brandt(p, true);
  if (model == "kannala_brandt") return lens::make_kannala_brandt(p, false);
  if (model == "double_sphere") return lens::make_double_sphere(p);
  if (model == "woodscape") return lens::make_woodscape(p);
  if (model == "dual_fisheye") return lens::make_dual_fisheye(p);
  if (model == "panoramic_annular") return lens::make_panoramic_annular(p);
  if (model == "omni" || model == "eucm")
    throw std::invalid_argument(
        "camera model \"" + model + "\" (Kalibr's " +
        (model == "omni" ? "unified omnidirectional (Mei)" : "enhanced unified") +
        " model) is not one of this toolkit's lenses: calibrate with "
        "double_sphere or kannala_brandt (Kalibr's ds, pinhole-equi)");
  throw std::invalid_argument("unknown camera model \"" + model +
                              "\" (pinhole, equidistant, kannala_brandt, double_sphere, "
                              "woodscape, dual_fisheye, panoramic_annular; OpenCV's fisheye and "
                              "plumb_bob, Kalibr's radtan name two of them)");
}

std::shared_ptr<const Lens> kannala_brandt_200(int size) {
  const std::vector<double> D{0.05, -0.01, 0.002, -0.0002};
  const double max_angle = 100 * lens::kDegree, t2 = max_angle * max_angle;
  const double edge = max_angle * (1 + t2 * (D[0] + t2 * (D[1] + t2 * (D[2] + t2 * D[3]))));
  const double f = 0.49 * size / edge, c = size / 2.0 - 0.5;  // the circle just inside the image
  return make_lens("kannala_brandt", {{"width", size},
                                      {"height", size},
                                      {"K", {{f, 0, c}, {0, f, c}, {0, 0, 1}}},
                                      {"D", D},
                                      {"max_angle_degrees", 100}});
}

std::shared_ptr<const Lens> woodscape_190(int width, int height) {
  // WoodScape's front camera (1280 x 966), scaled to the width: the circle spans the width and is
  // cut by the top and bottom of the image
  const double s = width / 1280.0;
  return make_lens("woodscape", {{"width", width},
                                 {"height", height},
                                 {"k", {339.749 * s, -31.988 * s, 48.275 * s, -7.201 * s}},
                                 {"cx_offset", 0},
                                 {"cy_offset", 0},
                                 {"aspect_ratio", 1},
                                 {"max_angle_degrees", 95}});
}

std::shared_ptr<const Lens> dual_fisheye_190(int height) {
  return make_lens("dual_fisheye",
                   {{"width", 2 * height}, {"height", height}, {"max_angle_degrees", 95}});
}

std::shared_ptr<const Lens> panoramic_annular(int size, double band_degrees) {
  return lens::panoramic_annular(size, band_degrees);
}

}  // namespace flowscape
