// The dataset card of a release: README.md with counts, sizes, classes, layout and licence, and an
// example frame per weather under card/.
#include <map>
#include <set>
#include <sstream>

#include "flowscape/city.h"
#include "flowscape/contact_sheet.h"
#include "flowscape/flow_io.h"
#include "flowscape/flow_viz.h"
#include "flowscape/io.h"
#include "flowscape/model_io.h"
#include "flowscape/release.h"
#include "flowscape/semantic_viz.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

std::string card_text(const ReleaseConfig& c, const std::vector<std::string>& examples) {
  std::map<std::string, int> per_weather;
  std::map<int, int> per_map;
  const std::vector<SequencePlan> plans = plan_sequences(c);
  for (const SequencePlan& p : plans) ++per_weather[p.weather], ++per_map[p.map];
  std::ostringstream md;
  md << "# FlowScape release\n\nSynthetic panoramic optical flow in procedural city maps, made by `"
     << kGeneratorVersion << "` (the FlowScape toolkit), after the FlowScape dataset of the "
     << "PanoFlow paper. Every file is listed with its sha256 in `manifest.json`.\n\n"
     << "## Counts\n\n| map | sequences | frames | flow pairs |\n| --- | --- | --- | --- |\n";
  for (const auto& [map, n] : per_map)
    md << "| " << map << " " << map_name(map) << " | " << n << " | " << n * c.frames << " | "
       << n * (c.frames - 1) << " |\n";
  md << "| all | " << plans.size() << " | " << plans.size() * c.frames << " | "
     << plans.size() * (c.frames - 1)
     << " |\n\n| weather | sequences | share |\n| --- | --- | --- |\n";
  for (const auto& [weather, n] : per_weather)
    md << "| " << weather << " | " << n << " | " << 100.0 * n / plans.size() << " % |\n";
  md << "\n## Sizes\n\n- ERP: " << c.height << " x " << 2 * c.height
     << " (H x W), 360-degree forward flow in pixels (`.flo`), " << c.frames
     << " frames at 30 Hz\n";
  if (c.cube)
    md << "- cube: six 90-degree faces (front right back left up down), " << c.face_size << " x "
       << c.face_size << ", focal " << c.face_size / 2.0
       << " px; the ERP colour is stitched from them\n";
  md << "- colour: path traced, " << c.spp << " samples per pixel, 8-bit sRGB PNG\n"
     << "- semantic: 8-bit class ids; instance: 16-bit ids (0 = static world and sky); depth: "
        "float "
        "EXR, metres along the ray (+inf for the sky); valid: 8-bit, 1 where the flow target is "
        "visible in the next frame\n\n## Classes (CARLA 0.9.10-0.9.13)\n\n| id | class | colour |\n"
        "| --- | --- | --- |\n";
  for (int id = 0; id <= 22; ++id) {
    const auto rgb = semantic_color(std::uint8_t(id));
    md << "| " << id << " | " << class_name(SemanticClass(id)) << " | " << int(rgb[0]) << ","
       << int(rgb[1]) << "," << int(rgb[2]) << " |\n";
  }
  md << "\n## Layout\n\n```\nsequences/<map>_<seq>/meta.json      map, weather, seed, poses, "
        "actors\n"
        "sequences/<map>_<seq>/erp/{color,flow,semantic,instance,depth,valid}/<frame>\n"
        "sequences/<map>_<seq>/cube/<face>/{color,flow,semantic,instance,depth,valid}/<frame>\n"
        "splits/, panoflow/                    written by flowscape_split\n```\n\n## Examples\n\n";
  for (const std::string& weather : examples)
    md << "![" << weather << "](card/" << weather << ".png)\n\n";
  md << "## Reproduce\n\n```\ngen_flowscape --config config.json --out <dir>\n```\nwith "
        "config.json =\n"
     << "```json\n"
     << to_json(c).dump(1) << "\n```\n\n## Licence\n\nThe generated data: CC BY 4.0.\n";
  return md.str();
}

}  // namespace

void write_dataset_card(const fs::path& out, const ReleaseConfig& config) {
  std::vector<std::string> examples;
  std::set<std::string> seen;
  for (const SequencePlan& plan : plan_sequences(config)) {
    if (!seen.insert(plan.weather).second) continue;
    write_image(out / "card" / (plan.weather + ".png"),
                contact_sheet({frame_preview_row(sequence_dir(out, plan), 0, 512)}));
    examples.push_back(plan.weather);
  }
  write_text(out / "README.md", card_text(config, examples));
}

}  // namespace flowscape
