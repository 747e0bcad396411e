#pragma once
// How a camera maps pixels to rays in the rig frame (x forward, y left, z up) and back: a pinhole
// (a cube face or any field of view) or a full equirectangular panorama.
#include <memory>
#include <optional>

#include "flowscape/geometry/geometry.h"
#include "flowscape/renderer/lens.h"

namespace flowscape {

struct Projection {
  // Pinhole: the cube's faces (focal, principal point at the centre); Equirectangular: the ERP;
  // Lens: any camera model of lens.h.
  enum class Kind { Pinhole, Equirectangular, Lens };
  Kind kind = Kind::Pinhole;
  int width = 0, height = 0;
  Mat3 rotation = Mat3::Identity();    // pinhole, lens: camera (x right, y down, z forward) -> rig
  double focal = 0;                    // pinhole, pixels; principal point at the image centre
  std::shared_ptr<const Lens> lens{};  // Lens

  static Projection cube_face(Face face, int face_size);
  // Horizontal field of view in degrees, looking along the rig's x axis.
  static Projection pinhole(int width, int height, double fov_x_degrees);
  static Projection equirectangular(int height);
  // A lens whose camera frame the rig sees turned by `camera_to_rig`.
  static Projection of_lens(std::shared_ptr<const Lens> lens, const Mat3& camera_to_rig);

  // Whether the pixel position sees anything: false outside a lens's image (circle, annulus);
  // there ray() is the zero vector.
  bool covers(Vec2 pixel) const;
  // Whether its columns continue round (the ERP): its flow wraps at the seam, and filters reach
  // across it.
  bool wraps_around() const { return kind == Kind::Equirectangular; }
  // Whether straight lines stay straight: the cube's faces, a pinhole, a lens of the pinhole model.
  bool rectilinear() const;
  // The camera model and its parameters as rig files and meta.json give them: "equirectangular"
  // with its height, "pinhole" with K (OpenCV's pixel convention) for a face, or the lens's.
  std::string model() const;
  nlohmann::json parameters() const;

  // The view's camera frame (x right, y down, z forward) -> rig: a pinhole's rotation; for the ERP
  // the front face's (the ERP's centre, phi = theta = 0, looks along the camera's z). Normals and
  // scene flow are given in this frame.
  Mat3 camera_to_rig() const;
  // Ray through a continuous pixel position (pixel centres at +0.5); not normalised.
  Vec3 ray(Vec2 pixel) const;
  // Continuous pixel position of a rig-frame direction; nullopt behind a pinhole and where a lens
  // sees nothing.
  std::optional<Vec2> project(const Vec3& direction) const;
  // The angle the pixel at `pixel` spans, the square root of its solid angle: how fast a camera
  // ray's footprint grows with distance. A pinhole pixel at angle a off the axis spans
  // cos(a)^1.5 / focal, so its footprint on a plane parallel to the image is depth / focal
  // wherever it is in the image. An ERP pixel spans 2 pi / width across its long side (its width
  // on the equator, its height everywhere), so textures never alias near the poles.
  // A lens pixel spans the geometric mean of the angles between the rays through its opposite
  // edge midpoints (one side's twice where the other leaves the image).
  double pixel_spread(Vec2 pixel) const;
};

// Rays through many points of one pixel (the samples of a path tracer). The ERP form takes the sin
// and cos of the pixel centre's angles once and adds each offset (at most half a pixel) by the
// angle-sum formulas with short series, exact to double precision (for ERPs at least 64 wide).
class PixelRays {
 public:
  PixelRays(const Projection& projection, int x, int y);
  Vec3 operator()(Vec2 offset) const;  // offset in [0, 1)^2 from the pixel's corner; not normalised

 private:
  const Projection& projection_;
  Vec2 corner_;
  bool incremental_;    // ERP at least 64 pixels wide
  SinCos phi_, theta_;  // the pixel centre's angles
};

}  // namespace flowscape
