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
  // over non-occluded and over occluded pixels, where the dataset gives masks
  double wpe_visible = 0, wpe_occluded = 0;
  // the forward-backward check (round_trip.h), pooled over the pixels of the pairs that have
  // backward flow: the share of pixels visible both ways that return within 0.01 px
  int round_trip_pairs = 0;
  long both_ways = 0, returned = 0;
  double round_trip_share() const { return both_ways ? double(returned) / double(both_ways) : 0; }
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
