#include <embree3/rtcore.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <sstream>

#include "../temp_dir.h"
#include "flowscape/renderer/ray_kernels.h"
#include "flowscape/renderer/renderer.h"
#include "flowscape/scenes/test_scenes.h"

using namespace flowscape;

namespace {

// FLOWSCAPE_EMBREE_CONFIG set for one scope, restored after it.
class EmbreeConfig {
 public:
  explicit EmbreeConfig(const std::string& config) {
    if (const char* before = std::getenv(kEmbreeConfigVariable)) before_ = before;
    setenv(kEmbreeConfigVariable, config.c_str(), 1);
  }
  ~EmbreeConfig() {
    if (before_)
      setenv(kEmbreeConfigVariable, before_->c_str(), 1);
    else
      unsetenv(kEmbreeConfigVariable);
  }

 private:
  std::optional<std::string> before_;
};

// What Embree itself prints about a device of `config` (verbose=1), from its standard output.
std::string embree_report(const std::string& config) {
  TempDir dir;
  const std::string file = (dir.path / "embree.txt").string();
  std::cout.flush(), std::fflush(stdout);
  const int saved = dup(STDOUT_FILENO);
  REQUIRE(std::freopen(file.c_str(), "w", stdout));
  RTCDevice device = rtcNewDevice((config + ",verbose=1").c_str());
  std::cout.flush(), std::fflush(stdout);
  dup2(saved, STDOUT_FILENO), close(saved);
  REQUIRE(device);
  rtcReleaseDevice(device);
  return file_bytes(file);
}

// The best kernel family of the "Targets : ... (supported)" line Embree prints for a device.
std::string reported_family(const std::string& report) {
  std::istringstream lines(report);
  std::string best;
  for (std::string line; std::getline(lines, line);) {
    if (line.find("(supported)") == std::string::npos) continue;
    std::istringstream words(line.substr(line.find(':') + 1));
    for (std::string word; words >> word && word != "(supported)";) {
      std::transform(word.begin(), word.end(), word.begin(),
                     [](unsigned char c) { return char(std::tolower(c)); });
      if (std::find(kKernelFamilies.begin(), kKernelFamilies.end(), word) != kKernelFamilies.end())
        best = word;
    }
  }
  return best;
}

}  // namespace

TEST_CASE("FLOWSCAPE_EMBREE_CONFIG picks each family this CPU runs, as Embree reports it") {
  const std::vector<std::string> families = cpu_kernel_families();
  REQUIRE(families.size() >= 2);  // every x86-64 CPU runs sse2; every one since 2008 sse4.2 too
  CHECK(families.front() == "sse2");
  for (const std::string& family : families) {
    CAPTURE(family);
    const EmbreeConfig config("isa=" + family);
    const RayKernels kernels = ray_kernels();
    CHECK(kernels.family == family);
    CHECK(kernels.config == "isa=" + family);
    CHECK(reported_family(embree_report("isa=" + family)) == family);
    CHECK(describe(kernels) == "Embree " + kernels.embree + ", " + family +
                                   " kernels (FLOWSCAPE_EMBREE_CONFIG=isa=" + family + ")");
  }
  // empty (as unset): Embree's best, which is this CPU's best family
  const EmbreeConfig unset("");
  CHECK(ray_kernels().family == families.back());
  CHECK(reported_family(embree_report("")) == families.back());
  CHECK(ray_kernels().embree.rfind("3.", 0) == 0);
}

TEST_CASE("max_isa caps the family, in the order Embree applies the items") {
  {
    const EmbreeConfig config("max_isa=sse4.2");
    CHECK(ray_kernels().family == "sse4.2");
  }
  {
    const EmbreeConfig config("isa=sse4.2, max_isa=sse2 threads=2");
    CHECK(ray_kernels().family == "sse2");
    CHECK(reported_family(embree_report("isa=sse4.2,max_isa=sse2")) == "sse2");
  }
}

TEST_CASE("a FLOWSCAPE_EMBREE_CONFIG Embree would misread is refused, naming the variable") {
  const Scene room = box_room();
  const auto refused = [&room](const std::string& text, const std::string& problem) {
    const EmbreeConfig config(text);
    CHECK_THROWS_WITH(embree_config(), "FLOWSCAPE_EMBREE_CONFIG=\"" + text + "\": " + problem);
    CHECK_THROWS_AS(Renderer(room), std::invalid_argument);
  };
  // Embree itself would run SSE2 kernels for an ISA name it does not know, and ignore the rest
  refused("isa=avx3",
          "unknown instruction set \"avx3\" (give one of sse2, sse4.2, avx, avx2, avx512)");
  refused("quality=high",
          "unknown key \"quality\" (isa, max_isa, threads, verbose and hugepages are taken)");
  refused("isa", "\"isa\" is not key=value");
  refused("threads=many", "threads wants a whole number (got \"many\")");
  const std::vector<std::string> families = cpu_kernel_families();
  if (families.back() != "avx512")
    refused(
        "isa=avx512", "this CPU has no avx512 (it runs " + [&] {
          std::string list;
          for (const std::string& f : families) list += (list.empty() ? "" : ", ") + f;
          return list;
        }() + ")");
}

namespace {

// A rig 1e30 m from the origin: a float coordinate Embree's kernels would assert on.
FramePair far_away() {
  FramePair frames;
  frames.rig.translation() = frames.next_rig.translation() = Vec3(1e30, 0, 0);
  return frames;
}

void require_pixel_error(const RayError& e, int width, int height, const std::string& camera) {
  CHECK(e.camera == camera);
  CHECK((e.x >= 0 && e.x < width && e.y >= 0 && e.y < height));
  CHECK_THAT(e.what(), Catch::StartsWith((camera.empty() ? "" : "camera " + camera + ", ") +
                                         "pixel (" + std::to_string(e.x) + ", " +
                                         std::to_string(e.y) + "): a ray from (1e+30, "));
  CHECK_THAT(e.problem,
             Catch::EndsWith("cannot be traced (Embree takes finite coordinates below 1.8e18)"));
}

template <class Render>
void throws_ray_error(Render&& render, int width, int height, const std::string& camera = "") {
  try {
    render();
    FAIL("no RayError");
  } catch (const RayError& e) {
    require_pixel_error(e, width, height, camera);
  }
}

}  // namespace

TEST_CASE("a ray Embree cannot take is an error naming the camera and pixel, never an abort") {
  const Scene room = box_room();
  Renderer renderer(room);
  const Projection pinhole = Projection::pinhole(12, 8, 90);
  RenderOptions options;
  options.samples_per_pixel = 2;
  throws_ray_error([&] { renderer.color(pinhole, far_away(), options); }, 12, 8);
  throws_ray_error([&] { renderer.ground_truth(pinhole, far_away()); }, 12, 8);
  Renderer one_by_one(room);
  one_by_one.trace_as({.single_rays = true});
  throws_ray_error([&] { one_by_one.ground_truth(pinhole, far_away()); }, 12, 8);
  throws_ray_error(
      [&] { renderer.ground_truth_at(pinhole, TruthRequest{far_away()}, {Vec2(3.5, 2.5)}); }, 1, 1);
  const CameraTrack far_track = [](double) { return far_away().rig; };
  throws_ray_error([&] { renderer.depth(pinhole, 0, far_track); }, 12, 8);
  // a rolling shutter: every line at its own time
  TruthRequest rolling{far_away()};
  rolling.readout = Readout{0.02, false};
  rolling.track = far_track;
  throws_ray_error([&] { renderer.ground_truth(pinhole, rolling); }, 12, 8);
  throws_ray_error([&] { renderer.color_layers(pinhole, 0, far_track, rolling.readout, options); },
                   12, 8);
  // the cube's faces name themselves
  throws_ray_error([&] { render_cube(renderer, 6, far_away(), nullptr); }, 6, 6, "cube front");
  throws_ray_error([&] { cube_color_layers(renderer, 6, far_away(), options); }, 6, 6,
                   "cube front");
  // and a caller that knows the camera names it
  try {
    renderer.ground_truth(pinhole, far_away());
  } catch (const RayError& e) {
    require_pixel_error(e.of_camera("front_left"), 12, 8, "front_left");
  }
}

TEST_CASE("a mesh with a vertex Embree cannot take is refused before anything is traced") {
  Scene room = box_room();
  room.world.vertices[0] = Eigen::Vector3f(2e6f, 0, 0);
  CHECK_THROWS_WITH(Renderer(room), "world mesh: a vertex is not finite or lies beyond 1,000 km");
  room.world.vertices[0] = Eigen::Vector3f(std::nanf(""), 0, 0);
  CHECK_THROWS_WITH(Renderer(room), "world mesh: a vertex is not finite or lies beyond 1,000 km");
}
