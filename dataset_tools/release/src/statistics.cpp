#include "flowscape/release/statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>

#include "flowscape/core/files.h"
#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/geometry/geometry.h"
#include "flowscape/layout/classes.h"
#include "flowscape/layout/meta.h"
#include "flowscape/scenes/model_io.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

constexpr double kReferenceWidth = 1024;  // flow magnitudes are given in pixels of this width
constexpr int kBinsPerOctave = 8, kFirstOctave = -4, kLastOctave = 10;
constexpr double kSpeedBin = 1, kYawRateBin = 2;  // m/s, degrees/s
constexpr int kSpeedBins = 30, kYawRateBins = 45;

// x[ceil(n * percent / 100) - 1] of the sorted values (nearest rank), in integers so that a
// check in any language picks the same element.
template <class T>
T nearest_rank(std::vector<T>& values, int percent) {
  const std::size_t n = values.size();
  const std::size_t rank = std::max<std::size_t>((n * std::size_t(percent) + 99) / 100, 1) - 1;
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(rank), values.end());
  return values[rank];
}

std::size_t flow_bin(double magnitude) {
  const std::vector<double>& edges = flow_bin_edges();
  return std::size_t(std::upper_bound(edges.begin(), edges.end(), magnitude) - edges.begin()) - 1;
}

std::string view_name(const View& view) { return view_dir(view).generic_string(); }

std::string percentile_key(int percent) {
  std::string key = "p";  // not "p" + std::to_string: GCC 12 warns (-Wrestrict, a false alarm)
  return key.append(std::to_string(percent));
}

}  // namespace

const std::vector<double>& flow_bin_edges() {
  static const std::vector<double> edges = [] {
    std::vector<double> e{0};
    for (int k = kFirstOctave * kBinsPerOctave; k <= kLastOctave * kBinsPerOctave; ++k)
      e.push_back(std::exp2(double(k) / kBinsPerOctave));
    return e;
  }();
  return edges;
}

FrameStatistics frame_statistics(ImageView<const float> flow, ImageView<const std::uint8_t> valid,
                                 ImageView<const std::uint8_t> semantic,
                                 ImageView<const std::uint16_t> instance) {
  FrameStatistics s;
  s.pixels = semantic.pixel_count();
  for (std::size_t i = 0; i < s.pixels; ++i) {
    ++s.class_pixels[std::min<std::size_t>(semantic.data[i], kSemanticClasses - 1)];
    s.actor_pixels += instance.data[i] > 0;
  }
  if (flow.pixel_count() == 0) return s;
  s.flow_histogram.assign(flow_bin_edges().size(), 0);
  const double scale = kReferenceWidth / flow.width;
  std::vector<float> magnitudes;
  magnitudes.reserve(flow.pixel_count());
  for (std::size_t i = 0; i < flow.pixel_count(); ++i) {
    s.valid_pixels += valid.data[i] > 0;
    const float u = flow.data[2 * i], v = flow.data[2 * i + 1];
    if (!is_known_flow(u, v)) continue;
    const double magnitude = std::hypot(double(u), double(v)) * scale;
    ++s.flow_histogram[flow_bin(magnitude)];
    s.flow_sum += magnitude;
    magnitudes.push_back(float(magnitude));
  }
  if (magnitudes.empty()) return s;
  s.flow_p50 = nearest_rank(magnitudes, 50);
  s.flow_p90 = nearest_rank(magnitudes, 90);
  s.flow_p99 = nearest_rank(magnitudes, 99);
  return s;
}

FrameStatistics frame_statistics(const fs::path& dir, const ReleaseLayout& layout, const View& view,
                                 int frame, int frames) {
  const auto file = [&](const char* kind) {  // of the kinds every layout has
    return dir / frame_file(*layout.find(kind), view, frame);
  };
  const Image<std::uint8_t> semantic = read_image<std::uint8_t>(file("semantic"));
  const auto same_size = [&](const fs::path& path, const auto& image, int channels) {
    if (image.width != semantic.width || image.height != semantic.height ||
        image.channels != channels)
      throw FileError(path, std::to_string(image.width) + " x " + std::to_string(image.height) +
                                " x " + std::to_string(image.channels) + ", not " +
                                std::to_string(semantic.width) + " x " +
                                std::to_string(semantic.height) + " x " + std::to_string(channels) +
                                " as its frame's semantic image");
  };
  same_size(file("semantic"), semantic, 1);
  const Image<std::uint16_t> instance = read_image<std::uint16_t>(file("instance"));
  same_size(file("instance"), instance, 1);
  if (!has_frame(output_kind("flow"), frame, frames))
    return frame_statistics({}, {}, semantic.view(), instance.view());
  const Flow flow = read_flow(file("flow"));
  same_size(file("flow"), flow.uv, 2);
  const Image<std::uint8_t> valid = read_image<std::uint8_t>(file("valid"));
  same_size(file("valid"), valid, 1);
  return frame_statistics(flow.uv.view(), valid.view(), semantic.view(), instance.view());
}

nlohmann::json sequence_statistics_from_files(const fs::path& dir, const ReleaseLayout& layout,
                                              const std::vector<Pose>& poses, int frames,
                                              double fps, int classes) {
  const View view = statistics_view(layout);
  std::vector<FrameStatistics> statistics(static_cast<std::size_t>(frames));
  for (int f = 0; f < frames; ++f)
    statistics[std::size_t(f)] = frame_statistics(dir, layout, view, f, frames);
  return sequence_statistics_json(view, statistics, poses, fps, classes);
}

View statistics_view(const ReleaseLayout& layout) {
  for (const View& view : layout.views())
    if (!view.face) return view;
  return {};
}

namespace {

nlohmann::json per_frame_json(const std::vector<FrameStatistics>& frames) {
  nlohmann::json p50, p90, p99, mean, actor_share, valid_share;
  for (const FrameStatistics& f : frames) {
    const std::uint64_t known =
        std::accumulate(f.flow_histogram.begin(), f.flow_histogram.end(), std::uint64_t(0));
    const bool flow = !f.flow_histogram.empty();
    p50.push_back(flow ? nlohmann::json(f.flow_p50) : nlohmann::json());
    p90.push_back(flow ? nlohmann::json(f.flow_p90) : nlohmann::json());
    p99.push_back(flow ? nlohmann::json(f.flow_p99) : nlohmann::json());
    mean.push_back(known ? nlohmann::json(f.flow_sum / double(known)) : nlohmann::json());
    actor_share.push_back(double(f.actor_pixels) / double(f.pixels));
    valid_share.push_back(flow ? nlohmann::json(double(f.valid_pixels) / double(f.pixels))
                               : nlohmann::json());
  }
  return {{"flow_p50", p50},
          {"flow_p90", p90},
          {"flow_p99", p99},
          {"flow_mean", mean},
          {"actor_share", actor_share},
          {"valid_share", valid_share}};
}

nlohmann::json ego_json(const std::vector<Pose>& poses, double fps) {
  std::vector<double> speed, yaw_rate;
  double yaw_change = 0;
  for (std::size_t f = 0; f + 1 < poses.size(); ++f) {
    speed.push_back((poses[f + 1].translation() - poses[f].translation()).norm() * fps);
    const double turn = wrapped_angle(yaw_of(poses[f + 1]) - yaw_of(poses[f])) * 180 / kPi;
    yaw_rate.push_back(turn * fps);
    yaw_change += turn;
  }
  return {{"speed", speed}, {"yaw_rate", yaw_rate}, {"yaw_change_degrees", yaw_change}};
}

}  // namespace

nlohmann::json sequence_statistics_json(const View& view,
                                        const std::vector<FrameStatistics>& frames,
                                        const std::vector<Pose>& poses, double fps,
                                        int class_count) {
  std::vector<std::uint64_t> histogram(flow_bin_edges().size(), 0),
      classes(std::size_t(class_count), 0);
  double flow_sum = 0;
  std::uint64_t pixels = 0, actor = 0, valid = 0, flow_frame_pixels = 0;
  for (const FrameStatistics& f : frames) {
    for (std::size_t k = 0; k < f.flow_histogram.size(); ++k) histogram[k] += f.flow_histogram[k];
    for (int c = 0; c < class_count; ++c) classes[std::size_t(c)] += f.class_pixels[std::size_t(c)];
    flow_sum += f.flow_sum, pixels += f.pixels, actor += f.actor_pixels, valid += f.valid_pixels;
    if (!f.flow_histogram.empty()) flow_frame_pixels += f.pixels;
  }
  return {{"view", view_name(view)},
          {"flow_unit", "pixels of a 1024-wide image (the view's flow x 1024 / its width)"},
          {"flow_bin_edges", flow_bin_edges()},
          {"flow_histogram", histogram},
          {"flow_sum", flow_sum},
          {"class_pixels", classes},
          {"pixels", pixels},
          {"actor_pixels", actor},
          {"valid_pixels", valid},
          {"flow_frame_pixels", flow_frame_pixels},
          {"frames", per_frame_json(frames)},
          {"ego", ego_json(poses, fps)}};
}

double histogram_percentile(const std::vector<std::uint64_t>& histogram, double q) {
  const std::vector<double>& edges = flow_bin_edges();
  const double total =
      double(std::accumulate(histogram.begin(), histogram.end(), std::uint64_t(0)));
  if (total == 0) return 0;
  const double target = q * total;
  double before = 0;
  for (std::size_t k = 0; k < histogram.size(); ++k) {
    const double count = double(histogram[k]);
    if (count == 0 || before + count < target) {
      before += count;
      continue;
    }
    if (k + 1 == edges.size()) return edges[k];
    const double share = (target - before) / count, lo = edges[k], hi = edges[k + 1];
    return k == 0 ? lo + share * (hi - lo) : lo * std::pow(hi / lo, share);
  }
  return edges.back();
}

namespace {

// What a group of sequences (a map, a weather, the release) adds up to.
struct Group {
  int sequences = 0, frames = 0, turning = 0;
  std::vector<std::uint64_t> histogram = std::vector<std::uint64_t>(flow_bin_edges().size(), 0);
  std::vector<std::uint64_t> classes;
  double flow_sum = 0;
  std::uint64_t pixels = 0, actor = 0, valid = 0, flow_frame_pixels = 0;
  std::vector<double> speed, yaw_rate_abs, yaw_change_abs;

  void add(const nlohmann::json& s, int frames_of_sequence) {
    ++sequences, frames += frames_of_sequence;
    const auto add_all = [](std::vector<std::uint64_t>& sum, const nlohmann::json& values) {
      for (std::size_t k = 0; k < sum.size(); ++k) sum[k] += values.at(k).get<std::uint64_t>();
    };
    add_all(histogram, s.at("flow_histogram"));
    classes.resize(std::max(classes.size(), s.at("class_pixels").size()), 0);
    add_all(classes, s.at("class_pixels"));
    flow_sum += s.at("flow_sum").get<double>();
    pixels += s.at("pixels").get<std::uint64_t>();
    actor += s.at("actor_pixels").get<std::uint64_t>();
    valid += s.at("valid_pixels").get<std::uint64_t>();
    flow_frame_pixels += s.at("flow_frame_pixels").get<std::uint64_t>();
    const nlohmann::json& ego = s.at("ego");
    for (double v : ego.at("speed")) speed.push_back(v);
    for (double v : ego.at("yaw_rate")) yaw_rate_abs.push_back(std::abs(v));
    const double change = std::abs(ego.at("yaw_change_degrees").get<double>());
    yaw_change_abs.push_back(change);
    turning += change >= kTurnDegrees;
  }
};

double mean_of(const std::vector<double>& values) {
  return values.empty() ? 0 : std::accumulate(values.begin(), values.end(), 0.0) / values.size();
}

nlohmann::json distribution(std::vector<double> values, std::initializer_list<int> percents) {
  nlohmann::json d = {{"mean", mean_of(values)}};
  if (values.empty()) return d;
  for (int p : percents) d[percentile_key(p)] = nearest_rank(values, p);
  d["max"] = *std::max_element(values.begin(), values.end());
  return d;
}

// Counts of values in bins of `width` from 0, the last bin open.
std::vector<int> value_histogram(const std::vector<double>& values, double width, int bins) {
  std::vector<int> counts(std::size_t(bins), 0);
  for (double v : values) ++counts[std::size_t(std::clamp(int(v / width), 0, bins - 1))];
  return counts;
}

nlohmann::json group_json(const Group& g, const std::vector<std::string>& class_names) {
  const std::uint64_t known =
      std::accumulate(g.histogram.begin(), g.histogram.end(), std::uint64_t(0));
  nlohmann::json percentiles;
  for (int p : {10, 25, 50, 75, 90, 99})
    percentiles[percentile_key(p)] = histogram_percentile(g.histogram, p / 100.0);
  nlohmann::json shares;
  for (std::size_t c = 0; c < class_names.size(); ++c)
    shares[class_names[c]] = g.pixels && c < g.classes.size() ? double(g.classes[c]) / g.pixels : 0;
  return {{"sequences", g.sequences},
          {"frames", g.frames},
          {"flow",
           {{"pixels", known},
            {"mean", known ? g.flow_sum / double(known) : 0},
            {"percentiles", percentiles},
            {"histogram", g.histogram}}},
          {"class_shares", shares},
          {"actor_share", g.pixels ? double(g.actor) / g.pixels : 0},
          {"valid_share", g.flow_frame_pixels ? double(g.valid) / g.flow_frame_pixels : 0},
          {"ego_speed", distribution(g.speed, {10, 50, 90})},
          {"ego_speed_histogram", value_histogram(g.speed, kSpeedBin, kSpeedBins)},
          {"yaw_rate_abs_histogram", value_histogram(g.yaw_rate_abs, kYawRateBin, kYawRateBins)},
          {"yaw_rate_abs", distribution(g.yaw_rate_abs, {50, 90, 99})},
          {"yaw_change_abs_degrees", distribution(g.yaw_change_abs, {50})},
          {"turning_sequences", g.turning},
          {"turn_share", g.sequences ? double(g.turning) / g.sequences : 0}};
}

nlohmann::json groups_json(const std::map<std::string, Group>& groups,
                           const std::vector<std::string>& class_names) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, group] : groups) j[name] = group_json(group, class_names);
  return j;
}

}  // namespace

nlohmann::json release_statistics(const std::vector<SequenceStatistics>& sequences,
                                  const std::vector<std::string>& class_names) {
  Group all;
  std::map<std::string, Group> per_map, per_weather;
  for (const SequenceStatistics& s : sequences)
    for (Group* g : {&all, &per_map[s.map_name], &per_weather[s.weather]})
      g->add(s.statistics, s.frames);
  if (all.sequences == 0) return nullptr;
  return {{"view", sequences.front().statistics.at("view")},
          {"flow_unit", "pixels of a 1024-wide image"},
          {"flow_bin_edges", flow_bin_edges()},
          {"turn_degrees", kTurnDegrees},
          {"ego_speed_bin", kSpeedBin},
          {"yaw_rate_abs_bin", kYawRateBin},
          {"all", group_json(all, class_names)},
          {"maps", groups_json(per_map, class_names)},
          {"weathers", groups_json(per_weather, class_names)}};
}

SequenceStatistics checked_statistics(const fs::path& sequence_dir, const SequenceMeta& meta) {
  SequenceStatistics s{meta.map_name, meta.base_weather(), meta.frames, meta.statistics};
  try {
    Group().add(s.statistics, s.frames);
  } catch (const nlohmann::json::exception& e) {
    throw FileError(sequence_dir / kMetaFile, std::string("statistics: ") + e.what());
  }
  return s;
}

nlohmann::json release_statistics(const fs::path& out, const std::vector<std::string>& sequences,
                                  const std::string& class_table_name) {
  std::vector<SequenceStatistics> recorded;
  for (const std::string& name : sequences) {
    const fs::path dir = sequence_dir(out, name);
    const SequenceMeta meta = read_meta(dir);
    if (meta.statistics.is_object()) recorded.push_back(checked_statistics(dir, meta));
  }
  return release_statistics(recorded, class_table(class_table_name).names);
}

std::string statistics_summary(const nlohmann::json& statistics) {
  if (statistics.is_null()) return "";
  std::string text = "statistics (" + statistics.at("view").get<std::string>() +
                     " view, flow in pixels of a 1024-wide image):\n";
  const auto line = [&](const std::string& name, const nlohmann::json& g) {
    const nlohmann::json& flow = g.at("flow").at("percentiles");
    char row[256];
    std::snprintf(row, sizeof row,
                  "  %-12s flow p10 %.2f p50 %.2f p90 %.2f p99 %.2f px; ego %.1f m/s; turning "
                  "%d/%d\n",
                  name.c_str(), flow.at("p10").get<double>(), flow.at("p50").get<double>(),
                  flow.at("p90").get<double>(), flow.at("p99").get<double>(),
                  g.at("ego_speed").at("mean").get<double>(), g.at("turning_sequences").get<int>(),
                  g.at("sequences").get<int>());
    text += row;
  };
  for (const auto& [name, group] : statistics.at("maps").items()) line(name, group);
  line("all", statistics.at("all"));
  return text;
}

}  // namespace flowscape
