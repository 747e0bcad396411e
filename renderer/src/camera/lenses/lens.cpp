#include <cmath>
#include <stdexcept>

#include "camera/lenses/lens_math.h"

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

namespace {

// K as OpenCV writes it, for an image scaled by (sx, sy): pixel centres at integers, so the centre
// moves with the image's continuous coordinates (OpenCV's + 0.5).
nlohmann::json scaled_k(const nlohmann::json& k, double sx, double sy) {
  const lens::Intrinsics i = lens::intrinsics({{"K", k}});
  return lens::Intrinsics{i.fx * sx, i.fy * sy, i.cx * sx, i.cy * sy}.matrix();
}

}  // namespace

std::shared_ptr<const Lens> scaled_lens(const Lens& lens, double scale) {
  const std::string model = lens.model();
  const int height = int(std::lround(lens.height() * scale));
  const int width = model == "dual_fisheye" ? 2 * height : int(std::lround(lens.width() * scale));
  if (!(width >= 2 && height >= 2))
    throw std::invalid_argument("a scale of " + std::to_string(scale) + " leaves a " +
                                std::to_string(lens.width()) + " x " +
                                std::to_string(lens.height()) + " image under 2 pixels");
  const double sx = double(width) / lens.width(), sy = double(height) / lens.height();
  nlohmann::json p = lens.parameters();
  p["width"] = width, p["height"] = height;
  if (p.contains("K")) p["K"] = scaled_k(p["K"], sx, sy);
  if (model == "woodscape") {  // rho in pixels along x, the aspect ratio stretching y
    for (nlohmann::json& k : p["k"]) k = k.get<double>() * sx;
    p["aspect_ratio"] = p["aspect_ratio"].get<double>() * sy / sx;
    p["cx_offset"] = p["cx_offset"].get<double>() * sx;
    p["cy_offset"] = p["cy_offset"].get<double>() * sy;
  } else if (model == "dual_fisheye") {
    p["f"] = p["f"].get<double>() * sy;  // sx == sy
  } else if (model == "panoramic_annular") {
    // pixel = A m + centre with A = [c d; e 1]: scaled, A' = [sx c / sy, sx d / sy; e, 1] of
    // m' = sy m, and f'(sy rho) = sy f(rho), so a_i' = a_i sy^(1 - i); OCamCalib's centre as K's
    std::vector<double> a = p["affine"], centre = p["centre"], poly = p["polynomial"];
    p["affine"] = {a[0] * sx / sy, a[1] * sx / sy, a[2]};
    p["centre"] = {(centre[0] + 0.5) * sx - 0.5, (centre[1] + 0.5) * sy - 0.5};
    for (std::size_t i = 0; i < poly.size(); ++i) poly[i] *= std::pow(sy, 1.0 - double(i));
    p["polynomial"] = poly;
  }
  return make_lens(model, p);
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
