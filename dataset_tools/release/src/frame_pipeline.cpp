#include "flowscape/release/frame_pipeline.h"

#include "flowscape/core/profile.h"
#include "flowscape/formats/srgb.h"
#include "flowscape/layout/classes.h"
#include "flowscape/renderer/rolling_shutter.h"

namespace flowscape {
namespace {

// The kinds beside the clean colour and the ground truth (empty where the layout has none).
struct CameraImages {
  Image<std::uint8_t> final{};
  Image<float> time{};
  Image<std::uint8_t> lens_mask{};
};

// The images of one view of a frame, by release kind (layout.h), each in its file's pixel type,
// its semantic ids in the release's class table; truth.more[k] is the flow of step more_steps[k].
// A new output kind adds its image here.
ViewImages view_images(GroundTruth truth, Image<std::uint8_t> color,
                       const std::vector<int>& more_steps, const ClassTable& classes,
                       CameraImages camera = {}) {
  ViewImages images;
  images.emplace("color", std::move(color));
  images.emplace("final", std::move(camera.final));
  images.emplace("time", std::move(camera.time));
  images.emplace("lens_mask", std::move(camera.lens_mask));
  images.emplace("flow", std::move(truth.flow));
  to_table_ids(classes, truth.semantic.view());
  images.emplace("semantic", std::move(truth.semantic));
  images.emplace("instance", std::move(truth.instance));
  images.emplace("depth", std::move(truth.depth));
  images.emplace("valid", std::move(truth.valid));
  for (std::size_t k = 0; k < more_steps.size(); ++k) {
    const ReleaseKind flow = flow_kind_of_step(more_steps[k]);
    images.emplace(flow.name(), std::move(truth.more[k].flow));
    images.emplace(flow.valid_kind().name(), std::move(truth.more[k].valid));
  }
  images.emplace("scene_flow", std::move(truth.scene_flow));
  images.emplace("normal", std::move(truth.normal));
  images.emplace("normal_shading", std::move(truth.shading_normal));
  return images;
}

// The final pass of the six faces (stacked, as write_cube takes them) and the ERP stitched from
// them, each through the camera (virtual cameras: no vignetting).
struct FinalFlowscape {
  Image<std::uint8_t> faces, erp;
};
FinalFlowscape final_flowscape(const FramePipeline& p, const Exposure& exposure, int frame,
                               const CubeFrame& clean) {
  const int face_size = p.cube_to_erp->face_size;
  const Image<float> faces =
      final_cube_color(p.color, p.final_pass, face_size, p.sequence, p.renderer, frame, clean);
  FinalFlowscape out{Image<std::uint8_t>(faces.width, faces.height, 3), {}};
  const Projection face_camera = Projection::cube_face(Face::Front, face_size);
  int view = 1;
  for (Face face : kFaces) {
    const ImageView<const float> linear = face_view(faces.view(), face);
    const Image<std::uint8_t> developed =
        develop(p.final_pass, p.sequence, linear, face_camera, false, exposure, frame, view++);
    std::copy(developed.data.begin(), developed.data.end(), face_view(out.faces.view(), face).data);
  }
  const Image<float> erp = resample_bilinear(p.cube_to_erp->sampling, faces);
  out.erp = develop(p.final_pass, p.sequence, erp.view(), p.rig.cameras.front().projection, false,
                    exposure, frame, 0);
  return out;
}

// A virtual camera's (the ERP's, the stacked faces'): no readout, no lens to cover.
CameraImages virtual_camera_images(const ReleaseLayout& layout, const Projection& camera,
                                   const TruthPlan& plan, Image<std::uint8_t> final) {
  CameraImages images{std::move(final)};
  if (layout.has("time")) images.time = capture_times(camera, {}, plan.request.pair.time);
  if (layout.has("lens_mask"))
    images.lens_mask = Image<std::uint8_t>(camera.width, camera.height, 1);
  return images;
}

// A directly rendered camera: the ERP of the flowscape rig without faces, or a rig's camera.
struct DirectCamera {
  const Projection& projection;
  const TruthRequest& request;  // what its colour is traced for
  CameraTrack track;            // where it is over the final pass's shutter
  Readout readout;
  bool real_lens;  // a physical camera (vignetting, drops and dirt), not a virtual one
  int view;        // its number in the rig: the final pass's noise stream
  bool meters;     // its clean light sets the final pass's exposure
};
struct CameraColor {
  ColorLayers layers;
  Image<std::uint8_t> clean, final;
};

// Its colour: the layers path traced, the release's denoiser, sRGB; with the final pass (exposure
// not null) its shutter, sensor and development.
CameraColor camera_color(const FramePipeline& p, const DirectCamera& camera, int frame,
                         const GroundTruth& truth, Exposure* exposure) {
  CameraColor out;
  out.layers = release_layers(p.color, p.sequence, p.renderer, camera.projection, camera.request,
                              frame, truth);
  const Image<float> color = denoised_color(p.color, out.layers, camera.projection,
                                            truth.depth.view(), truth.instance.view());
  out.clean = linear_to_srgb8(color.view());
  if (!exposure) return out;
  const ScopedPhase phase("final pass");
  if (camera.meters)
    *exposure = exposure_after(p.final_pass, p.sequence, *exposure, out.clean.view(),
                               camera.projection, frame);
  const Image<float> linear =
      final_color(p.color, p.final_pass, p.sequence, p.renderer, camera.projection, camera.track,
                  frame, camera.readout, out.layers, truth.depth);
  out.final = develop(p.final_pass, p.sequence, linear.view(), camera.projection, camera.real_lens,
                      *exposure, frame, camera.view);
  return out;
}

GroundTruth timed_truth(Renderer& renderer, const Projection& camera, const TruthRequest& request) {
  const ScopedPhase phase("ground truth");
  return renderer.ground_truth(camera, request);
}

// The flowscape rig's faces and the ERP stitched from them: the faces path traced and denoised
// face by face, the ERP colour resampled from theirs (the final pass's likewise).
FrameImages faces_and_stitched_erp(const FramePipeline& p, const TruthPlan& plan, int frame,
                                   GroundTruth erp_truth, Exposure* exposure) {
  const int face_size = p.cube_to_erp->face_size;
  const Projection& erp = p.rig.cameras.front().projection;
  CubeFrame cube = render_cube(p.renderer, face_size, plan.request, nullptr);
  cube.color = release_cube_layers(p.color, face_size, p.sequence, p.renderer, cube.truth, frame);
  const Image<float> faces_color = denoised_cube_color(p.color, cube.color, cube.truth);
  const Image<float> erp_color = [&] {
    const ScopedPhase phase("cube to ERP");
    return resample_bilinear(p.cube_to_erp->sampling, faces_color);
  }();
  Image<std::uint8_t> erp_clean = linear_to_srgb8(erp_color.view());
  FinalFlowscape final;
  if (exposure) {
    const ScopedPhase phase("final pass");
    *exposure = exposure_after(p.final_pass, p.sequence, *exposure, erp_clean.view(), erp, frame);
    final = final_flowscape(p, *exposure, frame, cube);
  }
  FrameImages images;
  const Projection faces = Projection::pinhole(face_size, 6 * face_size, 90);
  images.cube =
      view_images(std::move(cube.truth), linear_to_srgb8(faces_color.view()), plan.steps, p.classes,
                  virtual_camera_images(p.layout, faces, plan, std::move(final.faces)));
  images.views.emplace_back(
      View(), view_images(std::move(erp_truth), std::move(erp_clean), plan.steps, p.classes,
                          virtual_camera_images(p.layout, erp, plan, std::move(final.erp))));
  return images;
}

// The flowscape rig: the ERP colour is stitched from the cube faces' (denoised face by face) when
// there are faces, else rendered and denoised directly; the ERP ground truth is always ray cast
// directly (exact, and cheap next to colour). With the final pass, `exposure` (the one after the
// previous frame) becomes this frame's.
FrameImages render_flowscape_frame(const FramePipeline& p, int frame, Exposure* exposure) {
  const TruthPlan plan = truth_plan(p.sequence, p.layout, frame, p.frames);
  const Projection& erp = p.rig.cameras.front().projection;
  GroundTruth truth = timed_truth(p.renderer, erp, plan.request);
  if (p.cube_to_erp) return faces_and_stitched_erp(p, plan, frame, std::move(truth), exposure);
  const TruthRequest pair{p.sequence.frame_pair(frame)};
  const Sequence& sequence = p.sequence;
  CameraColor color = camera_color(
      p, {erp, pair, [&](double t) { return sequence.city.rig(t); }, {}, false, 0, true}, frame,
      truth, exposure);
  FrameImages images;
  images.views.emplace_back(
      View(), view_images(std::move(truth), std::move(color.clean), plan.steps, p.classes,
                          virtual_camera_images(p.layout, erp, plan, std::move(color.final))));
  return images;
}

// Another rig: every camera ray cast and path traced directly from its own optical centre.
FrameImages render_rig_frame(const FramePipeline& p, int frame, Exposure* exposure) {
  const TruthPlan plan = truth_plan(p.sequence, p.layout, frame, p.frames);
  FrameImages images;
  for (const RigCamera& camera : p.rig.cameras) try {
      const int view = int(&camera - p.rig.cameras.data());
      const TruthRequest request = at_camera(plan.request, camera);
      GroundTruth truth = timed_truth(p.renderer, camera.projection, request);
      CameraColor color = camera_color(
          p, {camera.projection, request, request.track, camera.readout, true, view, view == 0},
          frame, truth, exposure);
      CameraImages extras{std::move(color.final)};
      if (p.layout.has("time"))
        extras.time = capture_times(camera.projection, camera.readout, request.pair.time);
      if (p.layout.has("lens_mask"))
        extras.lens_mask = release_lens_mask(p.final_pass, p.sequence, camera.projection, view);
      images.views.emplace_back(view_of(p.rig, camera),
                                view_images(std::move(truth), std::move(color.clean), plan.steps,
                                            p.classes, std::move(extras)));
    } catch (const RayError& e) {
      throw e.of_camera(camera.name);
    }
  return images;
}

}  // namespace

FrameImages render_frame(const FramePipeline& p, int frame, Exposure* exposure) {
  return p.rig.flowscape ? render_flowscape_frame(p, frame, exposure)
                         : render_rig_frame(p, frame, exposure);
}

}  // namespace flowscape
