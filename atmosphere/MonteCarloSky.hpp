#pragma once
// The sky's radiance by backward Monte-Carlo: the reference for skies the 4D tables cannot
// hold, above all the sky of a solar eclipse, where the Sun's light at a point of the air
// depends on where the point is and not only on its altitude and the Sun's zenith angle.
//
// The model. A spherical shell (the atmosphere's bottom and top radii), its components'
// scattering, absorption and phase functions at each wavelength, a Lambertian ground of
// the atmosphere's albedo; straight rays (no refraction); every order of scattering. The
// Sun is a distant source of unit irradiance in direction `sunDirection` (the same at every
// point: 100 km at 1 au turn it by 7e-7 rad); at a point x it lights the air with
//     E(x) = T(x -> space along the Sun) * V(x) * [the Sun's centre above the ground at x],
// V the caller's visible fraction of the Sun's disc (the Moon's shadow: 0 in the umbra,
// 1 outside the penumbra; 1 for no eclipse). The Sun's disc is not added: the radiance
// is the sky's alone, per unit solar irradiance [1/sr], as skyRadiance gives it.
//
// The estimator. Paths start at the observer along the view direction. Free paths are
// sampled by delta tracking against a constant majorant of the extinction (every null
// collision re-drawn: unbiased whatever the density profiles), the light of the Sun is
// added at every real collision and ground hit (next-event estimation: the mixture's
// phase function, or the ground's albedo / pi times the cosine, times E(x) with its
// transmittance by ratio tracking), then the path goes on: a component chosen by its share
// of the scattering, a direction from its phase function (drawn from a fine tabulation in
// the scattering angle and weighted by the true p over the drawn density, so the table's
// resolution changes the noise, not the mean), or from the cosine law at the ground; the
// weight takes the single-scattering albedo or the ground's albedo. Russian roulette ends
// paths whose weight has fallen, without bias.
//
// Deterministic for a seed: each block of paths of each direction and wavelength has its
// own generator seeded from (seed, direction, wavelength, block), and the blocks are summed
// in order, so the result does not depend on the threads. The standard error is that of the
// mean over the paths.
#include "Atmosphere.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace umbra::atmosphere {

/// The fraction of the Sun's light (its limb-darkened disc's flux) that reaches a point
/// unobstructed by anything but the planet and its air: 1 without an eclipse. Called from
/// several threads at once.
using SunVisibility = std::function<double(const glm::dvec3& pointM)>;

struct MonteCarloSkyOptions {
  std::uint64_t seed = 1;
  std::int64_t paths = 20000;  ///< per direction and wavelength
  /// Highest order counted (1: single scattering only); 0: every order (Russian roulette).
  int maxOrders = 0;
  int threads = 0;             ///< OpenMP threads (0: the default)
  /// Cells of the scattering angle the phase functions are drawn from (the noise, not the mean).
  int phaseSamplingCells = 2048;

  /// Empty when usable, else what is wrong.
  std::string validate() const;
};

/// One view direction, per wavelength of the atmosphere.
struct MonteCarloRadiance {
  std::vector<double> radiance;       ///< per unit solar irradiance [1/sr]
  std::vector<double> standardError;  ///< of the mean, same units
};

struct MonteCarloSky {
  std::vector<MonteCarloRadiance> directions;  ///< in the order of the view directions given
  std::int64_t pathsPerDirection = 0;          ///< per wavelength
  double seconds = 0.0;                        ///< wall-clock time of the whole computation
};

/// Called with the fraction done, from any of the run's threads but one call at a time;
/// false stops the run (MonteCarloCancelled is thrown).
using MonteCarloProgress = std::function<bool(double)>;

struct MonteCarloCancelled : std::runtime_error {
  MonteCarloCancelled() : std::runtime_error("Monte-Carlo sky cancelled") {}
};

/// The radiance reaching `observerM` (planet-centred, at or above the ground, inside the
/// atmosphere's top) from each of `viewDirections` (unit vectors away from the observer),
/// for a Sun towards `sunDirection` (unit) lit by `visibility` (empty: 1 everywhere).
/// Throws std::invalid_argument for an observer outside the shell, directions that are not
/// unit vectors, or bad options.
MonteCarloSky monteCarloSkyRadiance(const Atmosphere& atmosphere, const glm::dvec3& observerM,
                                    const std::vector<glm::dvec3>& viewDirections,
                                    const glm::dvec3& sunDirection, const SunVisibility& visibility = {},
                                    const MonteCarloSkyOptions& options = {},
                                    const MonteCarloProgress& progress = {});

/// The observer of a sky computed point by point (this reference, EclipsedSky.hpp's
/// quadrature), checked: planet-centred, from the ground to the atmosphere's top (a hair
/// below the ground, rounding, is put on it), with unit Sun and view directions. Returns the
/// observer; throws std::invalid_argument starting with `what` otherwise.
glm::dvec3 checkedSkyObserver(const char* what, const Atmosphere& atmosphere, const glm::dvec3& observerM,
                              const std::vector<glm::dvec3>& viewDirections, const glm::dvec3& sunDirection);

/// An upper bound of each wavelength's extinction coefficient over the shell [1/m] (the
/// majorant of delta tracking): each component's largest relative density, found on a 10 m
/// grid and at its profile's kinks, times its extinction at relative density 1, summed over
/// the components, plus 1 %. The tracking checks it at every collision (a density above it
/// throws std::logic_error: the result would be biased).
std::vector<double> extinctionMajorantPerM(const Atmosphere& atmosphere);

}  // namespace umbra::atmosphere
