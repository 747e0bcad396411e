#include "render/truth.h"

#include <optional>

#include "render/surface.h"

namespace flowscape {

CameraAt camera_at(const Pose& camera, const Projection& projection) {
  return {camera.translation(), (camera.linear() * projection.camera_to_rig()).transpose()};
}

GroundTruth allocate_truth(const TruthRequest& request, int width, int height) {
  const int W = width, H = height;
  GroundTruth gt{Image<float>(W, H, 2), Image<std::uint8_t>(W, H, 1), Image<std::uint16_t>(W, H, 1),
                 Image<float>(W, H, 1), Image<std::uint8_t>(W, H, 1)};
  for (std::size_t k = 0; k < request.more.size(); ++k)
    gt.more.push_back({Image<float>(W, H, 2), Image<std::uint8_t>(W, H, 1)});
  if (request.scene_flow) gt.scene_flow = Image<float>(W, H, 3);
  if (request.normal) gt.normal = Image<float>(W, H, 3);
  if (request.shading_normal) gt.shading_normal = Image<float>(W, H, 3);
  return gt;
}

void put_vector(Image<float>& image, int x, int y, const Vec3& value) {
  for (int i = 0; i < 3; ++i) image.pixel(x, y)[i] = float(value[i]);
}

void put_flow(Image<float>& flow, Image<std::uint8_t>& valid, int x, int y, const TargetTruth& t) {
  flow.pixel(x, y)[0] = t.u, flow.pixel(x, y)[1] = t.v;
  *valid.pixel(x, y) = t.valid;
}

void put_uncovered(GroundTruth& out, int x, int y) {
  *out.depth.pixel(x, y) = std::numeric_limits<float>::quiet_NaN();
  *out.semantic.pixel(x, y) = std::uint8_t(SemanticClass::Unlabeled);
  *out.instance.pixel(x, y) = 0;
  put_flow(out.flow, out.valid, x, y, {});
  for (FlowTruth& more : out.more) put_flow(more.flow, more.valid, x, y, {});
  for (Image<float>* image : {&out.scene_flow, &out.normal, &out.shading_normal})
    if (!image->data.empty()) std::fill_n(image->pixel(x, y), 3, kNoVector);
}

void put_surface(const EmbreeScene& scene, const Hit& hit, GroundTruth& out, int x, int y) {
  *out.depth.pixel(x, y) = float(hit.distance);
  *out.semantic.pixel(x, y) = std::uint8_t(
      hit.found ? scene.mesh(hit.mesh).mesh->classes[hit.triangle] : SemanticClass::Sky);
  *out.instance.pixel(x, y) = hit.found ? scene.mesh(hit.mesh).instance : 0;
}

void put_normals(const EmbreeScene& scene, const ImageTextures& images,
                 const Projection& projection, const TruthRequest& request, const CameraAt& camera,
                 const Hit& hit, const Vec3& direction, Vec2 pixel, GroundTruth& out, int x,
                 int y) {
  if (!hit.found) {
    for (Image<float>* image : {&out.normal, &out.shading_normal})
      if (!image->data.empty()) std::fill_n(image->pixel(x, y), 3, kNoVector);
    return;
  }
  if (request.normal) {
    Vec3 normal = (scene.pose_now(hit.mesh).linear() * hit.normal.cast<double>()).normalized();
    if (normal.dot(direction) > 0) normal = -normal;
    put_vector(out.normal, x, y, camera.world_to_camera * normal);
  }
  if (request.shading_normal) {
    const Vec3 point = camera.origin + hit.distance * direction;
    const double footprint = projection.pixel_spread(pixel) * hit.distance;
    std::optional<TexturedLook> look;
    if (is_textured(scene, hit))
      look = textured_look(scene, images, hit, point, direction, footprint);
    const Surface surface =
        surface_at(scene, hit, camera.origin, direction, look ? &*look : nullptr);
    put_vector(out.shading_normal, x, y, camera.world_to_camera * surface.normal);
  }
}

}  // namespace flowscape
