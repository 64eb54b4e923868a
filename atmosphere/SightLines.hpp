#pragma once
// Lines of sight through a model atmosphere: the refracted ray from an observer to space
// (eclipse paper, section 4.1), its total deviation, the lowest altitude it reaches, and
// the transmittance of the atmosphere along it. What `umbra atmosphere refraction` prints.
#include "Atmosphere.hpp"
#include "Refraction.hpp"

#include <vector>

namespace umbra::atmosphere {

/// The refractive medium of an atmosphere at one wavelength: n - 1 = atmosphere.refractivity
/// (its numbers copied: the medium may outlive the atmosphere), with the exact derivative
/// for exponential and double-exponential profiles (numerical for the others). The one
/// medium of the refraction table, the traced sight lines and the refracted scattering paths.
RefractiveMedium refractiveMedium(const Atmosphere& atmosphere, double wavelengthNm);

struct SightLine {
  double deviationRad = 0.0;      ///< total bending from the observer to the top of the atmosphere
  double contactAltitudeM = 0.0;  ///< lowest altitude on the path; < 0: the ray hits the ground
  bool hitGround = false;
  /// exp(-optical depth) along the refracted path, per wavelength of the atmosphere; 0 for
  /// a ray that hits the ground.
  std::vector<double> transmittance;
};

/// The line of sight from `altitudeM` at geometric view-zenith angle `zenithRad`, traced at
/// `referenceWavelengthNm` (RK4 with `stepM`; optical depth integrated over pieces of
/// `stepM / piecesPerStep`).
SightLine traceSightLine(const Atmosphere& atmosphere, double altitudeM, double zenithRad,
                         double referenceWavelengthNm = 550.0, double stepM = 10e3, int piecesPerStep = 20);

} // namespace umbra::atmosphere
