// The ground truth of a rolling-shutter view (docs/cameras.md, "Rolling shutter"). Line l of the
// frame is captured at t(l + 1/2); its pixels' rays are cast with the scene and the camera posed
// then. A pixel's point P(t) (fixed on its object; the sky: a fixed direction) is seen in a
// target's image at the line s with s = line(project(camera(t(s))^-1 P(t(s)))): first_crossing
// finds the earliest such s, and the flow goes to the point's pixel then. Whether nothing hides
// it is asked once per target line: the scene, the camera and the point posed at the centre time
// of line floor(s) (within half a line's time of t(s)).
#include <tbb/parallel_for.h>

#include <cmath>

#include "render/truth.h"

namespace flowscape {
namespace {

constexpr double kScanStep = 8;      // lines between the samples of the crossing scan
constexpr double kTolerance = 1e-6;  // lines

// What a pixel sees: a surface point, or the sky in a world direction.
struct Subject {
  bool surface = false;
  SurfacePoint point{};
  Vec3 direction = Vec3::Zero();
};

// A target's scan samples (first_crossing's) with the camera, every mesh's pose and every skinned
// mesh's bones at their times, evaluated once for all pixels.
struct TargetScan {
  double frame_time = 0;
  std::vector<Pose> cameras;                          // per sample
  std::vector<std::vector<Pose>> poses;               // [sample][mesh]
  std::vector<std::vector<std::vector<Pose>>> bones;  // [sample][mesh]; empty for rigid meshes
};

struct RollingContext {
  const EmbreeScene& scene;
  const Projection& projection;
  const TruthRequest& request;
  int lines, steps;
  std::vector<TargetScan> scans;  // the pair's next frame, then request.more

  double time_of(int k, double s) const {
    return scans[std::size_t(k)].frame_time + request.readout.offset(s, lines);
  }
};

TargetScan scan_of(const EmbreeScene& scene, const TruthRequest& request, double frame_time,
                   int lines, int steps) {
  TargetScan scan;
  scan.frame_time = frame_time;
  for (int j = 0; j <= steps; ++j) {
    const double t = frame_time + request.readout.offset(double(lines) * j / steps, lines);
    scan.cameras.push_back(request.track(t));
    scan.poses.emplace_back(), scan.bones.emplace_back();
    for (unsigned m = 0; m < scene.mesh_count(); ++m)
      scan.poses.back().push_back(scene.pose_at(m, t)),
          scan.bones.back().push_back(scene.bones_at(m, t));
  }
  return scan;
}

// The camera and the subject (a world point, or the sky's direction) at line coordinate s of
// target k: from the scan's table where s is one of its samples, else evaluated.
struct Posed {
  Pose camera;
  Vec3 world;
};
Posed posed_at(const RollingContext& c, const Subject& subject, int k, double s) {
  const TargetScan& scan = c.scans[std::size_t(k)];
  const long sample = std::lround(s * c.steps / c.lines);
  if (double(c.lines) * double(sample) / c.steps == s) {
    const auto j = std::size_t(sample);
    const unsigned m = subject.point.mesh;
    return {scan.cameras[j], subject.surface ? c.scene.world_point(subject.point, scan.poses[j][m],
                                                                   &scan.bones[j][m])
                                             : subject.direction};
  }
  const double t = c.time_of(k, s);
  return {c.request.track(t),
          subject.surface ? c.scene.world_point(subject.point, t) : subject.direction};
}

std::optional<Vec2> seen_pixel(const RollingContext& c, const Subject& subject, const Posed& p) {
  const Vec3 direction =
      subject.surface ? Vec3(p.world - p.camera.translation()).normalized() : p.world;
  return c.projection.project(p.camera.linear().transpose() * direction);
}

// A pixel's flow to target k (valid is set by the visibility pass) and the line it is seen at.
struct Found {
  TargetTruth truth;
  int line = -1;  // -1: not seen
};
Found find_target(const RollingContext& c, const Subject& subject, bool on_rig, Vec2 pixel, int k) {
  const Readout& readout = c.request.readout;
  std::optional<double> line;
  if (on_rig) {
    line = readout.line_of(pixel);  // fixed to the camera: the same pixel at every time
  } else {
    line = first_crossing(
        [&](double s) -> std::optional<double> {
          const auto seen = seen_pixel(c, subject, posed_at(c, subject, k, s));
          return seen ? std::optional<double>(readout.line_of(*seen)) : std::nullopt;
        },
        c.lines, kScanStep, kTolerance);
  }
  Found found;
  if (!line) return found;
  const Posed posed = posed_at(c, subject, k, *line);
  if (subject.surface) found.truth.moved = posed.world;
  const std::optional<Vec2> seen = on_rig ? pixel : seen_pixel(c, subject, posed);
  if (!seen) return found;
  found.truth.u = float(seen->x() - pixel.x()), found.truth.v = float(seen->y() - pixel.y());
  found.line = std::min(int(std::floor(*line)), c.lines - 1);
  return found;
}

// Per target, per pixel: the line its visibility is asked at (-1: none) and what it sees.
struct Visibility {
  std::vector<int> lines;
  std::vector<Subject> subjects;
};

void trace_pixel(const RollingContext& c, const ImageTextures& images, const CameraAt& camera,
                 const Pose& pose, int x, int y, GroundTruth& out,
                 std::vector<Visibility>& visibility) {
  const Vec2 pixel(x + 0.5, y + 0.5);
  const Vec3 ray = c.projection.ray(pixel);
  if (ray.isZero()) return put_uncovered(out, x, y);
  const Vec3 direction = (pose.linear() * ray).normalized();
  const Hit hit = c.scene.intersect(camera.origin, direction);
  put_surface(c.scene, hit, out, x, y);
  const Vec3 point = camera.origin + hit.distance * direction;
  const Subject subject{hit.found, hit.found ? c.scene.surface_point(hit, point) : SurfacePoint{},
                        direction};
  const bool on_rig = hit.found && c.request.camera_on_rig && c.scene.mesh(hit.mesh).on_rig;
  const std::size_t index = std::size_t(y) * std::size_t(c.projection.width) + std::size_t(x);
  for (std::size_t k = 0; k < c.scans.size(); ++k) {
    const Found found = find_target(c, subject, on_rig, pixel, int(k));
    visibility[k].lines[index] = found.line, visibility[k].subjects[index] = subject;
    if (k > 0) {
      put_flow(out.more[k - 1].flow, out.more[k - 1].valid, x, y, found.truth);
      continue;
    }
    put_flow(out.flow, out.valid, x, y, found.truth);
    if (c.request.scene_flow)
      put_vector(out.scene_flow, x, y,
                 hit.found ? Vec3(camera.world_to_camera * (found.truth.moved - point))
                           : Vec3::Constant(kNoVector));
  }
  if (c.request.normal || c.request.shading_normal)
    put_normals(c.scene, images, c.projection, c.request, camera, hit, direction, pixel, out, x, y);
}

// valid = 1 where nothing hides a found target, asked per target line with the scene, the camera
// and the point posed at the line's centre time.
void test_visibility(EmbreeScene& scene, const RollingContext& c, int k,
                     const Visibility& visibility, Image<std::uint8_t>& valid) {
  std::vector<std::vector<std::size_t>> by_line(std::size_t(c.lines));
  for (std::size_t i = 0; i < visibility.lines.size(); ++i)
    if (visibility.lines[i] >= 0) by_line[std::size_t(visibility.lines[i])].push_back(i);
  for (int line = 0; line < c.lines; ++line) {
    const std::vector<std::size_t>& pixels = by_line[std::size_t(line)];
    if (pixels.empty()) continue;
    const double t = c.time_of(k, line + 0.5);
    scene.set_line_time(t);
    const Vec3 origin = c.request.track(t).translation();
    tbb::parallel_for(std::size_t(0), pixels.size(), [&](std::size_t p) {
      const std::size_t i = pixels[p];
      const Subject& subject = visibility.subjects[i];
      Vec3 direction = subject.direction;
      double distance = std::numeric_limits<double>::infinity();
      if (subject.surface) {
        direction = scene.world_point(subject.point, t) - origin;
        distance = direction.norm(), direction /= distance;
      }
      const int width = c.projection.width;
      naming_pixels(
          [&] { valid.data[i] = !scene.occluded(EmbreeScene::kNow, origin, direction, distance); },
          [&](int) {
            return std::pair{int(i % width), int(i / width)};
          });
    });
  }
}

}  // namespace

GroundTruth rolling_ground_truth(EmbreeScene& scene, const ImageTextures& images,
                                 const Projection& projection, const TruthRequest& request) {
  if (!request.track)
    throw std::invalid_argument("a rolling shutter needs the camera's track (TruthRequest::track)");
  if (projection.wraps_around())
    throw std::invalid_argument("a rolling shutter needs a lens or pinhole camera, not the ERP");
  const int lines = request.readout.lines(projection);
  RollingContext c{scene, projection, request, lines, scan_steps(lines, kScanStep), {}};
  c.scans.push_back(scan_of(scene, request, request.pair.next_time, lines, c.steps));
  for (const Moment& more : request.more)
    c.scans.push_back(scan_of(scene, request, more.time, lines, c.steps));
  GroundTruth out = allocate_truth(request, projection.width, projection.height);
  const std::size_t pixels = std::size_t(projection.width) * std::size_t(projection.height);
  std::vector<Visibility> visibility(c.scans.size(),
                                     {std::vector<int>(pixels, -1), std::vector<Subject>(pixels)});
  for_each_line(projection, request.readout, request.pair.time,
                [&](double t, const PixelWindow& window) {
                  scene.set_line_time(t);
                  const Pose pose = request.track(t);
                  const CameraAt camera = camera_at(pose, projection);
                  parallel_pixels(window, [&](int x, int y) {
                    trace_pixel(c, images, camera, pose, x, y, out, visibility);
                  });
                });
  test_visibility(scene, c, 0, visibility[0], out.valid);
  for (std::size_t k = 1; k < c.scans.size(); ++k)
    test_visibility(scene, c, int(k), visibility[k], out.more[k - 1].valid);
  return out;
}

}  // namespace flowscape
