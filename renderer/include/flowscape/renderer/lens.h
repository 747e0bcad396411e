#pragma once
// Camera models beyond the cube's pinholes, in the manner of pbrt's cameras: one small interface,
// a model per file (renderer/src/camera/lenses/). A lens maps continuous pixel positions (pixel
// centres at +0.5) to unit rays in its camera frame (x right, y down, z forward; a panoramic
// annular lens looks along its z, which its mount points up) and back. docs/cameras.md has every
// model's equations, parameters and limits.
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "flowscape/core/types.h"

namespace flowscape {

class Lens {
 public:
  virtual ~Lens() = default;
  // "pinhole", "equidistant", "kannala_brandt", "double_sphere", "woodscape", "dual_fisheye",
  // "panoramic_annular"
  virtual std::string model() const = 0;
  // What meta.json records and rig files give (the same keys both ways), size included.
  virtual nlohmann::json parameters() const = 0;
  virtual int width() const = 0;
  virtual int height() const = 0;
  // The unit ray through a pixel position; nullopt outside the lens's image (its image circle, the
  // annulus, the rectangle's edge for a distorted pinhole where the model folds).
  virtual std::optional<Vec3> ray(Vec2 pixel) const = 0;
  // The pixel position a direction (any length) is seen at; nullopt where the lens sees nothing
  // (beyond its field of view). Positions off the image rectangle are returned as they are.
  virtual std::optional<Vec2> project(const Vec3& direction) const = 0;
};

// Builds a lens from its model name and parameters (lens->parameters() gives them back); throws
// std::invalid_argument naming what is wrong: an unknown model, a missing or non-finite parameter,
// a field of view the model cannot reach monotonically.
std::shared_ptr<const Lens> make_lens(const std::string& model, const nlohmann::json& parameters);

// The same lens for an image `scale` times as large (a preview's smaller image): width and height
// rounded (a dual fisheye's width twice its height), and the model's pixel-valued parameters
// scaled with them per axis, sx = new width / width and sy likewise, so that every direction is
// seen at the same place of the image: pixel' = (sx, sy) pixel in continuous coordinates. In
// OpenCV's pixel convention K's focal lengths scale by sx and sy and its centre by
// cx' = sx (cx + 0.5) - 0.5 (docs/cameras.md). Throws std::invalid_argument for a scale that
// leaves fewer than 2 pixels.
std::shared_ptr<const Lens> scaled_lens(const Lens& lens, double scale);

// The lenses of the rig presets (rig.h), each with the size of its image.
std::shared_ptr<const Lens> kannala_brandt_200(int size);  // 200 degrees, mild distortion
std::shared_ptr<const Lens> woodscape_190(int width, int height);
std::shared_ptr<const Lens> dual_fisheye_190(int height);  // two side by side: height x 2 height
// Axis up, 360 degrees round, elevations from -band/2 to +band/2 degrees about the horizon.
std::shared_ptr<const Lens> panoramic_annular(int size, double band_degrees = 60);

}  // namespace flowscape
