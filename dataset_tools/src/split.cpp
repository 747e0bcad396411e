#include "flowscape/split.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "flowscape/io.h"
#include "flowscape/random.h"
#include "flowscape/release.h"

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
    for (int f = 0; f + 1 < s.frames; ++f) text += s.name + " " + frame_name(f) + "\n";
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
  const fs::path root = release / "sequences";
  if (!fs::is_directory(root)) throw FileError(root, "not a FlowScape release (no sequences/)");
  std::vector<SequenceInfo> sequences;
  for (const auto& entry : fs::directory_iterator(root)) {
    const fs::path meta = entry.path() / "meta.json";
    std::ifstream in(meta);
    if (!in) throw FileError(meta, "missing (an unfinished sequence?)");
    try {
      const nlohmann::json j = nlohmann::json::parse(in);
      sequences.push_back({j.at("scene").get<std::string>(),
                           j.at("weather").at("preset").get<std::string>(),
                           j.at("frames").get<int>()});
    } catch (const nlohmann::json::exception& e) {
      throw FileError(meta, std::string("bad meta.json: ") + e.what());
    }
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
  write_text(release / "splits" / "train.txt", pair_lines(split.train));
  write_text(release / "splits" / "test.txt", pair_lines(split.test));
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
        jobs.push_back({release / "sequences" / s.name, base / "img" / s.name, f, false});
        if (f + 1 < s.frames)
          jobs.push_back({release / "sequences" / s.name, base / "flow" / s.name, f, true});
      }
    }
  tbb::parallel_for(std::size_t(0), jobs.size(), [&](std::size_t k) {
    const Job& job = jobs[k];
    const std::string name = frame_name(job.frame);
    const fs::path target = job.target / (name + (job.flow ? ".flo" : ".jpg"));
    if (fs::exists(target)) return;
    if (job.flow)
      link_or_copy(job.sequence / "erp" / "flow" / (name + ".flo"), target);
    else
      write_image(target,
                  read_image<std::uint8_t>(job.sequence / "erp" / "color" / (name + ".png")));
  });
}

}  // namespace flowscape
