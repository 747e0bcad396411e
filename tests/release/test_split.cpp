#include <catch2/catch.hpp>
#include <map>
#include <string>

#include "flowscape/layout/layout.h"
#include "flowscape/layout/split.h"
#include "flowscape/release/config.h"

using namespace flowscape;

TEST_CASE("the default release is the paper's FlowScape and its split is 14 of 64 sequences") {
  const ReleaseConfig config;
  const std::vector<SequencePlan> plans = plan_sequences(config);
  REQUIRE(plans.size() == 64);
  std::vector<SequenceInfo> sequences;
  for (const SequencePlan& p : plans)
    sequences.push_back({p.name, p.weather, p.weather, config.frames});
  CHECK(sequences.front().name == "map00_seq00");
  CHECK(sequences.back().name == "map07_seq07");
  const Split split = split_sequences(sequences, 0);
  REQUIRE(split.test.size() == 14);
  REQUIRE(split.train.size() == 50);
  std::map<std::string, int> test;
  for (const SequenceInfo& s : split.test) ++test[s.weather];
  CHECK(test == std::map<std::string, int>{{"cloud", 2}, {"fog", 2}, {"rain", 2}, {"sunny", 8}});
  int pairs = 0;
  for (const SequenceInfo& s : split.test) pairs += s.frames - 1;
  CHECK(pairs == 14 * 99);  // the paper counts 1,400 test frames
  for (const SequenceInfo& s : split.test)
    for (const SequenceInfo& t : split.train) REQUIRE(s.name != t.name);
  CHECK(split_sequences(sequences, 0).test.front().name == split.test.front().name);
  CHECK(split_sequences(sequences, 1).test.front().name != split.test.front().name);
}

TEST_CASE("splits of small releases are never empty") {
  const auto sequence = [](const char* name, const char* weather) {
    return SequenceInfo{name, weather, weather, 4};
  };
  // the demo: one sunny and one rain sequence, each alone in its weather
  const std::vector<SequenceInfo> demo{sequence("map00_seq00", "sunny"),
                                       sequence("map00_seq01", "rain")};
  for (std::uint64_t seed = 0; seed < 8; ++seed) {
    const Split split = split_sequences(demo, seed);
    REQUIRE((split.train.size() == 1 && split.test.size() == 1));
    CHECK(split.train.front().name != split.test.front().name);
  }
  // two weathers with two sequences each: one of each goes to test
  std::vector<SequenceInfo> four = demo;
  four.push_back(sequence("map00_seq02", "sunny"));
  four.push_back(sequence("map00_seq03", "rain"));
  const Split split = split_sequences(four, 3);
  CHECK((split.train.size() == 2 && split.test.size() == 2));
  CHECK(split.test.front().weather != split.test.back().weather);
  CHECK_THROWS_WITH(split_sequences({sequence("map00_seq00", "sunny")}, 0),
                    Catch::Contains("a split needs at least 2 sequences, the release has 1"));
}

namespace {

std::vector<SequenceInfo> release_of(int maps, int per_map) {
  std::vector<SequenceInfo> sequences;
  for (int m = 0; m < maps; ++m)
    for (int s = 0; s < per_map; ++s)
      sequences.push_back({sequence_name(m, s), "sunny", "sunny", 5});
  return sequences;
}

std::string side_of(const Split& split, const std::string& name) {
  for (const auto& [label, side] :
       {std::pair{"train", &split.train}, {"test", &split.test}, {"val", &split.val}})
    for (const SequenceInfo& s : *side)
      if (s.name == name) return label;
  return "";
}

}  // namespace

TEST_CASE("a hash split keeps every sequence where it was when the release grows") {
  // issue 35, point 6: the stratified split reshuffles when sequences are added
  const HashSplitOptions options{0.25, 0.15, {}};
  const Split small = split_by_hash(release_of(2, 8), 7, options);
  const Split grown = split_by_hash(release_of(4, 12), 7, options);
  for (const SequenceInfo& s : release_of(2, 8))
    CHECK(side_of(grown, s.name) == side_of(small, s.name));
  CHECK(small.train.size() + small.test.size() + small.val.size() == 16);
  // the shares hold on average: 48 sequences, 25 % test and 15 % val expected
  CHECK((grown.test.size() >= 6 && grown.test.size() <= 20));
  CHECK((grown.val.size() >= 2 && grown.val.size() <= 14));
  for (const SequenceInfo& s : release_of(4, 12)) {
    const double u = split_hash(s.name, 7);
    REQUIRE((u >= 0 && u < 1));
    CHECK(side_of(grown, s.name) == (u < 0.25 ? "test" : u < 0.4 ? "val" : "train"));
  }
  CHECK(split_hash("map00_seq00", 7) != split_hash("map00_seq00", 8));  // the seed picks
}

TEST_CASE("held-out maps go to test whole") {
  const Split split = split_by_hash(release_of(8, 4), 0, {0.1, 0.1, {3, 7}});
  for (const SequenceInfo& s : release_of(8, 4))
    if (s.name.starts_with("map03_") || s.name.starts_with("map07_"))
      CHECK(side_of(split, s.name) == "test");
  int others_in_test = 0;
  for (const SequenceInfo& s : split.test)
    others_in_test += !(s.name.starts_with("map03_") || s.name.starts_with("map07_"));
  CHECK(others_in_test < 24);  // the rest by the hash (10 % on average)
}
