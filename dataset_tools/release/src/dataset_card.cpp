#include "flowscape/release/dataset_card.h"

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "flowscape/core/files.h"
#include "flowscape/formats/contact_sheet.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/layout/classes.h"
#include "flowscape/layout/layout.h"
#include "flowscape/layout/preview.h"
#include "flowscape/release/adaptive_sampling.h"
#include "flowscape/release/manifest.h"
#include "flowscape/release/scenario.h"
#include "flowscape/release/sequence.h"
#include "flowscape/release/statistics.h"
#include "flowscape/renderer/denoiser.h"
#include "flowscape/scenes/city.h"
#include "flowscape/scenes/model_io.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

constexpr const char* kCardFile = "README.md";
constexpr const char* kStatisticsFigure = "statistics.svg";

void counts_section(std::ostringstream& md, const ReleaseConfig& c) {
  std::map<std::string, int> per_weather, per_time, per_sky;
  std::map<int, int> per_map;
  const std::vector<SequencePlan> plans = plan_sequences(c);
  for (const SequencePlan& p : plans)
    ++per_weather[p.weather], ++per_time[p.time_of_day], ++per_sky[p.sky], ++per_map[p.map];
  md << "## Counts\n\n| map | sequences | frames | flow pairs |\n| --- | --- | --- | --- |\n";
  for (const auto& [map, n] : per_map)
    md << "| " << map << " " << map_name(map) << " | " << n << " | " << n * c.frames << " | "
       << n * (c.frames - 1) << " |\n";
  md << "| all | " << plans.size() << " | " << plans.size() * c.frames << " | "
     << plans.size() * (c.frames - 1)
     << " |\n\n| weather | sequences | share |\n| --- | --- | --- |\n";
  for (const auto& [weather, n] : per_weather)
    md << "| " << weather << " | " << n << " | " << 100.0 * n / plans.size() << " % |\n";
  md << "\n| time of day | sequences | share |\n| --- | --- | --- |\n";
  for (const auto& [time, n] : per_time)
    md << "| " << time << " | " << n << " | " << 100.0 * n / plans.size() << " % |\n";
  md << "\n| sky | sequences | share |\n| --- | --- | --- |\n";
  for (const auto& [sky, n] : per_sky)
    md << "| " << sky << " | " << n << " | " << 100.0 * n / plans.size() << " % |\n";
  md << "\nDawn and dusk put the sun between 5 degrees below the horizon and 6 above, night 18-40 "
        "below with the moon up or not and the lamps on; every "
        "sequence has one exposure, recorded in its meta.json (`exposure`). A sky map (CC0 Poly "
        "Haven "
        "panoramas from the npm package @pmndrs/assets 1.7.0) shows above its recorded horizon "
        "line and its sun sets the time of day; a sequence whose meta.json `weather` has no "
        "`sky_map` shows the physical sky.\n";
}

// Mean bytes per frame of each kind of the release (all views), from its files on disk.
std::map<std::string, double> bytes_per_frame(const fs::path& out, const ReleaseConfig& c) {
  const ReleaseLayout layout = release_layout(c);
  const std::vector<SequencePlan> plans = plan_sequences(c);
  std::map<std::string, double> bytes;
  for (const SequencePlan& plan : plans)
    for (int f = 0; f < c.frames; ++f)
      for (const fs::path& file : layout.frame_files(f, c.frames)) {
        const fs::path path = sequence_dir(out, plan.name) / file;
        if (fs::exists(path)) bytes[file.parent_path().filename().string()] += fs::file_size(path);
      }
  for (auto& [kind, sum] : bytes) sum /= double(plans.size()) * c.frames;
  return bytes;
}

std::string with_unit(double bytes) {
  std::ostringstream text;
  text.precision(3);
  if (bytes >= 1 << 20)
    text << bytes / (1 << 20) << " MiB";
  else
    text << bytes / 1024 << " KiB";
  return text.str();
}

std::string rates_text(const std::vector<double>& rates) {
  std::ostringstream text;
  for (std::size_t k = 0; k < rates.size(); ++k) text << (k ? ", " : "") << rates[k];
  return text.str() + (rates.size() > 1 ? " (per sequence: meta.json fps)" : "");
}

void sizes_section(std::ostringstream& md, const ReleaseConfig& c, const fs::path& out) {
  md << "\n## Sizes\n\n- ERP: " << c.height << " x " << 2 * c.height << " (H x W), " << c.frames
     << " frames at " << rates_text(release_frame_rates(c)) << " Hz\n";
  if (c.cube)
    md << "- cube: six 90-degree faces (front right back left up down), " << c.face_size << " x "
       << c.face_size << ", focal " << c.face_size / 2.0
       << " px; the ERP colour is stitched from them\n";
  md << "- colour path traced with " << c.spp << " samples per pixel ("
     << indirect_samples(color_section(c)) << " of them gathering indirect light"
     << (sample_split(c.spp, c.adaptive).half > 0
             ? "; on average, adaptively: half everywhere, the other half on the " +
                   std::to_string(int(std::lround(100 * c.adaptive))) +
                   " % of the pixels where the denoised halves disagree most"
             : std::string())
     << (c.temporal > 0
             ? "; each frame's samples averaged with those of the " + std::to_string(c.temporal) +
                   (c.temporal == 1 ? " frame" : " frames") +
                   " before and after it along the exact flow where their shading agrees "
                   "(temporal reconstruction)"
             : std::string())
     << "), " << release_denoiser(color_section(c))->description()
     << "\n\n## Output kinds\n\nEach kind is a folder of every view (the ERP"
     << (c.cube ? " and each face" : "")
     << "); bytes per frame are the mean over the release, all views together. The six kinds "
        "every release has come first; `--outputs` picks more (this release: "
     << (c.outputs.empty() ? std::string("none") : nlohmann::json(c.outputs).dump())
     << ", flow gaps " << nlohmann::json(c.flow_gaps).dump()
     << "; gen_flowscape's default: " << nlohmann::json(ReleaseConfig{}.outputs).dump()
     << ", chosen by their cost in bench_render).\n\n"
        "| kind | frames | bytes per frame | what it holds |\n| --- | --- | --- | --- |\n";
  const std::map<std::string, double> bytes = bytes_per_frame(out, c);
  double total = 0;
  for (const ReleaseKind& kind : release_layout(c).kinds) {
    const double size = bytes.count(kind.folder()) ? bytes.at(kind.folder()) : 0;
    total += size;
    const int step = kind.step();
    md << "| " << kind.name() << " | "
       << (step > 0   ? "all but the last " + std::to_string(step)
           : step < 0 ? "all but the first " + std::to_string(-step)
                      : std::string("all"))
       << " | " << with_unit(size) << " | " << kind.row->description
       << (kind.gap > 1 ? " (gap " + std::to_string(kind.gap) + ")" : "") << " |\n";
  }
  md << "| all | | " << with_unit(total) << " | |\n";
}

std::string percent(double share) {
  std::ostringstream text;
  text.precision(3);
  text << 100 * share << " %";
  return text.str();
}

void statistics_row(std::ostringstream& md, const std::string& name, const nlohmann::json& g) {
  const nlohmann::json& flow = g.at("flow").at("percentiles");
  std::ostringstream row;
  row.precision(3);
  row << "| " << name << " | " << g.at("sequences") << " | " << percent(g.at("turn_share")) << " | "
      << g.at("ego_speed").at("mean").get<double>() << " | "
      << g.at("yaw_rate_abs").value("p90", 0.0) << " | " << flow.at("p50").get<double>() << " | "
      << flow.at("p90").get<double>() << " | " << flow.at("p99").get<double>() << " | "
      << percent(g.at("actor_share")) << " | " << percent(g.at("valid_share")) << " |\n";
  md << row.str();
}

// The release's statistics (statistics.h), from its sequences' meta.json.
void statistics_section(std::ostringstream& md, const nlohmann::json& statistics) {
  md << "\n## Statistics\n\n";
  if (statistics.is_null()) {
    md << "No sequence recorded statistics.\n";
    return;
  }
  md << "Of the " << statistics.at("view").get<std::string>() << " view of every frame, as `"
     << kManifestFile
     << "` states them (`statistics`). Flow in pixels of a 1024-wide image, every pixel whose "
        "flow is known (percentiles from eighth-octave histograms); a sequence turns when its "
        "heading changes by "
     << statistics.at("turn_degrees")
     << " degrees or more; speed and yaw rate of the rig "
        "between frames.\n\n![statistics]("
     << kCardDir << "/" << kStatisticsFigure
     << ")\n\n| group | sequences | turning | ego speed m/s (mean) | yaw rate deg/s (p90) | "
        "flow p50 | flow p90 | flow p99 | actor pixels | valid pixels |\n| --- | --- | --- | --- "
        "| --- | --- | --- | --- | --- | --- |\n";
  for (const auto& [kind, label] : {std::pair{"maps", "map "}, {"weathers", "weather "}})
    for (const auto& [name, group] : statistics.at(kind).items())
      statistics_row(md, label + name, group);
  statistics_row(md, "all", statistics.at("all"));
}

void conventions_section(std::ostringstream& md, const ReleaseConfig& c) {
  md << "\n## Conventions\n\nAs `" << kManifestFile
     << "` states them for programs (`conventions`); each kind's `step` in its `layout` says which "
        "frame a flow goes to.\n\n```json\n"
     << conventions_json(c.classes, release_frame_rates(c), flow_format_from_name(c.flow_format))
            .dump(1)
     << "\n```\n";
}

void classes_section(std::ostringstream& md, const ReleaseConfig& c) {
  const ClassTable& table = class_table(c.classes);
  md << "\n## Classes (" << table.name << ")\n\n| id | class | colour |\n| --- | --- | --- |\n";
  for (int id = 0; id < table.size(); ++id) {
    const auto& rgb = table.colours[std::size_t(id)];
    md << "| " << id << " | " << table.names[std::size_t(id)] << " | " << int(rgb[0]) << ","
       << int(rgb[1]) << "," << int(rgb[2]) << " |\n";
  }
}

void layout_section(std::ostringstream& md, const ReleaseConfig& c) {
  std::string erp, cube;
  for (const ReleaseKind& kind : release_layout(c).kinds) {
    if (kind.row->erp) erp.append(erp.empty() ? "" : ",").append(kind.folder());
    if (kind.row->cube) cube.append(cube.empty() ? "" : ",").append(kind.folder());
  }
  const fs::path sequence = sequence_dir("", "<map>_<seq>");
  md << "\n## ReleaseLayout\n\n```\n"
     << (sequence / kMetaFile).generic_string()
     << "      map, weather, seed, poses, calibration, actors, 2-D boxes\n"
     << (sequence / view_dir(std::nullopt)).generic_string() << "/{" << erp << "}/<frame>\n";
  if (c.cube) md << (sequence / kCubeDir).generic_string() << "/<face>/{" << cube << "}/<frame>\n";
  md << "splits/, panoflow/                    written by flowscape_split\n```\n";
}

// CC BY 4.0, unless asset packs bring models under other terms: each listed with its licence and
// copyright; images that show them carry those terms (meta.json names each actor's model).
std::string licence_text(const ReleaseConfig& c) {
  if (c.asset_packs.empty()) return "The generated data: CC BY 4.0.\n";
  std::ostringstream md;
  md << "The generated data: CC BY 4.0, except where it shows a model of an asset pack: an image "
        "showing one (meta.json's `actors` name each actor's `model` and `licence`, and "
        "`instance` finds its pixels) is also under that model's licence, which travels with "
        "it (GPL-2+: the images are its derived works under GPL-2+; Free Art License 1.3: "
        "share-alike).\n\n| model | licence | copyright | file |\n| --- | --- | --- | --- |\n";
  for (const std::string& pack : c.asset_packs)
    for (const PackModel& m : asset_pack(pack))
      md << "| " << model_id(m) << " | " << m.licence << " | " << m.copyright << " | `" << m.path
         << "` |\n";
  return md.str();
}

std::string card_text(const ReleaseConfig& c, const fs::path& out,
                      const std::vector<std::string>& examples, const nlohmann::json& statistics) {
  std::ostringstream md;
  md << "# FlowScape release\n\nSynthetic panoramic optical flow in procedural city maps, made by `"
     << kGeneratorVersion << "` (the FlowScape toolkit), after the FlowScape dataset of the "
     << "PanoFlow paper. Every file is listed with its sha256 in `" << kManifestFile << "`.\n\n";
  counts_section(md, c);
  sizes_section(md, c, out);
  statistics_section(md, statistics);
  conventions_section(md, c);
  classes_section(md, c);
  layout_section(md, c);
  md << "\n## Examples\n\n";
  for (const std::string& weather : examples)
    md << "![" << weather << "](" << kCardDir << "/" << weather << ".png)\n\n";
  md << "## Reproduce\n\n```\ngen_flowscape --config config.json --out <dir>\n```\nwith "
        "config.json =\n"
     << "```json\n"
     << to_json(c).dump(1) << "\n```\n\n## Licence\n\n"
     << licence_text(c);
  return md.str();
}

}  // namespace

namespace {

// The weathers of the release, each once, in the order of the first sequence that has it.
std::vector<SequencePlan> first_of_each_weather(const ReleaseConfig& config) {
  std::vector<SequencePlan> firsts;
  std::set<std::string> seen;
  for (const SequencePlan& plan : plan_sequences(config))
    if (seen.insert(plan.weather).second) firsts.push_back(plan);
  return firsts;
}

fs::path example_file(const std::string& weather) {
  return fs::path(kCardDir) / (weather + ".png");
}

}  // namespace

void write_dataset_card(const fs::path& out, const ReleaseConfig& config,
                        const nlohmann::json& statistics) {
  remove_temporary_files(out / kCardDir);
  std::vector<std::string> examples;
  const ReleaseLayout layout = release_layout(config);
  for (const SequencePlan& plan : first_of_each_weather(config)) {
    std::vector<std::vector<Image<std::uint8_t>>> rows;  // the ERP, or each camera of the rig
    for (const View& view : layout.views())
      if (!view.face)
        rows.push_back(frame_preview_row(sequence_dir(out, plan.name), 0, 512, view, config.classes,
                                         layout.flow_format));
    write_image(out / example_file(plan.weather), contact_sheet(rows));
    examples.push_back(plan.weather);
  }
  write_text(out / kCardDir / kStatisticsFigure, statistics_svg(statistics));
  write_text(out / kCardFile, card_text(config, out, examples, statistics));
}

std::vector<fs::path> dataset_card_files(const ReleaseConfig& config) {
  std::vector<fs::path> files{kCardFile, fs::path(kCardDir) / kStatisticsFigure};
  for (const SequencePlan& plan : first_of_each_weather(config))
    files.push_back(example_file(plan.weather));
  std::sort(files.begin(), files.end());
  return files;
}

void remove_dataset_card(const fs::path& out) {
  fs::remove(out / kCardFile);
  fs::remove_all(out / kCardDir);
}

}  // namespace flowscape
