#include "flowscape/release/stitch_folder.h"

#include <algorithm>
#include <optional>
#include <set>

#include "flowscape/core/files.h"
#include "flowscape/core/progress.h"
#include "flowscape/formats/complete_file.h"
#include "flowscape/formats/cubemap_io.h"
#include "flowscape/formats/flow_viz.h"
#include "flowscape/release/layout.h"
#include "flowscape/stitcher/stitch.h"
#include "flowscape/stitcher/synthetic.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

struct Job {
  const OutputKind* kind;
  std::string file;
};

std::string folder(const OutputKind& kind) { return std::string(kind.folder); }
std::string stem(const std::string& file) { return fs::path(file).stem().string(); }
std::string mask_file(const std::string& file) {
  return stem(file) + std::string(output_kind("valid").extension);
}

bool has_cube_file(const fs::path& cube_dir, const OutputKind& kind, const std::string& file) {
  return fs::exists(cube_file(cube_dir, Face::Front, folder(kind), file));
}

// A cube frame read from the folder must have the faces the map was made for (the size of the
// first frame file found), else its front face file is named.
void check_face_size(int width, const CubeToErp& map, const StitchFolderOptions& o,
                     const OutputKind& kind, const std::string& file) {
  const std::string expected = std::to_string(map.sampling.src_width);
  if (width != map.sampling.src_width)
    throw FileError(cube_file(o.cube_dir, Face::Front, folder(kind), file),
                    "cube face is " + std::to_string(width) + "x" + std::to_string(width) +
                        ", the cube's other files have " + expected + "x" + expected + " faces");
}

void stitch_flow(const StitchFolderOptions& o, const CubeToErp& map, const std::string& file) {
  const OutputKind &flow_kind = output_kind("flow"), &instance_kind = output_kind("instance"),
                   &valid_kind = output_kind("valid");
  const Flow flow = read_cube_flow(o.cube_dir, file);
  check_face_size(flow.uv.width, map, o, flow_kind, file);
  const std::string mask = mask_file(file);
  std::optional<Image<std::uint16_t>> instance;
  std::optional<Image<std::uint8_t>> valid;
  if (has_cube_file(o.cube_dir, instance_kind, mask)) {
    instance = read_cube_image_as<std::uint16_t>(o.cube_dir, folder(instance_kind), mask);
    check_face_size(instance->width, map, o, instance_kind, mask);
  }
  if (has_cube_file(o.cube_dir, valid_kind, mask)) {
    valid = read_cube_image_as<std::uint8_t>(o.cube_dir, folder(valid_kind), mask);
    check_face_size(valid->width, map, o, valid_kind, mask);
  }
  FlowInput input{flow.uv.view()};
  if (instance) input.instance = instance->view();
  input.valid = valid ? valid->view() : flow.valid.view();
  const FlowOutput erp = cube_to_erp_flow(map, input, o.flow_mode);
  write_flow(o.out_dir / folder(flow_kind) / file, erp.flow.view(), erp.valid.view());
  if (valid) write_image(o.out_dir / folder(valid_kind) / mask, erp.valid);
}

void stitch_image(const StitchFolderOptions& o, const CubeToErp& map, const Job& job) {
  const AnyImage cube = read_cube_image(o.cube_dir, folder(*job.kind), job.file);
  std::visit(
      [&](const auto& stack) {
        check_face_size(stack.width, map, o, *job.kind, job.file);
        const auto erp = job.kind->resampling == Resampling::Bilinear
                             ? resample_bilinear(map.sampling, stack.view())
                             : resample_nearest(map.sampling, stack.view());
        write_image(o.out_dir / folder(*job.kind) / job.file, erp);
      },
      cube);
}

// The files a job writes; it is done when they all exist and are complete.
std::vector<fs::path> outputs(const StitchFolderOptions& o, const Job& job) {
  std::vector<fs::path> files{o.out_dir / folder(*job.kind) / job.file};
  const OutputKind& valid = output_kind("valid");
  if (job.kind->is_flow() && has_cube_file(o.cube_dir, valid, mask_file(job.file)))
    files.push_back(o.out_dir / folder(valid) / mask_file(job.file));
  return files;
}

std::vector<Job> list_jobs(const StitchFolderOptions& o) {
  std::set<std::string> flow_frames;
  for (const std::string& file : cube_frame_files(o.cube_dir, folder(output_kind("flow"))))
    flow_frames.insert(stem(file));
  std::vector<Job> jobs;
  std::size_t inputs = 0;
  for (const OutputKind& kind : kOutputKinds) {
    if (!kind.cube) continue;
    for (const std::string& file : cube_frame_files(o.cube_dir, folder(kind))) {
      ++inputs;
      if (kind.name == "valid" && flow_frames.contains(stem(file))) continue;  // see stitch_flow
      const Job job{&kind, file};
      const auto files = outputs(o, job);
      const bool done = std::all_of(files.begin(), files.end(), is_complete_file);
      if (o.force || !done) jobs.push_back(job);
    }
  }
  if (inputs == 0)
    throw FileError(o.cube_dir, "no cubemap frames found (expected <face>/<kind>/<frame> files)");
  return jobs;
}

int face_size_of(const fs::path& cube_dir) {
  for (const OutputKind& kind : kOutputKinds)
    for (const std::string& file : cube_frame_files(cube_dir, folder(kind))) {
      const fs::path front = cube_file(cube_dir, Face::Front, folder(kind), file);
      if (kind.is_flow()) return read_flow(front).uv.width;
      return std::visit([](const auto& image) { return image.width; }, read_any_image(front));
    }
  throw FileError(cube_dir, "no cubemap frames found (expected <face>/<kind>/<frame> files)");
}

}  // namespace

std::size_t stitch_cube_folder(const StitchFolderOptions& o) {
  if (!fs::is_directory(o.cube_dir)) throw FileError(o.cube_dir, "cubemap folder not found");
  for (const OutputKind& kind : kOutputKinds)
    if (kind.cube) remove_temporary_files(o.out_dir / folder(kind));
  const std::vector<Job> jobs = list_jobs(o);
  if (jobs.empty()) return 0;
  const CubeToErp map = make_cube_to_erp(face_size_of(o.cube_dir), o.height);
  std::optional<Progress> progress;
  if (o.progress) progress.emplace("stitch_erp", jobs.size(), "files");
  std::size_t written = 0;
  for (const Job& job : jobs) {
    if (job.kind->is_flow())
      stitch_flow(o, map, job.file);
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
    write_cube_image(o.cube_dir, folder(kind), file(kind, frame), stack.view());
  };
  put("color", 0, cube.color0), put("color", 1, cube.color1);
  put("semantic", 0, cube.semantic), put("instance", 0, cube.instance);
  put("depth", 0, cube.depth), put("valid", 0, cube.valid);
  const OutputKind& flow = output_kind("flow");
  write_cube_flow(o.cube_dir, file(flow, 0), cube.flow.view());
  stitch_cube_folder(o);
  const Flow erp = read_flo(o.out_dir / folder(flow) / file(flow, 0));
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
