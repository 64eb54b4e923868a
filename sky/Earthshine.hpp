#pragma once
// Earthshine: the sunlight the Earth reflects onto the Moon (day-and-night-sky paper,
// Sect. 2.2.1). It depends on the Earth's phase seen from the Moon, which is pi minus
// the Moon's phase angle phi seen from the Earth: brightest at new Moon (full Earth).
//
//   paper, Eq. 4:   E_em(phi) = -0.0061 phi^3 + 0.0289 phi^2 - 0.0105 sin phi
//   Jensen et al.:  E_em(phi) = 0.19 * 0.5 * J(pi - phi)   (van de Hulst; J: the
//                   Lommel–Seeliger disc integral, sky::lommelSeeligerPhase)
//
// The paper's cubic is a fit to Jensen's within 3 % of its largest value (0.095) over
// 0..pi; it dips below 0 for phi < 21 deg, where it is taken as 0 (the Earth a thin
// crescent). As an irradiance on the Moon (W m^-2), the full Earth gives
// E_sun p_E (R_E / d)^2 (p_E: the Earth's geometric albedo, d: the Earth-Moon distance),
// and the phase scales it by E_em(phi) / E_em(pi):
//
//   E_earthshine = E_sun(at the Earth) p_E (R_E / d)^2 E_em(pi - alpha_E) / E_em(pi)
//
// with alpha_E the Earth's phase angle at the Moon (Sun-Earth-Moon). Its colour is the
// paper's beta_e = (0.88, 0.96, 1.00) in R, G, B, scaled to keep its luminance.
#include <glm/vec3.hpp>

namespace umbra::sky {

/// The paper's Eq. 4, clamped at 0 (moonPhaseRad in [0, pi]).
double earthshinePaper(double moonPhaseRad);
/// Jensen et al. 2001's closed form, 0.095 J(pi - phi).
double earthshineJensen(double moonPhaseRad);

/// The earthshine irradiance on the Moon, W m^-2 (the header comment's formula).
/// earthPhaseRad: the Earth's phase angle seen from the Moon (0: full Earth).
double earthshineIrradiance(double sunIrradianceAtEarthWm2, double earthGeometricAlbedo, double earthRadiusM,
                            double earthMoonDistanceM, double earthPhaseRad);

/// beta_e over its luminance (colour::luminance): the colour of the earthshine, R, G, B.
glm::dvec3 earthshineColour();

}  // namespace umbra::sky
