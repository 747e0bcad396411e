#include <catch2/catch.hpp>

#include "flowscape/release/sequence.h"
#include "tiny_release.h"

using namespace flowscape;

TEST_CASE("a sequence's frame pairs are one frame apart at 30 Hz, with the rig's poses then") {
  const Sequence s = make_sequence({3, "fog", 77, 6, 4, 12, 10, {}});
  for (int f : {0, 4, 9}) {
    const FramePair pair = s.frame_pair(f);
    CHECK(pair.time == Approx(f / 30.0));
    CHECK(pair.next_time == Approx((f + 1) / 30.0));
    CHECK(pair.rig.matrix() == s.city.rig(pair.time).matrix());
    CHECK(pair.next_rig.matrix() == s.city.rig(pair.next_time).matrix());
    // the ego drives: at most 40 m/s, so at most 4/3 m between frames
    const double step = (pair.next_rig.translation() - pair.rig.translation()).norm();
    CHECK(step < 40.0 / 30);
  }
  CHECK(s.color_seed(1) != s.color_seed(2));
}

TEST_CASE("a sequence renders the preset varied by its seed, as its meta.json records") {
  const Sequence a = make_sequence({0, "fog", 1, 2, 2, 0, 3, {}}),
                 b = make_sequence({0, "fog", 2, 2, 2, 0, 3, {}});
  CHECK(to_json(a.weather) == to_json(randomized(weather_preset("fog"), 1)));
  CHECK(to_json(a.weather) != to_json(b.weather));
  CHECK(a.city.scene.environment.fog.density > 0);
  const ReleaseConfig config = tiny_release_config(2);
  const SequencePlan plan = plan_sequences(config)[1];
  const SequenceSpec spec = sequence_spec(config, plan);
  CHECK((spec.map == 0 && spec.weather == "rain" && spec.seed == plan.seed));
  CHECK(spec.ego_start == int(plan.seed % 100));
  const Sequence s = make_sequence(spec);
  const SequenceMeta meta = sequence_meta(s, plan, config);
  CHECK(meta.scene == "map00_seq01");
  CHECK(meta.weather == to_json(s.weather));
  REQUIRE(meta.poses.size() == 3);
  CHECK(meta.poses[2].matrix() == s.frame_pair(2).rig.matrix());
  CHECK(meta.face_size == 8);
}
