#include "flowscape/renderer/rig.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "flowscape/core/names.h"
#include "flowscape/scenes/trajectory.h"

namespace flowscape {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("rig: " + what);
}

// Every key of `object` is one of `known` (a misspelt key: the nearest known one suggested).
void require_known_keys(const nlohmann::json& object, const std::vector<std::string>& known,
                        const std::string& what,
                        const std::vector<std::pair<std::string, std::string>>& aliases = {}) {
  for (const auto& [key, value] : object.items())
    require(std::find(known.begin(), known.end(), key) != known.end(),
            what + "unknown key \"" + key + "\"" + did_you_mean(key, known, aliases));
}

// Other names calibration tools give a lens's parameters (OpenCV's FileStorage, Kalibr).
const std::vector<std::pair<std::string, std::string>> kParameterAliases = {
    {"camera_matrix", "K"},     {"cameraMatrix", "K"},    {"intrinsics", "K"},
    {"dist_coeffs", "D"},       {"distCoeffs", "D"},      {"distortion_coefficients", "D"},
    {"distortion_coeffs", "D"}, {"image_width", "width"}, {"image_height", "height"}};

// `key`'s text (`fallback` when absent); another type is an error naming the key.
std::string text(const nlohmann::json& object, const char* key, const std::string& fallback,
                 const std::string& what) {
  if (!object.contains(key)) return fallback;
  require(object.at(key).is_string(),
          what + "\"" + key + "\" must be text (got " + object.at(key).dump() + ")");
  return object.at(key).get<std::string>();
}

Vec3 vector3(const nlohmann::json& value, const std::string& what) {
  require(value.is_array() && value.size() == 3, what + " must be 3 numbers");
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    require(value[std::size_t(i)].is_number(), what + " must be 3 numbers");
    v[i] = value[std::size_t(i)].get<double>();
  }
  require(v.allFinite(), what + " must be finite");
  return v;
}

Mat3 rotation_rows(const nlohmann::json& rows, const std::string& what) {
  require(rows.is_array() && rows.size() == 3, what + " must be 3 rows of 3 numbers");
  Mat3 m;
  for (int r = 0; r < 3; ++r) m.row(r) = vector3(rows[std::size_t(r)], what).transpose();
  require((m.transpose() * m - Mat3::Identity()).norm() < 1e-6 && m.determinant() > 0,
          what + " must be a rotation (orthonormal, determinant 1)");
  return m;
}

nlohmann::json rows(const Mat3& m) {
  return {{m(0, 0), m(0, 1), m(0, 2)}, {m(1, 0), m(1, 1), m(1, 2)}, {m(2, 0), m(2, 1), m(2, 2)}};
}

// {"readout_ms": r in (0, 1000], "lines": "rows" (default) | "columns"}
Readout readout_from_json(const nlohmann::json& j, const std::string& what) {
  require(j.is_object(), what + "\"rolling_shutter\" must be an object");
  for (const auto& [key, value] : j.items())
    require(key == "readout_ms" || key == "lines",
            what + "rolling_shutter: unknown key \"" + key + "\" (readout_ms, lines)");
  const nlohmann::json ms = j.value("readout_ms", nlohmann::json());
  require(ms.is_number() && ms.get<double>() > 0 && ms.get<double>() <= 1000,
          what + "rolling_shutter \"readout_ms\" must be a number in (0, 1000]");
  const nlohmann::json lines = j.value("lines", nlohmann::json("rows"));
  require(lines == "rows" || lines == "columns",
          what + "rolling_shutter \"lines\" must be \"rows\" or \"columns\"");
  return {ms.get<double>() / 1000, lines == "columns"};
}

RigCamera camera_from_json(const nlohmann::json& c) {
  require(c.is_object(), "every camera must be an object");
  const std::string name = text(c, "name", "", "a camera's ");
  require(!name.empty() &&
              name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") == std::string::npos,
          "camera names are lower-case letters, digits, - and _ (got \"" + name + "\")");
  const std::string what = "camera \"" + name + "\": ";
  require_known_keys(c, {"name", "model", "parameters", "mount", "rolling_shutter"}, what);
  const std::string model = text(c, "model", "", what);
  const nlohmann::json parameters = c.value("parameters", nlohmann::json::object());
  require(parameters.is_object(), what + "\"parameters\" must be an object");
  require(c.contains("mount"),
          what + "needs a \"mount\": {\"position\": [x, y, z] (metres, rig frame)" +
              (model == "equirectangular" ? std::string("}")
                                          : ", and \"yaw_pitch_roll_degrees\" or "
                                            "\"camera_to_rig\"}"));
  const nlohmann::json mount = c.at("mount");
  require(mount.is_object(), what + "\"mount\" must be an object");
  require_known_keys(mount, {"position", "camera_to_rig", "yaw_pitch_roll_degrees"},
                     what + "mount: ");
  require(mount.contains("position"), what + "mount needs a \"position\" [x, y, z] (metres)");
  require(model == "equirectangular" || mount.contains("camera_to_rig") ||
              mount.contains("yaw_pitch_roll_degrees"),
          what + "mount needs a rotation: \"yaw_pitch_roll_degrees\" or \"camera_to_rig\"");
  RigCamera camera{name, {}, Vec3::Zero()};
  camera.position = vector3(mount.at("position"), what + "position");
  require(within_world(camera.position), what + "position must lie within 1,000 km (metres)");
  Mat3 rotation = look(0, 0, 0);
  if (mount.contains("camera_to_rig"))
    rotation = rotation_rows(mount.at("camera_to_rig"), what + "camera_to_rig");
  else if (mount.contains("yaw_pitch_roll_degrees")) {
    const Vec3 a = vector3(mount.at("yaw_pitch_roll_degrees"), what + "yaw_pitch_roll_degrees");
    rotation = look(a[0], a[1], a[2]);
  }
  try {
    if (model == "equirectangular") {
      const nlohmann::json height = parameters.value("height", nlohmann::json());
      require(height.is_number_integer() && height.get<std::int64_t>() >= 2 &&
                  height.get<std::int64_t>() <= 8192,
              what + "equirectangular \"height\" must be a whole number in 2..8192");
      require(!mount.contains("camera_to_rig") && !mount.contains("yaw_pitch_roll_degrees"),
              what + "an equirectangular camera keeps the rig's axes (no rotation)");
      camera.projection = Projection::equirectangular(height.get<int>());
    } else {
      camera.projection = Projection::of_lens(make_lens(model, parameters), rotation);
      const nlohmann::json read_back = camera.projection.lens->parameters();
      std::vector<std::string> known;
      for (const auto& [key, value] : read_back.items()) known.push_back(key);
      require_known_keys(parameters, known, what + "lens parameters: ", kParameterAliases);
    }
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    throw std::invalid_argument(message.starts_with("rig: ") ? message : "rig: " + what + message);
  }
  if (c.contains("rolling_shutter")) {
    require(model != "equirectangular", what + "an equirectangular camera has no rolling shutter");
    camera.readout = readout_from_json(c.at("rolling_shutter"), what);
  }
  return camera;
}

}  // namespace

Pose RigCamera::mount() const {
  Pose pose = Pose::Identity();
  pose.linear() = projection.camera_to_rig();
  pose.translation() = position;
  return pose;
}

std::vector<Vec3> Rig::optical_centres() const {
  if (flowscape) return {cameras.front().position};
  std::vector<Vec3> centres;
  for (const RigCamera& camera : cameras) centres.push_back(camera.position);
  return centres;
}

Rig flowscape_rig(int height, int face_size) {
  Rig rig{kFlowscapeRig, {{"erp", Projection::equirectangular(height)}}, true};
  if (face_size > 0)
    for (Face face : kFaces)
      rig.cameras.push_back({std::string(face_name(face)), Projection::cube_face(face, face_size)});
  return rig;
}

Mat3 look(double yaw_degrees, double pitch_degrees, double roll_degrees) {
  Mat3 forward;  // camera x right = rig -y, y down = rig -z, z forward = rig x
  forward << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return yaw_pitch_roll(yaw_degrees, pitch_degrees, roll_degrees) * forward;
}

std::vector<std::string> rig_presets() { return {"fisheye", "woodscape", "pal", "dual-fisheye"}; }

Rig rig_preset(const std::string& name, int size) {
  const auto camera = [](std::string n, std::shared_ptr<const Lens> lens, Vec3 position,
                         const Mat3& rotation) {
    return RigCamera{std::move(n), Projection::of_lens(std::move(lens), rotation), position};
  };
  if (name == "fisheye")  // one forward-looking 200-degree fisheye at the rig's origin
    return {name, {camera("front", kannala_brandt_200(size), Vec3::Zero(), look(0, 0, 0))}};
  if (name == "woodscape") {  // WoodScape's four: bumpers and mirrors, pitched down
    const int W = 2 * ((5 * size / 4 + 1) / 2), H = 2 * ((W * 966 / 1280 + 1) / 2);
    const auto lens = woodscape_190(W, H);
    return {name,
            {camera("front", lens, {2.0, 0, -1.0}, look(0, -20, 0)),
             camera("rear", lens, {-2.3, 0, -0.8}, look(180, -20, 0)),
             camera("mirror_left", lens, {0.8, 1.0, -0.6}, look(90, -40, 0)),
             camera("mirror_right", lens, {0.8, -1.0, -0.6}, look(-90, -40, 0))}};
  }
  if (name == "pal")  // the paper's robot: a panoramic annular lens on a mast, axis up
    return {name, {camera("pal", panoramic_annular(size, 60), {0, 0, 0.5}, look(0, 90, 0))}};
  if (name == "dual-fisheye")  // a consumer 360 camera on the roof, lenses forward and back
    return {name, {camera("dual", dual_fisheye_190(size), {0, 0, 0.2}, look(0, 0, 0))}};
  std::string known = kFlowscapeRig;
  for (const std::string& p : rig_presets()) known += ", " + p;
  throw std::invalid_argument("unknown rig \"" + name + "\" (" + known + ", or a rig file .json)");
}

Rig rig_from_json(const nlohmann::json& json) {
  require(json.is_object(), "expected a JSON object {\"name\", \"cameras\"}");
  require_known_keys(json, {"name", "cameras"}, "");
  Rig rig{text(json, "name", "custom", ""), {}};
  const nlohmann::json cameras = json.value("cameras", nlohmann::json());
  require(cameras.is_array() && !cameras.empty() && cameras.size() <= kMaxRigCameras,
          "\"cameras\" must list 1 to 16 cameras");
  std::set<std::string> names;
  for (const nlohmann::json& c : cameras) {
    rig.cameras.push_back(camera_from_json(c));
    require(names.insert(rig.cameras.back().name).second,
            "two cameras are named \"" + rig.cameras.back().name + "\"");
  }
  return rig;
}

Rig scaled_rig(const Rig& rig, double scale) {
  Rig scaled = rig;
  for (RigCamera& camera : scaled.cameras) {
    const Mat3 rotation = camera.projection.rotation;
    if (camera.projection.wraps_around()) {
      const int height = int(std::lround(camera.projection.height * scale));
      require(height >= 2, "camera \"" + camera.name + "\": a scale of " + std::to_string(scale) +
                               " leaves its panorama under 2 pixels high");
      camera.projection = Projection::equirectangular(height);
    } else {
      try {
        camera.projection =
            Projection::of_lens(scaled_lens(*camera.projection.lens, scale), rotation);
      } catch (const std::invalid_argument& e) {
        require(false, "camera \"" + camera.name + "\": " + e.what());
      }
    }
  }
  return scaled;
}

nlohmann::json to_json(const Rig& rig) {
  nlohmann::json cameras = nlohmann::json::array();
  for (const RigCamera& c : rig.cameras) {
    nlohmann::json mount = {{"position", {c.position.x(), c.position.y(), c.position.z()}}};
    if (!c.projection.wraps_around()) mount["camera_to_rig"] = rows(c.projection.rotation);
    cameras.push_back({{"name", c.name},
                       {"model", c.projection.model()},
                       {"parameters", c.projection.parameters()},
                       {"mount", mount}});
    if (!c.readout.global())
      cameras.back()["rolling_shutter"] = {{"readout_ms", c.readout.seconds * 1000},
                                           {"lines", c.readout.columns ? "columns" : "rows"}};
  }
  return {{"name", rig.name}, {"cameras", cameras}};
}

TruthRequest at_camera(const TruthRequest& request, const RigCamera& camera) {
  const Eigen::Translation3d offset(camera.position);
  TruthRequest moved = request;
  moved.pair.rig = request.pair.rig * offset;
  moved.pair.next_rig = request.pair.next_rig * offset;
  for (Moment& m : moved.more) m.rig = m.rig * offset;
  if (request.track)
    moved.track = [track = request.track, offset](double t) { return track(t) * offset; };
  moved.readout = camera.readout;
  return moved;
}

}  // namespace flowscape
