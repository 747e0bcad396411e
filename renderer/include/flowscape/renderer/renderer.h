#pragma once
// Embree ray casting of a Scene: exact ground truth for the pixel-centre ray of every pixel.
// Each mesh gets its own BVH, built once; every frame only re-poses the instances.
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "flowscape/core/image.h"
#include "flowscape/renderer/projection.h"
#include "flowscape/renderer/rolling_shutter.h"
#include "flowscape/scenes/scene.h"

namespace flowscape {

// The two moments a forward flow connects, and where the rig (x forward, y left, z up) is then.
struct FramePair {
  double time = 0, next_time = 1 / kFrameRate;
  Pose rig = Pose::Identity(), next_rig = Pose::Identity();  // rig -> world
};

// A moment of a sequence: a time and where the rig is then.
struct Moment {
  double time = 0;
  Pose rig = Pose::Identity();  // rig -> world
};

// Where a camera (or the rig) is at any time: camera -> world, as FramePair::rig.
using CameraTrack = std::function<Pose(double time)>;

// The time a camera's shutter is open (shutter.h's centred_shutter makes one).
struct Shutter {
  double open = 0, close = 0;  // seconds
};

// The ground truth a frame needs: flow and validity to the pair's next moment and to each of
// `more` (other frame gaps, earlier frames: flow goes from pair.time to the target), and, when
// asked, the 3-D motion of each pixel's surface point to the pair's next moment and its normals.
struct TruthRequest {
  FramePair pair;
  std::vector<Moment> more{};
  bool scene_flow = false, normal = false, shading_normal = false;
  // The camera is one of the rig's (pair.rig is where the rig is, not another viewpoint): parts
  // fixed to the rig (Part::on_rig, the ego's body) then have exactly zero flow.
  bool camera_on_rig = false;
  // A rolling shutter (not readout.global()): each line of this frame's image and of every
  // target's is captured at its own time (rolling_shutter.h) with the camera where `track` puts it
  // then (the pair's and the moments' rigs are not used; their times are the frame times). A
  // pixel's flow goes to where its surface point is seen in the target's rolling-shutter image,
  // the earliest line where two see it, unknown where none does; every kind follows the line
  // times (docs/cameras.md, "Rolling shutter").
  Readout readout{};
  CameraTrack track{};
};

struct FlowTruth {
  Image<float> flow;          // 2 channels, pixels (ERP: 360-degree or classic)
  Image<std::uint8_t> valid;  // 1 where the target is in view then and visible
};

struct GroundTruth {
  Image<float> flow;              // 2 channels, forward flow in pixels (ERP: 360-degree or classic)
  Image<std::uint8_t> semantic;   // CARLA class id, Sky where the ray escapes
  Image<std::uint16_t> instance;  // 0 for the static world and the sky
  Image<float> depth;             // distance along the ray, metres; +infinity for the sky
  Image<std::uint8_t> valid;      // 1 where the target is in front of the camera and visible then
  std::vector<FlowTruth> more{};  // to TruthRequest::more, in its order
  // 3 channels each in the view's camera frame (Projection::camera_to_rig), NaN for the sky;
  // empty unless asked: the surface point's displacement to the pair's next moment (metres), the
  // unit geometric normal facing the camera, the unit shading normal (textures' bumps included).
  Image<float> scene_flow{}, normal{}, shading_normal{};
};

struct RenderOptions {
  int samples_per_pixel = 16;
  int max_bounces = 4;     // Russian roulette may end paths earlier after the third bounce
  std::uint64_t seed = 0;  // with the pixel, the sample and the dimension: every random number
  // Procedural patterns and image maps; false: every material's plain albedo and roughness (for
  // comparisons; alpha masks still cut holes: they are geometry).
  bool textures = true;
  // How many of a pixel's samples go on past a diffuse first surface (the costly, incoherent
  // bounces that gather its indirect light), weighted to stand for all; 0: every sample. The rest
  // still bring the camera ray, the sun's direct light, the specular chains and the features.
  int indirect_samples = 0;
  // Where a pixel's samples disagree on the light they meet before any surface (the edge of a lit
  // window, a lamp or the sky), camera rays up to this many in all, which gather only that light
  // (the coverage); their surface light stays the pixel's samples' (path_tracer.cpp's
  // PixelSamples::put_means). At or below samples_per_pixel: none.
  int edge_samples = 32;
  // Where set (the image's size; for render_cube the stacked faces'), only the pixels where it is
  // non-zero are traced and the others' layers stay zero: adaptive sampling's second pass. A
  // pixel's samples are the same as in a render of every pixel.
  ImageView<const std::uint8_t> pixels{};
};

// A colour frame split the way a denoiser needs it (linear RGB, each averaged over the pixel's
// samples). The first surface is the first opaque one a camera ray meets (rain streaks are passed).
struct ColorLayers {
  Image<float> direct;    // the sun's light the first surface reflects diffusely (sharp shadows)
  Image<float> indirect;  // all other light the first surface reflects diffusely (the noisy part)
  Image<float> specular;  // light from a specular event at the first surface (coats, metal, glass)
  Image<float> other;     // light met before it: sky, sun disc, emission, fog, rain streaks
  Image<float> albedo;    // the first surface's albedo, weighted as its diffuse light is
  Image<float> normal;    // the first surface's shading normal, world frame, summed over samples
  // The variance of the mean luminance of direct, indirect and specular (3 channels): how much of
  // each is noise, for the denoiser's edge-stopping.
  Image<float> variance;
};
// direct + indirect + specular + other: the raw colour.
Image<float> raw_color(const ColorLayers& layers);
// Two renders of a_samples and b_samples per pixel (other seeds) as one render of both's samples:
// the means weighted by the samples, the normals summed, and the variance of the pooled mean from
// both renders' second moments (the spread between them included, as one render would see it).
ColorLayers pooled(ColorLayers a, int a_samples, const ColorLayers& b, int b_samples);

// A ray the renderer would not hand to Embree (a coordinate NaN, infinite or beyond 1.8e18):
// thrown instead, naming the pixel it was traced for and, once a caller names it, the camera.
class RayError : public std::runtime_error {
 public:
  RayError(int x, int y, const std::string& problem, const std::string& camera = "")
      : std::runtime_error((camera.empty() ? "" : "camera " + camera + ", ") + "pixel (" +
                           std::to_string(x) + ", " + std::to_string(y) + "): " + problem),
        x(x),
        y(y),
        problem(problem),
        camera(camera) {}
  // The same error of the camera named `name` (unless one is named already).
  RayError of_camera(const std::string& name) const {
    return camera.empty() ? RayError(x, y, problem, name) : *this;
  }
  int x, y;
  std::string problem, camera;
};

struct RenderStats {
  std::uint64_t rays = 0;  // camera, bounce and shadow rays traced
};

// Ways of tracing that earlier versions used, kept only as bench_release's baseline (what the
// current ones gain) and for the tests that show the ground truth the same either way. No release
// sets them (Renderer::trace_as).
struct TracingBaseline {
  // Ground truth: each camera and visibility ray handed to Embree alone rather than a row's 16
  // neighbours as one packet (the same hits, so the same bytes).
  bool single_rays = false;
  // Colour: paths that scattered diffusely find the sky at the dome's full resolution, not averaged
  // as SkySampler's blocks (larger tables, more cache misses).
  bool full_sky_when_scattered = false;
};

class Renderer {
 public:
  explicit Renderer(const Scene& scene);  // holds on to `scene`: it must outlive the renderer
  Renderer(Scene&&) = delete;             // a temporary scene would not
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;
  // From now on, trace as the baseline says (benchmarks and tests only).
  void trace_as(const TracingBaseline& baseline);

  // Flow: the hit point, fixed on its object, moved to the object's pose at next_time and projected
  // by the camera at next_time; the sky moves with the rig's rotation only.
  GroundTruth ground_truth(const Projection& projection, const FramePair& frames,
                           FlowMode mode = FlowMode::Wrap360);
  // Every kind the request asks for, with one camera ray per pixel.
  GroundTruth ground_truth(const Projection& projection, const TruthRequest& request,
                           FlowMode mode = FlowMode::Wrap360);
  // The same for the rays through the given continuous pixel positions (not only pixel centres),
  // as images of pixels.size() x 1: column k is pixels[k]'s.
  // (Global shutter only: throws std::invalid_argument for a rolling one.)
  GroundTruth ground_truth_at(const Projection& projection, const TruthRequest& request,
                              const std::vector<Vec2>& pixels, FlowMode mode = FlowMode::Wrap360);
  // The distance along each pixel centre's ray (+infinity for the sky, NaN outside a lens's image)
  // with the camera on `camera` at `time`, each line at its own time with a rolling shutter.
  Image<float> depth(const Projection& projection, double time, const CameraTrack& camera,
                     const Readout& readout = {});

  // Linear HDR radiance (RGB) at frames.time, path traced: Lambertian, clear-coat, metal, glass
  // and emissive surfaces, sun (sampled directly) and sky, fog integrated in closed form, Russian
  // roulette, Owen-scrambled Sobol samples (docs/renderer.md). The same bytes for any thread count.
  Image<float> color(const Projection& projection, const FramePair& frames,
                     const RenderOptions& options = {}, RenderStats* stats = nullptr);
  // The same estimate in layers (raw_color(color_layers(...)) == color(...)).
  ColorLayers color_layers(const Projection& projection, const FramePair& frames,
                           const RenderOptions& options = {}, RenderStats* stats = nullptr);
  // The same with the camera on `camera` at `time`; with a rolling shutter each line is traced
  // with the scene, its lights and the camera posed at the line's time (the pixels' samples and
  // seeds as for a global shutter).
  ColorLayers color_layers(const Projection& projection, double time, const CameraTrack& camera,
                           const Readout& readout, const RenderOptions& options = {},
                           RenderStats* stats = nullptr);
  // The colour layers over an open shutter (motion blur, continuous: Embree's): each sample traced
  // at its own time in [open, close] (stratified over the pixel's samples) with the scene and the
  // camera on `camera` then, the lights at its middle. With a rolling shutter each line's shutter
  // is shifted by the line's offset, so the image holds the skew and the blur together.
  ColorLayers color_layers(const Projection& projection, const Shutter& shutter,
                           const CameraTrack& camera, const Readout& readout,
                           const RenderOptions& options, RenderStats* stats = nullptr);
  // The distance along each pixel centre's ray averaged over kShutterDepthTimes times spread over
  // the shutter, those it meets a surface at (+infinity where it never does, NaN outside a lens's
  // image): a denoising guide that does not cut the blur trails.
  Image<float> depth(const Projection& projection, const Shutter& shutter,
                     const CameraTrack& camera, const Readout& readout = {});
  static constexpr int kShutterDepthTimes = 2;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The cube rig: the six 90-degree faces at one optical centre, rendered for the same frame pair and
// stacked into N x 6N images in kFaces order (geometry.h's face_view; the layout stitch.h takes).
struct CubeFrame {
  ColorLayers color;  // empty when not asked for
  GroundTruth truth;
};
CubeFrame render_cube(Renderer& renderer, int face_size, const FramePair& frames,
                      const RenderOptions* color_options, FlowMode mode = FlowMode::Wrap360);
CubeFrame render_cube(Renderer& renderer, int face_size, const TruthRequest& request,
                      const RenderOptions* color_options, FlowMode mode = FlowMode::Wrap360);
// The colour layers of the six faces alone, stacked (render_cube's).
ColorLayers cube_color_layers(Renderer& renderer, int face_size, const FramePair& frames,
                              const RenderOptions& options);

}  // namespace flowscape
