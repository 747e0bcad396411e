#include "flowscape/quality/gt_quality.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>

#include "flowscape/core/progress.h"
#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/quality/photoconsistency.h"
#include "flowscape/quality/round_trip.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

// 8-bit intensities (16-bit images rounded to 8 bits; alpha dropped).
Image<std::uint8_t> intensities(const fs::path& path) {
  AnyImage any = read_any_image(path);
  if (auto* image = std::get_if<Image<std::uint8_t>>(&any);
      image && (image->channels == 1 || image->channels == 3))
    return std::move(*image);
  if (std::holds_alternative<Image<float>>(any))
    throw FileError(path, "float images have no 0-255 intensities; use 8- or 16-bit images");
  return std::visit(
      [&](const auto& image) {
        const int channels = image.channels >= 3 ? 3 : 1;  // grey + alpha counts as grey
        const bool wide = sizeof(image.data[0]) == 2;
        Image<std::uint8_t> out(image.width, image.height, channels);
        for (std::size_t i = 0; i < image.pixel_count(); ++i)
          for (int c = 0; c < channels; ++c) {
            const unsigned v = unsigned(image.data[i * image.channels + c]);
            out.data[i * channels + c] = std::uint8_t(wide ? (v + 128) / 257 : v);
          }
        return out;
      },
      any);
}

Image<std::uint8_t> visible_mask(const PairFiles& pair) {
  switch (pair.visible_kind) {
    case VisibleMask::None:
      return {};
    case VisibleMask::FlowValid:
      return read_flow(pair.visible).valid;
    case VisibleMask::NonZero:
    case VisibleMask::Zero: {
      Image<std::uint8_t> mask = read_image<std::uint8_t>(pair.visible);
      Image<std::uint8_t> out(mask.width, mask.height, 1);
      for (std::size_t i = 0; i < out.pixel_count(); ++i)
        out.data[i] =
            (mask.data[i * mask.channels] != 0) == (pair.visible_kind == VisibleMask::NonZero);
      return out;
    }
  }
  return {};
}

struct PairResult {
  PairErrors errors;
  std::optional<RoundTrip> trip;
};

// The pair's forward flow against its second frame's backward flow (round_trip.h).
RoundTrip check_round_trip(const PairFiles& pair, const Flow& forward,
                           const Image<std::uint8_t>& visible) {
  const Flow backward = read_flow(pair.backward);
  const Image<std::uint8_t> back_visible = read_image<std::uint8_t>(pair.backward_visible);
  if (backward.uv.width != forward.uv.width || backward.uv.height != forward.uv.height)
    throw FileError(pair.backward, "backward flow's size differs from the forward flow's");
  if (back_visible.width != forward.uv.width || back_visible.height != forward.uv.height)
    throw FileError(pair.backward_visible, "mask size differs from the flow's");
  return round_trip(
      {forward.uv.view(), visible.view(), backward.uv.view(), back_visible.view(), pair.panorama});
}

PairResult evaluate_pair(const PairFiles& pair, const QualityOptions& options) {
  const Image<std::uint8_t> image1 = intensities(pair.image1), image2 = intensities(pair.image2);
  const Flow flow = read_flow(pair.flow);
  const Image<std::uint8_t> visible = visible_mask(pair);
  if (flow.uv.width != image1.width || flow.uv.height != image1.height)
    throw FileError(pair.flow, "flow is " + std::to_string(flow.uv.width) + "x" +
                                   std::to_string(flow.uv.height) + " but the image is " +
                                   std::to_string(image1.width) + "x" +
                                   std::to_string(image1.height));
  if (image2.width != image1.width || image2.height != image1.height ||
      image2.channels != image1.channels)
    throw FileError(pair.image2, "differs in size or channels from " + pair.image1.string());
  if (!visible.data.empty() && (visible.width != image1.width || visible.height != image1.height))
    throw FileError(pair.visible, "mask size differs from the images'");
  PairImages images{image1.view(),     image2.view(),  flow.uv.view(),
                    flow.valid.view(), visible.view(), pair.panorama};
  PairResult result;
  if (!pair.backward.empty()) result.trip = check_round_trip(pair, flow, visible);
  if (options.error_images.empty()) {
    result.errors = photo_errors(images);
    return result;
  }
  Image<float> error;
  result.errors = photo_errors(images, &error);
  Image<std::uint8_t> png(error.width, error.height, 1);
  for (std::size_t i = 0; i < png.pixel_count(); ++i)
    png.data[i] = std::uint8_t(std::min(255.0f, error.data[i] + 0.5f));
  write_image(options.error_images /
                  (pair.category + "_" + pair.group + "_" + pair.flow.stem().string() + ".png"),
              png);
  return result;
}

void add(QualityRow& row, const PairResult& r, bool has_visible) {
  const PairErrors& e = r.errors;
  ++row.pairs, row.pe += e.pe, row.wpe += e.wpe;
  if (has_visible)
    ++row.visible_pairs, row.wpe_visible += e.wpe_visible, row.wpe_occluded += e.wpe_occluded;
  if (r.trip)
    ++row.round_trip_pairs, row.both_ways += r.trip->both_ways, row.returned += r.trip->returned;
}

void finish(QualityRow& row) {
  if (row.pairs) row.pe /= row.pairs, row.wpe /= row.pairs;
  if (row.visible_pairs)
    row.wpe_visible /= row.visible_pairs, row.wpe_occluded /= row.visible_pairs;
  row.diff = diff_percent(row.pe, row.wpe);
}

}  // namespace

QualityReport evaluate_quality(const FlowDataset& dataset, const QualityOptions& options) {
  if (!options.error_images.empty()) fs::create_directories(options.error_images);
  std::vector<PairResult> errors(dataset.pairs.size());
  std::unique_ptr<Progress> progress;
  if (options.progress) progress = std::make_unique<Progress>("gt_quality", errors.size(), "pairs");
  tbb::parallel_for(std::size_t(0), errors.size(), [&](std::size_t k) {
    errors[k] = evaluate_pair(dataset.pairs[k], options);
    if (progress) progress->advance();
  });
  if (progress) progress->finish();
  QualityRow all{"all"};
  std::map<std::string, QualityRow> categories, groups;
  const std::string category_key = dataset.layout == "flowscape" || dataset.layout == "panoflow"
                                       ? "weather"
                                   : dataset.layout == "sintel" ? "pass"
                                                                : "images";
  for (std::size_t k = 0; k < errors.size(); ++k) {
    const PairFiles& pair = dataset.pairs[k];
    const bool has_visible = pair.visible_kind != VisibleMask::None;
    add(all, errors[k], has_visible);
    QualityRow& category = categories[pair.category];
    category.name = category_key + "=" + pair.category;
    add(category, errors[k], has_visible);
    const std::string group = pair.category + "/" + pair.group;
    groups[group].name = "sequence=" + group;
    add(groups[group], errors[k], has_visible);
  }
  QualityReport report{dataset.layout, {all}};
  if (categories.size() > 1)
    for (auto& [_, row] : categories) report.rows.push_back(row);
  if (groups.size() > 1)
    for (auto& [_, row] : groups) report.rows.push_back(row);
  for (QualityRow& row : report.rows) finish(row);
  return report;
}

namespace {

// "-" where a row has no such measure.
std::string measure(bool has, double value, const char* format) {
  if (!has) return "-";
  char text[32];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

}  // namespace

std::string report_table(const QualityReport& report) {
  std::ostringstream out;
  char line[512];
  int name_width = 36;  // the paper's rows fit; longer names (sequence/camera) widen the column
  for (const QualityRow& r : report.rows) name_width = std::max(name_width, int(r.name.size()));
  std::snprintf(line, sizeof line, "%-*s %6s %8s %8s %8s  %-10s %10s %10s %8s\n", name_width,
                report.layout.c_str(), "pairs", "PE", "WPE", "Diff", "quality", "WPE (noc)",
                "WPE (occ)", "FB ok");
  out << line;
  for (const QualityRow& r : report.rows) {
    const std::string noc = measure(r.visible_pairs, r.wpe_visible, "%.2f"),
                      occ = measure(r.visible_pairs, r.wpe_occluded, "%.2f"),
                      trip = measure(r.round_trip_pairs, 100 * r.round_trip_share(), "%.2f%%");
    std::snprintf(line, sizeof line, "%-*s %6d %8.2f %8.2f %7.1f%%  %-10s %10s %10s %8s\n",
                  name_width, r.name.substr(0, 256).c_str(), r.pairs, r.pe, r.wpe, r.diff,
                  quality_label(r.diff), noc.c_str(), occ.c_str(), trip.c_str());
    out << line;
  }
  return out.str();
}

nlohmann::json report_json(const QualityReport& report) {
  nlohmann::json rows = nlohmann::json::array();
  for (const QualityRow& r : report.rows) {
    nlohmann::json row = {
        {"name", r.name}, {"pairs", r.pairs},       {"pe", r.pe},
        {"wpe", r.wpe},   {"diff_percent", r.diff}, {"quality", quality_label(r.diff)}};
    if (r.visible_pairs) row["wpe_noc"] = r.wpe_visible, row["wpe_occ"] = r.wpe_occluded;
    if (r.round_trip_pairs)
      row["round_trip"] = {{"pairs", r.round_trip_pairs},
                           {"visible_both_ways", r.both_ways},
                           {"returned", r.returned},
                           {"share", r.round_trip_share()}};
    rows.push_back(row);
  }
  return {{"layout", report.layout}, {"rows", rows}};
}

std::string report_csv(const QualityReport& report) {
  std::ostringstream out;
  out << "name,pairs,pe,wpe,diff_percent,quality,wpe_noc,wpe_occ,round_trip_share\n";
  for (const QualityRow& r : report.rows) {
    out << r.name << "," << r.pairs << "," << r.pe << "," << r.wpe << "," << r.diff << ","
        << quality_label(r.diff) << ",";
    if (r.visible_pairs) out << r.wpe_visible;
    out << ",";
    if (r.visible_pairs) out << r.wpe_occluded;
    out << ",";
    if (r.round_trip_pairs) out << r.round_trip_share();
    out << "\n";
  }
  return out.str();
}

}  // namespace flowscape
