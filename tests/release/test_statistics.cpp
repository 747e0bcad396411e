#include <catch2/catch.hpp>
#include <cmath>

#include "flowscape/core/files.h"
#include "flowscape/layout/classes.h"
#include "flowscape/layout/meta.h"
#include "flowscape/quality/flow_datasets.h"
#include "flowscape/release/statistics.h"
#include "temp_dir.h"

using namespace flowscape;

namespace {

struct FrameImages {
  Image<float> flow;
  Image<std::uint8_t> valid, semantic;
  Image<std::uint16_t> instance;
};

// 64 x 32: the left half flows 4 px right (64 px in 1024-wide pixels), the right half stands
// still, pixel (0, 0) is unknown; road everywhere but 100 vehicle pixels of instance 5 at the top;
// the left half valid.
FrameImages two_halves() {
  FrameImages f{Image<float>(64, 32, 2, 0.0f), Image<std::uint8_t>(64, 32, 1, 0),
                Image<std::uint8_t>(64, 32, 1, 7), Image<std::uint16_t>(64, 32, 1, 0)};
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) f.flow.pixel(x, y)[0] = 4, *f.valid.pixel(x, y) = 1;
  f.flow.pixel(0, 0)[0] = f.flow.pixel(0, 0)[1] = 1e10f;
  for (int x = 0; x < 50; ++x)
    for (int y = 0; y < 2; ++y) *f.semantic.pixel(x, y) = 10, *f.instance.pixel(x, y) = 5;
  return f;
}

Pose rig_at(double x, double y, double yaw) {
  return Pose(Eigen::Translation3d(x, y, 1.7) * Eigen::AngleAxisd(yaw, Vec3::UnitZ()));
}

}  // namespace

TEST_CASE("flow bins are eighth octaves from 1/16 to 1024 px") {
  const std::vector<double>& edges = flow_bin_edges();
  REQUIRE(edges.size() == 1 + 14 * 8 + 1);
  CHECK(edges[0] == 0);
  CHECK(edges[1] == 1.0 / 16);
  CHECK(edges.back() == 1024);
  for (std::size_t k = 2; k < edges.size(); ++k)
    CHECK(edges[k] / edges[k - 1] == Approx(std::exp2(1.0 / 8)).epsilon(1e-12));
}

TEST_CASE("a frame's statistics count what its images hold") {
  const FrameImages f = two_halves();
  const FrameStatistics s =
      frame_statistics(f.flow.view(), f.valid.view(), f.semantic.view(), f.instance.view());
  const std::vector<double>& edges = flow_bin_edges();
  const std::size_t bin64 = std::size_t(1 + 10 * 8);  // edges[1 + 8 * (6 + 4)] = 64
  REQUIRE(edges[bin64] == 64);
  CHECK(s.flow_histogram[0] == 32 * 32);  // standing still
  CHECK(s.flow_histogram[bin64] == 32 * 32 - 1);
  CHECK(std::accumulate(s.flow_histogram.begin(), s.flow_histogram.end(), 0ull) == 2047);
  CHECK(s.flow_sum == 64.0 * 1023);
  CHECK(s.flow_p50 == 0);  // rank ceil(2047 / 2) = 1024: the last of the 1024 still pixels
  CHECK(s.flow_p90 == 64);
  CHECK(s.pixels == 2048);
  CHECK(s.valid_pixels == 1024);
  CHECK(s.actor_pixels == 100);
  CHECK(s.class_pixels[10] == 100);
  CHECK(s.class_pixels[7] == 2048 - 100);
  const FrameStatistics last = frame_statistics({}, {}, f.semantic.view(), f.instance.view());
  CHECK(last.flow_histogram.empty());
  CHECK(last.valid_pixels == 0);
  CHECK(last.actor_pixels == 100);
}

TEST_CASE("histogram percentiles interpolate inside the bin") {
  const std::vector<double>& edges = flow_bin_edges();
  std::vector<std::uint64_t> histogram(edges.size(), 0);
  histogram[0] = 10;   // [0, 1/16): linear
  histogram[33] = 10;  // [1, 2^(1/8)): geometric
  REQUIRE(edges[33] == 1);
  CHECK(histogram_percentile(histogram, 0.25) == Approx(0.5 / 16));
  CHECK(histogram_percentile(histogram, 0.75) == Approx(std::exp2(0.5 / 8)));
  CHECK(histogram_percentile(histogram, 1.0) == Approx(std::exp2(1.0 / 8)));
  histogram.back() = 20;  // the open bin above 1024 px gives its lower edge
  CHECK(histogram_percentile(histogram, 0.9) == 1024);
  CHECK(histogram_percentile(std::vector<std::uint64_t>(edges.size(), 0), 0.5) == 0);
}

TEST_CASE("ego speed and yaw rate follow a rig driving a circle") {
  // radius 20 m at 10 m/s: 0.5 rad/s; per frame the chord 2 R sin(dtheta / 2)
  const double radius = 20, rate = 0.5, fps = 30, dtheta = rate / fps;
  std::vector<Pose> poses;
  for (int f = 0; f < 31; ++f) {
    const double a = f * dtheta;
    poses.push_back(rig_at(radius * std::sin(a), radius * (1 - std::cos(a)), a));
  }
  const nlohmann::json s = sequence_statistics_json({}, {}, poses, fps, 23).at("ego");
  REQUIRE(s.at("speed").size() == 30);
  for (std::size_t f = 0; f < 30; ++f) {
    CHECK(s["speed"][f].get<double>() ==
          Approx(2 * radius * std::sin(dtheta / 2) * fps).epsilon(1e-12));
    CHECK(s["yaw_rate"][f].get<double>() == Approx(rate * 180 / kPi).epsilon(1e-9));
  }
  CHECK(s["yaw_change_degrees"].get<double>() == Approx(30 * dtheta * 180 / kPi).epsilon(1e-9));
  // across the +-180 degree seam of the heading the change stays small
  const nlohmann::json seam = sequence_statistics_json(
      {}, {}, {rig_at(0, 0, kPi - 0.01), rig_at(0, 0, -kPi + 0.01)}, fps, 23);
  CHECK(seam["ego"]["yaw_change_degrees"].get<double>() == Approx(0.02 * 180 / kPi));
}

TEST_CASE("release statistics group sequences by map and weather") {
  const FrameImages f = two_halves();
  const FrameStatistics moving =
      frame_statistics(f.flow.view(), f.valid.view(), f.semantic.view(), f.instance.view());
  const FrameStatistics last = frame_statistics({}, {}, f.semantic.view(), f.instance.view());
  const auto sequence = [&](double turn_degrees, double speed) {
    const double yaw = turn_degrees * kPi / 180;
    return sequence_statistics_json({}, {moving, last},
                                    {rig_at(0, 0, 0), rig_at(speed / 30, 0, yaw)}, 30, 23);
  };
  const std::vector<std::string>& names = class_table("carla-0.9.13").names;
  const nlohmann::json s = release_statistics({{"downtown", "sunny", 2, sequence(50, 6)},
                                               {"downtown", "rain", 2, sequence(10, 9)},
                                               {"highway", "rain", 2, sequence(-90, 12)}},
                                              names);
  CHECK(s["all"]["sequences"] == 3);
  CHECK(s["all"]["turning_sequences"] == 2);  // |50| and |-90| >= 45
  CHECK(s["maps"]["downtown"]["turn_share"].get<double>() == 0.5);
  CHECK(s["weathers"]["rain"]["sequences"] == 2);
  CHECK(s["all"]["ego_speed"]["mean"].get<double>() == Approx(9));
  CHECK(s["all"]["ego_speed"]["p50"].get<double>() == Approx(9));
  CHECK(s["all"]["ego_speed"]["max"].get<double>() == Approx(12));
  CHECK(s["all"]["flow"]["pixels"] == 3 * 2047);
  CHECK(s["all"]["flow"]["mean"].get<double>() == Approx(64.0 * 1023 / 2047));
  CHECK(s["all"]["actor_share"].get<double>() == Approx(100.0 / 2048));
  CHECK(s["all"]["valid_share"].get<double>() == Approx(0.5));  // of the frames with flow
  CHECK(s["all"]["class_shares"]["Vehicles"].get<double>() == Approx(100.0 / 2048));
  CHECK(release_statistics(std::vector<SequenceStatistics>{}, names).is_null());
}

TEST_CASE("a bad statistics record in meta.json is named") {
  TempDir release;
  SequenceMeta meta;
  meta.scene = "map00_seq00", meta.map_name = "downtown", meta.weather = {{"preset", "sunny"}};
  meta.frames = 2, meta.poses = {rig_at(0, 0, 0), rig_at(0.1, 0, 0)};
  meta.statistics = {{"view", "erp"}, {"flow_histogram", {1, 2}}};  // cut short
  write_meta(sequence_dir(release.path, meta.scene), meta);
  CHECK_THROWS_WITH(release_statistics(release.path, {meta.scene}, "carla-0.9.13"),
                    Catch::Contains("meta.json") && Catch::Contains("statistics"));
}

TEST_CASE("gt_quality's sample spreads N pairs over each weather") {
  FlowDataset dataset{"flowscape", {}};
  for (int k = 0; k < 13; ++k) {
    PairFiles pair;
    pair.image1 = std::to_string(k);
    pair.category = k < 10 ? "sunny" : "rain";
    dataset.pairs.push_back(pair);
  }
  const FlowDataset sample = sample_pairs(dataset, 2);
  std::vector<std::string> names;
  for (const PairFiles& p : sample.pairs) names.push_back(p.image1.string());
  // sunny (pairs 0-9): floor((2k + 1) 10 / 4) = 2, 7; rain (10-12): 10 + floor((2k + 1) 3 / 4)
  CHECK(names == std::vector<std::string>{"2", "7", "10", "12"});
  CHECK(sample_pairs(dataset, 50).pairs.size() == 13);
}
