// What encoding a release frame's files costs at each lossless compression setting: per kind, the
// bytes and the encoding time of the ERP's file and the six cube faces' (frame 1 of map 0's first
// sequence, written first at flowscape 0.10's settings), against 0.10's setting in the same run
// (PNG level 6, EXR zip). The pixels decoded are the same at every setting; only the file's bytes
// and the time differ. Then each flow kind in each --flow-format (encoded and written), against
// .flo, with the largest error each format leaves. Median of the repeats, one thread (the
// writer's).
// Usage: bench_encoding [repeats = 5]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/release/writer.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

struct Cost {
  double seconds = 0;
  std::size_t bytes = 0;
};

Cost encoding_cost(const fs::path& file, const AnyImage& image, const Compression& compression,
                   int repeats) {
  std::vector<double> seconds;
  Cost cost;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    cost.bytes = std::visit(
        [&](const auto& pixels) {
          return encode_image(file, pixels.view(), {}, compression).size();
        },
        image);
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  cost.seconds = seconds[seconds.size() / 2];
  return cost;
}

// The settings tried for a file of this extension, by name; the first is flowscape 0.10's.
std::vector<std::pair<std::string, Compression>> settings_for(const fs::path& file) {
  if (file.extension() == ".png")
    return {{"level 6", {6, "zip"}},
            {"level 1", {1, "zip"}},
            {"level 2", {2, "zip"}},
            {"level 3", {3, "zip"}},
            {"level 9", {9, "zip"}}};
  return {{"zip", {6, "zip"}},
          {"zips", {6, "zips"}},
          {"piz", {6, "piz"}},
          {"rle", {6, "rle"}},
          {"none", {6, "none"}}};
}

// Frame 1's files of one kind with an extension of `extensions`: the ERP's and the six faces'.
std::map<std::string, std::vector<fs::path>> files_by_kind(
    const fs::path& sequence, const std::vector<std::string>& extensions) {
  std::map<std::string, std::vector<fs::path>> kinds;
  for (const auto& entry : fs::recursive_directory_iterator(sequence)) {
    const fs::path& file = entry.path();
    const std::string ext = file.extension().string();
    if (file.stem() != "000001" ||
        std::find(extensions.begin(), extensions.end(), ext) == extensions.end())
      continue;
    kinds[file.parent_path().filename().string() + ext].push_back(file);
  }
  return kinds;
}

// A frame's flow of one kind in `format`: median seconds to encode and write, bytes, and the
// largest error against the float flow where it is known in both.
struct FlowCost {
  double seconds = 0, max_error = 0;
  std::size_t bytes = 0, flagged = 0;
};

FlowCost flow_cost(const std::vector<fs::path>& files, FlowFormat format, const fs::path& scratch,
                   int repeats) {
  FlowCost cost;
  for (const fs::path& file : files) {
    const Flow flow = read_flo(file);
    const fs::path out = scratch / ("flow" + std::string(flow_format_extension(format)));
    std::vector<double> seconds;
    for (int r = 0; r < repeats; ++r) {
      const auto start = std::chrono::steady_clock::now();
      const std::size_t flagged = write_flow_as(out, format, flow.uv.view());
      if (r == 0) cost.flagged += flagged;
      seconds.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(seconds.begin(), seconds.end());
    cost.seconds += seconds[seconds.size() / 2];
    cost.bytes += fs::file_size(out);
    const Flow back = read_flow(out);
    for (std::size_t i = 0; i < back.uv.data.size(); ++i)
      if (*back.valid.pixel(int(i / 2 % flow.uv.width), int(i / 2 / flow.uv.width)) &&
          *flow.valid.pixel(int(i / 2 % flow.uv.width), int(i / 2 / flow.uv.width)))
        cost.max_error =
            std::max(cost.max_error, double(std::abs(back.uv.data[i] - flow.uv.data[i])));
  }
  return cost;
}

void print_flow_formats(const fs::path& sequence, const fs::path& scratch, int repeats) {
  std::printf("  flow formats (--flow-format), ERP + six faces per kind, against .flo:\n");
  for (const auto& [kind, files] : files_by_kind(sequence, {".flo"})) {
    std::printf("  %-22s", kind.c_str());
    FlowCost flo;
    for (FlowFormat format : {FlowFormat::Flo, FlowFormat::KittiPng, FlowFormat::HalfExr}) {
      const FlowCost cost = flow_cost(files, format, scratch, repeats);
      if (format == FlowFormat::Flo) flo = cost;
      std::printf(
          "  %s %6.1f ms %6.0f kB (%+4.0f %% t, %+4.0f %% B; error <= %.4f px, %zu flagged)",
          std::string(flow_format_name(format)).c_str(), 1e3 * cost.seconds, cost.bytes / 1e3,
          100 * (cost.seconds / flo.seconds - 1),
          100 * (double(cost.bytes) / double(flo.bytes) - 1), cost.max_error, cost.flagged);
    }
    std::printf("\n");
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  ReleaseConfig config;  // the paper's FlowScape, one frame
  config.maps = 1, config.sequences_per_map = 1, config.frames = 3;  // frame 1 has both flows
  const fs::path out = fs::temp_directory_path() / "flowscape-bench-encoding";
  fs::remove_all(out);
  const SequencePlan plan = plan_sequences(config).front();
  write_sequence(config, plan, out, {[] {}, [] {}});
  std::printf(
      "bench_encoding: frame 1 of %s, ERP + six faces per kind, median of %d; milliseconds "
      "and kB per frame, then against flowscape 0.10's setting (first)\n",
      plan.name.c_str(), repeats);
  const fs::path sequence = sequence_dir(out, plan.name);
  for (const auto& [kind, files] : files_by_kind(sequence, {".png", ".exr"})) {
    std::printf("  %-22s", kind.c_str());
    Cost release;
    for (const auto& [name, compression] : settings_for(files.front())) {
      Cost frame;
      for (const fs::path& file : files) {
        const Cost cost = encoding_cost(file, read_any_image(file), compression, repeats);
        frame.seconds += cost.seconds, frame.bytes += cost.bytes;
      }
      if (release.bytes == 0) release = frame;
      std::printf("  %s %6.1f ms %6.0f kB (%+4.0f %% t, %+4.0f %% B)", name.c_str(),
                  1e3 * frame.seconds, frame.bytes / 1e3,
                  100 * (frame.seconds / release.seconds - 1),
                  100 * (double(frame.bytes) / double(release.bytes) - 1));
    }
    std::printf("\n");
  }
  const fs::path scratch = out / "scratch";
  fs::create_directories(scratch);
  print_flow_formats(sequence, scratch, repeats);
  fs::remove_all(out);
  return 0;
}
