#include "flowscape/release/explorer.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <optional>

#include "explorer_page.h"  // kExplorerPage: explorer/index.html, embedded at build time
#include "flowscape/core/files.h"
#include "flowscape/core/progress.h"
#include "flowscape/formats/contact_sheet.h"
#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/flow_viz.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/layout/classes.h"
#include "flowscape/layout/meta.h"
#include "flowscape/layout/split.h"
#include "flowscape/release/statistics.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

constexpr const char* kPreviewsDir = "previews";

// `wanted` frames of `frames`, spread evenly, first and last included (one: the first).
std::vector<int> sampled_frames(int frames, int wanted) {
  if (wanted == 1) return {0};
  if (frames <= wanted) {
    std::vector<int> all(std::size_t(frames), 0);
    for (int f = 0; f < frames; ++f) all[std::size_t(f)] = f;
    return all;
  }
  std::vector<int> picked;
  for (int k = 0; k < wanted; ++k)
    picked.push_back(int(std::lround(double(k) * (frames - 1) / (wanted - 1))));
  return picked;
}

std::vector<ReleaseKind> kinds_of(const ReleaseLayout& layout, const View& view) {
  std::vector<ReleaseKind> kinds;
  for (const ReleaseKind& kind : layout.kinds)
    if (in_view(kind, view)) kinds.push_back(kind);
  return kinds;
}

template <class Colour>
Image<std::uint8_t> colourise(const Image<float>& image, const Colour& colour) {
  Image<std::uint8_t> rgb(image.width, image.height, 3);
  for (std::size_t i = 0; i < image.pixel_count(); ++i)
    colour(&image.data[i * image.channels], &rgb.data[i * 3]);
  return rgb;
}

std::uint8_t unit_to_byte(double v) {
  return std::uint8_t(std::lround(255 * std::clamp(v, 0.0, 1.0)));
}

// Depth: near bright, log scale to 1 km; the sky black.
Image<std::uint8_t> depth_preview(const Image<float>& depth) {
  return colourise(depth, [](const float* d, std::uint8_t* rgb) {
    const double shade = std::isfinite(*d) ? 1 - std::log1p(*d) / std::log1p(1000.0) : 0;
    rgb[0] = rgb[1] = rgb[2] = unit_to_byte(shade);
  });
}

// 3-vectors as 0.5 + 0.5 v / scale per axis (x red, y green, z blue); NaN black.
Image<std::uint8_t> vector_preview(const Image<float>& vectors, double scale) {
  return colourise(vectors, [scale](const float* v, std::uint8_t* rgb) {
    for (int c = 0; c < 3; ++c)
      rgb[c] = std::isfinite(v[c]) ? unit_to_byte(0.5 + 0.5 * v[c] / scale) : 0;
  });
}

// A mask: white where it is not 0.
Image<std::uint8_t> mask_preview(const Image<std::uint8_t>& mask) {
  Image<std::uint8_t> rgb(mask.width, mask.height, 3);
  for (std::size_t i = 0; i < mask.pixel_count(); ++i)
    rgb.data[3 * i] = rgb.data[3 * i + 1] = rgb.data[3 * i + 2] = mask.data[i] ? 255 : 0;
  return rgb;
}

// Instance ids in colours of a fixed hash (0, the static world, black).
Image<std::uint8_t> instance_preview(const Image<std::uint16_t>& ids) {
  Image<std::uint8_t> rgb(ids.width, ids.height, 3);
  for (std::size_t i = 0; i < ids.pixel_count(); ++i) {
    const std::uint32_t id = ids.data[i], hash = id * 2654435761u;
    for (int c = 0; c < 3; ++c)
      rgb.data[3 * i + std::size_t(c)] = id ? std::uint8_t(64 + (hash >> (8 * c + 5)) % 192) : 0;
  }
  return rgb;
}

// A kind's file as an RGB image to look at.
Image<std::uint8_t> kind_preview(const fs::path& dir, const ReleaseKind& kind, const View& view,
                                 int frame, const ClassTable& table) {
  const fs::path file = dir / frame_file(kind, view, frame);
  const std::string_view name = kind.row->name;
  if (kind.row->is_flow()) {
    const Flow flow = read_flow(file);
    const fs::path mask = dir / frame_file(kind.valid_kind(), view, frame);
    const Image<std::uint8_t> valid = read_image<std::uint8_t>(mask);
    if (valid.width != flow.uv.width || valid.height != flow.uv.height || valid.channels != 1)
      throw FileError(mask, "not a one-channel mask of its flow's size (" +
                                std::to_string(flow.uv.width) + " x " +
                                std::to_string(flow.uv.height) + ")");
    return flow_to_color(flow.uv.view(), valid.view(), {});
  }
  if (name == "color" || name == "final") return read_image<std::uint8_t>(file);
  if (name == "semantic") return table_colours(table, read_image<std::uint8_t>(file).view());
  if (kind.row->pixel == PixelType::UInt8) return mask_preview(read_image<std::uint8_t>(file));
  if (kind.row->pixel == PixelType::UInt16)
    return instance_preview(read_image<std::uint16_t>(file));
  if (kind.row->channels == 1) return depth_preview(read_image<float>(file));
  return vector_preview(read_image<float>(file), name == "scene_flow" ? 0.5 : 1);
}

fs::path preview_file(const std::string& sequence, const View& view, const ReleaseKind& kind,
                      int frame) {
  return fs::path(kPreviewsDir) / sequence / view_dir(view) / kind.folder() /
         (frame_name(frame) + ".png");
}

struct SequenceEntry {
  SequenceInfo info;
  SequenceMeta meta;
  std::vector<int> frames;
};

nlohmann::json view_json(const SequenceEntry& s, const View& view,
                         const std::vector<ReleaseKind>& kinds) {
  const std::string dir = view_dir(view).generic_string();
  nlohmann::json kind_list = nlohmann::json::array();
  for (const ReleaseKind& kind : kinds)
    kind_list.push_back({{"name", kind.name()}, {"folder", kind.folder()}, {"step", kind.step()}});
  nlohmann::json calibration =
      s.meta.views.is_object() ? s.meta.views.value(dir, nlohmann::json()) : nlohmann::json();
  if (calibration.is_object()) calibration.erase("poses");  // per frame: in meta.json
  return {{"name", dir}, {"kinds", kind_list}, {"calibration", calibration}};
}

nlohmann::json sequence_json(const SequenceEntry& s, const std::vector<View>& views,
                             const ReleaseLayout& layout) {
  nlohmann::json view_list = nlohmann::json::array();
  for (const View& view : views) view_list.push_back(view_json(s, view, kinds_of(layout, view)));
  const nlohmann::json city = s.meta.city.is_object() ? s.meta.city : nlohmann::json::object();
  return {{"name", s.info.name},
          {"map", s.meta.map},
          {"map_name", s.meta.map_name},
          {"weather", s.info.weather},
          {"base_weather", s.info.base_weather},
          {"frames", s.meta.frames},
          {"sampled_frames", s.frames},
          {"fps", s.meta.fps},
          {"views", view_list},
          {"statistics", s.meta.statistics},
          {"ego_route", city.value("ego_route", nlohmann::json())},
          {"ego_start", city.value("ego", nlohmann::json())}};
}

// manifest.json's description of the release, where it has one.
nlohmann::json release_json(const fs::path& release) {
  nlohmann::json about = nlohmann::json::object();  // no folder name: the same bytes wherever
  const fs::path manifest = release / kManifestFile;
  if (fs::exists(manifest)) {
    const nlohmann::json m = read_json(manifest);
    for (const char* key : {"generator", "config", "counts", "conventions"})
      if (m.is_object() && m.contains(key)) about[key] = m[key];
  }
  if (fs::exists(release / kQualityFile)) about["quality"] = read_json(release / kQualityFile);
  return about;
}

std::vector<View> shown_views(const ReleaseLayout& layout, bool faces) {
  std::vector<View> views;
  for (const View& view : layout.views())
    if (faces || !view.face) views.push_back(view);
  return views;
}

}  // namespace

nlohmann::json write_explorer(const fs::path& release, const fs::path& out,
                              const ExplorerOptions& options) {
  const ReleaseLayout layout = read_release_layout(release);
  const ClassTable& table = class_table(read_release_class_table(release));
  const std::vector<View> views = shown_views(layout, options.faces);
  std::vector<SequenceEntry> sequences;
  std::vector<SequenceStatistics> statistics_of;
  for (const SequenceInfo& info : read_release_sequences(release)) {
    const fs::path dir = sequence_dir(release, info.name);
    SequenceMeta meta = read_meta(dir);
    if (meta.statistics.is_null())  // a release from before meta.json recorded them
      meta.statistics = sequence_statistics_from_files(dir, layout, meta.poses, meta.frames,
                                                       meta.fps, table.size());
    statistics_of.push_back(checked_statistics(dir, meta));
    std::vector<int> frames = sampled_frames(meta.frames, options.frames);
    sequences.push_back({info, std::move(meta), std::move(frames)});
  }
  struct Task {
    const SequenceEntry* sequence;
    int frame;
  };
  std::vector<Task> tasks;
  for (const SequenceEntry& s : sequences)
    for (int f : s.frames) tasks.push_back({&s, f});

  fs::create_directories(out);
  remove_temporary_files(out);
  fs::remove_all(out / kPreviewsDir);
  std::optional<Progress> progress;
  if (options.progress) progress.emplace("explorer", tasks.size(), "frames");
  tbb::parallel_for(std::size_t(0), tasks.size(), [&](std::size_t t) {
    const auto& [s, frame] = tasks[t];
    const fs::path dir = sequence_dir(release, s->info.name);
    for (const View& view : views) {
      const int width = view.is_erp() ? options.width : options.width / 2;
      for (const ReleaseKind& kind : kinds_of(layout, view))
        if (kind.has_frame(frame, s->meta.frames))
          write_image(out / preview_file(s->info.name, view, kind, frame),
                      shrink_to_width(kind_preview(dir, kind, view, frame, table), width));
    }
    if (progress) progress->advance();
  });
  if (progress) progress->finish();

  nlohmann::json sequence_list = nlohmann::json::array();
  for (const SequenceEntry& s : sequences) sequence_list.push_back(sequence_json(s, views, layout));
  const nlohmann::json statistics = release_statistics(statistics_of, table.names);
  nlohmann::json data = {{"release", release_json(release)},
                         {"statistics", statistics},
                         {"previews", kPreviewsDir},
                         {"sequences", sequence_list}};
  write_text(out / "statistics.svg", statistics_svg(statistics));
  write_text(out / "data.js", "window.FLOWSCAPE_RELEASE = " + data.dump() + ";\n");
  write_text(out / "index.html", kExplorerPage);
  return statistics;
}

}  // namespace flowscape
