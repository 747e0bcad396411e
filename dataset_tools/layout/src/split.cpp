#include "flowscape/layout/split.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "flowscape/core/files.h"
#include "flowscape/core/random.h"
#include "flowscape/formats/complete_file.h"
#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/layout/layout.h"
#include "flowscape/layout/meta.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

int test_count(const std::string& weather, int n) {
  if (n < 2) return 0;
  const double share = weather == "sunny" ? 0.2 : 0.25;
  return std::clamp(int(std::lround(n * share)), 1, n - 1);
}

std::string pair_lines(const std::vector<SequenceInfo>& sequences) {
  std::string text;
  for (const SequenceInfo& s : sequences)
    for (int f = 0; has_frame(output_kind("flow"), f, s.frames); ++f)
      text += s.name + " " + frame_name(f) + "\n";
  return text;
}

// The release's ERP flow of a frame in the tree's conventions: classic or 360-degree, and sky
// (infinite depth) and, if asked, occluded pixels (valid = 0) marked unknown (kUnknownFlow), which
// the public loader's |u|, |v| < 1000 mask drops.
Image<float> panoflow_flow(const fs::path& sequence, const ReleaseKind& flow_kind, int frame,
                           const PanoflowOptions& o) {
  Image<float> flow = read_flow(sequence / frame_file(flow_kind, View(), frame)).uv;
  const Image<float> depth =
      o.sky_invalid ? read_image<float>(erp_file(sequence, "depth", frame)) : Image<float>();
  const Image<std::uint8_t> valid =
      o.occluded_invalid ? read_image<std::uint8_t>(erp_file(sequence, "valid", frame))
                         : Image<std::uint8_t>();
  for (int y = 0; y < flow.height; ++y)
    for (int x = 0; x < flow.width; ++x) {
      float* f = flow.pixel(x, y);
      const bool sky = o.sky_invalid && std::isinf(*depth.pixel(x, y));
      const bool occluded = o.occluded_invalid && *valid.pixel(x, y) == 0;
      if (sky || occluded || !is_known_flow(f[0], f[1])) {
        f[0] = f[1] = kUnknownFlow;
        continue;
      }
      f[0] = float(erp_flow_u(f[0], x + 0.5, flow.width, o.flow));
    }
  return flow;
}

}  // namespace

std::vector<SequenceInfo> read_release_sequences(const fs::path& release) {
  const fs::path root = sequence_dir(release, "");
  if (!fs::is_directory(root)) throw FileError(root, "not a FlowScape release (no sequences/)");
  if (!fs::exists(release / kManifestFile))
    throw FileError(release / kManifestFile,
                    "missing: the release is unfinished (rerun gen_flowscape, or flowscape_merge "
                    "after shards)");
  std::vector<SequenceInfo> sequences;
  for (const auto& entry : fs::directory_iterator(root)) {
    const SequenceMeta meta = read_meta(entry.path());
    sequences.push_back({meta.scene, meta.weather_preset(), meta.base_weather(), meta.frames});
  }
  std::sort(sequences.begin(), sequences.end(),
            [](const SequenceInfo& a, const SequenceInfo& b) { return a.name < b.name; });
  return sequences;
}

Split split_sequences(const std::vector<SequenceInfo>& sequences, std::uint64_t seed) {
  if (sequences.size() < 2)
    throw std::invalid_argument("a split needs at least 2 sequences, the release has " +
                                std::to_string(sequences.size()));
  std::map<std::string, std::vector<SequenceInfo>> by_weather;
  for (const SequenceInfo& s : sequences) by_weather[s.weather].push_back(s);
  Split split;
  for (auto& [weather, group] : by_weather) {
    std::sort(group.begin(), group.end(),
              [](const SequenceInfo& a, const SequenceInfo& b) { return a.name < b.name; });
    Random random(seed ^ std::hash<std::string>{}(weather));
    for (int k = int(group.size()) - 1; k > 0; --k) std::swap(group[k], group[random.below(k + 1)]);
    const int tests = test_count(weather, int(group.size()));
    for (int k = 0; k < int(group.size()); ++k)
      (k < tests ? split.test : split.train).push_back(group[k]);
  }
  if (split.test.empty()) {  // every weather has one sequence: one of them (by the seed) is test
    Random random(seed);
    const std::size_t pick = random.below(int(split.train.size()));
    split.test.push_back(split.train[pick]);
    split.train.erase(split.train.begin() + std::ptrdiff_t(pick));
  }
  for (auto* side : {&split.train, &split.test})
    std::sort(side->begin(), side->end(),
              [](const SequenceInfo& a, const SequenceInfo& b) { return a.name < b.name; });
  return split;
}

void write_all_split(const fs::path& release, const std::vector<SequenceInfo>& sequences) {
  remove_temporary_files(split_file(release, "all").parent_path());
  write_text(split_file(release, "all"), pair_lines(sequences));
}

void write_split_files(const fs::path& release, const Split& split) {
  remove_temporary_files(split_file(release, "train").parent_path());
  write_text(split_file(release, "train"), pair_lines(split.train));
  write_text(split_file(release, "test"), pair_lines(split.test));
  if (split.val.empty())
    fs::remove(split_file(release, "val"));
  else
    write_text(split_file(release, "val"), pair_lines(split.val));
}

double split_hash(const std::string& name, std::uint64_t seed) {
  std::uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a
  for (const char c : name) h = (h ^ std::uint8_t(c)) * 0x100000001b3ull;
  return double(mix_bits(h ^ mix_bits(seed)) >> 11) * 0x1.0p-53;
}

Split split_by_hash(const std::vector<SequenceInfo>& sequences, std::uint64_t seed,
                    const HashSplitOptions& options) {
  Split split;
  for (const SequenceInfo& s : sequences) {
    const bool held_out =  // the name starts "mapMM_" of a held-out map
        std::any_of(options.held_out_maps.begin(), options.held_out_maps.end(), [&](int map) {
          return s.name.starts_with(sequence_name(map, 0).substr(0, 6));
        });
    const double u = split_hash(s.name, seed);
    (held_out || u < options.test_share           ? split.test
     : u < options.test_share + options.val_share ? split.val
                                                  : split.train)
        .push_back(s);
  }
  return split;
}

namespace {

nlohmann::json to_json(const PanoflowOptions& o) {
  nlohmann::json j = {{"flow", o.flow == FlowMode::Classic ? "classic" : "360"},
                      {"sky", o.sky_invalid ? "invalid" : "kept"},
                      {"occluded", o.occluded_invalid ? "invalid" : "kept"}};
  if (o.final_pass) j["pass"] = "final";  // a clean tree's record as it was
  return j;
}

}  // namespace

std::vector<std::string> write_panoflow_tree(const fs::path& release, const Split& split,
                                             const PanoflowOptions& options) {
  const fs::path tree = release / "panoflow", conventions = tree / "flowscape.json";
  const ReleaseLayout layout = read_release_layout(release);
  if (options.final_pass && !layout.has("final"))
    throw FileError(release, "the release has no final pass (gen_flowscape --outputs final)");
  if (fs::exists(tree) && (!fs::exists(conventions) || read_json(conventions) != to_json(options)))
    fs::remove_all(tree);  // made with other conventions or pass: none of its files can be kept
  remove_temporary_files_under(tree);
  struct Job {
    fs::path sequence, target;
    int frame;
    bool flow;
  };
  std::vector<Job> jobs;
  std::vector<std::string> empty;
  for (const auto& [side, sequences] : {std::pair{"train", &split.train}, {"test", &split.test}})
    for (const char* weather : kBaseWeathers) {
      fs::create_directories(tree / side / weather / "img");
      fs::create_directories(tree / side / weather / "flow");
      if (std::none_of(sequences->begin(), sequences->end(),
                       [&](const SequenceInfo& s) { return s.base_weather == weather; }))
        empty.push_back(std::string(side) + "/" + weather);
    }
  for (const auto& [side, sequences] : {std::pair{"train", &split.train}, {"test", &split.test}})
    for (const SequenceInfo& s : *sequences) {
      const fs::path base = tree / side / s.base_weather;
      for (int f = 0; f < s.frames; ++f) {
        const fs::path sequence = sequence_dir(release, s.name);
        jobs.push_back({sequence, base / "img" / s.name, f, false});
        if (has_frame(output_kind("flow"), f, s.frames))
          jobs.push_back({sequence, base / "flow" / s.name, f, true});
      }
    }
  tbb::parallel_for(std::size_t(0), jobs.size(), [&](std::size_t k) {
    const Job& job = jobs[k];
    const std::string name = frame_name(job.frame);
    const fs::path target = job.target / (name + (job.flow ? ".flo" : ".jpg"));
    if (is_complete_file(target)) return;  // resumed: whole files only
    if (job.flow)
      write_flo(target,
                panoflow_flow(job.sequence, *layout.find("flow"), job.frame, options).view());
    else
      write_image(target, read_image<std::uint8_t>(erp_file(
                              job.sequence, options.final_pass ? "final" : "color", job.frame)));
  });
  write_text(conventions, to_json(options).dump(1) + "\n");
  return empty;
}

}  // namespace flowscape
