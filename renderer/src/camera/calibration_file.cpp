#include "flowscape/renderer/calibration_file.h"

#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <opencv2/core.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "flowscape/core/files.h"
#include "flowscape/core/names.h"
#include "flowscape/scenes/model_io.h"

namespace flowscape {
namespace {

constexpr double kDegree = kPi / 180;
// Deeper than any calibration nests; refused before a recursive parser sees it (a file nested
// tens of thousands deep would overflow the stack of yaml-cpp's or OpenCV's parser).
constexpr int kMaxNesting = 64;
// A glTF camera's image height (glTF gives a field of view, no pixels); --scale sets another.
constexpr int kGltfCameraHeight = 512;

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

// ---- the file as a JSON document, whatever wrote it ------------------------------------------

// The deepest nesting of a YAML file's flow collections and block indentation (comments and
// quoted text skipped).
int yaml_depth(const std::string& text) {
  int depth = 0, deepest = 0;
  char quote = 0;
  for (std::size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '#' && (k == 0 || std::isspace(static_cast<unsigned char>(text[k - 1])))) {
      k = std::min(text.find('\n', k), text.size()) - 1;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    } else if (c == '\n') {
      const std::size_t content = text.find_first_not_of(' ', k + 1);
      if (content != std::string::npos) deepest = std::max(deepest, int((content - k - 1) / 2));
    }
  }
  return deepest;
}

// The deepest nesting of an XML file's elements.
int xml_depth(const std::string& text) {
  int depth = 0, deepest = 0;
  for (std::size_t k = text.find('<'); k != std::string::npos; k = text.find('<', k + 1)) {
    const std::size_t end = text.find('>', k);
    if (k + 1 >= text.size() || text[k + 1] == '?' || text[k + 1] == '!') continue;
    if (text[k + 1] == '/')
      --depth;
    else if (end != std::string::npos && text[end - 1] != '/')
      deepest = std::max(deepest, ++depth);
  }
  return deepest;
}

nlohmann::json number_or_text(const std::string& text, bool plain) {
  if (plain && !text.empty()) {
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end == text.c_str() + text.size()) {
      const bool integral = text.find_first_of(".eEnN") == std::string::npos &&
                            std::abs(value) < 9e15;  // exactly an int64
      return integral ? nlohmann::json(std::int64_t(value)) : nlohmann::json(value);
    }
  }
  return text;
}

nlohmann::json from_yaml(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Sequence: {
      nlohmann::json list = nlohmann::json::array();
      for (const YAML::Node& item : node) list.push_back(from_yaml(item));
      return list;
    }
    case YAML::NodeType::Map: {
      nlohmann::json map = nlohmann::json::object(), merged = nlohmann::json::object();
      for (const auto& entry : node) {
        const std::string key = entry.first.as<std::string>();
        if (key != "<<") {
          require(!map.contains(key), "line " + std::to_string(entry.first.Mark().line + 1) +
                                          ": key \"" + key +
                                          "\" appears twice in one map (YAML keys are unique)");
          map[key] = from_yaml(entry.second);
          continue;
        }
        // YAML 1.1's merge key (PyYAML's "<<: *anchor"): the anchored maps' keys, the map's own
        // winning, as PyYAML reads them
        const nlohmann::json sources = from_yaml(entry.second);
        for (const nlohmann::json& source : sources.is_array() ? sources : nlohmann::json{sources})
          if (source.is_object())
            for (const auto& [name, value] : source.items()) merged.emplace(name, value);
      }
      for (const auto& [name, value] : merged.items()) map.emplace(name, value);
      return map;
    }
    case YAML::NodeType::Scalar:  // quoted scalars carry the tag "!": text, even "3"
      return number_or_text(node.Scalar(), node.Tag() != "!");
    default:
      return nullptr;
  }
}

nlohmann::json from_file_node(const cv::FileNode& node) {
  if (node.isSeq() || node.isMap()) {
    nlohmann::json out = node.isSeq() ? nlohmann::json::array() : nlohmann::json::object();
    for (const cv::FileNode& item : node) {
      if (node.isSeq())
        out.push_back(from_file_node(item));
      else
        out[item.name()] = from_file_node(item);
    }
    return out;
  }
  if (node.isInt()) return int(node);
  if (node.isReal()) return double(node);
  if (node.isString()) return node.string();
  return nullptr;
}

// YAML as any YAML tool reads it (Kalibr's PyYAML, ROS, OpenCV's own "%YAML:1.0" with its
// !!opencv-matrix maps); XML as OpenCV's FileStorage writes it.
nlohmann::json calibration_document(const std::filesystem::path& file, std::string text) {
  const bool xml = file.extension() == ".xml";
  require((xml ? xml_depth(text) : yaml_depth(text)) <= kMaxNesting,
          "nested more than " + std::to_string(kMaxNesting) + " levels deep: not a calibration");
  if (xml) {
    try {
      return from_file_node(
          cv::FileStorage(text, cv::FileStorage::READ | cv::FileStorage::MEMORY).root());
    } catch (const cv::Exception& e) {  // OpenCV's parser names the line in `func`
      throw std::invalid_argument("not XML OpenCV can read (" + e.func + " " + e.err + ")");
    }
  }
  if (text.starts_with("%YAML:")) text.erase(0, text.find('\n'));  // OpenCV's directive
  try {
    return from_yaml(YAML::Load(text));
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument("not YAML (line " + std::to_string(e.mark.line + 1) + ": " + e.msg +
                                ")");
  }
}

// ---- reading the document ---------------------------------------------------------------------

// The entry of `map` under any of `keys`, their case ignored (OpenCV's tutorial writes
// Camera_Matrix and image_Width, ROS's messages K, D, width); null when there is none.
const nlohmann::json* field(const nlohmann::json& map, std::initializer_list<const char*> keys) {
  if (!map.is_object()) return nullptr;
  for (const char* key : keys)
    for (const auto& [name, value] : map.items())
      if (lower(name) == lower(key)) return &value;
  return nullptr;
}

// A list of numbers: a flat list, rows of numbers (Kalibr's 4 x 4), or OpenCV's and ROS's
// {rows, cols, data}, row by row.
std::vector<double> numbers(const nlohmann::json* node, const std::string& key) {
  require(node, "needs \"" + key + "\" (a list of numbers)");
  const nlohmann::json& list =
      node->is_object() && node->contains("data") ? node->at("data") : *node;
  require(list.is_array(), "\"" + key + "\" must be a list of numbers");
  std::vector<double> values;
  for (const nlohmann::json& item : list) {
    if (item.is_array())
      for (const nlohmann::json& value : item) {
        require(value.is_number(), "\"" + key + "\" must hold numbers");
        values.push_back(value.get<double>());
      }
    else {
      require(item.is_number(), "\"" + key + "\" must hold numbers");
      values.push_back(item.get<double>());
    }
  }
  for (double v : values) require(std::isfinite(v), "\"" + key + "\" must be finite");
  return values;
}

std::vector<double> numbers(const nlohmann::json* node, const std::string& key, std::size_t count) {
  const std::vector<double> values = numbers(node, key);
  require(values.size() == count, "\"" + key + "\" must hold " + std::to_string(count) +
                                      " numbers (has " + std::to_string(values.size()) + ")");
  return values;
}

int whole_number(const nlohmann::json* node, const std::string& key) {
  require(node && node->is_number_integer(), "needs \"" + key + "\" (a whole number of pixels)");
  const std::int64_t value = node->get<std::int64_t>();
  require(value >= 2 && value <= 16384, "\"" + key + "\" must be in 2..16384 pixels");
  return int(value);
}

std::string text_of(const nlohmann::json* node, const std::string& fallback) {
  return node && node->is_string() ? node->get<std::string>() : fallback;
}

nlohmann::json k_matrix(double fx, double fy, double cx, double cy) {
  return {{fx, 0, cx}, {0, fy, cy}, {0, 0, 1}};
}

nlohmann::json sized(int width, int height, nlohmann::json K) {
  return {{"width", width}, {"height", height}, {"K", std::move(K)}};
}

// The angle from the axis of the image's farthest corner for a Kannala-Brandt lens (OpenCV's
// centre convention), where theta_d(theta) keeps growing: its max_angle_degrees, so that the
// whole image sees.
double kannala_brandt_reach_degrees(const nlohmann::json& K, const std::vector<double>& d,
                                    int width, int height) {
  const double fx = K[0][0], fy = K[1][1], cx = K[0][2], cy = K[1][2];
  double corner = 0;
  for (double x : {-0.5 - cx, width - 0.5 - cx})
    for (double y : {-0.5 - cy, height - 0.5 - cy})
      corner = std::max(corner, std::hypot(x / fx, y / fy));
  const auto theta_d = [&d](double t) {
    const double t2 = t * t;
    return t * (1 + t2 * (d[0] + t2 * (d[1] + t2 * (d[2] + t2 * d[3]))));
  };
  const auto at = [](int tenths) { return tenths * 0.1 * kDegree; };
  int tenths = 1;  // of a degree
  while (tenths < 1799 && theta_d(at(tenths)) < corner &&
         theta_d(at(tenths + 1)) > theta_d(at(tenths)))
    ++tenths;
  return tenths / 10.0;
}

std::shared_ptr<const Lens> fisheye(nlohmann::json p, const std::vector<double>& d) {
  p["D"] = d;
  p["max_angle_degrees"] = kannala_brandt_reach_degrees(p["K"], d, p["width"], p["height"]);
  return make_lens("kannala_brandt", p);
}

// Brown-Conrady coefficients k1 k2 p1 p2 [k3 [k4 k5 k6 [s1..s4 [tx ty]]]], as OpenCV orders
// them: this toolkit's pinhole has k1, k2, p1, p2, k3.
std::shared_ptr<const Lens> distorted_pinhole(nlohmann::json p, std::vector<double> d,
                                              const std::string& key) {
  require(d.size() == 4 || d.size() == 5 || d.size() == 8 || d.size() == 12 || d.size() == 14,
          "\"" + key + "\" must hold 4, 5, 8, 12 or 14 numbers");
  for (std::size_t i = 5; i < d.size(); ++i)
    require(d[i] == 0, "\"" + key +
                           "\": the rational, thin-prism and tilt coefficients (after k3) must be "
                           "0: this toolkit's pinhole has k1, k2, p1, p2, k3");
  d.resize(std::min<std::size_t>(d.size(), 5));
  p["D"] = d;
  return make_lens("pinhole", p);
}

// One camera as OpenCV's calibration sample and tutorial (cv::calibrateCamera, cv::fisheye) and
// ROS's camera_info (YAML file or message) write it.
std::shared_ptr<const Lens> opencv_lens(const nlohmann::json& doc) {
  const std::vector<double> K = numbers(field(doc, {"camera_matrix", "K"}), "camera_matrix", 9);
  const std::vector<double> D =
      numbers(field(doc, {"distortion_coefficients", "D"}), "distortion_coefficients");
  require(K[1] == 0 && K[3] == 0 && K[6] == 0 && K[7] == 0 && K[8] == 1,
          "\"camera_matrix\" must be [fx 0 cx; 0 fy cy; 0 0 1]");
  const nlohmann::json p =
      sized(whole_number(field(doc, {"image_width", "width"}), "image_width"),
            whole_number(field(doc, {"image_height", "height"}), "image_height"),
            k_matrix(K[0], K[4], K[2], K[5]));
  const nlohmann::json* fisheye_model = field(doc, {"fisheye_model"});
  const std::string model = lower(text_of(field(doc, {"distortion_model"}), "plumb_bob"));
  if ((fisheye_model && fisheye_model->is_number() && fisheye_model->get<double>() != 0) ||
      model == "equidistant" || model == "fisheye") {
    require(D.size() == 4,
            "a fisheye (cv::fisheye, ROS equidistant) has 4 distortion coefficients");
    return fisheye(p, D);
  }
  require(model == "plumb_bob" || model == "rational_polynomial",
          "\"distortion_model\": \"" + model +
              "\" is not one of this toolkit's (plumb_bob, rational_polynomial with k4-k6 0, "
              "equidistant)");
  return distorted_pinhole(p, D, "distortion_coefficients");
}

// One camera of a Kalibr camchain: pinhole with radtan, equidistant or no distortion, or ds.
std::shared_ptr<const Lens> kalibr_lens(const nlohmann::json& cam) {
  const std::string model = text_of(field(cam, {"camera_model"}), "");
  const std::string distortion = text_of(field(cam, {"distortion_model"}), "none");
  const std::vector<double> size = numbers(field(cam, {"resolution"}), "resolution", 2);
  const int width = int(size[0]), height = int(size[1]);
  require(width == size[0] && height == size[1] && width >= 2 && height >= 2 && width <= 16384 &&
              height <= 16384,
          "\"resolution\" must be two whole numbers in 2..16384");
  if (model == "pinhole") {
    const std::vector<double> i = numbers(field(cam, {"intrinsics"}), "intrinsics", 4);
    const nlohmann::json p = sized(width, height, k_matrix(i[0], i[1], i[2], i[3]));
    if (distortion == "none") return make_lens("pinhole", p);
    const std::vector<double> d =
        numbers(field(cam, {"distortion_coeffs"}), "distortion_coeffs", 4);
    if (distortion == "radtan") return distorted_pinhole(p, d, "distortion_coeffs");
    require(distortion == "equidistant",
            "\"distortion_model\": \"" + distortion +
                "\" is not one of this toolkit's (radtan, equidistant, none; calibrate fov "
                "cameras with pinhole-equi or ds)");
    return fisheye(p, d);
  }
  if (model == "ds") {
    require(distortion == "none",
            "a ds camera has no distortion model (got \"" + distortion + "\")");
    const std::vector<double> i = numbers(field(cam, {"intrinsics"}), "intrinsics", 6);
    nlohmann::json p = sized(width, height, k_matrix(i[2], i[3], i[4], i[5]));
    p["xi"] = i[0], p["alpha"] = i[1];
    return make_lens("double_sphere", p);
  }
  return make_lens(model, {});  // omni, eucm: refused by name; others: unknown
}

// A 4 x 4 rigid transform (Kalibr's T_cn_cnm1, T_cam_imu).
Pose rigid_transform(const nlohmann::json* node, const std::string& key) {
  const std::vector<double> t = numbers(node, key, 16);
  const Eigen::Matrix4d m =
      Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(t.data());
  const Mat3 r = m.topLeftCorner<3, 3>();
  require((r.transpose() * r - Mat3::Identity()).norm() < 1e-5 && r.determinant() > 0,
          "\"" + key + "\"'s rotation must be a rotation (orthonormal, determinant 1)");
  require(m.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1)),
          "\"" + key + "\"'s last row must be 0 0 0 1");
  Pose pose = Pose::Identity();
  pose.linear() = Eigen::Quaterniond(r).normalized().toRotationMatrix();
  pose.translation() = m.topRightCorner<3, 1>();
  require(within_world(pose.translation()),
          "\"" + key + "\"'s translation must lie within 1,000 km (metres)");
  return pose;
}

// Camera n-1 -> camera n: T_cn_cnm1, or from the two cameras' T_cam_imu (camchain-imucam files
// that give only those: T_cn_cnm1 = T_cn_imu T_cnm1_imu^-1).
Pose previous_to_this(const nlohmann::json& cam, const nlohmann::json& previous,
                      const std::string& previous_name) {
  if (const nlohmann::json* chained = field(cam, {"T_cn_cnm1"}))
    return rigid_transform(chained, "T_cn_cnm1");
  const nlohmann::json *here = field(cam, {"T_cam_imu"}), *there = field(previous, {"T_cam_imu"});
  require(here && there, "needs \"T_cn_cnm1\" (or \"T_cam_imu\" here and in " + previous_name +
                             ") to place it on the rig");
  return rigid_transform(here, "T_cam_imu") *
         rigid_transform(there, "T_cam_imu in " + previous_name).inverse();
}

RigCamera mounted(std::string name, std::shared_ptr<const Lens> lens, const Pose& camera_to_rig) {
  return {std::move(name), Projection::of_lens(std::move(lens), camera_to_rig.linear()),
          camera_to_rig.translation()};
}

Pose first_mount(const CameraMount& m) {
  Pose pose = Pose::Identity();
  pose.linear() =
      look(m.yaw_pitch_roll_degrees[0], m.yaw_pitch_roll_degrees[1], m.yaw_pitch_roll_degrees[2]);
  pose.translation() = m.position;
  return pose;
}

std::vector<RigCamera> kalibr_cameras(const nlohmann::json& doc, const CameraMount& first) {
  std::size_t count = 0;
  while (doc.contains("cam" + std::to_string(count))) ++count;
  require(count <= kMaxRigCameras, "holds " + std::to_string(count) +
                                       " cameras; a rig takes at most " +
                                       std::to_string(kMaxRigCameras));
  std::vector<RigCamera> cameras;
  Pose mount = first_mount(first);
  for (std::size_t n = 0; n < count; ++n) {
    const std::string name = "cam" + std::to_string(n);
    try {
      const nlohmann::json& cam = doc.at(name);
      require(cam.is_object(), "must be a map of the camera's keys");
      if (n > 0)
        mount = mount * previous_to_this(cam, doc.at("cam" + std::to_string(n - 1)),
                                         "cam" + std::to_string(n - 1))
                            .inverse();
      cameras.push_back(mounted(name, kalibr_lens(cam), mount));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(name + ": " + e.what());
    }
  }
  return cameras;
}

// ---- COLMAP's cameras.txt ---------------------------------------------------------------------

// One camera of COLMAP's cameras.txt (CAMERA_ID MODEL WIDTH HEIGHT PARAMS...). COLMAP puts the
// centre of the top-left pixel at (0.5, 0.5), OpenCV (and this toolkit's K) at (0, 0).
std::shared_ptr<const Lens> colmap_lens(const std::string& model, int width, int height,
                                        const std::vector<double>& v) {
  static const std::map<std::string, std::size_t> kCounts = {
      {"SIMPLE_PINHOLE", 3}, {"PINHOLE", 4},
      {"SIMPLE_RADIAL", 4},  {"RADIAL", 5},
      {"OPENCV", 8},         {"FULL_OPENCV", 12},
      {"OPENCV_FISHEYE", 8}, {"SIMPLE_RADIAL_FISHEYE", 4},
      {"RADIAL_FISHEYE", 5}};
  const auto count = kCounts.find(model);
  require(count != kCounts.end(),
          "camera model " + model +
              " is not one of this toolkit's (SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, "
              "OPENCV, FULL_OPENCV, OPENCV_FISHEYE, SIMPLE_RADIAL_FISHEYE, RADIAL_FISHEYE)");
  require(v.size() == count->second, model + " has " + std::to_string(count->second) +
                                         " parameters (got " + std::to_string(v.size()) + ")");
  const bool one_focal = model.starts_with("SIMPLE") || model.starts_with("RADIAL");
  const double fx = v[0], fy = one_focal ? v[0] : v[1];
  const std::size_t c = one_focal ? 1 : 2;  // where cx is
  const nlohmann::json p = sized(width, height, k_matrix(fx, fy, v[c] - 0.5, v[c + 1] - 0.5));
  const std::vector<double> rest(v.begin() + std::ptrdiff_t(c) + 2, v.end());
  if (model.ends_with("PINHOLE")) return make_lens("pinhole", p);
  if (model == "OPENCV_FISHEYE") return fisheye(p, rest);
  if (model.ends_with("FISHEYE")) return fisheye(p, {rest[0], rest.size() > 1 ? rest[1] : 0, 0, 0});
  if (model.ends_with("OPENCV")) return distorted_pinhole(p, rest, "params");
  return distorted_pinhole(p, {rest[0], rest.size() > 1 ? rest[1] : 0, 0, 0}, "params");
}

std::vector<RigCamera> colmap_cameras(const std::string& text, const CameraMount& first) {
  std::istringstream lines(text);
  std::vector<RigCamera> cameras;
  std::set<std::string> ids;
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    std::istringstream words(line);
    std::string id, model;
    if (!(words >> id) || id[0] == '#') continue;
    const std::string where = "line " + std::to_string(number) + ": ";
    int width = 0, height = 0;
    require(bool(words >> model >> width >> height) && width >= 2 && height >= 2 &&
                width <= 16384 && height <= 16384,
            where + "a camera is CAMERA_ID MODEL WIDTH HEIGHT PARAMS... (sizes in 2..16384)");
    require(ids.insert(id).second, where + "camera " + id + " is listed twice");
    std::vector<double> params;
    for (std::string word; words >> word;) {
      char* end = nullptr;
      params.push_back(std::strtod(word.c_str(), &end));
      require(end == word.c_str() + word.size() && std::isfinite(params.back()),
              where + "\"" + word + "\" is not a finite number");
    }
    try {
      cameras.push_back(
          mounted("cam" + id, colmap_lens(model, width, height, params), first_mount(first)));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(where + e.what());
    }
  }
  require(!cameras.empty(), "no camera (COLMAP's cameras.txt: CAMERA_ID MODEL WIDTH HEIGHT ...)");
  require(cameras.size() == 1,
          "holds " + std::to_string(cameras.size()) +
              " cameras: COLMAP does not know where they sit on a rig; keep the one your "
              "images.txt uses");
  return cameras;
}

// ---- glTF cameras -----------------------------------------------------------------------------

std::string camera_name(const std::string& name, std::size_t k) {
  std::string out;
  for (char c : lower(name)) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return out.empty() ? "cam" + std::to_string(k) : out;
}

std::vector<RigCamera> gltf_rig_cameras(const std::filesystem::path& file,
                                        const CameraMount& first) {
  const std::vector<FileCamera> found = gltf_cameras(file.string());
  require(!found.empty(), "holds no perspective camera");
  require(found.size() <= kMaxRigCameras, "holds " + std::to_string(found.size()) +
                                              " cameras; a rig takes at most " +
                                              std::to_string(kMaxRigCameras));
  const Pose rig_from_first = first_mount(first) * found.front().pose.inverse();
  std::vector<RigCamera> cameras;
  std::set<std::string> names;
  for (std::size_t k = 0; k < found.size(); ++k) {
    const FileCamera& c = found[k];
    const int height = kGltfCameraHeight,
              width = int(std::lround(height * (c.aspect_ratio > 0 ? c.aspect_ratio : 1)));
    require(width >= 2 && width <= 16384, "camera " + c.name + ": aspectRatio " +
                                              std::to_string(c.aspect_ratio) + " gives an image " +
                                              std::to_string(width) + " pixels wide");
    const double focal = height / 2.0 / std::tan(c.yfov_degrees * kDegree / 2);
    const nlohmann::json p =
        sized(width, height, k_matrix(focal, focal, (width - 1) / 2.0, (height - 1) / 2.0));
    const std::string base = camera_name(c.name, k);
    const std::string name = names.count(base) ? base + "_" + std::to_string(k) : base;
    names.insert(name);
    cameras.push_back(mounted(name, make_lens("pinhole", p), rig_from_first * c.pose));
  }
  return cameras;
}

}  // namespace

bool is_calibration_file(const std::filesystem::path& path) {
  const std::string extension = lower(path.extension().string());
  return extension == ".yaml" || extension == ".yml" || extension == ".xml" ||
         extension == ".txt" || extension == ".gltf" || extension == ".glb";
}

Rig rig_from_calibration(const std::filesystem::path& file,
                         const std::optional<CameraMount>& first_camera) {
  if (!first_camera)
    throw FileError(file,
                    "a calibration has no place on the vehicle: give the first camera's mount "
                    "with --rig-mount x,y,z,yaw,pitch,roll (metres in the rig frame, x forward, "
                    "y left, z up; degrees as in a rig file), e.g. 0.5,0,0.3,0,-5,0 on the roof");
  const std::string extension = lower(file.extension().string());
  Rig rig{file.stem().string(), {}};
  try {
    if (extension == ".gltf" || extension == ".glb") {
      rig.cameras = gltf_rig_cameras(file, *first_camera);
      return rig;
    }
    const std::string text = read_file(file, 1u << 24);
    if (extension == ".txt") {
      rig.cameras = colmap_cameras(text, *first_camera);
      return rig;
    }
    const nlohmann::json doc = calibration_document(file, text);
    if (field(doc, {"cam0"}))
      rig.cameras = kalibr_cameras(doc, *first_camera);
    else if (field(doc, {"camera_matrix", "K"}))
      rig.cameras = {mounted("cam0", opencv_lens(doc), first_mount(*first_camera))};
    else
      require(false,
              "neither a Kalibr camchain (cam0, cam1, ...) nor an OpenCV or ROS calibration "
              "(camera_matrix or K, distortion_coefficients or D, image_width, image_height)");
  } catch (const std::invalid_argument& e) {
    throw FileError(file, e.what());
  }
  return rig;
}

std::vector<std::string> calibration_warnings(const Rig& rig) {
  std::vector<std::string> warnings;
  for (const RigCamera& camera : rig.cameras) {
    const Lens& lens = *camera.projection.lens;
    std::size_t seen = 0;
    double widest = 0;  // degrees off the axis
    for (int y = 0; y < lens.height(); ++y)
      for (int x = 0; x < lens.width(); ++x)
        if (const std::optional<Vec3> ray = lens.ray(Vec2(x + 0.5, y + 0.5))) {
          ++seen;
          widest = std::max(widest, std::acos(std::clamp(ray->normalized().z(), -1.0, 1.0)));
        }
    const double share = double(seen) / (double(lens.width()) * lens.height());
    if (share >= 0.5) continue;
    char text[256];
    std::snprintf(text, sizeof text,
                  "%s sees only %.0f %% of its pixels: its model stops %.1f degrees off the axis "
                  "(where its distortion stops being invertible); the rest see nothing",
                  camera.name.c_str(), 100 * share, widest / kDegree);
    warnings.push_back(text);
  }
  return warnings;
}

}  // namespace flowscape
