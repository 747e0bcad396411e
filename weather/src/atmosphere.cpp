#include "atmosphere.h"

#include <algorithm>
#include <cmath>

namespace flowscape::sky {
namespace {

const Spectrum kRayleigh(5.802e-3, 13.558e-3, 33.1e-3);  // 1/km at sea level (Hillaire 2020)
const Spectrum kOzone(0.650e-3, 1.881e-3, 0.085e-3);     // absorption, 1/km at its peak
const Spectrum kHazeColour(0.759, 1.0, 1.337);           // Angstrom exponent 1.3 about 550 nm
constexpr double kRayleighHeight = 8, kMieHeight = 1.2;  // km
constexpr double kMieAlbedo = 0.9, kGroundAlbedo = 0.3;
constexpr double kMaxAltitude = kTopRadius - kGroundRadius;
constexpr int kTransmittanceRows = 64, kTransmittanceColumns = 512;
constexpr int kMultipleRows = 32, kMultipleColumns = 32;

// Bilinear lookup at fractional cell coordinates (clamped).
Spectrum bilinear(const std::vector<Spectrum>& cells, int rows, int columns, double row,
                  double column) {
  row = std::clamp(row, 0.0, rows - 1.0), column = std::clamp(column, 0.0, columns - 1.0);
  const int r0 = std::min(int(row), rows - 2), c0 = std::min(int(column), columns - 2);
  const double fr = row - r0, fc = column - c0;
  const auto cell = [&](int r, int c) { return cells[std::size_t(r) * columns + c]; };
  return (1 - fr) * ((1 - fc) * cell(r0, c0) + fc * cell(r0, c0 + 1)) +
         fr * ((1 - fc) * cell(r0 + 1, c0) + fc * cell(r0 + 1, c0 + 1));
}

// Altitude rows are spaced as the square root, dense near the ground where the air is.
double altitude_row(double altitude, int rows) {
  return std::sqrt(std::clamp(altitude / kMaxAltitude, 0.0, 1.0)) * (rows - 1);
}
double row_altitude(int row, int rows) {
  const double x = double(row) / (rows - 1);
  return x * x * kMaxAltitude;
}

// A point at distance t along a ray from radius r with zenith cosine mu: its radius and the
// cosine of the ray's direction with its own zenith.
struct Along {
  double r, mu;
};
Along along(double r, double mu, double t) {
  const double r_t = std::sqrt(r * r + t * t + 2 * r * mu * t);
  return {r_t, (r * mu + t) / r_t};
}

// The t = T u^2 steps of a march over [0, T]: dense near the start, where a level ray's air is.
template <class Visit>
void march(double length, int steps, Visit&& visit) {
  for (int i = 0; i < steps; ++i) {
    const double u = (i + 0.5) / steps;
    visit(length * u * u, 2 * length * u / steps);  // position, step length
  }
}

}  // namespace

double rayleigh_phase(double c) { return 3 / (16 * kPi) * (1 + c * c); }

double mie_phase(double c, double g) {
  const double g2 = g * g;
  return 3 / (8 * kPi) * (1 - g2) * (1 + c * c) / ((2 + g2) * std::pow(1 + g2 - 2 * g * c, 1.5));
}

double distance_to_top(double r, double mu) {
  return std::max(
      0.0, -r * mu + std::sqrt(std::max(0.0, r * r * (mu * mu - 1) + kTopRadius * kTopRadius)));
}

bool meets_ground(double r, double mu) {
  return mu < 0 && r * r * (mu * mu - 1) + kGroundRadius * kGroundRadius >= 0;
}

double distance_to_boundary(double r, double mu) {
  if (!meets_ground(r, mu)) return distance_to_top(r, mu);
  return -r * mu - std::sqrt(r * r * (mu * mu - 1) + kGroundRadius * kGroundRadius);
}

AirColumn::AirColumn(double turbidity)
    : mie_extinction((turbidity - 1) * kRayleigh[1] * kRayleighHeight / kMieHeight) {}

Medium AirColumn::at(double altitude) const {
  const double h = std::max(altitude, 0.0);
  const double ozone = std::max(0.0, 1 - std::abs(h - 25) / 15);
  const Spectrum rayleigh = kRayleigh * std::exp(-h / kRayleighHeight);
  const Spectrum mie = kHazeColour * (mie_extinction * std::exp(-h / kMieHeight));
  return {rayleigh, mie * kMieAlbedo, rayleigh + mie + kOzone * ozone};
}

Spectrum AirColumn::optical_depth(double altitude, double mu, int steps) const {
  const double r = kGroundRadius + altitude;
  Spectrum depth = Spectrum::Zero();
  march(distance_to_top(r, mu), steps, [&](double t, double dt) {
    depth += at(along(r, mu, t).r - kGroundRadius).extinction * dt;
  });
  return depth;
}

Atmosphere::Atmosphere(double turbidity) : air_(turbidity) {
  build_transmittance();
  build_multiple_scattering();
}

// Columns are spaced evenly in the zenith angle, so the steep fall near the horizon is resolved.
void Atmosphere::build_transmittance() {
  transmittance_.resize(std::size_t(kTransmittanceRows) * kTransmittanceColumns);
  for (int row = 0; row < kTransmittanceRows; ++row)
    for (int column = 0; column < kTransmittanceColumns; ++column) {
      const double altitude = row_altitude(row, kTransmittanceRows);
      const double mu = std::cos(kPi * column / (kTransmittanceColumns - 1));
      transmittance_[std::size_t(row) * kTransmittanceColumns + column] =
          meets_ground(kGroundRadius + altitude, mu)
              ? Spectrum::Zero()
              : Spectrum(exp(-air_.optical_depth(altitude, mu, 96)));
    }
}

Spectrum Atmosphere::transmittance(double altitude, double mu) const {
  const double column = std::acos(std::clamp(mu, -1.0, 1.0)) / kPi * (kTransmittanceColumns - 1);
  return bilinear(transmittance_, kTransmittanceRows, kTransmittanceColumns,
                  altitude_row(altitude, kTransmittanceRows), column);
}

// Hillaire 2020, Eqs. 5-10: at each altitude and sun angle, the second-order light arriving
// isotropically from a sphere of directions (with the ground's diffuse reflection) and the share
// f_ms of light the air around scatters back, summed as a geometric series: psi = L2 / (1 - f_ms).
void Atmosphere::build_multiple_scattering() {
  constexpr int kRings = 8, kSegments = 8, kSteps = 24;
  multiple_.resize(std::size_t(kMultipleRows) * kMultipleColumns);
  for (int row = 0; row < kMultipleRows; ++row)
    for (int column = 0; column < kMultipleColumns; ++column) {
      const double altitude = row_altitude(row, kMultipleRows), r = kGroundRadius + altitude;
      const double mu_sun = -1 + 2.0 * column / (kMultipleColumns - 1);
      const Vec3 sun(std::sqrt(1 - mu_sun * mu_sun), 0, mu_sun);
      Spectrum second = Spectrum::Zero(), transfer = Spectrum::Zero();
      for (int ring = 0; ring < kRings; ++ring)
        for (int segment = 0; segment < kSegments; ++segment) {
          const double mu = -1 + 2 * (ring + 0.5) / kRings,
                       phi = 2 * kPi * (segment + 0.5) / kSegments;
          const double s = std::sqrt(1 - mu * mu);
          const Vec3 dir(s * std::cos(phi), s * std::sin(phi), mu);
          const bool ground = meets_ground(r, mu);
          const double length = distance_to_boundary(r, mu);
          Spectrum through = Spectrum::Ones();
          march(length, kSteps, [&](double t, double dt) {
            const Vec3 p = Vec3(0, 0, r) + t * dir;
            const double r_t = p.norm(), h = r_t - kGroundRadius;
            const Medium m = air_.at(h);
            const Spectrum scattering = m.rayleigh + m.mie_scattering;
            const Spectrum sun_light = transmittance(h, p.dot(sun) / r_t);
            const Spectrum reaching = through * exp(-m.extinction * dt / 2);
            second += reaching * scattering * sun_light * dt / (4 * kPi);
            transfer += reaching * scattering * dt;
            through *= exp(-m.extinction * dt);
          });
          if (ground) {
            const Vec3 p = Vec3(0, 0, r) + length * dir;
            const double mu_ground = std::max(0.0, p.normalized().dot(sun));
            second += through * transmittance(0, mu_ground) * (mu_ground * kGroundAlbedo / kPi);
          }
        }
      const double directions = kRings * kSegments;
      second /= directions, transfer /= directions * 4 * kPi;
      multiple_[std::size_t(row) * kMultipleColumns + column] = second / (1 - transfer);
    }
}

Spectrum Atmosphere::multiple_scattering(double altitude, double mu) const {
  return bilinear(multiple_, kMultipleRows, kMultipleColumns, altitude_row(altitude, kMultipleRows),
                  (mu + 1) / 2 * (kMultipleColumns - 1));
}

Spectrum Atmosphere::Scattered::radiance(double cos_to_sun) const {
  return rayleigh * rayleigh_phase(cos_to_sun) + mie * mie_phase(cos_to_sun) + multiple;
}

Atmosphere::Scattered Atmosphere::scattered(double altitude, const Vec3& view, const Vec3& sun,
                                            int steps) const {
  const double r = kGroundRadius + altitude, length = distance_to_boundary(r, view.z());
  Scattered out{Spectrum::Zero(), Spectrum::Zero(), Spectrum::Zero()};
  Spectrum through = Spectrum::Ones();
  march(length, steps, [&](double t, double dt) {
    const Vec3 p = Vec3(0, 0, r) + t * view;
    const double r_t = p.norm(), h = r_t - kGroundRadius, mu_sun = p.dot(sun) / r_t;
    const Medium m = air_.at(h);
    const Spectrum step = through * exp(-m.extinction * dt / 2) * dt;  // reaching the observer
    const Spectrum sun_light = transmittance(h, mu_sun);
    out.rayleigh += step * m.rayleigh * sun_light;
    out.mie += step * m.mie_scattering * sun_light;
    out.multiple += step * (m.rayleigh + m.mie_scattering) * multiple_scattering(h, mu_sun);
    through *= exp(-m.extinction * dt);
  });
  return out;
}

}  // namespace flowscape::sky
