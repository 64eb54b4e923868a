#include "TextureCoords.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace umbra::atmosphere {

double distanceToBottomBoundaryM(double bottomRadiusM, double r, double mu) {
  const double b = bottomRadiusM;
  const double above = (r - b) * (r + b);  // r^2 - bottom^2
  const double disc = std::max(0.0, r * r * mu * mu - above);
  const double denominator = -r * mu + std::sqrt(disc);
  if (denominator <= 0.0) return 0.0;
  return std::max(0.0, above / denominator);  // = -r mu - sqrt(disc)
}

bool rayIntersectsGround(double bottomRadiusM, double r, double mu) {
  const double b = bottomRadiusM;
  return mu < 0.0 && r * r * mu * mu - (r - b) * (r + b) >= 0.0;
}

double horizonCosine(double bottomRadiusM, double r) {
  const double b = bottomRadiusM;
  return r <= b ? 0.0 : -safeSqrt((r - b) * (r + b)) / r;
}

double distanceToSunCosineM(double r, double mu, double muS, double nu, double muSMin) {
  if (muS >= muSMin) return 0.0;
  if (muSMin == 0.0) return nu > 0.0 ? -muS / nu * r : std::numeric_limits<double>::infinity();  // linear
  const double m2 = muSMin * muSMin;
  const double A = nu * nu - m2, B = muS * nu - m2 * mu, C = muS * muS - m2;
  double roots[2] = {-1.0, -1.0};
  if (A == 0.0) {
    if (B != 0.0) roots[0] = -0.5 * C / B;
  } else {
    // A tangent (disc = 0, as for m = 0) may round to a slightly negative disc.
    const double disc = B * B - A * C;
    if (disc < -1e-12 * (B * B + std::abs(A * C))) return std::numeric_limits<double>::infinity();
    const double q = -(B + std::copysign(std::sqrt(std::max(disc, 0.0)), B));  // no cancellation
    roots[0] = q / A;
    if (q != 0.0) roots[1] = C / q;
  }
  double u = std::numeric_limits<double>::infinity();
  for (double x : roots)
    if (x >= 0.0 && (muS + x * nu) * muSMin >= 0.0) u = std::min(u, x);
  return u * r;
}

double textureCoordFromUnitRange(double x, int textureSize) {
  const double n = static_cast<double>(textureSize);
  return 0.5 / n + x * (1.0 - 1.0 / n);
}

double unitRangeFromTextureCoord(double u, int textureSize) {
  const double n = static_cast<double>(textureSize);
  return (u - 0.5 / n) / (1.0 - 1.0 / n);
}

TransmittanceCoords transmittanceCoordsFromRMu(const ShellRadii& shell, double radiusM, double mu) {
  const double b = shell.bottomRadiusM, t = shell.topRadiusM;
  const double r = std::clamp(radiusM, b, t);
  const double H = std::sqrt((t - b) * (t + b));
  const double rho = safeSqrt((r - b) * (r + b));
  return {transmittanceXMu(t, r, rho, H, mu), std::clamp(rho / H, 0.0, 1.0)};
}

RadiusMu rMuFromTransmittanceCoords(const ShellRadii& shell, const TransmittanceCoords& c) {
  const double b = shell.bottomRadiusM, t = shell.topRadiusM;
  const double xMu = std::clamp(c.xMu, 0.0, 1.0), xR = std::clamp(c.xR, 0.0, 1.0);
  const double H = std::sqrt((t - b) * (t + b));
  const double rho = H * xR;
  const double r = std::min(t, std::sqrt(rho * rho + b * b));
  if (xMu <= 0.0) return {r, 1.0};
  if (xMu >= 1.0) return {r, -rho / r};  // the horizon, exactly (0 on the ground)
  const double outside = H * H * (1.0 - xR) * (1.0 + xR);  // top^2 - r^2 = H^2 - rho^2
  const double dMin = outside / (t + r), dMax = rho + H;
  const double d = (1.0 - xMu) * dMin + xMu * dMax;
  if (d <= 0.0) return {r, 1.0};
  return {r, clampCosine((outside - d * d) / (2.0 * r * d))};
}

TransmittanceCoords transmittanceUvFromRMu(const ShellRadii& shell, double radiusM, double mu,
                                           int width, int height) {
  const TransmittanceCoords x = transmittanceCoordsFromRMu(shell, radiusM, mu);
  return {textureCoordFromUnitRange(x.xMu, width), textureCoordFromUnitRange(x.xR, height)};
}

RadiusMu rMuFromTransmittanceUv(const ShellRadii& shell, const TransmittanceCoords& uv, int width,
                                int height) {
  return rMuFromTransmittanceCoords(
      shell, {unitRangeFromTextureCoord(uv.xMu, width), unitRangeFromTextureCoord(uv.xR, height)});
}

RadiusMu rMuAtTexel(const ShellRadii& shell, int x, int y, int width, int height) {
  const double xMu = width > 1 ? static_cast<double>(x) / (width - 1) : 0.0;
  const double xR = height > 1 ? static_cast<double>(y) / (height - 1) : 0.0;
  return rMuFromTransmittanceCoords(shell, {xMu, xR});
}

} // namespace umbra::atmosphere
