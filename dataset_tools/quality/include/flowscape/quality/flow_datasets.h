#pragma once
// Image pairs and their ground-truth flow in the layouts of common optical-flow datasets, found
// from a folder: a FlowScape release (sequences/), the PanoFlow tree (<split>/<weather>/img|flow),
// MPI-Sintel (training/clean|final, training/flow, training/occlusions), KITTI 2012 (colored_0)
// and 2015 (image_2) with flow_occ / flow_noc, FlyingChairs (*_img1.ppm, *_img2.ppm, *_flow.flo),
// or any two globs.
#include <filesystem>
#include <string>
#include <vector>

namespace flowscape {

enum class VisibleMask {
  None,
  NonZero,    // an 8-bit image, non-zero = visible (FlowScape valid)
  Zero,       // an 8-bit image, non-zero = occluded (Sintel occlusions)
  FlowValid,  // a KITTI flow PNG whose valid bit marks the non-occluded pixels (flow_noc)
};

struct PairFiles {
  std::filesystem::path image1, image2, flow, visible;
  VisibleMask visible_kind = VisibleMask::None;
  std::string group, category;  // group: sequence or scene; category: weather, pass, split
  bool panorama = false;
  // optional: the backward flow of image2's frame to image1's and its mask (FlowScape releases
  // that hold it), for the forward-backward check
  std::filesystem::path backward{}, backward_visible{};
};

struct FlowDataset {
  std::string layout;  // flowscape, panoflow, sintel, kitti2012, kitti2015, flyingchairs, generic
  std::vector<PairFiles> pairs;
};

// Throws FileError when the folder holds none of the known layouts. A FlowScape release's kinds and
// conventions are read from its manifest.json (one without: FlowScape's own); flow it does not
// know how to read (another direction, units or axes) is a FileError naming the manifest.
// `pass`: "clean" or, for a FlowScape release made with it, "final" (its final pass's images; the
// flow is the same); std::invalid_argument for another layout or name.
FlowDataset find_flow_dataset(const std::filesystem::path& root, const std::string& pass = "clean");
// Images sorted by name pair up as (k, k + 1) with the k-th flow file: one image more than flows.
// Patterns use * and ? in the file name part (the folder part is taken literally).
FlowDataset glob_flow_dataset(const std::string& images, const std::string& flows, bool panorama);

// At most `per_category` pairs of each category (weather, pass, split), spread evenly over its
// pairs in their order (the k-th of n taken: pair floor((k + 0.5) n / per_category)); the same
// dataset gives the same sample.
FlowDataset sample_pairs(const FlowDataset& dataset, int per_category);

}  // namespace flowscape
