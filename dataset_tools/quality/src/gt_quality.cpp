#include "flowscape/quality/gt_quality.h"

#include <tbb/parallel_for.h>

#include <cstdio>
#include <map>
#include <sstream>

#include "flowscape/core/progress.h"
#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/quality/photoconsistency.h"

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

PairErrors evaluate_pair(const PairFiles& pair, const QualityOptions& options) {
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
  if (options.error_images.empty()) return photo_errors(images);
  Image<float> error;
  const PairErrors errors = photo_errors(images, &error);
  Image<std::uint8_t> png(error.width, error.height, 1);
  for (std::size_t i = 0; i < png.pixel_count(); ++i)
    png.data[i] = std::uint8_t(std::min(255.0f, error.data[i] + 0.5f));
  write_image(options.error_images /
                  (pair.category + "_" + pair.group + "_" + pair.flow.stem().string() + ".png"),
              png);
  return errors;
}

void add(QualityRow& row, const PairErrors& e, bool has_visible) {
  ++row.pairs, row.pe += e.pe, row.wpe += e.wpe;
  if (has_visible) ++row.visible_pairs, row.wpe_visible += e.wpe_visible;
}

void finish(QualityRow& row) {
  if (row.pairs) row.pe /= row.pairs, row.wpe /= row.pairs;
  if (row.visible_pairs) row.wpe_visible /= row.visible_pairs;
  row.diff = diff_percent(row.pe, row.wpe);
}

}  // namespace

QualityReport evaluate_quality(const FlowDataset& dataset, const QualityOptions& options) {
  if (!options.error_images.empty()) fs::create_directories(options.error_images);
  std::vector<PairErrors> errors(dataset.pairs.size());
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

std::string report_table(const QualityReport& report) {
  std::ostringstream out;
  char line[256];
  std::snprintf(line, sizeof line, "%-36s %6s %8s %8s %8s  %-10s %10s\n", report.layout.c_str(),
                "pairs", "PE", "WPE", "Diff", "quality", "WPE (noc)");
  out << line;
  for (const QualityRow& r : report.rows) {
    char visible[32] = "-";
    if (r.visible_pairs) std::snprintf(visible, sizeof visible, "%.2f", r.wpe_visible);
    std::snprintf(line, sizeof line, "%-36s %6d %8.2f %8.2f %7.1f%%  %-10s %10s\n", r.name.c_str(),
                  r.pairs, r.pe, r.wpe, r.diff, quality_label(r.diff), visible);
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
    if (r.visible_pairs) row["wpe_noc"] = r.wpe_visible;
    rows.push_back(row);
  }
  return {{"layout", report.layout}, {"rows", rows}};
}

std::string report_csv(const QualityReport& report) {
  std::ostringstream out;
  out << "name,pairs,pe,wpe,diff_percent,quality,wpe_noc\n";
  for (const QualityRow& r : report.rows) {
    out << r.name << "," << r.pairs << "," << r.pe << "," << r.wpe << "," << r.diff << ","
        << quality_label(r.diff) << ",";
    if (r.visible_pairs) out << r.wpe_visible;
    out << "\n";
  }
  return out.str();
}

}  // namespace flowscape
