#include "flowscape/release/gallery.h"

#include <cmath>

#include "flowscape/formats/contact_sheet.h"
#include "flowscape/formats/semantic_viz.h"
#include "flowscape/formats/srgb.h"
#include "flowscape/release/sequence.h"
#include "flowscape/scenes/city.h"
#include "flowscape/scenes/showcase.h"
#include "flowscape/weather/weather.h"

namespace flowscape {
namespace {

// A rig at `azimuth` (radians, 0: in front of the model, on its +x side) looking at the model's
// middle from a distance that frames it in a 40-degree view.
FramePair view_from(const Showcase& model, double azimuth) {
  const double size = std::max(model.length, 1.3 * model.height),
               distance = 1.2 * size / std::tan(0.35) / 2;
  const Vec3 target(0, 0, 0.45 * model.height);
  const Vec3 eye =
      target + Vec3(distance * std::cos(azimuth), distance * std::sin(azimuth), 0.3 * distance);
  const Vec3 forward = (target - eye).normalized(),
             left = Vec3::UnitZ().cross(forward).normalized(), up = forward.cross(left);
  Pose rig = Pose::Identity();
  rig.linear() << forward, left, up;
  rig.translation() = eye;
  return {1.0, 1.0 + 1 / kFrameRate, rig, rig};
}

// The model under a clear physical sky at `time`: once the lamps are on, a street lamp's light
// (1500 cd down a wide cone, as the maps' lamps) 6 m up, 4 m to the model's right.
void light_for(const std::string& time, Showcase& model) {
  apply_weather(at_time_of_day(weather_preset("sunny"), time, 0), 0, fixed_pose(), model.scene);
  model.scene.lamps.push_back(street_lamp_light(Vec3(0, -4, 6)));
}

// One model's row at `time` (empty: sky light): its four views, then its semantics.
std::vector<Image<std::uint8_t>> gallery_row(const std::string& name, const std::string& time,
                                             const GalleryOptions& o, const Projection& camera) {
  Showcase model = showcase(name, o.variant);
  if (!time.empty()) light_for(time, model);
  Renderer renderer(model.scene);
  std::vector<Image<std::uint8_t>> row;
  const std::pair<const char*, double> views[] = {
      {"front", 0}, {"side", kPi / 2}, {"back", kPi}, {"three-quarter", kPi / 5}};
  Image<std::uint8_t> semantic;
  for (const auto& [view, azimuth] : views) {
    const FramePair pair = view_from(model, azimuth);
    const GroundTruth gt = renderer.ground_truth(camera, pair);
    RenderOptions options;
    options.samples_per_pixel = o.color.spp, options.seed = 11;
    options.indirect_samples = indirect_samples(color_section(o.color));
    const ColorLayers layers = renderer.color_layers(camera, pair, options);
    const Image<float> color = release_denoiser(color_section(o.color))
                                   ->view(layers, camera, gt.depth.view(), gt.instance.view());
    row.push_back(linear_to_srgb8(color.view()));
    label_tile(row.back(), name + " " + view + (time.empty() ? "" : " " + time));
    if (semantic.data.empty()) semantic = semantic_to_color(gt.semantic.view());
  }
  row.push_back(std::move(semantic));
  return row;
}

}  // namespace

std::vector<std::vector<Image<std::uint8_t>>> actor_gallery(const GalleryOptions& o) {
  const std::vector<std::string> names = o.models.empty() ? showcase_models() : o.models;
  const std::vector<std::string> times =
      o.times_of_day.empty() ? std::vector<std::string>{""} : o.times_of_day;
  const Projection camera = Projection::pinhole(4 * o.height / 3, o.height, 40);
  std::vector<std::vector<Image<std::uint8_t>>> rows;
  for (const std::string& name : names)
    for (const std::string& time : times) rows.push_back(gallery_row(name, time, o, camera));
  return rows;
}

}  // namespace flowscape
