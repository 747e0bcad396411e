#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/layout/layout.h"
#include "flowscape/layout/meta.h"
#include "flowscape/release/dataset_card.h"
#include "flowscape/release/sequence.h"
#include "flowscape/release/writer.h"
#include "independent_math.h"
#include "temp_dir.h"
#include "tiny_release.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

struct Counts {
  int done = 0, skipped = 0;
};

Counts write(const ReleaseConfig& config, const fs::path& out) {
  Counts counts;
  write_sequence(config, plan_sequences(config).front(), out,
                 {[&] { ++counts.done; }, [&] { ++counts.skipped; }});
  return counts;
}

int pixel_type_index(PixelType type) {
  return type == PixelType::UInt8 ? 0 : type == PixelType::UInt16 ? 1 : 2;
}

}  // namespace

TEST_CASE("the writer makes every file of the layout, each as its row of the table says") {
  TempDir dir;
  const ReleaseConfig config = tiny_release_config();
  REQUIRE(write(config, dir.path).done == 3);
  const fs::path seq = sequence_dir(dir.path, "map00_seq00");
  CHECK(read_meta(seq).frames == 3);
  int files = 0;
  for (int f = 0; f < 3; ++f)
    for (const fs::path& file : release_layout(config).frame_files(f, 3)) {
      INFO(file);
      const bool cube = file.begin()->string() == "cube";
      const int width = cube ? 8 : 32, height = cube ? 8 : 16;
      const OutputKind& kind = *release_kind(file.parent_path().filename().string())->row;
      if (kind.is_flow()) {
        const Flow flow = read_flo(seq / file);
        CHECK((flow.uv.width == width && flow.uv.height == height));
      } else {
        const AnyImage image = read_any_image(seq / file);
        CHECK(int(image.index()) == pixel_type_index(kind.pixel));
        std::visit(
            [&](const auto& i) {
              CHECK((i.width == width && i.height == height && i.channels == kind.channels));
              // encoded at the row's PNG level (colour 2, every ground-truth kind libpng's
              // default 6 as before, so its bytes are flowscape 0.10's) and EXR zip
              const std::vector<unsigned char> expected =
                  encode_image(file, i.view(), {}, Compression{kind.png_level, "zip"});
              CHECK(file_bytes(seq / file) == std::string(expected.begin(), expected.end()));
              CHECK(kind.png_level == (kind.name == "color" || kind.name == "final" ? 2 : 6));
            },
            image);
      }
      ++files;
    }
  // per view: the six (the last frame four), normal on every frame, scene flow on frames 0 and 1,
  // backward flow and valid on frames 1 and 2
  CHECK(files == 7 * ((6 + 6 + 4) + 3 + 2 + 2 * 2));
}

// The sky is at infinity: its flow is the rig's rotation only, derived here from the poses that
// meta.json records with the hand-written ERP formulas.
TEST_CASE("the ERP flow of the sky is the rotation between the recorded rig poses") {
  TempDir dir;
  ReleaseConfig config = tiny_release_config(1, 3);
  config.height = 24, config.cube = false;
  write(config, dir.path);
  const fs::path seq = sequence_dir(dir.path, "map00_seq00");
  const SequenceMeta meta = read_meta(seq);
  const int W = 48;
  for (int f = 0; f < 2; ++f) {
    const Flow flow = read_flo(seq / frame_file(output_kind("flow"), std::nullopt, f));
    const Image<std::uint8_t> semantic =
        read_image<std::uint8_t>(seq / frame_file(output_kind("semantic"), std::nullopt, f));
    const Mat3 turn = meta.poses[f + 1].linear().transpose() * meta.poses[f].linear();
    int sky = 0;
    for (int y = 0; y < 24; ++y)
      for (int x = 0; x < W; ++x) {
        if (*semantic.pixel(x, y) != 13) continue;
        const indep::V3 d = indep::erp_direction(x + 0.5, y + 0.5, W);
        const Vec3 seen = turn * Vec3(d.x, d.y, d.z);
        const indep::V3 e{seen.x(), seen.y(), seen.z()};
        double u = (indep::longitude(e) + indep::pi) * W / (2 * indep::pi) - (x + 0.5);
        u = u > W / 2.0 ? u - W : u <= -W / 2.0 ? u + W : u;
        const double v = (indep::latitude(e) + indep::pi / 2) * 24 / indep::pi - (y + 0.5);
        REQUIRE(flow.uv.pixel(x, y)[0] == Approx(u).margin(2e-3));
        REQUIRE(flow.uv.pixel(x, y)[1] == Approx(v).margin(2e-3));
        ++sky;
      }
    CHECK(sky > 100);
  }
}

TEST_CASE("a rerun skips finished frames and redoes a damaged one to the same bytes") {
  TempDir dir;
  const ReleaseConfig config = tiny_release_config();
  write(config, dir.path);
  const fs::path seq = sequence_dir(dir.path, "map00_seq00");
  const fs::path lost = seq / frame_file(output_kind("depth"), Face::Up, 1);
  const fs::path kept = seq / frame_file(output_kind("color"), std::nullopt, 1);
  const std::string lost_bytes = file_bytes(lost), kept_bytes = file_bytes(kept);
  const Counts again = write(config, dir.path);
  CHECK((again.done == 0 && again.skipped == 3));
  fs::remove(lost);
  std::ofstream(seq / "erp" / "flow" / ".partial-4242-000001.flo") << "half";  // a killed run's
  const Counts redo = write(config, dir.path);
  CHECK((redo.done == 1 && redo.skipped == 2));
  CHECK(file_bytes(lost) == lost_bytes);
  CHECK(file_bytes(kept) == kept_bytes);
  CHECK_FALSE(fs::exists(seq / "erp" / "flow" / ".partial-4242-000001.flo"));
}

TEST_CASE("compressed flow: the flow files keep the flow to the format, nothing else moves") {
  TempDir flo_dir, dir;
  ReleaseConfig config = tiny_release_config();
  write(config, flo_dir.path);
  const ReleaseLayout flo_layout = release_layout(config);
  for (const char* format : {"kitti-png", "half-exr"}) {
    INFO(format);
    config.flow_format = format;
    const fs::path out = dir.path / format;
    write(config, out);
    const ReleaseLayout layout = release_layout(config);
    const fs::path seq = sequence_dir(out, "map00_seq00"),
                   flo_seq = sequence_dir(flo_dir.path, "map00_seq00");
    int flows = 0;
    for (int f = 0; f < 3; ++f) {
      const std::vector<fs::path> files = layout.frame_files(f, 3),
                                  flo_files = flo_layout.frame_files(f, 3);
      REQUIRE(files.size() == flo_files.size());
      for (std::size_t k = 0; k < files.size(); ++k) {
        INFO(files[k]);
        if (files[k].extension() == flo_files[k].extension()) {  // every other kind's bytes
          CHECK(file_bytes(seq / files[k]) == file_bytes(flo_seq / flo_files[k]));
          continue;
        }
        const FlowFormat stored = flow_format_from_name(format);
        CHECK(files[k].extension() == flow_format_extension(stored));
        CHECK(read_flow(seq / files[k]).uv.data ==
              stored_flow(stored, read_flo(flo_seq / flo_files[k]).uv.view()).data);
        ++flows;
      }
    }
    CHECK(flows == 7 * (2 + 2));  // forward on frames 0, 1 and backward on 1, 2, in seven views
    // statistics read back from the files on resume are those of the flow as stored
    const std::string meta = file_bytes(seq / kMetaFile);
    fs::remove(seq / frame_file(*layout.find("color"), std::nullopt, 0));
    fs::remove(seq / kMetaFile);
    CHECK(write(config, out).done == 1);
    CHECK(file_bytes(seq / kMetaFile) == meta);
  }
}

TEST_CASE(
    "bench_release's baseline (0.10's order and renderer) writes every ground-truth byte the same, "
    "and colour within its noise") {
  TempDir dir;
  ReleaseConfig config = tiny_release_config(1, 2);
  config.height = 48, config.face_size = 48, config.spp = 8;  // the default samples: noise small
  const SequencePlan plan = plan_sequences(config).front();
  write_sequence(config, plan, dir.path / "new", {[] {}, [] {}});
  const TracingBaseline earlier{.single_rays = true, .full_sky_when_scattered = true};
  write_sequence(config, plan, dir.path / "old", {[] {}, [] {}}, &earlier);
  const fs::path now = sequence_dir(dir.path / "new", plan.name),
                 before = sequence_dir(dir.path / "old", plan.name);
  const ReleaseLayout layout = release_layout(config);
  int colour = 0, truth = 0;
  // the largest mean absolute difference of a colour image (the noise drawn otherwise) and the
  // largest difference of its mean (a bias), in 8-bit levels
  double noise = 0, bias = 0;
  for (int f = 0; f < config.frames; ++f)
    for (const fs::path& file : layout.frame_files(f, config.frames)) {
      INFO(file);
      if (std::find(file.begin(), file.end(), fs::path("color")) == file.end()) {
        CHECK(file_bytes(now / file) == file_bytes(before / file));
        ++truth;
        continue;
      }
      const Image<std::uint8_t> a = read_image<std::uint8_t>(now / file),
                                b = read_image<std::uint8_t>(before / file);
      REQUIRE(a.data.size() == b.data.size());
      double absolute = 0, signed_sum = 0;
      for (std::size_t i = 0; i < a.data.size(); ++i) {
        const int d = int(a.data[i]) - b.data[i];
        absolute += std::abs(d), signed_sum += d;
      }
      noise = std::max(noise, absolute / double(a.data.size()));
      bias = std::max(bias, std::abs(signed_sum) / double(a.data.size()));
      ++colour;
    }
  CHECK(colour > 0);
  CHECK(truth > colour);
  CHECK(noise > 0);  // 0.10's renderer draws its sky samples otherwise (0.41 levels here)
  CHECK(noise < 1.5);
  CHECK(bias < 0.4);  // 0.14 here
}

TEST_CASE("a rig's cameras each write every kind in their own folder, and meta.json says how") {
  TempDir dir;
  ReleaseConfig config = tiny_release_config(1, 2);
  config.rig = "woodscape";
  write(config, dir.path);
  const fs::path seq = sequence_dir(dir.path, "map00_seq00");
  const ReleaseLayout layout = release_layout(config);
  REQUIRE(layout.cameras.size() == 4);
  CHECK_FALSE(layout.has_erp());
  CHECK_FALSE(fs::exists(seq / "erp"));
  for (const fs::path& file : layout.sequence_files(2)) {
    INFO(file);
    REQUIRE(fs::exists(seq / file));
    if (file.begin()->string() != "cameras") continue;
    const OutputKind& kind = *release_kind(file.parent_path().filename().string())->row;
    if (kind.is_flow()) continue;
    const AnyImage image = read_any_image(seq / file);
    std::visit([&](const auto& i) { CHECK((i.width == 20 && i.height == 16)); }, image);
  }
  const nlohmann::json meta = read_json(seq / "meta.json");
  const nlohmann::json& front = meta["views"]["cameras/front"];
  CHECK(front["model"] == "woodscape");
  CHECK(front["translation_in_rig"] == nlohmann::json{2.0, 0.0, -1.0});
  CHECK(meta["rig"]["name"] == "woodscape");
  // the camera's pose per frame: the rig's pose times its mount
  REQUIRE(front["poses"].size() == 2);
  const std::vector<double> rig = meta["poses"][1], camera = front["poses"][1];
  Pose rig_pose = Pose::Identity(), camera_pose = Pose::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c)
      rig_pose.matrix()(r, c) = rig[std::size_t(4 * r + c)],
                           camera_pose.matrix()(r, c) = camera[std::size_t(4 * r + c)];
  CHECK(camera_pose.translation().isApprox(rig_pose * Vec3(2, 0, -1), 1e-9));
  CHECK(camera_pose.linear().isApprox(rig_pose.linear() * look(0, -20, 0), 1e-9));
  // outside the image circle: nothing, in every kind
  const Image<float> depth = read_image<float>(seq / "cameras/front/depth/000000.exr");
  const Image<std::uint8_t> valid =
      read_image<std::uint8_t>(seq / "cameras/front/valid/000000.png");
  CHECK(std::isnan(*depth.pixel(0, 0)));
  CHECK(*valid.pixel(0, 0) == 0);
  CHECK(std::isfinite(*depth.pixel(10, 8)));
}

TEST_CASE("a rolling-shutter camera writes its capture times and meta.json records its readout") {
  TempDir dir;
  const fs::path rig_file = dir.path / "rolling.json";
  std::ofstream(rig_file) << R"({"name": "rolling", "cameras": [{"name": "front",
    "model": "pinhole", "parameters": {"width": 24, "height": 16,
    "K": [[12, 0, 11.5], [0, 12, 7.5], [0, 0, 1]]},
    "mount": {"position": [0, 0, 0], "yaw_pitch_roll_degrees": [0, 0, 0]},
    "rolling_shutter": {"readout_ms": 32, "lines": "rows"}}]})";
  ReleaseConfig config = tiny_release_config(1, 2);
  config.rig = rig_file.string();
  config.outputs = {"time"};
  const fs::path out = dir.path / "release";
  write(config, out);
  const fs::path seq = sequence_dir(out, "map00_seq00");
  for (int frame : {0, 1}) {
    char name[32];
    std::snprintf(name, sizeof name, "cameras/front/time/%06d.exr", frame);
    const Image<float> time = read_image<float>(seq / name);
    for (int y = 0; y < 16; ++y)  // the frame's time plus 32 ms x ((y + 1/2) / 16 - 1/2)
      CHECK(*time.pixel(5, y) ==
            Approx(frame / 30.0 + 0.032 * ((y + 0.5) / 16 - 0.5)).epsilon(1e-6));
  }
  const nlohmann::json meta = read_json(seq / "meta.json");
  CHECK(meta["views"]["cameras/front"]["rolling_shutter"]["readout_s"] == 0.032);
  CHECK(meta["rig"]["cameras"][0]["rolling_shutter"]["readout_ms"] == 32.0);
  // the flow is found for most pixels, and a valid pixel's flow is always known
  const Flow flow = read_flo(seq / "cameras/front/flow/000000.flo");
  const Image<std::uint8_t> valid =
      read_image<std::uint8_t>(seq / "cameras/front/valid/000000.png");
  int found = 0;
  for (int i = 0; i < 24 * 16; ++i)
    if (valid.data[std::size_t(i)]) {
      ++found;
      CHECK(std::abs(flow.uv.data[std::size_t(2 * i)]) < 100);
    }
  CHECK(found > 24 * 16 / 2);
}

// Opt-in asset packs: each actor showing a pack's model names it and its licence in meta.json, and
// the card's licence lists them. Runs where Debian's torcs-data is installed (333 MB, not in CI).
TEST_CASE("an asset pack's models carry their licence into meta.json and the card") {
  ReleaseConfig config = tiny_release_config(1, 2);
  config.weathers = {"sunny"};
  config.asset_packs = {"flightgear"};
  CHECK_THROWS_WITH(validate(config), Catch::Contains("unknown asset pack \"flightgear\""));
  config.asset_packs = {"torcs"}, config.actors = "legacy";
  if (!fs::is_directory("/usr/share/games/torcs/cars")) {
    WARN("torcs-data is not installed: the pack's release is not checked");
    return;
  }
  CHECK_THROWS_WITH(validate(config), Catch::Contains("asset_packs need detailed actors"));
  config.actors = "detailed", config.vehicles = 12;
  TempDir dir;
  write(config, dir.path);
  nlohmann::json meta;
  std::ifstream(sequence_dir(dir.path, "map00_seq00") / "meta.json") >> meta;
  const std::map<std::string, std::string> licences{{"torcs/p406", "GPL-2+"},
                                                    {"torcs/baja-bug", "Free Art License 1.3"},
                                                    {"torcs/acura-nsx-sz", "Free Art License 1.3"}};
  int shown = 0, cars = 0;
  for (const nlohmann::json& actor : meta["actors"]) {
    if (actor["kind"] == "car" && !actor.contains("ego")) ++cars;
    if (!actor.contains("model")) continue;
    ++shown;
    INFO(actor["model"]);
    CHECK(actor["kind"] == "car");
    CHECK(actor["licence"] == licences.at(actor["model"].get<std::string>()));
    // the model is scaled to its car's length, and it stands on its wheels on the road
    const nlohmann::json& box = actor["fixed_box"];
    CHECK((box["size"][0].get<double>() > 3.5 && box["size"][0].get<double>() < 5.2));
    CHECK(std::abs(box["centre_in_actor"][2].get<double>() - box["size"][2].get<double>() / 2) <
          0.05);
  }
  CHECK((shown > 0 && shown < cars));  // a quarter of the cars, by instance
  write_dataset_card(dir.path, config, nullptr);
  std::ifstream card(dir.path / "README.md");
  const std::string text((std::istreambuf_iterator<char>(card)), std::istreambuf_iterator<char>());
  CHECK_THAT(text, Catch::Contains("| torcs/p406 | GPL-2+ |") &&
                       Catch::Contains("| torcs/baja-bug | Free Art License 1.3 |") &&
                       Catch::Contains("also under that model's licence"));
}

TEST_CASE("the final pass leaves the clean colour and the ground truth as they were, and resumes") {
  TempDir clean_dir, final_dir;
  ReleaseConfig config = tiny_release_config(1, 4);
  config.spp = 4;
  write(config, clean_dir.path);
  config.outputs.push_back("final");
  write(config, final_dir.path);
  const fs::path clean = sequence_dir(clean_dir.path, "map00_seq00"),
                 with_final = sequence_dir(final_dir.path, "map00_seq00");
  int compared = 0;
  for (const fs::path& file : release_layout(tiny_release_config(1, 4)).frame_files(2, 4)) {
    CHECK(file_bytes(with_final / file) == file_bytes(clean / file));
    ++compared;
  }
  CHECK(compared > 20);
  const fs::path final_erp = with_final / frame_file(output_kind("final"), std::nullopt, 2);
  const fs::path final_face = with_final / frame_file(output_kind("final"), Face::Front, 2);
  REQUIRE(fs::exists(final_erp));
  REQUIRE(fs::exists(final_face));
  CHECK(file_bytes(final_erp) !=
        file_bytes(clean / frame_file(output_kind("color"), std::nullopt, 2)));
  const SequenceMeta meta = read_meta(with_final);
  REQUIRE(meta.final.at("exposures").size() == 4);
  CHECK(meta.final.at("shutter_angle") == 180);
  CHECK(meta.final.at("exposures")[3].at("adapted_key").get<double>() > 0);
  // a resumed sequence: the same final bytes and exposures as one made in one go
  const std::string final_bytes = file_bytes(final_erp);
  const nlohmann::json exposures = meta.final.at("exposures");
  fs::remove(final_erp);
  fs::remove(with_final / frame_file(output_kind("final"), std::nullopt, 3));
  write(config, final_dir.path);
  CHECK(file_bytes(final_erp) == final_bytes);
  CHECK(read_meta(with_final).final.at("exposures") == exposures);
}

TEST_CASE("drops on a real lens: final shows them, lens_mask marks them, the ground truth holds") {
  TempDir dry_dir, wet_dir;
  ReleaseConfig config = tiny_release_config(1, 2);
  config.rig = "fisheye", config.spp = 2, config.height = 48;
  config.outputs = {"final", "lens_mask"};
  config.lens_drops = 0;
  write(config, dry_dir.path);
  config.lens_drops = 30, config.lens_dirt = 0.7;
  write(config, wet_dir.path);
  const fs::path dry = sequence_dir(dry_dir.path, "map00_seq00"),
                 wet = sequence_dir(wet_dir.path, "map00_seq00");
  const auto file = [](const char* kind, int frame) {
    return frame_file(output_kind(kind), View::of_camera("front"), frame);
  };
  for (const char* kind : {"color", "flow", "depth", "semantic", "instance", "valid"})
    CHECK(file_bytes(wet / file(kind, 0)) == file_bytes(dry / file(kind, 0)));
  CHECK(file_bytes(wet / file("final", 0)) != file_bytes(dry / file("final", 0)));
  const Image<std::uint8_t> dry_mask = read_image<std::uint8_t>(dry / file("lens_mask", 0));
  const Image<std::uint8_t> mask = read_image<std::uint8_t>(wet / file("lens_mask", 0));
  CHECK(std::count(dry_mask.data.begin(), dry_mask.data.end(), 1) == 0);
  CHECK(std::count(mask.data.begin(), mask.data.end(), 1) > 0);
  const Image<float> depth = read_image<float>(wet / file("depth", 0));
  for (std::size_t i = 0; i < mask.data.size(); ++i)  // nothing to hide outside the image circle
    if (std::isnan(depth.data[i])) CHECK(mask.data[i] == 0);
  // the cover stays on the lens for the whole sequence
  CHECK(file_bytes(wet / file("lens_mask", 1)) == file_bytes(wet / file("lens_mask", 0)));
  CHECK(read_meta(wet).final.at("lens_drops") == 30);
}

TEST_CASE("a release grows by maps: the sequences it had keep their bytes") {
  // issue 35, point 6: more sequences needed --force and a full re-render
  TempDir dir;
  ReleaseConfig config = tiny_release_config(1, 2);
  config.sequences_per_map = 2, config.spp = 1;
  write_release(config, dir.path, false);
  const fs::path first = sequence_dir(dir.path, "map00_seq01");
  std::map<fs::path, std::string> before;
  for (const auto& entry : fs::recursive_directory_iterator(first))
    if (entry.is_regular_file()) before[entry.path()] = file_bytes(entry.path());
  config.maps = 2;
  write_release(config, dir.path, false);  // no --force: it only adds map 1
  for (const auto& [path, bytes] : before) CHECK(file_bytes(path) == bytes);
  CHECK(fs::exists(sequence_dir(dir.path, "map01_seq01") / "meta.json"));
  CHECK(read_json(dir.path / "config.json")["maps"] == 2);
  config.maps = 1;  // shrinking is another release
  CHECK_THROWS_WITH(write_release(config, dir.path, false),
                    Catch::Contains("this release was made with another config"));
}

TEST_CASE("adaptive sampling changes the colour and nothing else, and the card says so") {
  for (const bool cube : {true, false}) {  // the faces' colour, or the ERP's traced directly
    INFO("cube " << cube);
    TempDir uniform_dir, adaptive_dir;
    ReleaseConfig config = tiny_release_config(1, 2);
    config.spp = 8, config.cube = cube;
    write(config, uniform_dir.path);
    config.adaptive = 0.25;
    write(config, adaptive_dir.path);
    const fs::path uniform = sequence_dir(uniform_dir.path, "map00_seq00"),
                   adaptive = sequence_dir(adaptive_dir.path, "map00_seq00");
    int truth = 0, changed = 0;
    for (const fs::path& file : release_layout(config).frame_files(0, 2)) {
      INFO(file);
      if (file.string().find("color") != std::string::npos) {
        changed += file_bytes(adaptive / file) != file_bytes(uniform / file);
      } else {
        CHECK(file_bytes(adaptive / file) == file_bytes(uniform / file));
        ++truth;
      }
    }
    CHECK(truth > (cube ? 20 : 5));
    CHECK(changed == (cube ? 7 : 1));  // the ERP and the six faces
    write_dataset_card(adaptive_dir.path, config, nullptr);
    std::ifstream card(adaptive_dir.path / "README.md");
    const std::string text((std::istreambuf_iterator<char>(card)),
                           std::istreambuf_iterator<char>());
    CHECK_THAT(text, Catch::Contains("the other half on the 25 % of the pixels"));
  }
}
