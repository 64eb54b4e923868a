#include "ShadowMapping.hpp"

#include "SolarDisc.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace umbra::eclipse {
namespace {
constexpr double kHalfPi = 1.57079632679489661923;
}

double angularRadiusRad(double radiusM, double distanceM) {
  return distanceM <= radiusM ? kHalfPi : std::asin(radiusM / distanceM);
}

double AngularRadiusExpansion::at(double d) const {
  const double e = distanceM / d - 1.0;
  return phi0Rad + e * (c1Rad + e * c2Rad);
}

AngularRadiusExpansion angularRadiusExpansion(double radiusM, double distanceM, double halfWidthM) {
  AngularRadiusExpansion x;
  x.distanceM = distanceM;
  x.phi0Rad = angularRadiusRad(radiusM, distanceM);
  x.maxPhiRad = angularRadiusRad(radiusM, distanceM - halfWidthM);
  if (!(distanceM - halfWidthM > radiusM)) {
    x.maxErrorRad = std::numeric_limits<double>::infinity();
    return x;
  }
  // d/dw asin(r w) = r / s, d2/dw2 = r^3 w / s^3 (s = sqrt(1 - r^2 w^2)); times w0 and w0^2.
  const double q = radiusM / distanceM, s = std::sqrt((1.0 - q) * (1.0 + q));
  x.c1Rad = q / s;
  x.c2Rad = 0.5 * q * q * q / (s * s * s);
  constexpr int kPoints = 65;
  for (int k = 0; k < kPoints; ++k) {
    const double d = distanceM - halfWidthM + 2.0 * halfWidthM * k / (kPoints - 1);
    x.maxErrorRad = std::max(x.maxErrorRad, std::abs(angularRadiusRad(radiusM, d) - x.at(d)));
  }
  return x;
}

bool receiverShadowExpands(const AngularRadiusExpansion& sun, const AngularRadiusExpansion& occluder) {
  return sun.exactToFloat() && occluder.exactToFloat() && sun.maxPhiRad + occluder.maxPhiRad <= kSmallAngleSeriesMaxRad;
}

double angleBetweenRad(const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 na = a / glm::length(a), nb = b / glm::length(b);
  return 2.0 * std::atan2(glm::length(na - nb), glm::length(na + nb));
}

ShadowAngles shadowAngles(const glm::dvec3& p, const glm::dvec3& sun, double sunRadiusM,
                          const glm::dvec3& occ, double occRadiusM) {
  return {angularRadiusRad(sunRadiusM, glm::length(sun - p)),
          angularRadiusRad(occRadiusM, glm::length(occ - p)), angleBetweenRad(sun - p, occ - p)};
}

double equatorialRadiusM(double meanRadiusM, const Oblateness& figure) {
  return figure.flattening == 0.0 ? meanRadiusM : meanRadiusM / std::cbrt(1.0 - figure.flattening);
}

double outlinePolarRatio(double cosViewToPole, double flattening) {
  const double e2 = flattening * (2.0 - flattening);
  return std::sqrt(1.0 - e2 * (1.0 - cosViewToPole * cosViewToPole));
}

double ellipseRadius(double q, double cosToMinorSq) {
  return q / std::sqrt(q * q + (1.0 - q * q) * cosToMinorSq);
}

double outlineRadiusFactor(const glm::dvec3& viewDir, const glm::dvec3& towards, const Oblateness& figure) {
  const double cosView = glm::dot(viewDir, figure.pole);
  const double poleAcrossSq = 1.0 - cosView * cosView;  // the pole's part across the view, squared
  const glm::dvec3 across = towards - glm::dot(towards, viewDir) * viewDir;
  const double acrossSq = glm::dot(across, across);
  if (!(poleAcrossSq > 0.0 && acrossSq > 0.0)) return 1.0;
  const double tp = glm::dot(across, figure.pole);
  const double cosToPoleSq = std::min(1.0, tp * tp / (acrossSq * poleAcrossSq));
  return ellipseRadius(outlinePolarRatio(cosView, figure.flattening), cosToPoleSq);
}

double outlineRadiusTowardsSunM(const glm::dvec3& p, const glm::dvec3& sun, const glm::dvec3& occ,
                                double meanRadiusM, const Oblateness& figure) {
  if (figure.flattening == 0.0) return meanRadiusM;
  return equatorialRadiusM(meanRadiusM, figure) * outlineRadiusFactor(glm::normalize(occ - p), sun - p, figure);
}

ShadowAngles shadowAngles(const glm::dvec3& p, const glm::dvec3& sun, double sunRadiusM, const glm::dvec3& occ,
                          double meanRadiusM, const Oblateness& figure) {
  return shadowAngles(p, sun, sunRadiusM, occ, outlineRadiusTowardsSunM(p, sun, occ, meanRadiusM, figure));
}

double visibleFractionPastSpheroid(const glm::dvec3& p, const glm::dvec3& sun, double sunRadiusM,
                                   const glm::dvec3& occ, double meanRadiusM, const Oblateness& figure,
                                   double limbDarkening, int n) {
  // The spheroid stretched along its pole by a / b is the sphere of radius a, and a ray
  // meets the one where its stretched image meets the other.
  const double f = figure.flattening;
  const double a = equatorialRadiusM(meanRadiusM, figure), stretch = 1.0 / (1.0 - f);
  const auto stretched = [&](const glm::dvec3& v) { return v + (stretch - 1.0) * glm::dot(v, figure.pole) * figure.pole; };
  const glm::dvec3 toSun = sun - p;
  const double phiSun = angularRadiusRad(sunRadiusM, glm::length(toSun));
  const glm::dvec3 s = glm::normalize(toSun);
  const glm::dvec3 e1 = glm::normalize(std::abs(s.x) < 0.9 ? glm::cross(s, glm::dvec3(1, 0, 0)) : glm::cross(s, glm::dvec3(0, 1, 0)));
  const glm::dvec3 e2 = glm::cross(s, e1);
  const glm::dvec3 origin = stretched(p - occ);
  double total = 0.0, seen = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = -1.0 + (2.0 * i + 1.0) / n, y = -1.0 + (2.0 * j + 1.0) / n, rho2 = x * x + y * y;
      if (rho2 > 1.0) continue;
      const double w = limbDarkenedLuminanceAtSquare(rho2, limbDarkening);
      total += w;
      const double rho = std::sqrt(rho2), angle = rho * phiSun;
      const glm::dvec3 across = rho > 0.0 ? (x * e1 + y * e2) / rho : e1;
      const glm::dvec3 d = stretched(std::cos(angle) * s + std::sin(angle) * across);
      // |origin + t d| = a for some t > 0 (the occluder nearer than the Sun).
      const double b = glm::dot(origin, d), c = glm::dot(origin, origin) - a * a, dd = glm::dot(d, d);
      const bool hit = b * b - dd * c >= 0.0 && (c < 0.0 || b < 0.0);
      if (!hit) seen += w;
    }
  return total > 0.0 ? seen / total : 1.0;
}

bool occluderInFront(const glm::dvec3& p, const glm::dvec3& sun, const glm::dvec3& occ) {
  return glm::length(occ - p) < glm::length(sun - p);
}

LutCoords lutCoords(const ShadowAngles& a) {
  const double sum = a.occluderAngularRadiusRad + a.sunAngularRadiusRad;
  return {a.sunAngularRadiusRad / sum, a.separationRad / sum};
}

NormalisedDiscs normalisedDiscs(const ShadowAngles& a) {
  return {a.occluderAngularRadiusRad / a.sunAngularRadiusRad,
          a.separationRad / a.sunAngularRadiusRad};
}

NormalisedDiscs normalisedDiscs(const LutCoords& c) {
  // phi_occ/phi_sun = 1/u - 1 and delta/phi_sun = v (phi_occ/phi_sun + 1) = v/u.
  return {(1.0 - c.u) / c.u, c.v / c.u};
}

namespace {

/// One step of Eq. 5-6 for a fixed (u, v): from a guess of d_sun to the next one.
struct Eq56 {
  LutCoords c;
  SunOccluderSystem s;

  struct State {
    double phiSun, phiOcc, delta, dOcc, dSun;
  };
  State at(double dSun) const {
    State st{};
    st.phiSun = angularRadiusRad(s.sunRadiusM, dSun);
    st.phiOcc = st.phiSun * (1.0 - c.u) / c.u;                       // Eq. 5
    st.delta = c.v * (st.phiOcc + st.phiSun);
    st.dOcc = s.occluderRadiusM / std::sin(std::min(st.phiOcc, kHalfPi));  // Eq. 6
    const double sinD = std::sin(st.delta), cosD = std::cos(st.delta);
    const double disc = s.sunOccluderDistanceM * s.sunOccluderDistanceM - st.dOcc * st.dOcc * sinD * sinD;
    st.dSun = st.dOcc * cosD + std::sqrt(std::max(0.0, disc));
    return st;
  }
};

/// Solve the law of cosines for the point at distance dOcc from the occluder whose
/// occluder and Sun are `delta` apart: returns the u reached there (used for clamping).
double uAtOccluderDistance(double dOcc, double v, const SunOccluderSystem& s) {
  const double phiOcc = angularRadiusRad(s.occluderRadiusM, dOcc);
  double phiSun = angularRadiusRad(s.sunRadiusM, s.sunOccluderDistanceM + dOcc);
  for (int i = 0; i < 50; ++i) {  // contracts by ~phi_sun per step
    const double delta = v * (phiOcc + phiSun);
    const double d = s.sunOccluderDistanceM, sinD = std::sin(delta);
    const double dSun = dOcc * std::cos(delta) + std::sqrt(std::max(0.0, d * d - dOcc * dOcc * sinD * sinD));
    const double next = angularRadiusRad(s.sunRadiusM, dSun);
    if (std::abs(next - phiSun) <= 1e-15 * phiSun) break;
    phiSun = next;
  }
  return phiSun / (phiOcc + phiSun);
}

} // namespace

InverseMapping inverseLutCoords(const LutCoords& requested, const SunOccluderSystem& sys,
                                double tol, int maxIterations, double maxDistanceFactor) {
  InverseMapping out;
  LutCoords c{std::clamp(requested.u, 0.0, 1.0), std::clamp(requested.v, 0.0, 1.0)};

  // Points behind the occluder see u between its value at the occluder's surface and its
  // value "at infinity" (here maxDistanceFactor * d); outside that range no point exists.
  const double uMin = uAtOccluderDistance(sys.occluderRadiusM * (1.0 + 1e-9), c.v, sys);
  const double uMax = uAtOccluderDistance(maxDistanceFactor * sys.sunOccluderDistanceM, c.v, sys);
  if (!(c.u >= uMin)) { c.u = uMin; out.clamped = true; }
  if (!(c.u <= uMax)) { c.u = uMax; out.clamped = true; }

  // Eq. 5-6 as a fixed-point iteration on d_sun, starting at the occluder (d_sun = d).
  // Near u_max the iteration contracts slowly (rate -> 1); then an Aitken extrapolation
  // over the last three iterates jumps to the limit (Steffensen's method).
  const Eq56 eq{c, sys};
  double x = sys.sunOccluderDistanceM;
  Eq56::State st = eq.at(x);
  double prevStep = std::numeric_limits<double>::quiet_NaN();
  double prevDOcc = st.dOcc;
  out.iterations = 1;
  while (out.iterations < maxIterations) {
    const double step = st.dSun - x;
    const double dOccChange = std::abs(st.dOcc - prevDOcc);
    x = st.dSun;
    if (std::abs(step) <= tol * x && dOccChange <= tol * st.dOcc && out.iterations > 1) {
      out.converged = true;
      break;
    }
    if (std::isfinite(prevStep) && prevStep != 0.0) {
      const double ratio = step / prevStep;
      if (ratio > 0.3 && ratio < 1.0) {            // slow, monotone: extrapolate
        x += step * ratio / (1.0 - ratio);
        x = std::max(x, sys.sunRadiusM * (1.0 + 1e-12));
        prevStep = std::numeric_limits<double>::quiet_NaN();
        prevDOcc = st.dOcc;
        st = eq.at(x);
        ++out.iterations;
        continue;
      }
    }
    prevStep = step;
    prevDOcc = st.dOcc;
    st = eq.at(x);
    ++out.iterations;
  }

  // The point itself: in the triangle (point, occluder, Sun) the angle at the Sun is
  // sigma = asin(d_occ sin(delta) / d); the point lies delta + sigma off the anti-Sun axis.
  const double sigma = std::asin(std::min(1.0, st.dOcc * std::sin(st.delta) / sys.sunOccluderDistanceM));
  const double off = st.delta + sigma;
  out.pointM = {st.dOcc * std::cos(off), st.dOcc * std::sin(off), 0.0};
  out.occluderDistanceM = st.dOcc;
  out.sunDistanceM = glm::length(out.pointM - glm::dvec3(-sys.sunOccluderDistanceM, 0.0, 0.0));
  out.angles = shadowAngles(out.pointM, {-sys.sunOccluderDistanceM, 0.0, 0.0}, sys.sunRadiusM,
                            {0.0, 0.0, 0.0}, sys.occluderRadiusM);
  out.reached = lutCoords(out.angles);
  return out;
}

double occluderDistanceForUmbraM(double D, double sunRadiusM, double occRadiusM, double r) {
  return D * (occRadiusM - r) / (sunRadiusM - r);
}

ShadowConeRadii shadowConeRadii(const SunOccluderSystem& s, double x) {
  // Umbra: the cone of external tangents, half angle asin((R_sun - R_occ) / d), tip at
  // R_occ / sin(half angle) behind the occluder. Penumbra: internal tangents, half angle
  // asin((R_sun + R_occ) / d), tip R_occ / sin(half angle) in front of the occluder.
  const double sinU = (s.sunRadiusM - s.occluderRadiusM) / s.sunOccluderDistanceM;
  const double sinP = (s.sunRadiusM + s.occluderRadiusM) / s.sunOccluderDistanceM;
  const double tanU = sinU / std::sqrt(1.0 - sinU * sinU);
  const double tanP = sinP / std::sqrt(1.0 - sinP * sinP);
  ShadowConeRadii r;
  r.umbraLengthM = s.occluderRadiusM / sinU;
  r.umbraRadiusM = std::max(0.0, (r.umbraLengthM - x) * tanU);
  r.antumbraRadiusM = std::max(0.0, (x - r.umbraLengthM) * tanU);
  r.penumbraRadiusM = (s.occluderRadiusM / sinP + x) * tanP;
  return r;
}

} // namespace umbra::eclipse
