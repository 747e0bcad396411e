#pragma once
// The sky as a table of radiance over the upper hemisphere of directions (clouds and all): a
// function of direction only, so it sits at infinity and its flow is the flow of a direction.
#include <Eigen/Core>
#include <vector>

#include "flowscape/core/types.h"

namespace flowscape {

// Latitude-longitude table: row r holds elevation (r + 0.5) / rows * 90 degrees, column c azimuth
// (c + 0.5) / columns * 360 degrees counter-clockwise from the world's x axis.
struct SkyDome {
  int rows = 0, columns = 0;
  std::vector<Eigen::Vector3f> radiance;  // linear RGB, row-major

  Vec3 direction(double row, double column) const;  // of a (fractional) cell centre
  // Bilinear in elevation and azimuth (clamped at the horizon and the zenith rows, cyclic in
  // azimuth); d points up (d.z() >= 0) and has unit length.
  Eigen::Vector3f at(const Vec3& d) const;
  // The mean radiance over the hemisphere's solid angle, and the irradiance on a level surface.
  Eigen::Vector3f mean() const;
  Eigen::Vector3f horizontal_irradiance() const;
};

}  // namespace flowscape
