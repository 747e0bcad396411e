#pragma once
// Internal: the clear sky of a physically based atmosphere, after Bruneton and Neyret ("Precomputed
// Atmospheric Scattering", 2008) and Hillaire ("A Scalable and Production Ready Sky and Atmosphere
// Rendering Technique", 2020): a spherical planet with Rayleigh-scattering air, Mie-scattering haze
// and absorbing ozone; single scattering integrated along each view ray, multiple scattering from
// Hillaire's isotropic transfer table. Valid for any sun elevation: below the horizon the planet's
// shadow falls on the air. Lengths in km; radiance per unit solar irradiance at the top of the
// atmosphere, in three wavelengths (680, 550, 440 nm) taken as linear R, G, B.
#include <Eigen/Core>
#include <vector>

#include "flowscape/core/types.h"

namespace flowscape::sky {

using Spectrum = Eigen::Array3d;

constexpr double kGroundRadius = 6360, kTopRadius = 6460;  // km

// Scattering and extinction coefficients at one altitude (1/km).
struct Medium {
  Spectrum rayleigh, mie_scattering, extinction;
};

// The air at a given turbidity: Preetham's T = (tau_air + tau_haze) / tau_air at 550 nm.
struct AirColumn {
  explicit AirColumn(double turbidity);
  Medium at(double altitude) const;
  // Optical depth from `altitude` along a ray whose cosine with the local zenith is mu, to the
  // top of the atmosphere, integrated numerically with `steps` steps; the ground in the way is
  // not considered (the caller asks for rays that miss it).
  Spectrum optical_depth(double altitude, double mu, int steps = 256) const;

  double mie_extinction;  // at the ground, 1/km
};

// Rayleigh and Cornette-Shanks phase functions (1/sr) of the cosine between light and view.
double rayleigh_phase(double cos_angle);
double mie_phase(double cos_angle, double g = 0.8);

// Distance along a ray from radius r with zenith cosine mu to the top of the atmosphere, and
// whether the ray meets the ground first.
double distance_to_top(double r, double mu);
bool meets_ground(double r, double mu);
double distance_to_boundary(double r, double mu);  // to the ground if met, else to the top

class Atmosphere {
 public:
  explicit Atmosphere(double turbidity);
  // Share of sunlight reaching `altitude` with the sun at zenith cosine mu (0 in the planet's
  // shadow), from a table.
  Spectrum transmittance(double altitude, double mu) const;
  // What an observer at `altitude` sees along `view` (z up) with the sun towards `sun`:
  // single scattering (both phase functions) plus multiple scattering, per unit irradiance.
  struct Scattered {
    Spectrum rayleigh, mie, multiple;  // rayleigh and mie without their phase functions
    Spectrum radiance(double cos_to_sun) const;
  };
  Scattered scattered(double altitude, const Vec3& view, const Vec3& sun, int steps = 48) const;

  const AirColumn& air() const { return air_; }

 private:
  Spectrum multiple_scattering(double altitude, double mu) const;
  void build_transmittance();
  void build_multiple_scattering();

  AirColumn air_;
  std::vector<Spectrum> transmittance_, multiple_;
};

}  // namespace flowscape::sky
