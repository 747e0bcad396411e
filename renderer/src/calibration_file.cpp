#include "flowscape/renderer/calibration_file.h"

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <sstream>
#include <stdexcept>

#include "flowscape/core/files.h"

namespace flowscape {
namespace {

constexpr double kDegree = kPi / 180;

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// PyYAML (Kalibr) writes a block sequence at its key's indentation ("T_cn_cnm1:\n- [...]"), which
// YAML allows and OpenCV's reader refuses; it also wants the %YAML directive. Indents such items
// under their key and adds the directive.
std::string as_opencv_yaml(const std::string& yaml) {
  std::istringstream in(yaml);
  std::string line, out = yaml.starts_with("%YAML") ? "" : "%YAML:1.0\n---\n";
  std::size_t key_indent = std::string::npos;
  while (std::getline(in, line)) {
    const std::size_t indent = line.find_first_not_of(' ');
    const bool item = indent != std::string::npos && line[indent] == '-';
    if (item && indent == key_indent)
      line.insert(0, 2, ' ');
    else if (!item) {
      const std::size_t end = line.find_last_not_of(" \r");
      key_indent = end != std::string::npos && line[end] == ':' ? indent : std::string::npos;
    }
    out += line + '\n';
  }
  return out;
}

cv::FileStorage open_calibration(const std::filesystem::path& file) {
  std::string text = read_file(file, 1u << 24);
  if (file.extension() != ".xml") text = as_opencv_yaml(text);
  try {
    return cv::FileStorage(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  } catch (const cv::Exception& e) {  // OpenCV's parser names the line in `func`
    throw FileError(file, "not a calibration OpenCV can read (" + e.func + " " + e.err + ")");
  }
}

// A list of numbers: a YAML/XML sequence, or an opencv-matrix's elements row by row.
std::vector<double> numbers(const cv::FileNode& node, const std::string& key) {
  std::vector<double> values;
  if (node.isMap() && !node["data"].empty()) {
    cv::Mat m;
    node >> m;
    m.convertTo(m, CV_64F);
    values.assign(m.begin<double>(), m.end<double>());
  } else if (node.isSeq()) {
    for (const cv::FileNode& n : node) {
      require(n.isReal() || n.isInt(), "\"" + key + "\" must hold numbers");
      values.push_back(n.real());
    }
  } else
    require(false, "needs \"" + key + "\" (a list of numbers)");
  for (double v : values) require(std::isfinite(v), "\"" + key + "\" must be finite");
  return values;
}

std::vector<double> numbers(const cv::FileNode& node, const std::string& key, std::size_t count) {
  const std::vector<double> values = numbers(node, key);
  require(values.size() == count, "\"" + key + "\" must hold " + std::to_string(count) +
                                      " numbers (has " + std::to_string(values.size()) + ")");
  return values;
}

nlohmann::json k_matrix(double fx, double fy, double cx, double cy) {
  return {{fx, 0, cx}, {0, fy, cy}, {0, 0, 1}};
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

nlohmann::json sized(int width, int height, nlohmann::json K) {
  require(width >= 2 && height >= 2, "the image size must be at least 2 x 2");
  return {{"width", width}, {"height", height}, {"K", std::move(K)}};
}

// One camera of OpenCV's calibration sample or tutorial (cv::calibrateCamera, cv::fisheye).
std::shared_ptr<const Lens> opencv_lens(const cv::FileStorage& fs) {
  const cv::FileNode k = fs["camera_matrix"].empty() ? fs["Camera_Matrix"] : fs["camera_matrix"];
  const cv::FileNode d = fs["distortion_coefficients"].empty() ? fs["Distortion_Coefficients"]
                                                               : fs["distortion_coefficients"];
  const std::vector<double> K = numbers(k, "camera_matrix", 9);
  std::vector<double> D = numbers(d, "distortion_coefficients");
  require(!fs["image_width"].empty() && !fs["image_height"].empty(),
          "needs \"image_width\" and \"image_height\"");
  require(K[1] == 0 && K[3] == 0 && K[6] == 0 && K[7] == 0 && K[8] == 1,
          "camera_matrix must be [fx 0 cx; 0 fy cy; 0 0 1]");
  nlohmann::json p =
      sized(int(fs["image_width"]), int(fs["image_height"]), k_matrix(K[0], K[4], K[2], K[5]));
  if (!fs["fisheye_model"].empty() && int(fs["fisheye_model"]) != 0) {
    require(D.size() == 4, "a fisheye (cv::fisheye) calibration has 4 distortion coefficients");
    p["D"] = D;
    p["max_angle_degrees"] = kannala_brandt_reach_degrees(p["K"], D, p["width"], p["height"]);
    return make_lens("kannala_brandt", p);
  }
  require(D.size() == 4 || D.size() == 5 || D.size() == 8 || D.size() == 12 || D.size() == 14,
          "distortion_coefficients must hold 4, 5, 8, 12 or 14 numbers");
  for (std::size_t i = 5; i < D.size(); ++i)
    require(D[i] == 0,
            "the rational, thin-prism and tilt coefficients (after k3) must be 0: "
            "this toolkit's pinhole has k1, k2, p1, p2, k3");
  D.resize(std::min<std::size_t>(D.size(), 5));
  p["D"] = D;
  return make_lens("pinhole", p);
}

// One camera of a Kalibr camchain: pinhole with radtan, equidistant or no distortion, or ds.
std::shared_ptr<const Lens> kalibr_lens(const cv::FileNode& cam) {
  const std::string model = cam["camera_model"].string();
  const std::string distortion =
      cam["distortion_model"].empty() ? "none" : cam["distortion_model"].string();
  const std::vector<double> size = numbers(cam["resolution"], "resolution", 2);
  const int width = int(size[0]), height = int(size[1]);
  if (model == "pinhole") {
    const std::vector<double> i = numbers(cam["intrinsics"], "intrinsics", 4);  // fu fv pu pv
    nlohmann::json p = sized(width, height, k_matrix(i[0], i[1], i[2], i[3]));
    if (distortion == "radtan" || distortion == "none") {
      if (distortion == "radtan")
        p["D"] = numbers(cam["distortion_coeffs"], "distortion_coeffs", 4);
      return make_lens("pinhole", p);
    }
    require(distortion == "equidistant",
            "distortion model \"" + distortion +
                "\" is not one of this toolkit's (radtan, equidistant, none; calibrate fov "
                "cameras with pinhole-equi or ds)");
    const std::vector<double> d = numbers(cam["distortion_coeffs"], "distortion_coeffs", 4);
    p["D"] = d;
    p["max_angle_degrees"] = kannala_brandt_reach_degrees(p["K"], d, width, height);
    return make_lens("kannala_brandt", p);
  }
  if (model == "ds") {
    require(distortion == "none",
            "a ds camera has no distortion model (got \"" + distortion + "\")");
    const std::vector<double> i =
        numbers(cam["intrinsics"], "intrinsics", 6);  // xi alpha fu fv pu pv
    nlohmann::json p = sized(width, height, k_matrix(i[2], i[3], i[4], i[5]));
    p["xi"] = i[0], p["alpha"] = i[1];
    return make_lens("double_sphere", p);
  }
  return make_lens(model, {});  // omni, eucm: refused by name; others: unknown
}

// T_cn_cnm1: camera n-1 -> camera n, 4 rows of 4 numbers.
Pose chained_transform(const cv::FileNode& node) {
  const std::vector<double> t = [&node] {
    std::vector<double> flat;
    require(node.isSeq() && node.size() == 4, "\"T_cn_cnm1\" must be 4 rows of 4 numbers");
    for (const cv::FileNode& row : node) {
      const std::vector<double> r = numbers(row, "T_cn_cnm1", 4);
      flat.insert(flat.end(), r.begin(), r.end());
    }
    return flat;
  }();
  Eigen::Matrix4d m = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(t.data());
  const Mat3 r = m.topLeftCorner<3, 3>();
  require((r.transpose() * r - Mat3::Identity()).norm() < 1e-5 && r.determinant() > 0,
          "\"T_cn_cnm1\"'s rotation must be a rotation (orthonormal, determinant 1)");
  Pose pose = Pose::Identity();
  pose.linear() = Eigen::Quaterniond(r).normalized().toRotationMatrix();
  pose.translation() = m.topRightCorner<3, 1>();
  require(within_world(pose.translation()),
          "\"T_cn_cnm1\"'s translation must lie within 1,000 km (metres)");
  return pose;
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

std::vector<RigCamera> kalibr_cameras(const cv::FileStorage& fs, const CameraMount& first) {
  std::vector<RigCamera> cameras;
  Pose mount = first_mount(first);
  for (int n = 0; !fs["cam" + std::to_string(n)].empty(); ++n) {
    const std::string name = "cam" + std::to_string(n);
    const cv::FileNode cam = fs[name];
    try {
      if (n > 0) mount = mount * chained_transform(cam["T_cn_cnm1"]).inverse();
      cameras.push_back(mounted(name, kalibr_lens(cam), mount));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(name + ": " + e.what());
    }
  }
  return cameras;
}

}  // namespace

bool is_calibration_file(const std::filesystem::path& path) {
  const std::string extension = path.extension().string();
  return extension == ".yaml" || extension == ".yml" || extension == ".xml";
}

Rig rig_from_calibration(const std::filesystem::path& file,
                         const std::optional<CameraMount>& first_camera) {
  if (!first_camera)
    throw FileError(file,
                    "a calibration has no place on the vehicle: give the first camera's mount "
                    "with --rig-mount x,y,z,yaw,pitch,roll (metres in the rig frame, x forward, "
                    "y left, z up; degrees as in a rig file), e.g. 0.5,0,0.3,0,-5,0 on the roof");
  const cv::FileStorage fs = open_calibration(file);
  Rig rig{file.stem().string(), {}};
  try {
    if (!fs["cam0"].empty())
      rig.cameras = kalibr_cameras(fs, *first_camera);
    else if (!fs["camera_matrix"].empty() || !fs["Camera_Matrix"].empty())
      rig.cameras = {mounted("cam0", opencv_lens(fs), first_mount(*first_camera))};
    else
      require(false,
              "neither a Kalibr camchain (cam0, cam1, ...) nor an OpenCV calibration "
              "(camera_matrix, distortion_coefficients, image_width, image_height)");
  } catch (const std::invalid_argument& e) {
    throw FileError(file, e.what());
  } catch (const cv::Exception& e) {
    throw FileError(file, "a malformed entry (" + e.func + " " + e.err + ")");
  }
  return rig;
}

}  // namespace flowscape
