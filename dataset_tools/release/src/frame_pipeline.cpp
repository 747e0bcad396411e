#include "flowscape/release/frame_pipeline.h"

#include <algorithm>
#include <limits>

#include "flowscape/core/profile.h"
#include "flowscape/formats/srgb.h"
#include "flowscape/layout/classes.h"
#include "flowscape/renderer/rolling_shutter.h"
#include "flowscape/renderer/temporal.h"

namespace flowscape {

LayerHistory::Frame& LayerHistory::frame(int view, int frame, const std::function<Frame()>& trace) {
  const std::pair<int, int> key{frame, view};
  auto found = frames_.find(key);
  if (found == frames_.end()) found = frames_.emplace(key, trace()).first;
  return found->second;
}

void LayerHistory::drop_before(int frame) {
  frames_.erase(frames_.begin(), frames_.lower_bound({frame, std::numeric_limits<int>::min()}));
}

namespace {

constexpr int kCubeView = -1;  // the stacked cube faces' frames in a LayerHistory

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
FinalFlowscape final_flowscape(const FramePipeline& p, const Exposure& exposure, int frame) {
  const int face_size = p.cube_to_erp->face_size;
  const Image<float> faces =
      final_cube_color(p.color, p.final_pass, face_size, p.sequence, p.renderer, frame);
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
  const RigCamera* rig_camera;  // null: the flowscape rig's ERP, at the rig's own centre
  const Projection& projection;
  const TruthRequest& request;  // what its ground truth is cast and its colour traced for
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

GroundTruth timed_truth(Renderer& renderer, const Projection& camera, const TruthRequest& request) {
  const ScopedPhase phase("ground truth");
  return renderer.ground_truth(camera, request);
}

// Temporal reconstruction's window around `frame`: its first and last frames.
std::pair<int, int> window_of(const FramePipeline& p, int frame) {
  return {std::max(0, frame - p.color.temporal), std::min(p.frames - 1, frame + p.color.temporal)};
}

// The steps from `frame` to the other frames of its window that its ground truth does not reach
// already (the next frame, the layout's flow steps).
std::vector<int> window_only_steps(const FramePipeline& p, const TruthPlan& plan, int frame) {
  const auto [first, last] = window_of(p, frame);
  std::vector<int> steps;
  for (int f = first; f <= last; ++f)
    if (const int step = f - frame;
        step != 0 && step != 1 &&
        std::find(plan.steps.begin(), plan.steps.end(), step) == plan.steps.end())
      steps.push_back(step);
  return steps;
}

// With temporal reconstruction, what a frame's ground truth is cast for: the layout's targets
// (truth_plan), then the window's other frames it lacks, in order; a rig camera's at it.
TruthRequest windowed_request(const FramePipeline& p, const RigCamera* camera, int frame) {
  TruthPlan plan = truth_plan(p.sequence, p.layout, frame, p.frames);
  for (int step : window_only_steps(p, plan, frame))
    plan.request.more.push_back(p.sequence.moment(frame + step));
  return camera ? at_camera(plan.request, *camera) : plan.request;
}

// Where frame `frame`'s pixels are seen in frame `frame + step` of its window, in a
// windowed_request's truth: the next frame's flow, a layout step's, or a window-only target's.
struct FlowView {
  ImageView<const float> flow;
  ImageView<const std::uint8_t> valid;
};
FlowView flow_to(const GroundTruth& truth, const TruthPlan& plan,
                 const std::vector<int>& window_only, int step) {
  if (step == 1) return {truth.flow.view(), truth.valid.view()};
  const auto in_plan = std::find(plan.steps.begin(), plan.steps.end(), step);
  const std::size_t k = in_plan != plan.steps.end()
                            ? std::size_t(in_plan - plan.steps.begin())
                            : plan.steps.size() + std::size_t(std::find(window_only.begin(),
                                                                        window_only.end(), step) -
                                                              window_only.begin());
  return {truth.more[k].flow.view(), truth.more[k].valid.view()};
}

// A directly rendered camera's frame as the history keeps it: its raw layers, and its ground
// truth with the window's targets.
LayerHistory::Frame traced_view(const FramePipeline& p, const DirectCamera& camera, int frame) {
  const TruthRequest request = windowed_request(p, camera.rig_camera, frame);
  GroundTruth truth = timed_truth(p.renderer, camera.projection, request);
  ColorLayers layers = traced_layers(p.renderer, camera.projection, request,
                                     p.sequence.color_options(p.color, frame));
  Image<std::uint16_t> instance = truth.instance;
  return {std::move(layers), std::move(instance), std::move(truth)};
}

// The stacked cube faces' frame likewise.
LayerHistory::Frame traced_cube(const FramePipeline& p, int frame) {
  const int face_size = p.cube_to_erp->face_size;
  CubeFrame cube = render_cube(p.renderer, face_size, windowed_request(p, nullptr, frame), nullptr);
  {
    const ScopedPhase phase("path tracing");
    cube.color = cube_color_layers(p.renderer, face_size, p.sequence.frame_pair(frame),
                                   p.sequence.color_options(p.color, frame));
  }
  Image<std::uint16_t> instance = cube.truth.instance;
  return {std::move(cube.color), std::move(instance), std::move(cube.truth)};
}

// A view's layers of a frame with its window's frames reprojected in (temporal.h), each frame
// traced once (`trace`) and kept in the history; `truth` is the frame's, with the window's targets.
ColorLayers reconstructed(const FramePipeline& p, int view, int frame, const GroundTruth& truth,
                          const std::function<LayerHistory::Frame(int)>& trace,
                          const TemporalOptions& options) {
  const auto [first, last] = window_of(p, frame);
  const auto traced = [&](int f) -> const LayerHistory::Frame& {
    return p.history->frame(view, f, [&] { return trace(f); });
  };
  const LayerHistory::Frame& centre = traced(frame);
  const TruthPlan plan = truth_plan(p.sequence, p.layout, frame, p.frames);
  const std::vector<int> window_only = window_only_steps(p, plan, frame);
  std::vector<TemporalNeighbour> neighbours;
  for (int f = first; f <= last; ++f) {
    if (f == frame) continue;
    const LayerHistory::Frame& their = traced(f);
    const FlowView to = flow_to(truth, plan, window_only, f - frame);
    neighbours.push_back({&their.layers, their.instance.view(), to.flow, to.valid});
  }
  const ScopedPhase phase("temporal reconstruction");
  return temporal_layers(centre.layers, centre.instance.view(), neighbours, options);
}

// A directly rendered camera's ground truth of a frame: with temporal reconstruction the one cast
// when the history traced the frame, else cast now.
GroundTruth camera_truth(const FramePipeline& p, const DirectCamera& camera, int frame) {
  if (!p.history) return timed_truth(p.renderer, camera.projection, camera.request);
  return std::move(
      p.history->frame(camera.view, frame, [&] { return traced_view(p, camera, frame); }).truth);
}

// Its layers of a frame: path traced, or with temporal reconstruction its history's
// reconstructed over the window.
ColorLayers camera_layers(const FramePipeline& p, const DirectCamera& camera, int frame,
                          const GroundTruth& truth) {
  if (!p.history)
    return release_layers(p.color, p.sequence, p.renderer, camera.projection, camera.request, frame,
                          truth);
  return reconstructed(p, camera.view, frame, truth,
                       [&](int f) { return traced_view(p, camera, f); },
                       {.wraps = camera.projection.wraps_around()});
}

// The stacked cube faces' ground truth and colour layers of a frame, likewise.
CubeFrame cube_frame(const FramePipeline& p, const TruthPlan& plan, int frame) {
  const int face_size = p.cube_to_erp->face_size;
  if (!p.history) {
    CubeFrame cube = render_cube(p.renderer, face_size, plan.request, nullptr);
    cube.color = release_cube_layers(p.color, face_size, p.sequence, p.renderer, cube.truth, frame);
    return cube;
  }
  CubeFrame cube;
  cube.truth =
      std::move(p.history->frame(kCubeView, frame, [&] { return traced_cube(p, frame); }).truth);
  cube.color = reconstructed(p, kCubeView, frame, cube.truth,
                             [&](int f) { return traced_cube(p, f); }, {.tile_height = face_size});
  return cube;
}

// Its colour: the layers path traced (and reconstructed over the temporal window), the release's
// denoiser, sRGB; with the final pass (exposure not null) its shutter, sensor and development.
CameraColor camera_color(const FramePipeline& p, const DirectCamera& camera, int frame,
                         const GroundTruth& truth, Exposure* exposure) {
  CameraColor out;
  out.layers = camera_layers(p, camera, frame, truth);
  const Image<float> color = denoised_color(p.color, out.layers, camera.projection,
                                            truth.depth.view(), truth.instance.view());
  out.clean = linear_to_srgb8(color.view());
  if (!exposure) return out;
  const ScopedPhase phase("final pass");
  if (camera.meters)
    *exposure = exposure_after(p.final_pass, p.sequence, *exposure, out.clean.view(),
                               camera.projection, frame);
  const Image<float> linear = final_color(p.color, p.final_pass, p.sequence, p.renderer,
                                          camera.projection, camera.track, frame, camera.readout);
  out.final = develop(p.final_pass, p.sequence, linear.view(), camera.projection, camera.real_lens,
                      *exposure, frame, camera.view);
  return out;
}

// The flowscape rig's faces and the ERP stitched from them: the faces path traced and denoised
// face by face, the ERP colour resampled from theirs (the final pass's likewise).
FrameImages faces_and_stitched_erp(const FramePipeline& p, const TruthPlan& plan, int frame,
                                   GroundTruth erp_truth, Exposure* exposure) {
  const int face_size = p.cube_to_erp->face_size;
  const Projection& erp = p.rig.cameras.front().projection;
  CubeFrame cube = cube_frame(p, plan, frame);
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
    final = final_flowscape(p, *exposure, frame);
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
  if (p.cube_to_erp)
    return faces_and_stitched_erp(p, plan, frame, timed_truth(p.renderer, erp, plan.request),
                                  exposure);
  const DirectCamera camera{nullptr, erp, plan.request, plan.request.track, {}, false, 0, true};
  GroundTruth truth = camera_truth(p, camera, frame);
  CameraColor color = camera_color(p, camera, frame, truth, exposure);
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
      const DirectCamera direct{&camera,       camera.projection, request,
                                request.track, camera.readout,    true,
                                view,          view == 0};
      GroundTruth truth = camera_truth(p, direct, frame);
      CameraColor color = camera_color(p, direct, frame, truth, exposure);
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
