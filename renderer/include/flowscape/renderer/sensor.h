#pragma once
// The final pass's camera (after pbrt-v4's film and PixelSensor): the scene's light through a lens
// (relative illumination, glare round bright lights) onto a sensor that counts photo-electrons
// with their shot noise and read noise, clips at its full well, is exposed by an auto-exposure
// that adapts over a sequence, and is brought to display values by a filmic tone curve. Scene
// radiance comes in the sky's units (weather.h: the sun outside the atmosphere gives 1e5 lux), so
// one unit of radiance is kNitsPerUnit cd/m^2.
#include <cstdint>

#include "flowscape/core/image.h"
#include "flowscape/renderer/projection.h"

namespace flowscape {

inline constexpr double kNitsPerUnit = 1e5;

struct SensorModel {
  double f_number = 2.0;
  double pixel_pitch = 3e-6;  // metres
  double quantum_efficiency = 0.6;
  double full_well = 12000;  // electrons
  double read_noise = 2.5;   // electrons rms
  double max_gain = 32;      // the highest ISO over the base ISO
  double adaptation = 0.5;   // seconds: the auto-exposure's time constant
  // The share of the full well the adapted key is exposed to: 0.035 leaves five stops of
  // headroom for highlights, which the tone curve rolls off.
  double grey = 0.035;
  double glare = 0.02;     // share of the light the lens scatters round its path (bloom)
  bool noise = true;       // shot and read noise
  bool vignetting = true;  // a real lens's relative illumination (not the ERP's, not cube faces')
  // Lateral chromatic aberration of a real lens: red magnified and blue shrunk by this share about
  // the image centre (0.002: at 500 pixels from the centre, red and blue 1 pixel out each way).
  double chromatic_aberration = 0;
  // A Bayer colour filter (RGGB): each pixel counts one channel's electrons, then OpenCV's
  // demosaicking fills in the other two.
  bool bayer = false;
};
// Throws std::invalid_argument naming the value.
void validate(const SensorModel& sensor);

// Photo-electrons a pixel collects from 1 cd/m^2 in `seconds`: the sensor's illuminance
// pi T E / (4 N^2) (T = 0.9 through the lens) x seconds x pitch^2 x 4.09e15 photons per lux s m^2
// (at 555 nm) x the quantum efficiency.
double electrons_per_nit_second(const SensorModel& sensor);

// The geometric mean of an image's luminance (a scene's key), with 1e-3 cd/m^2 added against zeros.
double key_luminance(ImageView<const float> nits);

// How much of `grey` a scene whose key is `key` (cd/m^2) is exposed to: Krawczyk et al.'s
// (2005) key value 1.03 - 2 / (2 + log10(key + 1)) over its value at 1000 cd/m^2 (a bright day),
// at least 0.02 / that: a night stays dark, as a camera and the eye keep it (0.12 at 0.3 cd/m^2).
double key_scale(double key);

// How a frame is exposed: the auto-exposure's adapted key (cd/m^2), the share of the shutter time
// the sensor integrates (below 1 in bright light: an electronic shutter), and the analogue gain
// (above 1 in dim light, at most max_gain). Recorded per frame.
struct Exposure {
  double adapted_key = 0, integration = 1, gain = 1;
};
// The exposure after a frame whose key is `measured`, `elapsed` seconds after the one exposed as
// `previous` (adapted_key 0: the sequence's first frame, which adapts at once): the key moves
// towards the measured one by 1 - exp(-elapsed / adaptation) in log luminance; the adapted key is
// then exposed to grey x key_scale(key) of the full well, over at most `shutter` seconds.
Exposure auto_exposure(const SensorModel& sensor, const Exposure& previous, double measured,
                       double elapsed, double shutter);

// The light on the sensor: radiance (cd/m^2, RGB) times the lens's relative illumination (the
// pixel's solid angle over the centre's, times cos(theta) for a rectilinear lens: cos^4 for a
// pinhole, sin(theta) / theta for an equidistant fisheye; nothing for an ERP or a cube face,
// virtual cameras without a lens), red and blue scaled about the centre by
// 1 +- chromatic_aberration, plus `glare` of it spread by a wide point-spread function (three
// Gaussians, 2, 8 and 32 pixels).
Image<float> lens_image(ImageView<const float> nits, const Projection& camera,
                        const SensorModel& sensor);

// The raw image: each channel's electrons (Poisson with the light's mean over the integration
// time, plus Gaussian read noise; seeded per pixel by `seed`) clipped to the full well, times the
// gain, over the full well, clipped at 1 (the converter's range): the adapted key reads `grey`.
// With `bayer`, each pixel counts only its filter's channel and the mosaic is demosaicked.
Image<float> sensor_raw(ImageView<const float> sensor_nits, const SensorModel& sensor,
                        const Exposure& exposure, double shutter, std::uint64_t seed);

// A filmic tone curve (Narkowicz's fit of ACES) from raw to display values in [0, 1], linear
// (for linear_to_srgb8): raw grey shows as 20 % grey, raw 1 (saturation) near white.
Image<float> tone_map(ImageView<const float> raw, const SensorModel& sensor);
float filmic(float x);

}  // namespace flowscape
