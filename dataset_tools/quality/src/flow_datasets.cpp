#include "flowscape/quality/flow_datasets.h"

#include <fnmatch.h>

#include <algorithm>
#include <map>

#include "flowscape/core/files.h"
#include "flowscape/layout/layout.h"
#include "flowscape/layout/meta.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

std::vector<fs::path> sorted_files(const fs::path& dir, const std::string& pattern) {
  std::vector<fs::path> files;
  if (!fs::is_directory(dir)) return files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() &&
        fnmatch(pattern.c_str(), entry.path().filename().c_str(), 0) == 0)
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<fs::path> sorted_dirs(const fs::path& dir) {
  std::vector<fs::path> dirs;
  if (!fs::is_directory(dir)) return dirs;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_directory()) dirs.push_back(entry.path());
  std::sort(dirs.begin(), dirs.end());
  return dirs;
}

fs::path with_stem_suffix(const fs::path& file, const std::string& from, const std::string& to) {
  std::string name = file.filename().string();
  name.replace(name.rfind(from), from.size(), to);
  return file.parent_path() / name;
}

// What gt_quality reads a flow as: target - source in pixels, u right, v down (photoconsistency.h).
void check_conventions(const nlohmann::json& conventions, const fs::path& manifest) {
  if (conventions.is_null()) return;  // before conventions were recorded: FlowScape's
  const nlohmann::json flow =
      conventions.is_object() ? conventions.value("flow", nlohmann::json()) : nlohmann::json();
  const auto says = [&](const char* key, const char* value) {
    return flow.is_object() && flow.value(key, "") == value;
  };
  if (!says("value", "target - source") || !says("units", "pixels") || !says("u", "right") ||
      !says("v", "down") || !(says("erp_seam", "360") || says("erp_seam", "classic")))
    throw FileError(manifest,
                    "conventions: flow is not target - source in pixels with u right, "
                    "v down and a 360 or classic seam; gt_quality cannot score it");
}

// The layout a release states, its conventions checked.
ReleaseLayout release_layout_of(const fs::path& root) {
  const fs::path manifest = root / kManifestFile;
  if (fs::exists(manifest)) {
    const nlohmann::json json = read_json(manifest);
    check_conventions(
        json.is_object() ? json.value("conventions", nlohmann::json()) : nlohmann::json(),
        manifest);
  }
  return read_release_layout(root);
}

// The pairs of every sequence whose flow file exists (a release may be unfinished), in the ERP
// or, for another rig, in each of its cameras (grouped per sequence and camera), with the
// backward flow of each pair's second frame where the release has it.
FlowDataset flowscape_release(const fs::path& root, const std::string& pass) {
  FlowDataset d{"flowscape", {}};
  const ReleaseLayout layout = release_layout_of(root);
  const bool backward = layout.has("flow_backward") && layout.has("valid_backward");
  const std::string image_kind = pass == "final" ? "final" : "color";
  if (!layout.has(image_kind))
    throw FileError(root, "the release has no final pass (gen_flowscape --outputs final makes it)");
  const ReleaseKind color = output_kind(image_kind), valid = output_kind("valid"),
                    back_valid = output_kind("valid_backward");
  ReleaseKind flow = output_kind("flow"), back = output_kind("flow_backward");
  flow.flow_format = back.flow_format = layout.flow_format;  // files as the release stores them
  for (const fs::path& seq : sorted_dirs(sequence_dir(root, ""))) {
    const SequenceMeta meta = read_meta(seq);
    for (const View& view : layout.views()) {
      if (view.face) continue;  // the faces are the ERP's sources
      const bool panorama =
          view.is_erp() ||
          std::any_of(layout.cameras.begin(), layout.cameras.end(),
                      [&](const LayoutCamera& c) { return c.name == view.camera && c.panorama; });
      const std::string group = seq.filename().string() + (view.is_erp() ? "" : "/" + view.camera);
      const auto file = [&](const ReleaseKind& kind, int frame) {
        return seq / frame_file(kind, view, frame);
      };
      for (int f = 0; flow.has_frame(f, meta.frames); ++f) {
        if (!fs::exists(file(flow, f))) continue;
        PairFiles pair{file(color, f),        file(color, f + 1),
                       file(flow, f),         file(valid, f),
                       VisibleMask::NonZero,  group,
                       meta.weather_preset(), panorama};
        if (backward)
          pair.backward = file(back, f + 1), pair.backward_visible = file(back_valid, f + 1);
        d.pairs.push_back(pair);
      }
    }
  }
  return d;
}

// <...>/<category>/img/<scene>/<frame>.jpg with <...>/<category>/flow/<scene>/<frame>.flo
void add_panoflow(const fs::path& category_dir, const std::string& prefix, FlowDataset& d) {
  for (const fs::path& scene : sorted_dirs(category_dir / "img")) {
    const std::vector<fs::path> images = sorted_files(scene, "*.jpg");
    const fs::path flows = category_dir / "flow" / scene.filename();
    for (std::size_t k = 0; k + 1 < images.size(); ++k)
      d.pairs.push_back({images[k],
                         images[k + 1],
                         flows / (images[k].stem().string() + ".flo"),
                         {},
                         VisibleMask::None,
                         scene.filename().string(),
                         prefix + category_dir.filename().string(),
                         true});
  }
}

FlowDataset panoflow_tree(const fs::path& root) {
  FlowDataset d{"panoflow", {}};
  if (fs::is_directory(root / "img")) add_panoflow(root, "", d);  // one weather folder
  for (const fs::path& a : sorted_dirs(root)) {
    if (fs::is_directory(a / "img")) add_panoflow(a, "", d);  // a split folder
    for (const fs::path& b : sorted_dirs(a))
      if (fs::is_directory(b / "img")) add_panoflow(b, a.filename().string() + "/", d);
  }
  return d;
}

FlowDataset sintel(const fs::path& training) {
  FlowDataset d{"sintel", {}};
  for (const char* pass : {"clean", "final"})
    for (const fs::path& scene : sorted_dirs(training / pass)) {
      const std::vector<fs::path> images = sorted_files(scene, "frame_*.png");
      for (std::size_t k = 0; k + 1 < images.size(); ++k) {
        const std::string stem = images[k].stem().string();
        const fs::path flow = training / "flow" / scene.filename() / (stem + ".flo");
        if (!fs::exists(flow)) continue;
        const fs::path occlusion = training / "occlusions" / scene.filename() / (stem + ".png");
        const bool masked = fs::exists(occlusion);
        d.pairs.push_back({images[k], images[k + 1], flow, masked ? occlusion : fs::path{},
                           masked ? VisibleMask::Zero : VisibleMask::None,
                           scene.filename().string(), pass, false});
      }
    }
  return d;
}

FlowDataset kitti(const fs::path& training, const std::string& image_dir, const char* layout) {
  FlowDataset d{layout, {}};
  for (const fs::path& flow : sorted_files(training / "flow_occ", "*_10.png")) {
    const fs::path first = training / image_dir / flow.filename();
    const fs::path noc = training / "flow_noc" / flow.filename();
    const bool masked = fs::exists(noc);
    d.pairs.push_back(
        {first, with_stem_suffix(first, "_10", "_11"), flow, masked ? noc : fs::path{},
         masked ? VisibleMask::FlowValid : VisibleMask::None, "all", image_dir, false});
  }
  return d;
}

FlowDataset flying_chairs(const fs::path& dir) {
  FlowDataset d{"flyingchairs", {}};
  for (const fs::path& first : sorted_files(dir, "*_img1.ppm"))
    d.pairs.push_back({first,
                       with_stem_suffix(first, "_img1", "_img2"),
                       with_stem_suffix(with_stem_suffix(first, "_img1", "_flow"), ".ppm", ".flo"),
                       {},
                       VisibleMask::None,
                       "all",
                       "all",
                       false});
  return d;
}

bool has_panoflow(const fs::path& root) {
  if (fs::is_directory(root / "img") && fs::is_directory(root / "flow")) return true;
  for (const fs::path& a : sorted_dirs(root)) {
    if (fs::is_directory(a / "img") && fs::is_directory(a / "flow")) return true;
    for (const fs::path& b : sorted_dirs(a))
      if (fs::is_directory(b / "img") && fs::is_directory(b / "flow")) return true;
  }
  return false;
}

}  // namespace

FlowDataset find_flow_dataset(const fs::path& root, const std::string& pass) {
  if (pass != "clean" && pass != "final")
    throw std::invalid_argument("the pass is clean or final, not \"" + pass + "\"");
  if (!fs::is_directory(root)) throw FileError(root, "no such folder");
  const bool release = fs::is_directory(sequence_dir(root, ""));
  if (pass == "final" && !release)
    throw FileError(root,
                    "--pass final needs a FlowScape release (Sintel's passes are scored "
                    "both, as categories)");
  FlowDataset d;
  if (release)
    d = flowscape_release(root, pass);
  else if (fs::is_directory(root / "panoflow"))
    d = panoflow_tree(root / "panoflow");
  else if (fs::is_directory(root / "training" / "flow"))
    d = sintel(root / "training");
  else if (fs::is_directory(root / "flow") && fs::is_directory(root / "clean"))
    d = sintel(root);
  else if (fs::is_directory(root / "training" / "image_2"))
    d = kitti(root / "training", "image_2", "kitti2015");
  else if (fs::is_directory(root / "image_2"))
    d = kitti(root, "image_2", "kitti2015");
  else if (fs::is_directory(root / "training" / "colored_0"))
    d = kitti(root / "training", "colored_0", "kitti2012");
  else if (fs::is_directory(root / "colored_0"))
    d = kitti(root, "colored_0", "kitti2012");
  else if (!sorted_files(root, "*_img1.ppm").empty())
    d = flying_chairs(root);
  else if (!sorted_files(root / "data", "*_img1.ppm").empty())
    d = flying_chairs(root / "data");
  else if (has_panoflow(root))
    d = panoflow_tree(root);
  else
    throw FileError(root,
                    "not a known flow dataset layout (FlowScape, PanoFlow, Sintel, KITTI, "
                    "FlyingChairs); use --images and --flows");
  if (d.pairs.empty()) throw FileError(root, d.layout + " layout without any image pair");
  return d;
}

FlowDataset glob_flow_dataset(const std::string& images, const std::string& flows, bool panorama) {
  const auto expand = [](const std::string& glob) {
    const fs::path p(glob);
    const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    return sorted_files(dir, p.filename().string());
  };
  const std::vector<fs::path> image_files = expand(images), flow_files = expand(flows);
  if (flow_files.empty()) throw FileError(flows, "no flow file matches");
  if (image_files.size() != flow_files.size() + 1)
    throw FileError(images, std::to_string(image_files.size()) + " images for " +
                                std::to_string(flow_files.size()) +
                                " flows (need one image more than flows)");
  FlowDataset d{"generic", {}};
  for (std::size_t k = 0; k < flow_files.size(); ++k)
    d.pairs.push_back({image_files[k],
                       image_files[k + 1],
                       flow_files[k],
                       {},
                       VisibleMask::None,
                       "all",
                       "all",
                       panorama});
  return d;
}

FlowDataset sample_pairs(const FlowDataset& dataset, int per_category) {
  std::map<std::string, std::vector<std::size_t>> of_category;
  for (std::size_t k = 0; k < dataset.pairs.size(); ++k)
    of_category[dataset.pairs[k].category].push_back(k);
  std::vector<std::size_t> taken;
  for (const auto& [category, pairs] : of_category) {
    const std::size_t n = pairs.size(), wanted = std::min(n, std::size_t(per_category));
    for (std::size_t k = 0; k < wanted; ++k) taken.push_back(pairs[(2 * k + 1) * n / (2 * wanted)]);
  }
  std::sort(taken.begin(), taken.end());
  FlowDataset sample{dataset.layout, {}};
  for (std::size_t k : taken) sample.pairs.push_back(dataset.pairs[k]);
  return sample;
}

}  // namespace flowscape
