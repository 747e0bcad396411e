#pragma once
// A release's final pass (output kind "final", beside the clean "color"): the scene traced over
// each frame's shutter (renderer/shutter.h) and denoised as the clean colour is, then seen through
// the release's camera (renderer/sensor.h): an auto-exposure that adapts over the sequence, glare,
// vignetting on real lenses, shot and read noise, a filmic tone curve and sRGB. The ground truth
// stays the frame time's.
#include <nlohmann/json.hpp>
#include <vector>

#include "flowscape/release/config.h"
#include "flowscape/release/sequence.h"
#include "flowscape/renderer/lens_cover.h"
#include "flowscape/renderer/sensor.h"
#include "flowscape/renderer/shutter.h"

namespace flowscape {

SensorModel release_sensor(const FinalPassSection& final_pass);
// The shutter of a frame (shutter_angle, centred on the frame's time).
Shutter frame_shutter(const FinalPassSection& final_pass, const Sequence& sequence, int frame);

// The auto-exposure after a frame, its key measured on the frame's clean colour as written (8-bit
// sRGB, brought back to cd/m^2 through the sequence's exposure) where `camera` has an image (not
// outside a fisheye's circle): the same bytes whether the sequence was rendered in one go or
// resumed.
Exposure exposure_after(const FinalPassSection& final_pass, const Sequence& sequence,
                        const Exposure& previous, ImageView<const std::uint8_t> clean,
                        const Projection& camera, int frame);

// The drops and dirt on a real lens of a sequence's view (config lens_drops, lens_dirt; the
// same for every frame).
LensCover release_lens_cover(const FinalPassSection& final_pass, const Sequence& sequence,
                             const Projection& camera, int view);
// Its lens_mask: cover_mask where the lens has an image, 0 elsewhere.
Image<std::uint8_t> release_lens_mask(const FinalPassSection& final_pass, const Sequence& sequence,
                                      const Projection& camera, int view);

// One view's colour over the frame's shutter (motion blur: each sample at its own time,
// shutter.h), traced with shutter_options' samples and denoised (linear, the clean pass's units);
// with a rolling shutter each line's shutter is centred on its own time.
Image<float> final_color(const ColorSection& color_settings, const FinalPassSection& final_pass,
                         const Sequence& sequence, Renderer& renderer, const Projection& camera,
                         const CameraTrack& track, int frame, const Readout& readout);
// The six cube faces' (stacked), for the flowscape rig.
Image<float> final_cube_color(const ColorSection& color_settings,
                              const FinalPassSection& final_pass, int face_size,
                              const Sequence& sequence, Renderer& renderer, int frame);

// A view's final colour through the camera, 8-bit sRGB: `lens` says whether it is a real lens
// (vignetting) or a virtual camera (the ERP, a cube face); `view` seeds its noise apart.
Image<std::uint8_t> develop(const FinalPassSection& final_pass, const Sequence& sequence,
                            ImageView<const float> color, const Projection& camera, bool lens,
                            const Exposure& exposure, int frame, int view);

// meta.json's "final": the shutter, the sensor and each frame's exposure.
nlohmann::json final_json(const FinalPassSection& final_pass, const Sequence& sequence,
                          const std::vector<Exposure>& exposures);

}  // namespace flowscape
