#pragma once
// The transmittance-texture parametrisation of Bruneton's precomputed atmospheric
// scattering (2017 implementation, after [Bru16]); the eclipse paper (section 4.1, Eq. 2)
// stores the refraction table in the same space:
//   H = sqrt(r_top^2 - r_bottom^2), rho = sqrt(r^2 - r_bottom^2),
//   d = distance to the top boundary along (r, mu), d_min = r_top - r, d_max = rho + H,
//   x_mu = (d - d_min) / (d_max - d_min),  x_r = rho / H.
// x_mu = 0 is the zenith, x_mu = 1 the geometric horizon (mu = -rho / r); x_r = 0 the
// ground, x_r = 1 the top. Rays below the horizon are not in this space. Texture
// coordinates put the texel centres on x = 0 and x = 1 (GetTextureCoordFromUnitRange).
// All lengths in metres; mu is the cosine of the view-zenith angle.

#include <algorithm>
#include <cmath>

namespace umbra::atmosphere {

/// The radii that bound an atmosphere.
struct ShellRadii {
  double bottomRadiusM = 0.0;  ///< the ground
  double topRadiusM = 0.0;     ///< the end of the atmosphere
};

/// sqrt(max(0, a)).
inline double safeSqrt(double a) { return std::sqrt(std::max(0.0, a)); }
/// mu clamped to [-1, 1] (inline: the precomputation's inner loops call it).
inline double clampCosine(double mu) { return std::min(std::max(mu, -1.0), 1.0); }

/// Distance from radius r along mu to the sphere of radius `topRadiusM` (r <= top), the
/// far intersection; stable for mu near +-1 and for r near the top.
inline double distanceToTopBoundaryM(double topRadiusM, double r, double mu) {
  // disc = r^2 (mu^2 - 1) + top^2, written without cancellation for r <= top; inline and
  // free of early returns so that loops over mu vectorise.
  const double t = topRadiusM;
  const double outside = (t - r) * (t + r);  // top^2 - r^2
  const double root = std::sqrt(std::max(0.0, outside + r * r * mu * mu));
  const double down = std::max(0.0, -r * mu + root);
  const double denominator = r * mu + root;
  const double up = (outside <= 0.0 || denominator <= 0.0) ? 0.0 : outside / denominator;  // = -r mu + root
  return mu < 0.0 ? down : up;
}
/// Distance from radius r along mu to the ground sphere (near intersection); only
/// meaningful where rayIntersectsGround().
double distanceToBottomBoundaryM(double bottomRadiusM, double radiusM, double mu);
/// True when the straight ray (r, mu) hits the ground sphere: mu < 0 and below the horizon.
bool rayIntersectsGround(double bottomRadiusM, double radiusM, double mu);
/// Cosine of the geometric horizon seen from radius r: -sqrt(1 - (bottom / r)^2).
double horizonCosine(double bottomRadiusM, double radiusM);
/// Distance [m] from radius r along the straight ray of view-zenith cosine mu, with the Sun
/// at zenith cosine muS and at cosine nu from the view, to the first point where the Sun's
/// zenith cosine there, (r muS + d nu) / r(d), has risen to muSMin: 0 when muS >= muSMin,
/// infinity when it never does. With u = d / r the condition squared is the quadratic
///     (nu^2 - m^2) u^2 + 2 (muS nu - m^2 mu) u + muS^2 - m^2 = 0   (m = muSMin),
/// whose roots count where muS + u nu has the sign of m.
double distanceToSunCosineM(double radiusM, double mu, double muS, double nu, double muSMin);

/// Bruneton's GetTextureCoordFromUnitRange: x in [0, 1] to a texture coordinate whose
/// texel centres lie at x = 0 and x = 1.
double textureCoordFromUnitRange(double x, int textureSize);
/// Bruneton's GetUnitRangeFromTextureCoord (inverse of the above).
double unitRangeFromTextureCoord(double u, int textureSize);

/// Unit-range coordinates of Eq. 2 (before the texel-centre mapping).
struct TransmittanceCoords {
  double xMu = 0.0;
  double xR = 0.0;
};
struct RadiusMu {
  double radiusM = 0.0;
  double mu = 0.0;
};

/// Eq. 2 for bottom <= r <= top and mu at or above the horizon (r is clamped to the
/// shell, x_mu to [0, 1]). At r = top every upward ray has x_mu = 0.
TransmittanceCoords transmittanceCoordsFromRMu(const ShellRadii& shell, double radiusM, double mu);
/// Its x_mu for a radius r already clamped to [bottom, top], rho = sqrt(r^2 - bottom^2) and
/// H = sqrt(top^2 - bottom^2) (inline, for loops over mu at one radius).
inline double transmittanceXMu(double topRadiusM, double r, double rho, double H, double mu) {
  const double d = distanceToTopBoundaryM(topRadiusM, r, std::min(std::max(mu, -1.0), 1.0));
  const double dMin = topRadiusM - r, dMax = rho + H;
  return std::min(std::max((d - dMin) / (dMax - dMin), 0.0), 1.0);
}
/// Inverse of Eq. 2; x_mu = 1 gives exactly the horizon, x_mu = 0 exactly the zenith.
RadiusMu rMuFromTransmittanceCoords(const ShellRadii& shell, const TransmittanceCoords& coords);

/// As above with texture coordinates (texel centres at the unit-range ends):
/// Bruneton's GetTransmittanceTextureUvFromRMu / GetRMuFromTransmittanceTextureUv.
TransmittanceCoords transmittanceUvFromRMu(const ShellRadii& shell, double radiusM, double mu,
                                           int width, int height);
RadiusMu rMuFromTransmittanceUv(const ShellRadii& shell, const TransmittanceCoords& uv, int width,
                                int height);

/// The (r, mu) at the centre of texel (x, y) of a width x height table in this space:
/// x_mu = x / (width - 1), x_r = y / (height - 1).
RadiusMu rMuAtTexel(const ShellRadii& shell, int x, int y, int width, int height);

} // namespace umbra::atmosphere
