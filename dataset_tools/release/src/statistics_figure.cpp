// The statistics figure of the dataset card and the explorer: a self-contained SVG.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>

#include "flowscape/release/statistics.h"

namespace flowscape {
namespace {

constexpr int kPanelWidth = 440, kPanelHeight = 250, kMargin = 58;
constexpr const char* kPalette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                    "#9467bd", "#8c564b", "#e377c2", "#17becf"};

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

// One chart: data x0..x1, y0..y1 mapped into its box at (left, top) of the figure.
struct Panel {
  std::ostringstream& svg;
  double left, top, x0, x1, y0, y1;

  double px(double x) const {
    return left + kMargin + (x - x0) / (x1 - x0) * (kPanelWidth - kMargin - 22);
  }
  double py(double y) const {
    return top + kPanelHeight - 30 - (y - y0) / (y1 - y0) * (kPanelHeight - 60);
  }
  void frame(const std::string& title, const std::string& x_label) const {
    svg << "<text x='" << left + kMargin << "' y='" << top + 18 << "' font-weight='bold'>" << title
        << "</text><rect x='" << px(x0) << "' y='" << py(y1) << "' width='" << px(x1) - px(x0)
        << "' height='" << py(y0) - py(y1) << "' fill='none' stroke='#888'/><text x='"
        << (px(x0) + px(x1)) / 2 << "' y='" << top + kPanelHeight - 4 << "' text-anchor='middle'>"
        << x_label << "</text>\n";
  }
  void x_tick(double x, const std::string& label) const {
    svg << "<text x='" << px(x) << "' y='" << py(y0) + 14 << "' text-anchor='middle'>" << label
        << "</text>";
  }
  void y_tick(double y, const std::string& label) const {
    svg << "<text x='" << px(x0) - 4 << "' y='" << py(y) + 4 << "' text-anchor='end'>" << label
        << "</text>";
  }
  void line(const std::vector<std::pair<double, double>>& points, const char* colour) const {
    svg << "<polyline fill='none' stroke='" << colour << "' stroke-width='1.5' points='";
    for (const auto& [x, y] : points) svg << number(px(x)) << "," << number(py(y)) << " ";
    svg << "'/>\n";
  }
  void bar(double x, double width, double y, const char* colour) const {
    svg << "<rect x='" << number(px(x)) << "' y='" << number(py(y)) << "' width='"
        << number(px(x + width) - px(x)) << "' height='" << number(py(y0) - py(y)) << "' fill='"
        << colour << "'/>";
  }
  void legend(int row, const std::string& name, const char* colour) const {
    const double x = px(x1) - 120, y = py(y1) + 14 + 14 * row;
    svg << "<rect x='" << x << "' y='" << y - 9 << "' width='10' height='10' fill='" << colour
        << "'/><text x='" << x + 14 << "' y='" << y << "'>" << name << "</text>";
  }
};

// Each group's share of flow pixels per octave-eighth, on log2 of the magnitude.
void flow_panel(std::ostringstream& svg, double left, double top, const nlohmann::json& groups,
                const std::string& title) {
  const std::vector<double>& edges = flow_bin_edges();
  const double lo = std::log2(edges[1]), hi = std::log2(edges[edges.size() - 1]);
  std::vector<std::vector<std::pair<double, double>>> lines;
  double top_share = 1e-6;
  for (const auto& [name, group] : groups.items()) {
    const auto histogram = group.at("flow").at("histogram").get<std::vector<double>>();
    const double total = std::max(1.0, std::accumulate(histogram.begin(), histogram.end(), 0.0));
    std::vector<std::pair<double, double>> points;
    for (std::size_t k = 1; k + 1 < edges.size(); ++k) {
      points.emplace_back((std::log2(edges[k]) + std::log2(edges[k + 1])) / 2,
                          histogram[k] / total);
      top_share = std::max(top_share, points.back().second);
    }
    lines.push_back(points);
  }
  const Panel panel{svg, left, top, lo, hi, 0, top_share * 1.1};
  panel.frame(title, "flow magnitude, pixels of a 1024-wide image (log scale)");
  for (int e = int(lo); e <= int(hi); e += 2) panel.x_tick(e, number(std::exp2(e)));
  panel.y_tick(0, "0"), panel.y_tick(top_share, number(100 * top_share) + " %");
  int row = 0;
  for (const auto& [name, group] : groups.items()) {
    panel.line(lines[std::size_t(row)], kPalette[row % 8]);
    panel.legend(row, name, kPalette[row % 8]);
    ++row;
  }
}

void histogram_panel(std::ostringstream& svg, double left, double top, const nlohmann::json& all,
                     const char* key, double bin, const std::string& title,
                     const std::string& x_label) {
  const auto counts = all.at(key).get<std::vector<double>>();
  const double total = std::max(1.0, std::accumulate(counts.begin(), counts.end(), 0.0));
  const double top_share = std::max(1e-6, *std::max_element(counts.begin(), counts.end()) / total);
  const Panel panel{svg, left, top, 0, bin * double(counts.size()), 0, top_share * 1.1};
  panel.frame(title, x_label);
  for (std::size_t k = 0; k < counts.size(); ++k)
    panel.bar(bin * double(k), bin * 0.9, counts[k] / total, kPalette[0]);
  for (int t = 0; t <= 5; ++t) {
    const double x = bin * double(counts.size()) * t / 5;
    panel.x_tick(x, number(x) + (t == 5 ? "+" : ""));
  }
  panel.y_tick(0, "0"), panel.y_tick(top_share, number(100 * top_share) + " %");
}

// The ten largest class shares over the release, as horizontal bars.
void class_panel(std::ostringstream& svg, double left, double top, const nlohmann::json& all) {
  std::vector<std::pair<double, std::string>> shares;
  for (const auto& [name, share] : all.at("class_shares").items())
    shares.emplace_back(share.get<double>(), name);
  std::sort(shares.rbegin(), shares.rend());
  shares.resize(std::min<std::size_t>(shares.size(), 10));
  const double widest = std::max(1e-6, shares.empty() ? 0 : shares.front().first);
  svg << "<text x='" << left + kMargin << "' y='" << top + 18
      << "' font-weight='bold'>Class shares of the pixels (ten largest)</text>\n";
  for (std::size_t k = 0; k < shares.size(); ++k) {
    const double y = top + 34 + 21.0 * double(k), x = left + 130;
    svg << "<text x='" << x - 6 << "' y='" << y + 12 << "' text-anchor='end'>" << shares[k].second
        << "</text><rect x='" << x << "' y='" << y << "' width='"
        << number(shares[k].first / widest * (kPanelWidth - 200)) << "' height='15' fill='"
        << kPalette[2] << "'/><text x='" << x + shares[k].first / widest * (kPanelWidth - 200) + 4
        << "' y='" << y + 12 << "'>" << number(100 * shares[k].first) << " %</text>\n";
  }
}

}  // namespace

std::string statistics_svg(const nlohmann::json& statistics) {
  std::ostringstream svg;
  const int width = 2 * kPanelWidth + 20, height = 3 * kPanelHeight + 20;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << height
      << "' font-family='sans-serif' font-size='11'>\n<rect width='100%' height='100%' "
         "fill='white'/>\n";
  if (statistics.is_null()) {
    svg << "<text x='20' y='30'>No statistics recorded in this release's meta.json files.</text>";
  } else {
    const nlohmann::json& all = statistics.at("all");
    flow_panel(svg, 0, 0, statistics.at("weathers"), "Flow magnitudes per weather");
    flow_panel(svg, kPanelWidth + 20, 0, statistics.at("maps"), "Flow magnitudes per map");
    histogram_panel(svg, 0, kPanelHeight, all, "ego_speed_histogram",
                    statistics.at("ego_speed_bin").get<double>(), "Ego speed (frames)", "m/s");
    histogram_panel(svg, kPanelWidth + 20, kPanelHeight, all, "yaw_rate_abs_histogram",
                    statistics.at("yaw_rate_abs_bin").get<double>(), "Ego yaw rate (frames)",
                    "|degrees per second|");
    class_panel(svg, 0, 2 * kPanelHeight, all);
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace flowscape
