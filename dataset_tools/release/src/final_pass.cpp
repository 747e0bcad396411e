#include "flowscape/release/final_pass.h"

#include <vector>

#include "flowscape/core/profile.h"
#include "flowscape/core/random.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/formats/srgb.h"

namespace flowscape {
namespace {

// Colour in the clean pass's units (the sequence's exposure applied) to cd/m^2.
double nits_per_value(const Sequence& sequence) {
  return kNitsPerUnit / sequence.city.scene.environment.exposure;
}

}  // namespace

SensorModel release_sensor(const FinalPassSection& c) {
  SensorModel sensor;
  sensor.pixel_pitch = c.pixel_pitch * 1e-6;
  sensor.noise = c.sensor_noise, sensor.vignetting = c.vignetting, sensor.glare = c.lens_glare;
  sensor.chromatic_aberration = c.chromatic_aberration, sensor.bayer = c.bayer;
  return sensor;
}

Shutter frame_shutter(const FinalPassSection& final_pass, const Sequence& sequence, int frame) {
  return centred_shutter(sequence.time(frame), final_pass.shutter_angle, sequence.spec.frame_rate);
}

Exposure exposure_after(const FinalPassSection& final_pass, const Sequence& sequence,
                        const Exposure& previous, ImageView<const std::uint8_t> clean,
                        const Projection& camera, int frame) {
  std::vector<float> covered;  // the nits of the pixels the camera has an image at
  const double scale = nits_per_value(sequence);
  for (int y = 0; y < clean.height; ++y)
    for (int x = 0; x < clean.width; ++x)
      if (!camera.ray(Vec2(x + 0.5, y + 0.5)).isZero())
        for (int c = 0; c < 3; ++c)
          covered.push_back(float(srgb8_to_linear(clean.pixel(x, y)[c]) * scale));
  const ImageView<const float> nits{int(covered.size() / 3), 1, 3, covered.data()};
  const Shutter shutter = frame_shutter(final_pass, sequence, frame);
  return auto_exposure(release_sensor(final_pass), previous, key_luminance(nits),
                       1 / sequence.spec.frame_rate, shutter.close - shutter.open);
}

Image<float> final_color(const ColorSection& color_settings, const FinalPassSection& final_pass,
                         const Sequence& sequence, Renderer& renderer, const Projection& camera,
                         const CameraTrack& track, int frame, const Readout& readout) {
  const RenderOptions options = shutter_options(sequence.color_options(color_settings, frame));
  const Shutter shutter = frame_shutter(final_pass, sequence, frame);
  const ColorLayers layers = [&] {
    const ScopedPhase phase("final pass: path tracing");
    return renderer.color_layers(camera, shutter, track, readout, options);
  }();
  const Image<float> depth = [&] {
    if (!release_denoiser(color_settings)->guided_by_depth()) return Image<float>{};
    const ScopedPhase phase("final pass: depth guide");
    return renderer.depth(camera, shutter, track, readout);
  }();
  const Image<std::uint16_t> no_ids(camera.width, camera.height, 1);
  return denoised_color(color_settings, layers, camera, depth.view(), no_ids.view());
}

Image<float> final_cube_color(const ColorSection& color_settings,
                              const FinalPassSection& final_pass, int face_size,
                              const Sequence& sequence, Renderer& renderer, int frame) {
  const RenderOptions options = shutter_options(sequence.color_options(color_settings, frame));
  const CubeFrame cube = shutter_cube(
      renderer, face_size, frame_shutter(final_pass, sequence, frame),
      [&](double t) { return sequence.city.rig(t); }, options,
      release_denoiser(color_settings)->guided_by_depth());
  return denoised_cube_color(color_settings, cube.color, cube.truth);
}

namespace {

int lens_drops(const FinalPassSection& final_pass, const Sequence& sequence) {
  if (final_pass.lens_drops >= 0) return final_pass.lens_drops;
  const double rain = sequence.weather.precipitation;
  return rain > 0 ? std::max(1, int(std::lround(24 * rain))) : 0;
}

}  // namespace

LensCover release_lens_cover(const FinalPassSection& final_pass, const Sequence& sequence,
                             const Projection& camera, int view) {
  return lens_cover(camera.width, camera.height, lens_drops(final_pass, sequence),
                    final_pass.lens_dirt,
                    derived_seed(sequence.spec.city.seed, std::uint64_t(view), 11));
}

Image<std::uint8_t> release_lens_mask(const FinalPassSection& final_pass, const Sequence& sequence,
                                      const Projection& camera, int view) {
  Image<std::uint8_t> mask = cover_mask(release_lens_cover(final_pass, sequence, camera, view),
                                        camera.width, camera.height);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x)
      if (!camera.covers(Vec2(x + 0.5, y + 0.5))) *mask.pixel(x, y) = 0;
  return mask;
}

Image<std::uint8_t> develop(const FinalPassSection& final_pass, const Sequence& sequence,
                            ImageView<const float> color, const Projection& camera, bool lens,
                            const Exposure& exposure, int frame, int view) {
  const ScopedPhase phase("final pass: sensor and lens");
  SensorModel sensor = release_sensor(final_pass);
  if (!lens) sensor.vignetting = false, sensor.chromatic_aberration = 0;
  Image<float> nits(color.width, color.height, 3);
  const double scale = nits_per_value(sequence);
  for (std::size_t i = 0; i < nits.data.size(); ++i) nits.data[i] = float(color.data[i] * scale);
  if (lens) {
    const LensCover cover = release_lens_cover(final_pass, sequence, camera, view);
    if (!cover.empty()) nits = through_cover(nits.view(), cover);
  }
  const Shutter shutter = frame_shutter(final_pass, sequence, frame);
  const Image<float> raw =
      sensor_raw(lens_image(nits.view(), camera, sensor).view(), sensor, exposure,
                 shutter.close - shutter.open,
                 derived_seed(sequence.color_seed(frame), std::uint64_t(view), 3));
  const Image<std::uint8_t> display = linear_to_srgb8(tone_map(raw.view(), sensor).view());
  return final_pass.jpeg_quality > 0 ? jpeg_round_trip(display.view(), final_pass.jpeg_quality)
                                     : display;
}

nlohmann::json final_json(const FinalPassSection& final_pass, const Sequence& sequence,
                          const std::vector<Exposure>& exposures) {
  const SensorModel s = release_sensor(final_pass);
  nlohmann::json per_frame = nlohmann::json::array();
  for (const Exposure& e : exposures)
    per_frame.push_back(
        {{"adapted_key", e.adapted_key}, {"integration", e.integration}, {"gain", e.gain}});
  return {{"shutter_angle", final_pass.shutter_angle},
          {"motion_blur", "continuous"},
          {"sensor",
           {{"f_number", s.f_number},
            {"pixel_pitch_um", s.pixel_pitch * 1e6},
            {"quantum_efficiency", s.quantum_efficiency},
            {"full_well", s.full_well},
            {"read_noise", s.read_noise},
            {"max_gain", s.max_gain},
            {"adaptation_s", s.adaptation},
            {"grey", s.grey},
            {"glare", s.glare},
            {"noise", s.noise},
            {"vignetting", s.vignetting},
            {"chromatic_aberration", s.chromatic_aberration},
            {"bayer", s.bayer}}},
          {"jpeg_quality", final_pass.jpeg_quality},
          {"lens_drops", lens_drops(final_pass, sequence)},  // on each real lens
          {"lens_dirt", final_pass.lens_dirt},
          {"exposures", per_frame}};
}

}  // namespace flowscape
