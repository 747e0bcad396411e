// bench_motion [SEEDS] [FRAMES]: how the traffic drives, measured from the poses of every vehicle
// (and the ego) at 30 Hz on every map: the largest change of yaw rate from one frame to the next,
// the largest longitudinal acceleration and braking, the largest lateral acceleration, the mean
// speed, how many vehicles share a junction, and how many lane changes they make. Issue 18 asks for
// motion a vehicle model allows. Then the ego per route (city.h's EgoRoute: free, the old
// placement, is the baseline): its mean speed, its largest yaw change from the first frame, the
// share of cities whose ego turns by 45 degrees or more, the starts tried, make_city's time, and
// the extremes of every vehicle's motion in those cities.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "flowscape/core/types.h"
#include "flowscape/scenes/city.h"

using namespace flowscape;
using V2 = Eigen::Vector2d;

namespace {

constexpr double kFrame = 1 / kFrameRate;

struct Extremes {
  double yaw_change = 0, acceleration = 0, braking = 0, lateral = 0, speed_sum = 0;
  long speed_samples = 0;
  int junction_peak = 0;
  long lane_changes = 0;  // a vehicle on a straight road heading off its axis by over 2 degrees
  long junction_frames = 0, shared_frames = 0;  // frames with vehicles in a junction / with two+
};

V2 ground(const Pose& p) { return p.translation().head<2>(); }

void measure_track(const PoseTrack& track, int frames, Extremes& e, bool ego, double* ego_change) {
  for (int f = 1; f + 1 < frames; ++f) {
    const Pose a = track((f - 1) * kFrame), b = track(f * kFrame), c = track((f + 1) * kFrame);
    const double rate0 = wrapped_angle(yaw_of(b) - yaw_of(a)) / kFrame;
    const double rate1 = wrapped_angle(yaw_of(c) - yaw_of(b)) / kFrame;
    const double v0 = (ground(b) - ground(a)).norm() / kFrame;
    const double v1 = (ground(c) - ground(b)).norm() / kFrame;
    const double change = std::abs(rate1 - rate0);
    if (ego) *ego_change = std::max(*ego_change, change);
    e.yaw_change = std::max(e.yaw_change, change);
    e.acceleration = std::max(e.acceleration, (v1 - v0) / kFrame);
    e.braking = std::max(e.braking, (v0 - v1) / kFrame);
    e.lateral = std::max(e.lateral, std::abs(rate1) * v1);
    e.speed_sum += v1, ++e.speed_samples;
  }
}

// Roads run along x or y (but one diagonal street); between junctions a vehicle heads off both
// axes only changing lanes (back to its heading, at most 18 degrees off), rounding a bend (onto
// the other axis) or on the diagonal (45 degrees off).
void count_lane_changes(const City& city, const PoseTrack& track, int frames, Extremes& e) {
  int start = -1;
  double most_off = 0;  // a lane change heads at most 18 degrees off, the diagonal street 45
  for (int f = 0; f < frames; ++f) {
    const Pose p = track(f * kFrame);
    const double off_axis = std::abs(std::remainder(yaw_of(p), kPi / 2));
    const bool now = city.area_at(ground(p)) == Area::Road && off_axis > 1e-6;
    if (now && start < 0) start = std::max(0, f - 1), most_off = 0;
    most_off = std::max(most_off, off_axis);
    if (now || start < 0) continue;
    e.lane_changes +=
        std::abs(std::remainder(yaw_of(p) - yaw_of(track(start * kFrame)), 2 * kPi)) < 1e-6 &&
        most_off < 20 * kPi / 180;
    start = -1;
  }
}

// Vehicles in junctions: per junction vehicle, the junction vehicles within 30 m (one junction).
void measure_junctions(const City& city, const std::vector<PoseTrack>& vehicles, int frames,
                       Extremes& e) {
  for (int f = 0; f < frames; ++f) {
    std::vector<V2> inside;
    for (const PoseTrack& track : vehicles) {
      const V2 p = ground(track(f * kFrame));
      if (city.area_at(p) == Area::Junction) inside.push_back(p);
    }
    int peak = 0;
    for (const V2& p : inside)
      peak = std::max(peak, int(std::count_if(inside.begin(), inside.end(),
                                              [&](const V2& q) { return (p - q).norm() < 30; })));
    e.junction_peak = std::max(e.junction_peak, peak);
    e.junction_frames += !inside.empty(), e.shared_frames += peak >= 2;
  }
}

double ego_turn_degrees(const PoseTrack& ego, int frames) {
  double turned = 0;
  for (int f = 1; f < frames; ++f)
    turned = std::max(turned,
                      std::abs(std::remainder(yaw_of(ego(f * kFrame)) - yaw_of(ego(0)), 2 * kPi)));
  return turned * 180 / kPi;
}

void ego_routes(int seeds, int frames) {
  std::printf("\n%-11s %-6s %9s %9s %8s %7s %9s %9s %7s %7s %7s\n", "map", "route", "speed m/s",
              "turn deg", "turn>=45", "tries", "s/city", "all dw", "accel", "brake", "lateral");
  for (int map = 0; map < kMapCount; ++map)
    for (EgoRoute route : {EgoRoute::Free, EgoRoute::Drive, EgoRoute::Turn}) {
      double speed = 0, turn = 0, seconds = 0, ego_change = 0;
      int turned = 0, tries = 0;
      Extremes e;
      for (int seed = 0; seed < seeds; ++seed) {
        CityConfig config;
        config.map = map, config.seed = std::uint64_t(seed), config.vehicles = 120;
        config.pedestrians = 80, config.duration = (frames + 1) * kFrame;
        config.ego_start = (11 * map + 37 * seed) % 100, config.ego_route = route;
        const auto start = std::chrono::steady_clock::now();
        const City city = make_city(config);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        speed += city.ego_distance((frames - 1) * kFrame) / ((frames - 1) * kFrame);
        const double degrees = ego_turn_degrees(city.ego, frames);
        turn += degrees, turned += degrees >= 45, tries += city.ego_tries;
        measure_track(city.ego, frames, e, true, &ego_change);
        for (std::size_t k = 0; k < city.actors.size(); ++k)
          if (city.actors[k].kind != ActorKind::Pedestrian)
            measure_track(city.scene.actors[k].pose, frames, e, false, &ego_change);
      }
      std::printf("%-11s %-6s %9.2f %9.1f %7.0f%% %7.1f %9.3f %9.3f %7.2f %7.2f %7.2f\n",
                  map_name(map).c_str(), route_name(route).c_str(), speed / seeds, turn / seeds,
                  100.0 * turned / seeds, double(tries) / seeds, seconds / seeds, e.yaw_change,
                  e.acceleration, e.braking, e.lateral);
    }
}

}  // namespace

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::stoi(argv[1]) : 2, frames = argc > 2 ? std::stoi(argv[2]) : 100;
  std::printf("%d cities per map, 120 vehicles + 80 pedestrians, %d frames at 30 Hz\n", seeds,
              frames);
  std::printf("%-11s %9s %9s %7s %7s %7s %6s %9s %8s %8s\n", "map", "ego dw", "all dw", "accel",
              "brake", "lateral", "speed", "junction", "shared", "lane");
  std::printf("%-11s %9s %9s %7s %7s %7s %6s %9s %8s %8s\n", "", "rad/s/fr", "rad/s/fr", "m/s2",
              "m/s2", "m/s2", "m/s", "peak", "frames", "changes");
  for (int map = 0; map < kMapCount; ++map) {
    Extremes e;
    double ego_change = 0;
    for (int seed = 0; seed < seeds; ++seed) {
      CityConfig config;
      config.map = map, config.seed = std::uint64_t(seed), config.vehicles = 120;
      config.pedestrians = 80, config.duration = frames * kFrame;
      config.ego_start = (11 * map + 37 * seed) % 100;
      const City city = make_city(config);
      std::vector<PoseTrack> vehicles{city.ego};
      for (std::size_t k = 0; k < city.actors.size(); ++k)
        if (city.actors[k].kind != ActorKind::Pedestrian)
          vehicles.push_back(city.scene.actors[k].pose);
      for (std::size_t k = 0; k < vehicles.size(); ++k) {
        measure_track(vehicles[k], frames, e, k == 0, &ego_change);
        count_lane_changes(city, vehicles[k], frames, e);
      }
      measure_junctions(city, vehicles, frames, e);
    }
    std::printf("%-11s %9.3f %9.3f %7.2f %7.2f %7.2f %6.2f %9d %7.0f%% %8ld\n",
                map_name(map).c_str(), ego_change, e.yaw_change, e.acceleration, e.braking,
                e.lateral, e.speed_sum / double(e.speed_samples), e.junction_peak,
                100.0 * double(e.shared_frames) / double(std::max(1L, e.junction_frames)),
                e.lane_changes);
  }
  std::printf(
      "(model: acceleration <= 2.5, braking <= 3, lateral <= 3 m/s^2, yaw-rate change <= "
      "0.118 rad/s per frame; before it, 4 x 300: 0.4-23.6 rad/s per frame, braking "
      "8.9-22.8, lateral 28-235 m/s^2, one vehicle per junction)\n");
  ego_routes(seeds, frames);
  return 0;
}
