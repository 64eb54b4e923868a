#pragma once
// The Milky Way's diffuse light from a panorama: where the map lies on the sky, how the
// stars that are drawn one by one are taken out of it, and how its texels become a
// surface brightness.
//
// The map is an equirectangular image in equatorial (ICRS, J2000) coordinates, as
// stellarium-data's textures/milkyway.png (2048 x 1024) is laid: columns run from right
// ascension 90 deg at the left edge towards smaller right ascension (the sky seen from
// inside), rows from declination +90 deg at the top to -90 deg at the bottom. Its bright
// stars were checked against the Hipparcos catalogue: the dots of the isolated ones lie
// within a texel (0.18 deg) of their catalogue places (docs/stars.md, "The Milky Way").
//
// Its texels are sRGB colours of arbitrary scale. umbra decodes them to linear values and
// sets the scale by a published figure: the integrated starlight of the brightest parts of
// the Milky Way, about 250 S10 in V (stars of magnitude 10 per square degree; Cinzano
// 1997, "Inquinamento luminoso e protezione del cielo notturno", section 2.5, after Roach
// & Gordon 1973), given to the brightest 1-deg cap of the map (the Large Sagittarius Star
// Cloud in stellarium's). The map's colours are taken in the frames' white balance.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace umbra::sky {

/// Right ascension at the map's left edge.
inline constexpr double kMilkyWayMapLeftRaDeg = 90.0;

/// Map coordinates (u to the right, v up from the bottom row, as a texture's, both in
/// [0, 1]) of a unit direction in ICRS axes: u = frac((90 deg - RA) / 360 deg),
/// v = (90 deg + Dec) / 180 deg. The GLSL twin is umbraMilkyWayCoord (sky/glsl/MilkyWay.glsl).
glm::dvec2 milkyWayMapCoord(const glm::dvec3& icrsDirection);

/// The unit vector of right ascension and declination in ICRS axes (a catalogue star's J2000
/// place, a map texel's centre).
glm::dvec3 icrsDirection(double raRad, double decRad);

/// The unit ICRS direction at map coordinates (u, v): the inverse of milkyWayMapCoord.
glm::dvec3 milkyWayDirection(const glm::dvec2& uv);

/// A surface brightness of `s10` tenth-magnitude stars per square degree in V magnitudes
/// per square arcsecond: 10 + 2.5 log10(3600^2) - 2.5 log10(s10) (1 S10 = 27.78).
double s10ToVMagPerArcsec2(double s10);

/// The brightest parts of the Milky Way, S10 in V (see above).
inline constexpr double kMilkyWayBrightestS10 = 250.0;
/// The cap over which the map's brightest part is averaged for that figure [rad] (1 deg).
inline constexpr double kMilkyWayCalibrationCapRad = 3.14159265358979323846 / 180.0;
/// Catalogue stars to this V show in stellarium's map as dots (most to V 4, some to V 5):
/// those the scene draws itself are taken out of it.
inline constexpr double kMilkyWayStarsShownToV = 5.0;

/// A map's linear RGB texels, row by row from the bottom (declination -90 deg), as VTK
/// reads an image and a texture holds it.
struct MilkyWayMap {
  int width = 0, height = 0;
  std::vector<float> rgb;
  glm::vec3 at(int column, int row) const;
};

/// Takes the stars at `icrsDirections` (catalogue places, unit vectors) of V magnitudes
/// `vMags` out of the map: the texels within a radius of 1.5 texels (V >= 3), 2.5 (V 1-3)
/// or 3.5 (brighter: their halos) of each star's place take the median, channel by
/// channel, of the ring of texels 1 to 2 texels beyond it. Stars fainter than
/// kMilkyWayStarsShownToV are left. Throws std::invalid_argument when the two lists differ
/// in length.
void removeStars(MilkyWayMap& map, const std::vector<glm::dvec3>& icrsDirections, const std::vector<double>& vMags);

/// The luminance of a texel's colour in the frames' units: colour::luminance of the colour
/// with the frames' white balance undone (times sunLinearSrgb).
double frameLuminance(const glm::dvec3& rgb);

/// The cap of angular radius `capRadiusRad` whose mean texel luminance (frameLuminance,
/// texels weighted by their solid angle) is highest, and that mean: searched on a grid of
/// the cap's radius, then texel by texel within a grid step of the grid's best eight.
struct BrightestCap {
  glm::dvec3 direction{0.0, 0.0, 1.0};
  double meanLuminance = 0.0;
};
BrightestCap brightestCap(const MilkyWayMap& map, double capRadiusRad);

/// The mean luminance of a cap of angular radius `capRadiusRad` around `direction`.
double capMeanLuminance(const MilkyWayMap& map, const glm::dvec3& direction, double capRadiusRad);

/// The mean luminance of the whole map over the sphere (texels weighted by solid angle).
double sphereMeanLuminance(const MilkyWayMap& map);

/// The factor that turns the map's linear texels into the frames' radiance (W m^-2 sr^-1,
/// white-balanced to the Sun, for a Sun of `sunIrradianceAt1AuWm2` at 1 au): the radiance
/// of kMilkyWayBrightestS10 over the brightest cap's mean luminance. Throws
/// std::invalid_argument for a black map.
double milkyWayRadianceScale(const MilkyWayMap& map, double sunIrradianceAt1AuWm2);

}  // namespace umbra::sky
