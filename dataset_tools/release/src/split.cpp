#include "flowscape/release/split.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "flowscape/core/random.h"
#include "flowscape/formats/complete_file.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/release/layout.h"
#include "flowscape/release/meta.h"

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

void link_or_copy(const fs::path& from, const fs::path& to) {
  write_atomically(to, [&](const fs::path& temporary) {
    std::error_code error;
    fs::create_hard_link(from, temporary, error);
    if (error) fs::copy_file(from, temporary, fs::copy_options::overwrite_existing);
  });
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
    sequences.push_back({meta.scene, meta.weather_preset(), meta.frames});
  }
  std::sort(sequences.begin(), sequences.end(),
            [](const SequenceInfo& a, const SequenceInfo& b) { return a.name < b.name; });
  return sequences;
}

Split split_sequences(const std::vector<SequenceInfo>& sequences, std::uint64_t seed) {
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
  for (auto* side : {&split.train, &split.test})
    std::sort(side->begin(), side->end(),
              [](const SequenceInfo& a, const SequenceInfo& b) { return a.name < b.name; });
  return split;
}

void write_split_files(const fs::path& release, const Split& split) {
  write_text(split_file(release, "train"), pair_lines(split.train));
  write_text(split_file(release, "test"), pair_lines(split.test));
}

void write_panoflow_tree(const fs::path& release, const Split& split) {
  struct Job {
    fs::path sequence, target;
    int frame;
    bool flow;
  };
  std::vector<Job> jobs;
  for (const auto& [side, sequences] : {std::pair{"train", &split.train}, {"test", &split.test}})
    for (const SequenceInfo& s : *sequences) {
      const fs::path base = release / "panoflow" / side / s.weather;
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
    const fs::path source = job.sequence / frame_file(output_kind(job.flow ? "flow" : "color"),
                                                      std::nullopt, job.frame);
    if (job.flow)
      link_or_copy(source, target);
    else
      write_image(target, read_image<std::uint8_t>(source));
  });
}

}  // namespace flowscape
