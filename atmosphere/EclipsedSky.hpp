#pragma once
// The sky of a solar eclipse by quadrature: the fast path beside the Monte-Carlo reference
// (MonteCarloSky.hpp), for the same model (spherical shell, the atmosphere's components and
// phase functions, Lambertian ground, straight rays) and the same quantity (radiance per
// unit solar irradiance [1/sr] reaching the observer along each view direction; a view that
// ends on the ground includes the ground's reflected light, as the reference's paths do).
//
// What it computes. Along each view ray, in `viewSamples` steps:
//   - single scattering, as in the reference: the Sun's light at the point,
//     T(point -> space) * V(point), V the caller's visible fraction of the Sun's disc;
//   - the light scattered again towards the observer, sigma_s(x) * integral p(omega . d)
//     L_in(x, omega) d omega, with the radiance L_in arriving at x read from a light field.
// The light field lives at the points of a fan of rays from the observer (fieldElevations
// x fieldAzimuths rays, dense near the horizon, fieldSamples points along each) and is
// interpolated between them (a ray that ends on the ground short of a point does not
// count for it). At each field point:
//   - order 1: the once-scattered light from incomingZenith x incomingAzimuths directions
//     (Gauss-Legendre in the cosine on each side of the horizon, uniform in azimuth), each
//     marched in incomingSamples steps with V at every step, plus the ground's reflection
//     of the direct light where the direction ends on it (exact up to the quadrature: the
//     view's second order);
//   - orders 2 .. `orders`: from diffuseZenith x diffuseAzimuths directions, each marched
//     with the source sigma_s(y) * integral p L_prev at its steps (the previous order's
//     field filtered by each component's phase function towards the march's direction),
//     the ground lit by the previous order's mean radiance (E = 2 pi Lbar);
//   - the orders beyond: the last one times 1 / (1 - q), q the ratio of the last two
//     orders' mean radiance at the point (at most 0.9).
// Without an eclipse (V = 1) it is the tables' sky computed another way (within 2 % of
// the Monte-Carlo). In totality the orders past the second carry 30 to 60 % of the light.
// docs/accuracy-vs-speed/atmosphere-tables.md, "The sky of a solar eclipse", has its error against the
// reference and its time.
//
// The tables give the transmittance to space (the Sun's light at a point); they must be
// for `atmosphere` (same radii and wavelengths).
#include "Atmosphere.hpp"
#include "MonteCarloSky.hpp"  // SunVisibility
#include "Precompute.hpp"

#include <glm/vec3.hpp>

#include <functional>
#include <string>
#include <tuple>
#include <vector>

namespace umbra::atmosphere {

struct EclipsedSkyOptions {
  int viewSamples = 48;       ///< steps along each view ray
  int fieldElevations = 25;   ///< the light field's rays: odd (the horizon one of them), -90..90 deg, dense near 0
  int fieldAzimuths = 16;     ///< around the observer's vertical
  int fieldSamples = 16;      ///< points along each field ray
  int incomingZenith = 12;    ///< even: half above, half below each field point's horizon
  int incomingAzimuths = 16;
  int incomingSamples = 24;   ///< steps along each incoming direction
  /// Orders of the light arriving at the field points (the view's scattering adds one):
  /// 1 gives the view single and second order only; the last carries the rest.
  int orders = 4;
  int diffuseZenith = 8;      ///< directions of the light scattered twice and more (even)
  int diffuseAzimuths = 8;
  int threads = 0;            ///< OpenMP threads (0: the default)

  /// Empty when usable, else what is wrong.
  std::string validate() const;
  bool operator==(const EclipsedSkyOptions& o) const {
    return std::tie(viewSamples, fieldElevations, fieldAzimuths, fieldSamples, incomingZenith, incomingAzimuths,
                    incomingSamples, orders, diffuseZenith, diffuseAzimuths, threads) ==
           std::tie(o.viewSamples, o.fieldElevations, o.fieldAzimuths, o.fieldSamples, o.incomingZenith,
                    o.incomingAzimuths, o.incomingSamples, o.orders, o.diffuseZenith, o.diffuseAzimuths, o.threads);
  }
};

/// Quick knobs for interactive use: field 13 x 8 x 12, incoming 8 x 8 x 16, 3 orders, diffuse
/// 6 x 6, view 32 (some 20 times faster than the defaults; their error against the reference
/// in docs/accuracy-vs-speed/atmosphere-tables.md).
EclipsedSkyOptions draftEclipsedSkyOptions();

struct EclipsedSky {
  /// [direction][wavelength], per unit solar irradiance [1/sr], in the order of the view directions.
  std::vector<std::vector<double>> radiance;
  double seconds = 0.0;  ///< wall-clock time of the whole computation
};

/// Called with the fraction done, from the calling thread; false stops the run
/// (EclipsedSkyCancelled is thrown).
using EclipsedSkyProgress = std::function<bool(double)>;

struct EclipsedSkyCancelled : std::runtime_error {
  EclipsedSkyCancelled() : std::runtime_error("eclipsed sky cancelled") {}
};

/// The radiance reaching `observerM` (planet-centred, from the ground to the atmosphere's
/// top) from each of `viewDirections` (unit vectors away from the observer), for a Sun
/// towards `sunDirection` (unit) seen through `visibility` (empty: 1 everywhere). The
/// visibility is called some 10^7 times from several threads: hand a tabulated one (a
/// shadow LuT), not an adaptive integral. Throws std::invalid_argument for an observer outside the shell,
/// directions that are not unit vectors, bad options, tables that are not the
/// atmosphere's or more than 64 wavelengths.
EclipsedSky eclipsedSkyRadiance(const AtmosphereTables& tables, const Atmosphere& atmosphere,
                                const glm::dvec3& observerM, const std::vector<glm::dvec3>& viewDirections,
                                const glm::dvec3& sunDirection, const SunVisibility& visibility = {},
                                const EclipsedSkyOptions& options = {}, const EclipsedSkyProgress& progress = {});

}  // namespace umbra::atmosphere
