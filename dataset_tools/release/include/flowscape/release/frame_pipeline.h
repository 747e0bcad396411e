#pragma once
// What a frame of a sequence becomes before it is written: every view's images by release kind
// (layout.h's table), each in its file's pixel type. The colour of a view is made in one place:
// path traced (adaptive sampling where asked), denoised by the release's denoiser, and with the
// final pass its shutter, sensor and development; the ground truth is ray cast beside it. The
// writer (writer.h) only writes what it gets (Kubric's render-to-a-dict-of-layers, then writers).
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "flowscape/formats/image_io.h"
#include "flowscape/layout/classes.h"
#include "flowscape/layout/layout.h"
#include "flowscape/release/config.h"
#include "flowscape/release/final_pass.h"
#include "flowscape/release/sequence.h"
#include "flowscape/stitcher/stitch.h"

namespace flowscape {

// A view's images by release kind name ("color", "flow", "flow_backward_gap2", ...).
using ViewImages = std::map<std::string, AnyImage>;

struct FrameImages {
  std::optional<ViewImages> cube;                  // the flowscape rig's six faces, stacked
  std::vector<std::pair<View, ViewImages>> views;  // its ERP, or each camera of a rig in order
};

// The raw colour layers (and instance ids) of each view's frames that temporal reconstruction's
// windows still need (ColorSection::temporal), each traced once however the frames are asked for:
// a sequence resumed at frame f traces the frames before f its window reaches, the same bytes.
class LayerHistory {
 public:
  struct Frame {
    ColorLayers layers;  // raw, as traced
    Image<std::uint16_t> instance;
    GroundTruth truth;  // with the window's targets after the layout's, until the frame takes it
  };
  // View `view`'s (-1: the stacked cube faces) frame `frame`, made by `trace` the first time.
  Frame& frame(int view, int frame, const std::function<Frame()>& trace);
  void drop_before(int frame);  // forgets every view's frames before `frame`

 private:
  std::map<std::pair<int, int>, Frame> frames_;  // by frame, then view
};

// What every frame of a sequence shares.
struct FramePipeline {
  ColorSection color;
  FinalPassSection final_pass;
  const ClassTable& classes;  // the release's semantic ids
  int frames;                 // in the sequence
  const ReleaseLayout& layout;
  const Rig& rig;  // release_rig(config)
  const Sequence& sequence;
  Renderer& renderer;
  const CubeToErp* cube_to_erp;     // the flowscape rig's faces to its ERP; null without faces
  LayerHistory* history = nullptr;  // with temporal reconstruction (color.temporal > 0)
};

// Frame `frame`'s images. With the final pass, `exposure` (the one after the previous frame)
// becomes this frame's; null without it. RayErrors name the camera (a face or a rig camera; the
// flowscape ERP's are left for the caller to name).
FrameImages render_frame(const FramePipeline& pipeline, int frame, Exposure* exposure);

}  // namespace flowscape
