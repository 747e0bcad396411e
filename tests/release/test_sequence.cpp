#include <catch2/catch.hpp>

#include "flowscape/release/sequence.h"
#include "flowscape/scenes/skinning.h"
#include "tiny_release.h"

using namespace flowscape;

namespace {

// A foggy sequence of map `map` whose ego drives free from start point `ego_start`.
Sequence foggy_sequence(int map, std::uint64_t seed, int vehicles, int pedestrians, int ego_start,
                        int frames) {
  return make_sequence({.city = {.map = map,
                                 .seed = seed,
                                 .vehicles = vehicles,
                                 .pedestrians = pedestrians,
                                 .ego_start = ego_start,
                                 .ego_route = EgoRoute::Free},
                        .weather = "fog",
                        .frames = frames});
}

}  // namespace

TEST_CASE("a sequence's frame pairs are one frame apart at 30 Hz, with the rig's poses then") {
  const Sequence s = foggy_sequence(3, 77, 6, 4, 12, 10);
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
  const Sequence a = foggy_sequence(0, 1, 2, 2, 0, 3), b = foggy_sequence(0, 2, 2, 2, 0, 3);
  CHECK(to_json(a.weather) == to_json(randomized(weather_preset("fog"), 1)));
  CHECK(to_json(a.weather) != to_json(b.weather));
  CHECK(a.city.scene.environment.fog.density > 0);
  const ReleaseConfig config = tiny_release_config(2);
  const SequencePlan plan = plan_sequences(config)[1];
  const SequenceSpec spec = sequence_spec(config, plan);
  CHECK((spec.city.map == 0 && spec.weather == "rain" && spec.city.seed == plan.seed));
  CHECK(spec.city.ego_start == int(plan.seed % 100));
  const Sequence s = make_sequence(spec);
  const SequenceMeta meta = sequence_meta(s, plan, config);
  CHECK(meta.scene == "map00_seq01");
  nlohmann::json recorded = meta.weather;
  CHECK(recorded.at("exposure") == s.city.scene.environment.exposure);
  recorded.erase("exposure");
  CHECK(recorded == to_json(s.weather));
  CHECK(weather_from_json(meta.weather).time_of_day == plan.time_of_day);
  REQUIRE(meta.poses.size() == 3);
  CHECK(meta.poses[2].matrix() == s.frame_pair(2).rig.matrix());
  CHECK(meta.face_size == 8);
}

TEST_CASE("every actor's recorded box holds its vertices and its velocity is its poses' change") {
  const ReleaseConfig config = tiny_release_config(1, 12);
  const Sequence s = make_sequence(sequence_spec(config, plan_sequences(config).front()));
  const nlohmann::json actors = actor_records(s, config.frames);
  REQUIRE(actors.size() == s.city.actors.size());
  REQUIRE(actors.size() >= std::size_t(config.vehicles + config.pedestrians));
  const double h = 1 / kFrameRate;
  int moving = 0;
  for (std::size_t a = 0; a < actors.size(); ++a) {
    const nlohmann::json& record = actors[a];
    const Actor& actor = s.city.scene.actors[a];
    CHECK(record["instance"] == actor.instance);
    for (int f = 1; f + 1 < config.frames; ++f) {
      const double t = f * h;
      const auto column = [&](const char* key) {
        const std::vector<double> v = record[key][std::size_t(f)];
        return Vec3(v[0], v[1], v[2]);
      };
      const std::vector<double> q = record["rotation"][std::size_t(f)];
      const Eigen::Quaterniond rotation(q[0], q[1], q[2], q[3]);
      const Vec3 centre = column("centre"), half = column("size") / 2;
      // every vertex of every part, posed (and skinned) at t, lies in the box (to the record's
      // rounding)
      for (const Part& part : actor.parts)
        for (const Vec3& vertex : part_vertices_at(part, t)) {
          const Vec3 world = actor.pose(t) * vertex;
          const Vec3 in_box = rotation.conjugate() * (world - centre);
          REQUIRE((in_box.cwiseAbs() - half).maxCoeff() < 1e-5);
        }
      // the heading is the yaw of the box's x axis
      const Vec3 x_axis = rotation * Vec3::UnitX();
      CHECK(double(record["heading"][std::size_t(f)]) ==
            Approx(std::atan2(x_axis.y(), x_axis.x())).margin(2e-6));
      // velocity: the box centre, carried by the actor's poses one frame either way
      const Vec3 local = actor.pose(t).inverse() * centre;
      const Vec3 finite = (actor.pose(t + h) * local - actor.pose(t - h) * local) / (2 * h);
      CHECK((column("velocity") - finite).norm() < 0.05);
      const double yaw_rate =
          Eigen::AngleAxisd(actor.pose(t + h).linear() * actor.pose(t - h).linear().transpose())
              .angle() /
          (2 * h);
      CHECK(column("angular_velocity").norm() == Approx(yaw_rate).margin(0.01));
      // the rig frame's box is the world's seen from the rig then
      const Vec3 in_rig = s.city.rig(t).inverse() * centre;
      CHECK((column("centre_rig") - in_rig).norm() < 1e-5);
      moving += finite.norm() > 1;
    }
  }
  CHECK(moving > 0);
}

TEST_CASE("a frame's truth request has a target per flow step of its layout") {
  const ReleaseConfig config = tiny_release_config(1, 6);
  const Sequence s = make_sequence(sequence_spec(config, plan_sequences(config).front()));
  const ReleaseLayout layout =
      ReleaseLayout::of({"flow_backward", "scene_flow", "normal"}, {1, 2}, true);
  const TruthPlan middle = truth_plan(s, layout, 2, 6);
  CHECK(middle.steps == std::vector<int>{2, -1, -2});
  REQUIRE(middle.request.more.size() == 3);
  CHECK(middle.request.more[0].time == Approx(4 / 30.0));
  CHECK(middle.request.more[2].rig.matrix() == s.city.rig(0).matrix());
  CHECK((middle.request.scene_flow && middle.request.normal && !middle.request.shading_normal));
  CHECK(truth_plan(s, layout, 5, 6).steps == std::vector<int>{-1, -2});
  CHECK(truth_plan(s, layout, 0, 6).steps == std::vector<int>{2});
}

TEST_CASE("a release's sequence mix turns a quarter or more by 45 degrees at 6 m/s or more") {
  // the plan of gen_flowscape --maps 8 --sequences-per-map 4 --frames 100 (issue 27's release)
  ReleaseConfig config;
  config.maps = 8, config.sequences_per_map = 4, config.frames = 100;
  int turning = 0, planned_turns = 0, steps = 0;
  double distance = 0;
  for (const SequencePlan& plan : plan_sequences(config)) {
    const Sequence s = make_sequence(sequence_spec(config, plan));
    double yaw_change = 0;
    for (int f = 0; f + 1 < config.frames; ++f) {
      const Pose a = s.moment(f).rig, b = s.moment(f + 1).rig;
      const Vec3 forward_a = a.linear().col(0), forward_b = b.linear().col(0);
      yaw_change += std::remainder(
          std::atan2(forward_b.y(), forward_b.x()) - std::atan2(forward_a.y(), forward_a.x()),
          2 * kPi);
      distance += (b.translation() - a.translation()).norm(), ++steps;
    }
    turning += std::abs(yaw_change) * 180 / kPi >= 45;
    planned_turns += plan.turns;
  }
  CHECK(planned_turns == 10);  // floor(32 / 3)
  CHECK(turning >= 32 / 4);
  CHECK(distance / steps * kFrameRate >= 6);
}
