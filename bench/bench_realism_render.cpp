// bench_realism_render OUT [face size = 384] [frames = 10,60] [config.json]: the fixed set the
// actor-realism benchmark (bench/detector/bench_detector.py) runs a detector on. One sequence of
// each of the 8 maps (the release's first sequence of the map, its seed, ego route and traffic),
// the release's weather mix spread over the 8 (sunny x5, cloud, fog, rain), the six cube faces of
// two frames as the release renders them (colour denoised, sRGB), each with its instance and
// semantic image and depth (centimetres, 16-bit), and actors.json (every instance's kind, class
// and built-in family). A config.json
// (the gen_flowscape config keys) changes what the release would change (actor models, class
// table...); the set is by day unless its `times_of_day` says otherwise (cycled over the maps, like
// the weathers).
#include <tbb/parallel_for.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "flowscape/formats/image_io.h"
#include "flowscape/formats/srgb.h"
#include "flowscape/layout/meta.h"
#include "flowscape/release/config.h"
#include "flowscape/release/sequence.h"
#include "flowscape/scenes/actors.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

std::vector<int> parse_frames(const std::string& list) {
  std::vector<int> frames;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');) frames.push_back(std::stoi(item));
  return frames;
}

template <class T>
void write_faces(const fs::path& dir, const std::string& kind, const Image<T>& cube) {
  for (Face face : kFaces)
    write_image(dir / (std::string(face_name(face)) + "_" + kind + ".png"),
                face_view(cube.view(), face));
}

// Depth in centimetres (the sky and anything beyond 655 m: 65535), for telling what stands in front
// of an actor.
Image<std::uint16_t> depth_centimetres(const Image<float>& depth) {
  Image<std::uint16_t> out(depth.width, depth.height, 1);
  for (std::size_t k = 0; k < depth.data.size(); ++k)
    out.data[k] = std::uint16_t(std::min(65535.0, std::round(100.0 * double(depth.data[k]))));
  return out;
}

nlohmann::json actor_list(const Sequence& sequence) {
  nlohmann::json actors = nlohmann::json::object();
  const auto& records = sequence.city.actors;
  for (std::size_t a = 0; a < sequence.city.scene.actors.size(); ++a) {
    const Actor& actor = sequence.city.scene.actors[a];
    if (actor.color_only) continue;
    const std::string kind = a < records.size() ? kind_name(records[a].kind) : "other";
    nlohmann::json& record = actors[std::to_string(actor.instance)];
    record = {{"kind", kind}, {"class", int(actor_class(actor))}};
    if (a < records.size() && !records[a].family.empty()) record["family"] = records[a].family;
  }
  return actors;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_realism_render OUT [face size] [frames] [config.json]\n");
    return 2;
  }
  try {
    const fs::path out = argv[1];
    const int face_size = argc > 2 ? std::atoi(argv[2]) : 384;
    const std::vector<int> frames = parse_frames(argc > 3 ? argv[3] : "10,60");
    ReleaseConfig config;
    config.times_of_day = {"day"};
    if (argc > 4) {
      const std::vector<std::string> by_day = config.times_of_day;
      config = resolve_config({false, argv[4]});
      if (!read_json(argv[4]).contains("times_of_day")) config.times_of_day = by_day;
    }
    const std::vector<std::string> mix = ReleaseConfig{}.weathers;
    config.maps = kMapCount, config.sequences_per_map = 1;
    config.frames = *std::max_element(frames.begin(), frames.end()) + 1;
    for (const SequencePlan& plan : plan_sequences(config)) {
      SequenceSpec spec = sequence_spec(config, plan);
      spec.weather = mix[std::size_t(plan.map) % mix.size()];
      spec.time_of_day = config.times_of_day[std::size_t(plan.map) % config.times_of_day.size()];
      const Sequence sequence = make_sequence(spec);
      Renderer renderer(sequence.city.scene);
      for (int frame : frames) {
        const fs::path dir = out / (plan.name + "_" + std::to_string(frame));
        fs::create_directories(dir);
        const TruthRequest request{sequence.frame_pair(frame)};
        const RenderOptions options = sequence.color_options(color_section(config), frame);
        const CubeFrame cube = render_cube(renderer, face_size, request, &options);
        write_faces(dir, "color",
                    linear_to_srgb8(
                        denoised_cube_color(color_section(config), cube.color, cube.truth).view()));
        write_faces(dir, "instance", cube.truth.instance);
        write_faces(dir, "semantic", cube.truth.semantic);
        write_faces(dir, "depth", depth_centimetres(cube.truth.depth));
        std::ofstream(dir / "actors.json") << nlohmann::json{
            {"map", map_name(plan.map)},
            {"weather", spec.weather},
            {"time_of_day", spec.time_of_day},
            {"actors", actor_list(sequence)}}.dump();
        std::printf("%s frame %d (%s, %s)\n", plan.name.c_str(), frame, spec.weather.c_str(),
                    spec.time_of_day.c_str());
        std::fflush(stdout);
      }
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_realism_render: error: %s\n", e.what());
    return 1;
  }
}
