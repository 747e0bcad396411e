#include <catch2/catch.hpp>
#include <cmath>
#include <set>

#include "flowscape/formats/image_io.h"
#include "flowscape/formats/srgb.h"
#include "flowscape/renderer/renderer.h"
#include "flowscape/scenes/city.h"
#include "flowscape/scenes/test_scenes.h"
#include "flowscape/scenes/texture.h"
#include "flowscape/weather/weather.h"
#include "independent_math.h"
#include "temp_dir.h"
#include "weather/synthetic_sky.h"

using namespace flowscape;

namespace {

constexpr double kFrame = 1 / kFrameRate;  // one frame

struct WeatherFrame {
  GroundTruth truth;
  Image<float> color;
};

// One ERP frame of the suburb map under a weather, 1 s into the drive.
WeatherFrame render_city(const Weather& weather, bool drop_color_only = false) {
  CityConfig config;
  config.draw_ego = false;  // as a flowscape release has it
  config.map = 1, config.seed = 5, config.vehicles = 40, config.pedestrians = 20;
  config.ego_start = 20, config.duration = 1.2;
  City city = make_city(config);
  apply_weather(
      weather, 9, [&city](double t) { return city.rig(t); }, city.scene);
  if (drop_color_only)
    std::erase_if(city.scene.actors, [](const Actor& a) { return a.color_only; });
  Renderer renderer(city.scene);
  const FramePair frames{1.0, 1.0 + kFrame, city.rig(1.0), city.rig(1.0 + kFrame)};
  const Projection erp = Projection::equirectangular(64);
  return {renderer.ground_truth(erp, frames), renderer.color(erp, frames, {8, 4, 3})};
}

double luminance(const Image<float>& image, std::size_t pixel) {
  const float* p = &image.data[3 * pixel];
  return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

// Luminance of the light on level ground from the sun and the sky (after the exposure).
double level_light(const Weather& weather) {
  const Environment e = weather_environment(weather);
  const Eigen::Vector3f light = e.sky_dome->horizontal_irradiance() +
                                e.sun_irradiance * float(std::max(0.0, e.sun_direction.z()));
  return 0.2126 * light[0] + 0.7152 * light[1] + 0.0722 * light[2];
}

}  // namespace

TEST_CASE("the four weathers and the times of day change colour only and each in its own way") {
  const WeatherFrame sunny = render_city(weather_preset("sunny")),
                     cloud = render_city(weather_preset("cloud")),
                     fog = render_city(weather_preset("fog")),
                     rain = render_city(weather_preset("rain")),
                     dawn = render_city(at_time_of_day(weather_preset("sunny"), "dawn", 4)),
                     rainy_dusk = render_city(at_time_of_day(weather_preset("rain"), "-3", 4)),
                     night = render_city(at_time_of_day(weather_preset("wet"), "night", 4));
  for (const WeatherFrame* other : {&cloud, &fog, &rain, &dawn, &rainy_dusk, &night}) {
    CHECK(other->truth.flow.data == sunny.truth.flow.data);
    CHECK(other->truth.semantic.data == sunny.truth.semantic.data);
    CHECK(other->truth.instance.data == sunny.truth.instance.data);
    CHECK(other->truth.depth.data == sunny.truth.depth.data);
    CHECK(other->truth.valid.data == sunny.truth.valid.data);
    CHECK(other->color.data != sunny.color.data);
  }
  // fog: against the same light without fog, far things keep less of their contrast than near
  // things: the least-squares slope of fog luminance over clear luminance falls with distance
  // (about the transmittance exp(-sigma d); noise does not bias a slope); on the static world,
  // whose surfaces are lit the same way near and far (a car's windows mirror the sky, which fog
  // changes too)
  Weather clear = weather_preset("fog");
  clear.fog_density = 0;
  const WeatherFrame no_fog = render_city(clear);
  const auto slope = [&](double near, double far) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    for (std::size_t i = 0; i < no_fog.truth.depth.data.size(); ++i) {
      const double depth = no_fog.truth.depth.data[i];
      if (!(depth >= near && depth < far) || no_fog.truth.instance.data[i] != 0) continue;
      const double x = luminance(no_fog.color, i), y = luminance(fog.color, i);
      sx += x, sy += y, sxx += x * x, sxy += x * y, ++n;
    }
    REQUIRE(n > 50);
    return (sxy - sx * sy / n) / (sxx - sx * sx / n);
  };
  const double near_slope = slope(0, 10), far_slope = slope(40, 1e9);
  INFO("fog over clear luminance: slope near " << near_slope << ", far " << far_slope);
  CHECK(far_slope < 0.5 * near_slope);
  // rain: less light on the street than on a sunny day, even after the exposure (wet roads
  // mirroring a bright overcast can still make its frame as bright)
  CHECK(level_light(weather_preset("rain")) < 0.75 * level_light(weather_preset("sunny")));
  // rain streaks: the colour-only streaks (faint: opacity 0.13) and puddles change pixels the
  // ground truth never sees
  const WeatherFrame dry = render_city(weather_preset("rain"), true);
  int changed = 0;
  for (std::size_t i = 0; i < dry.truth.depth.data.size(); ++i)
    changed += std::abs(luminance(rain.color, i) - luminance(dry.color, i)) > 0.01;
  CHECK(changed > int(dry.truth.depth.data.size() / 300));
  CHECK(rain.truth.semantic.data == dry.truth.semantic.data);
}

TEST_CASE("a real HDR sky changes colour only") {
  TempDir maps;
  setenv("FLOWSCAPE_SKY_MAPS", maps.path.c_str(), 1);
  test::SyntheticSky sky;
  sky.sun = Vec3(0.5, -0.3, 0.6).normalized(), sky.sun_peak = 3000;
  write_image(maps.path / "sky.exr", test::synthetic_sky(sky));
  test::pin(maps.path / "sky.exr");
  const Weather sunny = weather_preset("sunny"), mapped = under_sky(sunny, "sky", 2);
  REQUIRE(mapped.sky_map == "sky");
  const WeatherFrame physical = render_city(sunny), real = render_city(mapped);
  unsetenv("FLOWSCAPE_SKY_MAPS");
  CHECK(real.truth.flow.data == physical.truth.flow.data);
  CHECK(real.truth.semantic.data == physical.truth.semantic.data);
  CHECK(real.truth.instance.data == physical.truth.instance.data);
  CHECK(real.truth.depth.data == physical.truth.depth.data);
  CHECK(real.truth.valid.data == physical.truth.valid.data);
  CHECK(real.color.data != physical.color.data);
}

TEST_CASE("a city's lamps and lit glass switch on after sunset and off by day") {
  CityConfig config;
  config.map = 0, config.seed = 2, config.vehicles = 6, config.pedestrians = 0;
  config.duration = 0.2;
  int on_rigid = 0;
  for (const char* time : {"day", "night"}) {
    City city = make_city(config);
    apply_weather(
        at_time_of_day(weather_preset("sunny"), time, 1), 1,
        [&city](double t) { return city.rig(t); }, city.scene);
    const bool night = std::string(time) == "night";
    int glowing = 0, lamp_materials = 0;
    for (const Material& m : city.scene.materials)
      if (!m.night_emission.isZero())
        ++lamp_materials, glowing += m.kind == Material::Kind::Emissive;
    CHECK(lamp_materials >= 3);  // street lamps, head and tail lamps
    CHECK(glowing == (night ? lamp_materials : 0));
    CHECK((city.scene.environment.lamp_level > 0) == night);
    // the traffic lights: red for one road and green for the other, only their lit lamp
    // glowing (the night pattern at the red lamp's centre, uv (0, 0.28), and the green's, (0,
    // -0.28))
    std::set<std::uint16_t> heads;
    for (std::size_t t = 0; t < city.scene.world.triangles.size(); ++t)
      if (city.scene.world.classes[t] == SemanticClass::TrafficLight)
        heads.insert(city.scene.world.materials[t]);
    int red = 0, green = 0;
    for (std::uint16_t index : heads) {
      const Material& m = city.scene.materials[index];
      REQUIRE(m.night_pattern);
      CHECK((m.kind == Material::Kind::Emissive && m.pattern == m.night_pattern) == night);
      const auto glow = [&](double v) {
        return (*m.night_pattern)({Vec2(0, v), Vec3::Zero(), 1e-3}, {m.albedo, m.roughness}).albedo;
      };
      CHECK(glow(0).isZero());  // amber is dark
      red += glow(0.28)[0] > 0.5 && glow(-0.28).isZero();
      green += glow(-0.28)[1] > 0.5 && glow(0.28).isZero();
    }
    CHECK(red == 1);
    CHECK(green == 1);
    // parked vehicles keep their lamps dark
    int parked = 0;
    for (std::size_t a = 0; a < city.actors.size(); ++a) {
      if (!city.actors[a].parked) continue;
      ++parked;
      for (const Part& part : city.scene.actors[a].parts)
        for (std::uint16_t m : part.materials)
          CHECK(city.scene.materials[m].kind != Material::Kind::Emissive);
    }
    CHECK(parked > 0);
    // street lamps along the roads and two beams per moving vehicle, on their actors
    on_rigid = 0;
    for (const Lamp& lamp : city.scene.lamps) on_rigid += lamp.actor >= 0;
    CHECK(city.scene.lamps.size() > std::size_t(on_rigid) + 20);
  }
  CHECK(on_rigid >= 2 * 5);
}

TEST_CASE("clouds soften the shadow of a box that the sun casts sharply") {
  const auto shadow_ratio = [](const std::string& preset) {
    Scene scene;
    add_box(scene.world, {-40, -40, -1}, {40, 40, 0}, SemanticClass::Ground);
    add_box(scene.world, {-1, -1, 0}, {1, 1, 2}, SemanticClass::Static);
    Weather weather = weather_preset(preset);
    weather.sun_elevation = 50, weather.sun_azimuth = 0;
    scene.environment = weather_environment(weather);
    Renderer renderer(scene);
    FramePair frames;
    frames.rig = frames.next_rig = Pose(Eigen::Translation3d(-2, 0, 8));
    const Projection down = Projection::cube_face(Face::Down, 48);
    const Image<float> image = renderer.color(down, frames, {32, 4, 1});
    // classify ground pixels by hand: the sun (elevation 50 deg, azimuth 0) casts the box's
    // shadow towards -x; a ground point is shaded if the ray to the sun passes through the box
    const Vec3 sun(std::cos(50 * indep::pi / 180), 0, std::sin(50 * indep::pi / 180));
    double shade = 0, lit = 0;
    int n_shade = 0, n_lit = 0;
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 48; ++x) {
        const Vec3 d = (frames.rig.linear() * down.ray(Vec2(x + 0.5, y + 0.5))).normalized();
        const Vec3 ground = frames.rig.translation() + (-8 / d.z()) * d;
        if (std::abs(ground.x()) < 1.3 && std::abs(ground.y()) < 1.3) continue;  // box or its rim
        // slab test of the segment ground + s sun against the box [-1,1]^2 x [0,2]
        double t0 = 0, t1 = 1e9;
        const Vec3 lo(-1, -1, 0), hi(1, 1, 2);
        for (int a = 0; a < 3; ++a) {
          if (std::abs(sun[a]) < 1e-12) {
            if (ground[a] < lo[a] || ground[a] > hi[a]) t1 = -1;
            continue;
          }
          double ta = (lo[a] - ground[a]) / sun[a], tb = (hi[a] - ground[a]) / sun[a];
          if (ta > tb) std::swap(ta, tb);
          t0 = std::max(t0, ta), t1 = std::min(t1, tb);
        }
        const double l = luminance(image, std::size_t(y) * 48 + x);
        if (t0 < t1)
          shade += l, ++n_shade;
        else
          lit += l, ++n_lit;
      }
    REQUIRE(n_shade > 20);
    return (shade / n_shade) / (lit / n_lit);
  };
  const double sunny = shadow_ratio("sunny"), cloud = shadow_ratio("cloud");
  INFO("shadow / light: sunny " << sunny << ", cloud " << cloud);
  CHECK(sunny < 0.45);
  CHECK(cloud > 0.7);
}

TEST_CASE("fog attenuates light by the optical depth of its height profile") {
  // an emissive wall seen through an absorbing fog (albedo 0) with no other light:
  // L = L_wall exp(-tau), tau = integral of sigma0 exp(-z / H) along the ray (derived by hand)
  const double distance = 30, sigma0 = 0.04, H = 12;
  for (double pitch_degrees : {0.0, 20.0}) {
    Scene scene = textured_plane(distance, 400);
    Material wall;
    wall.kind = Material::Kind::Emissive, wall.emission = {1, 1, 1};
    scene.materials = {wall};
    Environment& e = scene.environment;
    e.sun_irradiance = e.sky_zenith = e.sky_horizon = e.ground = Eigen::Vector3f::Zero();
    e.fog.density = sigma0, e.fog.height = H, e.fog.albedo = Eigen::Vector3f::Zero();
    const double pitch = pitch_degrees * indep::pi / 180, z0 = 1.5;
    FramePair frames;
    frames.rig = frames.next_rig =
        Pose(Eigen::Translation3d(0, 0, z0)) * Pose(Eigen::AngleAxisd(-pitch, Vec3::UnitY()));
    Renderer renderer(scene);
    const Projection camera = Projection::pinhole(8, 8, 2);
    const Image<float> image = renderer.color(camera, frames, {1024, 1, 4});
    double mean = 0;
    for (float v : image.data) mean += v;
    mean /= double(image.data.size());
    const double length = distance / std::cos(pitch), rise = std::sin(pitch);
    const double tau =
        rise == 0 ? sigma0 * std::exp(-z0 / H) * length
                  : sigma0 * std::exp(-z0 / H) * H / rise * (1 - std::exp(-length * rise / H));
    INFO("pitch " << pitch_degrees << " deg: tau " << tau);
    CHECK(mean == Approx(std::exp(-tau)).epsilon(0.02));
  }
}

TEST_CASE("weather presets and random variations round-trip through JSON") {
  CHECK(weather_presets().size() >= 4);
  for (const std::string& name : weather_presets()) {
    const Weather preset = weather_preset(name);
    for (std::uint64_t seed : {0u, 1u, 77u}) {
      const Weather w = randomized(preset, seed);
      CHECK_NOTHROW(validate(w));
      const Weather back = weather_from_json(nlohmann::json::parse(to_json(w).dump()));
      CHECK(to_json(back) == to_json(w));
      CHECK(to_json(randomized(preset, seed)) == to_json(w));  // reproducible from the seed
    }
    CHECK(to_json(randomized(preset, 1)) != to_json(randomized(preset, 2)));
  }
}

TEST_CASE("bad weather values are rejected with the value named") {
  CHECK_THROWS_WITH(weather_preset("snow"), Catch::Contains("unknown weather preset \"snow\""));
  nlohmann::json j = to_json(weather_preset("fog"));
  j["fog_density"] = -0.1;
  CHECK_THROWS_WITH(weather_from_json(j), Catch::Contains("fog_density"));
  j = to_json(weather_preset("rain"));
  j["cloudiness"] = std::nan("");
  CHECK_THROWS_WITH(weather_from_json(j), Catch::Contains("cloudiness"));
  j["cloudiness"] = "lots";
  CHECK_THROWS_WITH(weather_from_json(j), Catch::Contains("weather:"));
  j = to_json(weather_preset("sunny"));
  j["preset"] = "hail";
  CHECK_THROWS_WITH(weather_from_json(j), Catch::Contains("unknown weather preset"));
  Weather w = weather_preset("cloud");
  w.fog_height = 0;
  CHECK_THROWS_WITH(validate(w), Catch::Contains("fog_height"));
}
