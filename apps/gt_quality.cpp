// gt_quality: how well a flow dataset's ground truth explains its images (PE / WPE, design.md),
// for FlowScape releases, the PanoFlow tree, MPI-Sintel, KITTI 2012/2015, FlyingChairs, or two
// globs.
#include "flowscape/quality/gt_quality.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli.h"
#include "flowscape/core/files.h"

using namespace flowscape;

int main(int argc, char** argv) {
  CLI::App app{
      "Photoconsistency of optical-flow ground truth: PE = mean |I1 - I2|, WPE = mean "
      "|I2(x + V) - I1| (bilinear), Diff = (PE - WPE) / PE; 'high' quality from 10 %. The "
      "layout is recognised from the folder."};
  std::string root, images, flows, json, csv, error_images, pass = "clean";
  bool panorama = false, quiet = false;
  int sample = 0;
  app.add_option("dataset", root,
                 "dataset folder (FlowScape, PanoFlow tree, Sintel, KITTI, FlyingChairs)");
  app.add_option("--images", images,
                 "generic layout: images, e.g. 'frames/*.png' (one more than flows)");
  app.add_option("--flows", flows, "generic layout: flow files, e.g. 'flow/*.flo'");
  app.add_flag("--panorama", panorama,
               "generic layout: ERP images, targets wrap around horizontally");
  app.add_option("--sample", sample,
                 "score only N pairs per weather (category), spread evenly over its pairs")
      ->check(CLI::Range(1, 1 << 30));
  app.add_option("--json", json, "also write the rows as JSON here");
  app.add_option("--csv", csv, "also write the rows as CSV here");
  app.add_option("--error-images", error_images, "write |I2(x + V) - I1| per pair as PNGs here");
  app.add_option("--pass", pass,
                 "a FlowScape release's images: clean (color) or final (the final pass)")
      ->capture_default_str();
  app.add_flag("-q,--quiet", quiet, "no progress line");
  finish_options(app, "gt_quality");
  if (const auto status = parse_options(app, argc, argv)) return *status;
  try {
    if (root.empty() == images.empty() || images.empty() != flows.empty())
      throw std::invalid_argument("give a dataset folder, or --images and --flows");
    FlowDataset dataset =
        root.empty() ? glob_flow_dataset(images, flows, panorama) : find_flow_dataset(root, pass);
    if (sample > 0) dataset = sample_pairs(dataset, sample);
    const QualityReport report = evaluate_quality(dataset, {error_images, !quiet});
    std::fputs(report_table(report).c_str(), stdout);
    if (!json.empty()) write_text(json, report_json(report).dump(1) + "\n");
    if (!csv.empty()) write_text(csv, report_csv(report));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(diagnostics(), "gt_quality: error: %s\n", e.what());
    return 1;
  }
}
