#include <algorithm>
#include <catch2/catch.hpp>
#include <map>
#include <string>

#include "flowscape/release.h"
#include "flowscape/sha256.h"
#include "flowscape/split.h"

using namespace flowscape;

TEST_CASE("sha256 gives the FIPS 180-4 example digests") {
  CHECK(sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  Sha256 million;  // one million 'a', fed in uneven pieces
  const std::string piece(997, 'a');
  std::size_t fed = 0;
  while (fed + piece.size() <= 1000000)
    million.update(piece.data(), piece.size()), fed += piece.size();
  million.update(piece.data(), 1000000 - fed);
  CHECK(million.hex() == "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST_CASE("the default release is the paper's FlowScape and its split is 14 of 64 sequences") {
  const ReleaseConfig config;
  const std::vector<SequencePlan> plans = plan_sequences(config);
  REQUIRE(plans.size() == 64);
  std::vector<SequenceInfo> sequences;
  for (const SequencePlan& p : plans) sequences.push_back({p.name, p.weather, config.frames});
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

TEST_CASE("shards share out the sequences exactly once") {
  ReleaseConfig config;
  config.shards = 3;
  std::vector<int> owners(64, 0);
  for (config.shard = 0; config.shard < 3; ++config.shard)
    for (const SequencePlan& plan : plan_sequences(config))
      if (in_shard(plan, config)) ++owners[plan.number];
  CHECK(std::all_of(owners.begin(), owners.end(), [](int n) { return n == 1; }));
}

TEST_CASE("release configs round-trip through JSON and bad values are named") {
  ReleaseConfig config;
  config.maps = 3, config.frames = 7, config.weathers = {"rain", "fog"}, config.cube = false;
  CHECK(to_json(release_config_from_json(to_json(config))) == to_json(config));
  CHECK_THROWS_WITH(release_config_from_json({{"maps", 9}}),
                    Catch::Contains("maps must be in 1..8"));
  CHECK_THROWS_WITH(release_config_from_json({{"frames", 1}}), Catch::Contains("frames"));
  CHECK_THROWS_WITH(release_config_from_json({{"spp", "many"}}), Catch::Contains("release config"));
  CHECK_THROWS_WITH(release_config_from_json({{"weathers", {"hail"}}}),
                    Catch::Contains("unknown weather preset \"hail\""));
  CHECK_THROWS_WITH(release_config_from_json({{"vehicles", 150}, {"pedestrians", 60}}),
                    Catch::Contains("vehicles + pedestrians"));
}
