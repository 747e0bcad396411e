#include "flowscape/layout/stitch_folder.h"

#include <algorithm>
#include <optional>
#include <set>

#include "flowscape/core/files.h"
#include "flowscape/core/progress.h"
#include "flowscape/formats/complete_file.h"
#include "flowscape/formats/cubemap_io.h"
#include "flowscape/formats/flow_viz.h"
#include "flowscape/layout/layout.h"
#include "flowscape/stitcher/stitch.h"
#include "flowscape/stitcher/synthetic.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

struct Job {
  ReleaseKind kind;
  std::string file;
};

std::string stem(const std::string& file) { return fs::path(file).stem().string(); }
std::string mask_file(const std::string& file) {
  return stem(file) + std::string(output_kind("valid").extension);
}

bool has_cube_file(const fs::path& cube_dir, const ReleaseKind& kind, const std::string& file) {
  return fs::exists(cube_file(cube_dir, Face::Front, kind.folder(), file));
}

// The kinds whose folders the cube's front face has, in table order.
std::vector<ReleaseKind> cube_kinds(const fs::path& cube_dir) {
  std::vector<ReleaseKind> kinds;
  const fs::path front = cube_dir / std::string(face_name(Face::Front));
  if (fs::is_directory(front))
    for (const auto& entry : fs::directory_iterator(front)) {
      const std::optional<ReleaseKind> kind = release_kind(entry.path().filename().string());
      if (entry.is_directory() && kind && kind->row->cube) kinds.push_back(*kind);
    }
  std::sort(kinds.begin(), kinds.end(), [](const ReleaseKind& a, const ReleaseKind& b) {
    return std::pair(a.row, a.gap) < std::pair(b.row, b.gap);
  });
  return kinds;
}

// A cube frame read from the folder must have the faces the map was made for (the size of the
// first frame file found), else its front face file is named.
void check_face_size(int width, const CubeToErp& map, const StitchFolderOptions& o,
                     const ReleaseKind& kind, const std::string& file) {
  const std::string expected = std::to_string(map.sampling.src_width);
  if (width != map.sampling.src_width)
    throw FileError(cube_file(o.cube_dir, Face::Front, kind.folder(), file),
                    "cube face is " + std::to_string(width) + "x" + std::to_string(width) +
                        ", the cube's other files have " + expected + "x" + expected + " faces");
}

void stitch_flow(const StitchFolderOptions& o, const CubeToErp& map, const Job& job) {
  const ReleaseKind instance_kind = output_kind("instance"), valid_kind = job.kind.valid_kind();
  const Flow flow = read_cube_flow(o.cube_dir, job.kind.folder(), job.file);
  check_face_size(flow.uv.width, map, o, job.kind, job.file);
  const std::string mask = mask_file(job.file);
  std::optional<Image<std::uint16_t>> instance;
  std::optional<Image<std::uint8_t>> valid;
  if (has_cube_file(o.cube_dir, instance_kind, mask)) {
    instance = read_cube_image_as<std::uint16_t>(o.cube_dir, instance_kind.folder(), mask);
    check_face_size(instance->width, map, o, instance_kind, mask);
  }
  if (has_cube_file(o.cube_dir, valid_kind, mask)) {
    valid = read_cube_image_as<std::uint8_t>(o.cube_dir, valid_kind.folder(), mask);
    check_face_size(valid->width, map, o, valid_kind, mask);
  }
  FlowInput input{flow.uv.view()};
  if (instance) input.instance = instance->view();
  input.valid = valid ? valid->view() : flow.valid.view();
  const FlowOutput erp = cube_to_erp_flow(map, input, o.flow_mode);
  write_flow(o.out_dir / job.kind.folder() / job.file, erp.flow.view(), erp.valid.view());
  if (valid) write_image(o.out_dir / valid_kind.folder() / mask, erp.valid);
}

void stitch_image(const StitchFolderOptions& o, const CubeToErp& map, const Job& job) {
  const AnyImage cube = read_cube_image(o.cube_dir, job.kind.folder(), job.file);
  const fs::path out = o.out_dir / job.kind.folder() / job.file;
  std::visit(
      [&](const auto& stack) {
        check_face_size(stack.width, map, o, job.kind, job.file);
        using T = typename std::decay_t<decltype(stack)>::value_type;
        if constexpr (std::is_same_v<T, float>)
          if (job.kind.row->resampling == Resampling::Vector) {
            if (stack.channels != 3)
              throw FileError(cube_file(o.cube_dir, Face::Front, job.kind.folder(), job.file),
                              "a vector kind needs 3 channels");
            return write_image(out, cube_to_erp_vectors(map, stack.view()));
          }
        write_image(out, job.kind.row->resampling == Resampling::Bilinear
                             ? resample_bilinear(map.sampling, stack.view())
                             : resample_nearest(map.sampling, stack.view()));
      },
      cube);
}

// The files a job writes; it is done when they all exist and are complete.
std::vector<fs::path> outputs(const StitchFolderOptions& o, const Job& job) {
  std::vector<fs::path> files{o.out_dir / job.kind.folder() / job.file};
  if (!job.kind.row->is_flow()) return files;
  const ReleaseKind valid = job.kind.valid_kind();
  if (has_cube_file(o.cube_dir, valid, mask_file(job.file)))
    files.push_back(o.out_dir / valid.folder() / mask_file(job.file));
  return files;
}

std::vector<Job> list_jobs(const StitchFolderOptions& o, const std::vector<ReleaseKind>& kinds) {
  std::set<std::pair<std::string, std::string>> stitched_masks;  // (valid folder, stem)
  for (const ReleaseKind& kind : kinds)
    if (kind.row->is_flow())
      for (const std::string& file : cube_frame_files(o.cube_dir, kind.folder()))
        stitched_masks.insert({kind.valid_kind().folder(), stem(file)});
  std::vector<Job> jobs;
  std::size_t inputs = 0;
  for (const ReleaseKind& kind : kinds)
    for (const std::string& file : cube_frame_files(o.cube_dir, kind.folder())) {
      ++inputs;
      if (stitched_masks.contains({kind.folder(), stem(file)})) continue;  // see stitch_flow
      const Job job{kind, file};
      const auto files = outputs(o, job);
      const bool done = std::all_of(files.begin(), files.end(), is_complete_file);
      if (o.force || !done) jobs.push_back(job);
    }
  if (inputs == 0)
    throw FileError(o.cube_dir, "no cubemap frames found (expected <face>/<kind>/<frame> files)");
  return jobs;
}

int face_size_of(const fs::path& cube_dir, const std::vector<ReleaseKind>& kinds) {
  for (const ReleaseKind& kind : kinds)
    for (const std::string& file : cube_frame_files(cube_dir, kind.folder())) {
      const fs::path front = cube_file(cube_dir, Face::Front, kind.folder(), file);
      if (kind.row->is_flow()) return read_flow(front).uv.width;
      return std::visit([](const auto& image) { return image.width; }, read_any_image(front));
    }
  throw FileError(cube_dir, "no cubemap frames found (expected <face>/<kind>/<frame> files)");
}

}  // namespace

std::size_t stitch_cube_folder(const StitchFolderOptions& o) {
  if (!fs::is_directory(o.cube_dir)) throw FileError(o.cube_dir, "cubemap folder not found");
  const std::vector<ReleaseKind> kinds = cube_kinds(o.cube_dir);
  for (const ReleaseKind& kind : kinds) remove_temporary_files(o.out_dir / kind.folder());
  const std::vector<Job> jobs = list_jobs(o, kinds);
  if (jobs.empty()) return 0;
  const CubeToErp map = make_cube_to_erp(face_size_of(o.cube_dir, kinds), o.height);
  std::optional<Progress> progress;
  if (o.progress) progress.emplace("stitch_erp", jobs.size(), "files");
  std::size_t written = 0;
  for (const Job& job : jobs) {
    if (job.kind.row->is_flow())
      stitch_flow(o, map, job);
    else
      stitch_image(o, map, job);
    written += outputs(o, job).size();
    if (progress) progress->advance();
  }
  if (progress) progress->finish();
  return written;
}

YawDemo run_yaw_demo(const fs::path& dir, int face_size, int erp_height, double yaw_degrees) {
  const SyntheticCubemap cube = make_yaw_cubemap(face_size, yaw_degrees);
  const StitchFolderOptions o{dir / kCubeDir, dir / kErpDir, erp_height, FlowMode::Wrap360, true};
  const auto file = [](const OutputKind& kind, int frame) {
    return frame_name(frame) + std::string(kind.extension);
  };
  const auto put = [&](const char* name, int frame, const auto& stack) {
    const OutputKind& kind = output_kind(name);
    write_cube_image(o.cube_dir, std::string(kind.folder), file(kind, frame), stack.view());
  };
  put("color", 0, cube.color0), put("color", 1, cube.color1);
  put("semantic", 0, cube.semantic), put("instance", 0, cube.instance);
  put("depth", 0, cube.depth), put("valid", 0, cube.valid);
  const OutputKind& flow = output_kind("flow");
  write_cube_flow(o.cube_dir, "flow", file(flow, 0), cube.flow.view());
  stitch_cube_folder(o);
  const Flow erp = read_flo(o.out_dir / std::string(flow.folder) / file(flow, 0));
  write_image(o.out_dir / "flow_viz" / (frame_name(0) + ".png"),
              flow_to_color(erp.uv.view(), erp.valid.view(), {FlowWheel::PanoFlow, 0}));
  YawDemo demo{erp.uv.width, erp.uv.height, yaw_degrees / 360 * erp.uv.width, 0};
  for (std::size_t i = 0; i < erp.uv.pixel_count(); ++i)
    demo.largest_error =
        std::max({demo.largest_error, std::abs(erp.uv.data[2 * i] - demo.expected_u),
                  std::abs(double(erp.uv.data[2 * i + 1]))});
  return demo;
}

}  // namespace flowscape
