#pragma once
// Cloud layers: thin spherical shells around a planet, each with a seeded coverage and an
// optical depth, lit through the atmosphere (the render pass composes them:
// app/render/glsl/AtmosphereComposite.glsl; sky/glsl/Clouds.glsl is the GLSL twin of this
// file).
//
// Light through a layer of vertical optical depth tau (conservative scattering: water
// clouds absorb almost nothing in the visible), for light arriving at cosine mu0 to the
// layer's normal:
//   direct:   t = exp(-tau / mu0)                      (Beer-Lambert)
//   reflected: R = delta-Eddington plane albedo of a conservative slab (Joseph, Wiscombe &
//              Weinman 1976, J. Atmos. Sci. 33; the Eddington form in Liou, "An
//              Introduction to Atmospheric Radiation", 2002, section 6.5):
//              R = ((1 - g') tau' + (2/3 - mu0)(1 - exp(-tau'/mu0))) / (4/3 + (1 - g') tau')
//              with tau' = (1 - g^2) tau and g' = g / (1 + g) (the forward peak g^2 taken out),
//              clamped to [0, 1 - exp(-tau'/mu0)]
//   diffusely transmitted: 1 - R - t (what is not reflected nor direct: energy conserved)
// with the Henyey-Greenstein asymmetry g = 0.85 of water clouds in the visible (Hansen &
// Travis 1974, Space Sci. Rev. 16). Sky light (diffuse) counts at mu0 = 0.6 (the
// diffusivity factor 1.66). Both scattered parts leave the layer as Lambertian radiance:
// a surface of radiance R E mu0 / pi above it and (1 - R - t) E mu0 / pi below it, for
// irradiance E normal to the beam.
//
// Coverage: fractal value noise on the unit sphere (5 octaves of trilinear value noise on
// an integer lattice hashed with the seed), mapped to a near-uniform value by a logistic
// fit of its distribution, then thresholded smoothly so that `coverage` of the sphere is
// cloud: density 0 everywhere at coverage 0, 1 everywhere at coverage 1. The local
// optical depth is tau times the density.
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <cstdint>

namespace umbra::sky {

/// One cloud layer of a planet (a scene body's "clouds": docs/scene-format.md).
struct CloudLayer {
  double altitudeM = 2000.0;     ///< above the atmosphere's ground; drawn at most at its top
  double coverage = 0.5;         ///< the fraction of the sphere under cloud, [0, 1]
  double opticalDepth = 10.0;    ///< vertical, where the cloud is whole (grey: all wavelengths)
  std::uint32_t seed = 1;
  double featureSizeM = 20.0e3;  ///< the size of the largest clouds (the first octave's cell)
  double windEastMs = 0.0;       ///< drift at the point below the camera, m/s
  double windNorthMs = 0.0;
};

inline constexpr int kMaxCloudLayers = 4;
inline constexpr double kCloudAsymmetry = 0.85;
inline constexpr double kCloudDiffuseCosine = 0.6;
inline constexpr int kCloudOctaves = 5;
inline constexpr double kMinCloudFeatureSizeM = 1000.0;  ///< float noise stays smooth above it

/// The share of light at cosine mu (its absolute value; at least 1e-3) that crosses a layer
/// of optical depth tau unscattered: exp(-tau / |mu|).
double cloudDirectTransmittance(double opticalDepth, double mu);
/// The share reflected (the delta-Eddington plane albedo above), for light at cosine mu0 > 0
/// (at least 1e-3).
double cloudReflectance(double opticalDepth, double mu0);
/// The share transmitted after scattering: 1 - R - t.
double cloudDiffuseTransmittance(double opticalDepth, double mu0);

/// The radiance a layer sends towards an eye, per unit irradiance normal to the beam, lit
/// at cosine mu0 > 0 on one face: R mu0 / pi on the lit face (`litSide` true), (1 - R - t)
/// mu0 / pi on the other. 1/sr.
double cloudRadiance(double opticalDepth, double mu0, bool litSide);

/// The fractal noise in [0, 1] at p (noise units: the unit sphere times the layer's radius
/// over its feature size), seeded.
double cloudNoise(const glm::dvec3& p, std::uint32_t seed);
/// The density in [0, 1] for a noise value at a coverage: 0 at coverage 0, 1 at coverage 1.
double cloudDensity(double noise, double coverage);

/// The frame in which the noise is fixed: the rigid rotation of the layer from its place at
/// `epochSeconds` to `timeSeconds` (any common time scale) by the wind (east, north m/s) at
/// the unit point `footBodyFixed` under the camera, on a sphere of radius `layerRadiusM`:
/// turning about the axis foot x wind at |wind| / radius rad/s. Identity without wind.
glm::dmat3 cloudDrift(const CloudLayer& layer, const glm::dvec3& footBodyFixed, double layerRadiusM,
                      double epochSeconds, double timeSeconds);

}  // namespace umbra::sky
