#pragma once
// gt_quality's evaluation: photoconsistency of every pair of a flow dataset, summed up like the
// PanoFlow paper's Table II, overall, per category (weather, Sintel pass, KITTI images) and per
// group (sequence, scene).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flowscape/quality/flow_datasets.h"

namespace flowscape {

struct QualityRow {
  std::string name;  // "all", "weather=fog", "sequence=map00_seq06", ...
  int pairs = 0;
  double pe = 0, wpe = 0, diff = 0;  // means over the pairs; diff in %
  int visible_pairs = 0;
  double wpe_visible = 0;  // over non-occluded pixels, where the dataset gives masks
};

struct QualityReport {
  std::string layout;
  std::vector<QualityRow> rows;
};

struct QualityOptions {
  std::filesystem::path error_images;  // non-empty: a PNG of |I2(x + V) - I1| per pair here
  bool progress = true;
};

QualityReport evaluate_quality(const FlowDataset& dataset, const QualityOptions& options = {});

std::string report_table(const QualityReport& report);
nlohmann::json report_json(const QualityReport& report);
std::string report_csv(const QualityReport& report);

}  // namespace flowscape
