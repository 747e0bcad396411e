#include "flowscape/release/writer.h"

#include <future>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "flowscape/core/files.h"
#include "flowscape/core/profile.h"
#include "flowscape/core/progress.h"
#include "flowscape/formats/complete_file.h"
#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/layout/classes.h"
#include "flowscape/layout/layout.h"
#include "flowscape/layout/meta.h"
#include "flowscape/release/dataset_card.h"
#include "flowscape/release/explorer.h"
#include "flowscape/release/frame_pipeline.h"
#include "flowscape/release/manifest.h"
#include "flowscape/release/options.h"
#include "flowscape/release/sequence.h"
#include "flowscape/release/statistics.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

template <class T>
constexpr PixelType pixel_type() {
  if constexpr (std::is_same_v<T, std::uint8_t>) return PixelType::UInt8;
  if constexpr (std::is_same_v<T, std::uint16_t>) return PixelType::UInt16;
  return PixelType::Float32;
}

template <class T>
void write_output(const fs::path& path, const ReleaseKind& kind, ImageView<const T> image) {
  const OutputKind& row = *kind.row;
  if (pixel_type<T>() != row.pixel || image.channels != row.channels)
    throw std::logic_error(path.string() + ": the image does not match its output kind's row");
  if constexpr (std::is_same_v<T, float>)
    if (row.is_flow()) {
      write_flow_as(path, kind.flow_format, image);  // flow beyond the format's range flagged
      return;
    }
  write_image(path, image, {}, {row.png_level});
}

// Writes the kinds a view has at `frame`, from its images (a cube face's: its part of the six
// stacked, `face_of` cutting it out).
template <class Cut>
void write_view(const fs::path& dir, const ReleaseLayout& layout, const View& view, int frame,
                int frames, const ViewImages& images, const Cut& face_of) {
  for (const ReleaseKind& kind : layout.kinds) {
    if (!in_view(kind, view) || !kind.has_frame(frame, frames)) continue;
    std::visit(
        [&](const auto& image) {
          write_output(dir / frame_file(kind, view, frame), kind, face_of(image.view()));
        },
        images.at(kind.name()));
  }
}

void write_single_view(const fs::path& dir, const ReleaseLayout& layout, const View& view,
                       int frame, int frames, const ViewImages& images) {
  write_view(dir, layout, view, frame, frames, images, [](auto image) { return image; });
}

void write_cube(const fs::path& dir, const ReleaseLayout& layout, int frame, int frames,
                const ViewImages& stacked) {
  for (Face face : kFaces)
    write_view(dir, layout, face, frame, frames, stacked,
               [face](auto image) { return face_view(image, face); });
}

// The statistics of a view's frame, from its images before they are written (the flow as its
// files give it back, so that statistics read back from the files on resume are the same).
FrameStatistics statistics_of(const ViewImages& images, FlowFormat flow_format, int frame,
                              int frames) {
  const auto image = [&]<class T>(const char* kind, T) {
    return std::get<Image<T>>(images.at(kind)).view();
  };
  const bool flow = has_frame(output_kind("flow"), frame, frames);
  const Image<float> stored = flow ? stored_flow(flow_format, image("flow", 0.0f)) : Image<float>{};
  return frame_statistics(flow ? stored.view() : ImageView<const float>{},
                          flow ? image("valid", std::uint8_t()) : ImageView<const std::uint8_t>{},
                          image("semantic", std::uint8_t()), image("instance", std::uint16_t()));
}

// Writes a frame's files; returns the statistics of its first view (statistics_view's).
FrameStatistics write_frame(const fs::path& dir, const ReleaseLayout& layout, int frame, int frames,
                            const FrameImages& images) {
  {
    const ScopedPhase phase("encoding and writing");
    if (images.cube) write_cube(dir, layout, frame, frames, *images.cube);
    for (const auto& [view, view_images] : images.views)
      write_single_view(dir, layout, view, frame, frames, view_images);
  }
  const ScopedPhase phase("statistics");
  return statistics_of(images.views.front().second, layout.flow_format, frame, frames);
}

// The 2-D boxes of every instance per view and frame, from the sequence's instance images:
// {"erp": [[[id, x0, y0, x1, y1], ...] per frame], "cube/front": ...}.
nlohmann::json boxes_json(const fs::path& dir, const ReleaseLayout& layout, int frames) {
  nlohmann::json boxes = nlohmann::json::object();
  for (const View& view : layout.views()) {
    const bool panorama = view.is_erp() || std::any_of(layout.cameras.begin(), layout.cameras.end(),
                                                       [&](const LayoutCamera& c) {
                                                         return c.name == view.camera && c.panorama;
                                                       });
    nlohmann::json per_frame = nlohmann::json::array();
    for (int f = 0; f < frames; ++f) {
      const Image<std::uint16_t> ids =
          read_image<std::uint16_t>(dir / frame_file(output_kind("instance"), view, f));
      nlohmann::json frame = nlohmann::json::array();
      for (const InstanceBox& b : instance_boxes(ids.view(), panorama))
        frame.push_back({b.instance, b.x0, b.y0, b.x1, b.y1});
      per_frame.push_back(frame);
    }
    boxes[view_dir(view).generic_string()] = per_frame;
  }
  return boxes;
}

bool all_complete(const fs::path& dir, const std::vector<fs::path>& files) {
  return std::all_of(files.begin(), files.end(),
                     [&](const fs::path& f) { return is_complete_file(dir / f); });
}

bool meta_readable(const fs::path& dir) {
  try {
    read_meta(dir);
    return true;
  } catch (const FileError&) {
    return false;
  }
}

// The files and folders of a release that --force deletes (nothing else in `out` is touched).
void remove_release_files(const fs::path& out) {
  for (const fs::path& entry : {sequence_dir(out, ""), out / kConfigFile, out / kManifestFile,
                                out / kShardDir, out / kExplorerDir})
    fs::remove_all(entry);
  remove_dataset_card(out);
}

// The config a release in `out` was started with: config.json (written before any frame) or, for a
// release from before it, its manifest's; the keys of options added since as they were then.
nlohmann::json recorded_config(const fs::path& out) {
  nlohmann::json recorded;
  if (fs::exists(out / kConfigFile))
    recorded = read_json(out / kConfigFile);
  else if (fs::exists(out / kManifestFile))
    recorded = read_json(out / kManifestFile).value("config", nlohmann::json());
  return with_absent_keys(recorded);
}

}  // namespace

void write_sequence(const ReleaseConfig& config, const SequencePlan& plan, const fs::path& out,
                    const SequenceProgress& progress, const TracingBaseline* baseline) {
  const fs::path dir = sequence_dir(out, plan.name);
  const ReleaseLayout layout = release_layout(config);
  fs::create_directories(dir);
  remove_temporary_files_under(dir);
  std::vector<int> frames_to_render;
  for (int f = 0; f < config.frames; ++f) {
    if (all_complete(dir, layout.frame_files(f, config.frames)))
      progress.frame_skipped();
    else
      frames_to_render.push_back(f);
  }
  const bool has_meta = meta_readable(dir);
  if (frames_to_render.empty() && has_meta) return;
  std::optional<ScopedPhase> setting_up(std::in_place, "scene set-up: city and models");
  const Sequence sequence = make_sequence(sequence_spec(config, plan));
  setting_up.reset();
  // of every frame: those rendered now as they are written, the others read back
  const View view = statistics_view(layout);
  std::vector<FrameStatistics> statistics(std::size_t(config.frames));
  for (int f = 0; f < config.frames; ++f)
    if (!std::binary_search(frames_to_render.begin(), frames_to_render.end(), f))
      statistics[std::size_t(f)] = frame_statistics(dir, layout, view, f, config.frames);
  // the final pass's auto-exposure, frame by frame: frames written before are read back
  const bool final = layout.has("final");
  std::vector<Exposure> exposures(final ? std::size_t(config.frames) : 0);
  Exposure exposure;
  std::unique_ptr<Renderer> renderer;
  const Rig rig = release_rig(config);
  const bool faces = rig.has_cube_faces();
  const CubeToErp map = faces && !frames_to_render.empty()
                            ? make_cube_to_erp(config.face_size, config.height)
                            : CubeToErp{};
  const Projection& metering = rig.cameras.front().projection;  // the flowscape rig's: its ERP
  // frame f's files are written while frame f + 1 renders (one frame in flight)
  std::future<void> writing;
  const auto write = [&](int f, FrameImages images) {
    statistics[std::size_t(f)] = write_frame(dir, layout, f, config.frames, images);
    progress.frame_done();
  };
  const ColorSection color = color_section(config);
  const FinalPassSection final_pass = final_pass_section(config);
  LayerHistory history;  // temporal reconstruction's frames
  for (int f = 0; f < config.frames; ++f) {
    history.drop_before(f - config.temporal);
    if (!std::binary_search(frames_to_render.begin(), frames_to_render.end(), f)) {
      if (final)
        exposures[std::size_t(f)] = exposure = exposure_after(
            final_pass, sequence, exposure,
            read_image<std::uint8_t>(dir / frame_file(output_kind("color"), view, f)).view(),
            metering, f);
      continue;
    }
    if (!renderer) {
      const ScopedPhase phase("scene set-up: BVHs and textures");
      renderer = std::make_unique<Renderer>(sequence.city.scene);
      if (baseline) renderer->trace_as(*baseline);
    }
    Exposure* frame_exposure = final ? &exposure : nullptr;
    FrameImages images = [&] {
      try {
        return render_frame(
            {color, final_pass, class_table(config.classes), config.frames, layout, rig, sequence,
             *renderer, faces ? &map : nullptr, config.temporal > 0 ? &history : nullptr},
            f, frame_exposure);
      } catch (const RayError& e) {  // the ERP's, or a face's or rig camera's already named
        throw std::runtime_error(plan.name + ", frame " + std::to_string(f) + ", " +
                                 e.of_camera("erp").what());
      }
    }();
    if (final) exposures[std::size_t(f)] = exposure;
    if (writing.valid()) writing.get();  // its errors surface here
    if (baseline) {
      write(f, std::move(images));
      continue;
    }
    writing = std::async(std::launch::async, write, f, std::move(images));
  }
  if (writing.valid()) writing.get();
  const ScopedPhase phase("meta.json and 2-D boxes");
  // last: its 2-D boxes come from the frames' instance images, and it marks the sequence done
  SequenceMeta meta = sequence_meta(sequence, plan, config);
  meta.boxes = boxes_json(dir, layout, config.frames);
  meta.statistics = sequence_statistics_json(view, statistics, meta.poses, meta.fps,
                                             class_table(config.classes).size());
  if (final) meta.final = final_json(final_pass, sequence, exposures);
  write_meta(dir, meta);
}

// Whether `now` only adds maps at the end of the release `recorded` describes: sequences are
// numbered map by map and their weather, time of day, sky and route follow that number, so the
// sequences already made stay exactly as they are.
bool grows_by_maps(const nlohmann::json& recorded, const nlohmann::json& now) {
  if (recorded.is_null() || !recorded.contains("maps") || now.at("maps") <= recorded.at("maps"))
    return false;
  nlohmann::json same = recorded;
  same["maps"] = now.at("maps");
  return same == now && now.value("map_list", nlohmann::json::array()).empty();
}

void claim_release(const ReleaseConfig& config, const fs::path& out, bool force) {
  const nlohmann::json now = to_json(config), recorded = recorded_config(out);
  if (config.shards == 1 && grows_by_maps(recorded, now)) {
    std::fprintf(diagnostics(),
                 "gen_flowscape: %s: the release grows from %d to %d maps; its "
                 "sequences stay as they are\n",
                 out.string().c_str(), recorded.at("maps").get<int>(), config.maps);
  } else if (!recorded.is_null() && recorded != now) {
    if (!force) {
      if (config.shards > 1) write_refused_shard(out, config);
      throw FileError(out / (fs::exists(out / kConfigFile) ? kConfigFile : kManifestFile),
                      "this release was made with another config (" +
                          config_differences(recorded, "recorded", now, "now") +
                          "): rerun with the recorded values, use another folder, or --force to "
                          "delete the release's files and start over");
    }
    remove_release_files(out);
  }
  if (recorded != now) write_text(out / kConfigFile, now.dump(1) + "\n");
}

ReleaseWritten write_release(const ReleaseConfig& config, const fs::path& out, bool force) {
  // Only a process that makes the whole release owns the folder's top level: a shard may run
  // beside others writing config.json, so their temporaries are the merge's to remove.
  check_sky_resolution(config);
  if (fs::exists(out) && !fs::is_directory(out))
    throw FileError(out, "is a file, not a folder: a release needs a folder");
  if (config.shards == 1) remove_temporary_files(out);
  check_user_files(config);  // a bad world or model named before anything is written
  claim_release(config, out, force);
  const std::vector<SequencePlan> mine = shard_plans(config);
  Progress progress("gen_flowscape", mine.size() * std::size_t(config.frames), "frames");
  for (const SequencePlan& plan : mine)
    write_sequence(config, plan, out, {[&] { progress.advance(); }, [&] { progress.skip(); }});
  progress.finish();
  const nlohmann::json files = file_hashes(out, config, mine);
  ReleaseWritten written{out / kManifestFile, mine.size(), mine.size() * std::size_t(config.frames),
                         files.size()};
  if (config.shards > 1) {
    write_shard_manifest(out, config, files);
    written.manifest = shard_manifest_path(out, config);
    return written;
  }
  warn_of_mixed_kernels(out, sequence_names(config));  // a run resumed on another machine
  const nlohmann::json statistics = release_statistics(out, sequence_names(config), config.classes);
  write_dataset_card(out, config, statistics);
  write_manifest(out, config, files, statistics);
  write_explorer(out, out / kExplorerDir, {.progress = true});
  return written;
}

}  // namespace flowscape
