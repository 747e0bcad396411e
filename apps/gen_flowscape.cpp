// gen_flowscape: renders a FlowScape release (design.md's layout): per map its sequences in their
// weathers, every modality in ERP and on the six cube faces, meta.json per sequence, manifest.json
// with sha256 of every file and a dataset card. Killed at any moment, the same command resumes and
// finishes with the same bytes.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <functional>
#include <variant>

#include "cli.h"
#include "flowscape/core/files.h"
#include "flowscape/layout/meta.h"
#include "flowscape/release/manifest.h"
#include "flowscape/release/options.h"
#include "flowscape/release/scenario.h"
#include "flowscape/release/sequence.h"
#include "flowscape/release/statistics.h"
#include "flowscape/release/writer.h"
#include "flowscape/renderer/calibration_file.h"
#include "tracing_cli.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

// A default as the command line writes it: text bare, lists comma-separated.
std::string default_text(const nlohmann::json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (!value.is_array()) return value.dump();
  std::string text;
  for (const nlohmann::json& item : value) text += (text.empty() ? "" : ",") + default_text(item);
  return text;
}

// Runs `set` on an option's text, an error in it a usage error.
template <class Value>
std::function<void(const Value&)> usage_checked(std::function<void(const Value&)> set) {
  return [set](const Value& value) {
    try {
      set(value);
    } catch (const std::invalid_argument& e) {
      throw CLI::ValidationError(e.what());
    }
  };
}

// An option of OptionForm::Value, typed as its member: its value is the config key's.
CLI::Option* add_value_option(CLI::App& app, const ReleaseOption& option, nlohmann::json& given) {
  return std::visit(
      [&](auto member) {
        using T = std::decay_t<decltype(std::declval<ReleaseConfig>().*member)>;
        const char* key = option.key;
        CLI::Option* added = app.add_option_function<T>(
            option.flag, [&given, key](const T& value) { given[key] = value; }, option.help);
        if constexpr (std::is_unsigned_v<T>)
          added->check(CLI::Validator(
              [](const std::string& text) {
                return text.find('-') == std::string::npos ? "" : "must be a whole number >= 0";
              },
              "UINT64"));
        return added;
      },
      option.field);
}

// The release's options (release/options.h) on the command line, each writing its config keys to
// `given`.
void add_release_options(CLI::App& app, nlohmann::json& given) {
  const ReleaseConfig defaults;
  for (const ReleaseOption& option : release_options()) {
    const char* key = option.key;
    CLI::Option* added = nullptr;
    switch (option.form) {
      case OptionForm::Value:
        added = add_value_option(app, option, given);
        break;
      case OptionForm::List:
        added = app.add_option_function<std::string>(
            option.flag, usage_checked<std::string>([&given, &option](const std::string& text) {
              given[option.key] = parse_list(option, text);
            }),
            option.help);
        break;
      case OptionForm::Each:
        added = app.add_option_function<std::vector<std::string>>(
            option.flag,
            usage_checked<std::vector<std::string>>([&given, &option](const auto& values) {
              given[option.key] = parse_each(option, values);
            }),
            option.help);
        break;
      case OptionForm::Off:
      case OptionForm::On:
        app.add_flag_function(
            option.flag,
            [&given, key, on = option.form == OptionForm::On](std::int64_t) { given[key] = on; },
            option.help);
        continue;
      case OptionForm::Parsed:
        added = app.add_option_function<std::string>(
            option.flag, usage_checked<std::string>([&given, &option](const std::string& text) {
              given.update(option.parse(text));
            }),
            option.help);
        break;
      case OptionForm::None:
        continue;
    }
    added->default_str(default_text(option_value(option, defaults)));
  }
}

// Options a rig other than the flowscape one cannot use: a usage error, not silently ignored.
void refuse_rig_options(const nlohmann::json& given, const std::string& rig) {
  if (rig == kFlowscapeRig) return;
  if (given.contains("face_size") || given.contains("cube"))
    throw std::invalid_argument(
        std::string(given.contains("face_size") ? "--face-size" : "--no-cube") +
        ": only the flowscape rig has cube faces (the rig is \"" + rig + "\")");
  const bool file = rig.ends_with(".json") || is_calibration_file(rig);
  if (file && given.contains("resolution"))
    throw std::invalid_argument("--resolution: " + rig +
                                " sets its cameras' image sizes (--scale scales them)");
}

// What the command line gives besides the release's options.
struct RunOptions {
  ConfigSources sources;
  std::string out = "dataset", config_file, shard;
  std::vector<std::string> scenarios;
  int threads = 0;
  bool check = false, force = false, markdown = false;
  CLI::Option* out_option = nullptr;
};

void add_run_options(CLI::App& app, RunOptions& run) {
  nlohmann::json& given = run.sources.command_line;
  run.out_option = app.add_option("-o,--out", run.out, "release folder");
  app.add_option("--config", run.config_file,
                 "JSON with any of the options below; options given here win over the file, and "
                 "the file over --demo");
  add_release_options(app, given);
  auto* rig_from = app.add_option_function<std::string>(
      "--rig-from", [&given](const std::string& file) { given["rig"] = file; },
      "a calibration as the rig: OpenCV's (cv::FileStorage .yaml/.xml) or Kalibr's camchain "
      "(.yaml); its first camera placed by --rig-mount (docs/cameras.md)");
  rig_from->excludes(app.get_option("--rig"));
  app.add_option("--scenario", run.scenarios,
                 "scenario files (.json, docs/scenarios.md), one sequence each, instead of the "
                 "maps' sequences; options given here override their rig, ego and frames");
  app.add_option("--shard", run.shard, "K/N: make only the sequences k with k % N == K");
  app.add_option("--threads", run.threads, "threads (0: all cores)")->check(CLI::Range(0, 1024));
  app.add_flag("--demo", run.sources.demo,
               "a small release in demo/ (1 map, 2 sequences of 4 frames, 128 x 256, 8 spp, sunny "
               "and rain) unless options say otherwise");
  app.add_flag("--force", run.force,
               "the folder holds a release made with another config: delete its files "
               "(sequences/, manifests, card, config.json, manifest.json) and start over");
  app.add_flag("--check", run.check,
               "only check the options and print the plan, and report what the --out folder holds "
               "that the release should not (temporary files, foreign files, files missing or "
               "changed since manifest.json); write nothing");
  app.add_flag("--options-markdown", run.markdown,
               "print docs/options.md (every option's key, flag, default, values and help)");
}

// Usage errors only the resolved config shows: options the rig cannot use, maps with scenarios.
void refuse_option_mix(const RunOptions& run, const ReleaseConfig& c) {
  const nlohmann::json& given = run.sources.command_line;
  refuse_rig_options(given, c.rig);
  if (!run.scenarios.empty() &&
      (given.contains("maps") || given.contains("map_list") || given.contains("sequences_per_map")))
    throw std::invalid_argument(
        std::string(given.contains("sequences_per_map") ? "--sequences-per-map" : "--maps") +
        ": the scenarios say which sequences the release holds");
}

// Every user file the config names read before anything is written; their warnings printed.
void check_inputs(const ReleaseConfig& c, bool scenarios) {
  if (scenarios)
    for (const SequencePlan& plan : plan_sequences(c)) {
      const std::string file = plan.scenario_file.string();
      if (const std::string warning = version_warning(read_scenario(file)); !warning.empty())
        std::fprintf(diagnostics(), "gen_flowscape: %s: %s\n", file.c_str(), warning.c_str());
      sequence_spec(c, plan);
    }
  if (is_calibration_file(c.rig))  // a wide-angle calibration that sees only part of its image
    for (const std::string& warning : calibration_warnings(release_rig(c)))
      std::fprintf(diagnostics(), "gen_flowscape: %s: warning: %s\n", c.rig.c_str(),
                   warning.c_str());
}

// --check: the plan, and what the folder holds that the release should not.
int check_release(const ReleaseConfig& c, const std::string& out) {
  check_user_files(c);
  std::printf("%zu sequences of %d frames; shard %d/%d makes %zu of them\n",
              plan_sequences(c).size(), c.frames, c.shard, c.shards, shard_plans(c).size());
  const std::vector<ReleaseProblem> problems = release_problems(out, c);
  for (const ReleaseProblem& p : problems)
    std::fprintf(diagnostics(), "gen_flowscape: %s: %s\n", p.path.c_str(), p.problem.c_str());
  if (problems.empty()) return 0;
  std::fprintf(diagnostics(), "gen_flowscape: error: %s: %zu file(s) not as the release has them\n",
               out.c_str(), problems.size());
  return 1;
}

int make_release(const ReleaseConfig& c, const std::string& out, bool force) {
  const ReleaseWritten written = write_release(c, out, force);
  std::printf("%s: %zu sequences, %zu frames, %zu files\n", written.manifest.c_str(),
              written.sequences, written.frames, written.files);
  if (c.shards == 1)
    std::fputs(statistics_summary(read_json(written.manifest).value("statistics", nlohmann::json()))
                   .c_str(),
               stdout);
  return 0;
}

int run_release(RunOptions& run) {
  embree_config();  // a bad FLOWSCAPE_EMBREE_CONFIG fails before anything is written
  run.sources.file = run.config_file;
  run.sources.scenarios.assign(run.scenarios.begin(), run.scenarios.end());
  ReleaseConfig c = resolve_config(run.sources);
  try {
    refuse_option_mix(run, c);
  } catch (const std::invalid_argument& e) {
    std::fprintf(diagnostics(), "gen_flowscape: error: %s (see --help)\n", e.what());
    return kUsageError;
  }
  check_inputs(c, !run.scenarios.empty());
  if (!run.shard.empty()) parse_shard(run.shard, c);
  if (run.sources.demo && !run.out_option->count()) run.out = kDemoOut;
  tbb::global_control limit(
      tbb::global_control::max_allowed_parallelism,
      run.threads > 0 ? run.threads : tbb::this_task_arena::max_concurrency());
  return run.check ? check_release(c, run.out) : make_release(c, run.out, run.force);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Render a FlowScape release: ERP and cube-face colour, 360-degree flow, semantics, "
      "instances, depth and validity for every frame of every sequence, with a manifest. "
      "Rerun the same command to resume an interrupted run."};
  RunOptions run;
  add_run_options(app, run);
  finish_options(app, "gen_flowscape");
  version_with_kernels(app, "gen_flowscape");
  if (const auto status = parse_options(app, argc, argv)) return *status;
  if (run.markdown) return std::fputs(options_markdown().c_str(), stdout) < 0;
  try {
    return run_release(run);
  } catch (const std::exception& e) {
    std::fprintf(diagnostics(), "gen_flowscape: error: %s\n", e.what());
    return 1;
  }
}
