#include "ShadowLut.hpp"

#include "Colour.hpp"
#include "ParallelErrors.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

namespace umbra::eclipse {

glm::dvec3 ShadowLut::texel(int i, int j) const {
  const std::size_t k = 3 * (static_cast<std::size_t>(j) * width + i);
  return {rgb[k], rgb[k + 1], rgb[k + 2]};
}

glm::dvec3 ShadowLut::sample(const LutCoords& c) const {
  // A NaN would pass std::clamp and become an index.
  if (!(std::isfinite(c.u) && std::isfinite(c.v)))
    throw std::invalid_argument("shadow LuT lookup at a non-finite (u, v): the shadow's geometry is degenerate");
  // GL_LINEAR with GL_CLAMP_TO_EDGE: texel centres at (i + 0.5) / size.
  const double x = std::clamp(range().textureU(c.u) * width - 0.5, 0.0, width - 1.0);
  const double y = std::clamp(textureV(c.v) * height - 0.5, 0.0, height - 1.0);
  const int i0 = std::min(static_cast<int>(x), width - 1), j0 = std::min(static_cast<int>(y), height - 1);
  const int i1 = std::min(i0 + 1, width - 1), j1 = std::min(j0 + 1, height - 1);
  const double fx = x - i0, fy = y - j0;
  return (1 - fy) * ((1 - fx) * texel(i0, j0) + fx * texel(i1, j0)) +
         fy * ((1 - fx) * texel(i0, j1) + fx * texel(i1, j1));
}

double airlessShadow(const LutCoords& c, double limbDarkening, double tol) {
  if (c.v >= 1.0) return 1.0;
  const NormalisedDiscs n = normalisedDiscs(c);
  return visibleFractionLimbDarkened(n.occluderRadius, n.separation, limbDarkening, tol).value;
}

double LutRange::textureV(double v) const {
  if (vLowFraction > 0.0 && v < vMin) return vLowFraction * v / vMin;
  return vLowFraction + (1.0 - vLowFraction) * (v - vMin) / (vMax - vMin);
}

LutRange::TextureMap LutRange::textureMap() const {
  TextureMap m;
  m.uOrigin = uMin;
  m.uScale = 1.0 / (uMax - uMin);
  // f + (1 - f)(v - vMin) / (vMax - vMin) = (v - (vMin - f / s)) s with s = (1 - f) / (vMax - vMin).
  m.vScale = (1.0 - vLowFraction) / (vMax - vMin);
  m.vOrigin = vMin - vLowFraction / m.vScale;
  if (vLowFraction > 0.0) {  // f v / vMin below vMin
    m.vSplit = vMin;
    m.vLowOrigin = 0.0;
    m.vLowScale = vLowFraction / vMin;
  } else {
    m.vLowOrigin = m.vOrigin;
    m.vLowScale = m.vScale;
  }
  return m;
}

double LutRange::texelV(int j, int height) const {
  if (vLowFraction <= 0.0) return vMin + (vMax - vMin) * (j + 0.5) / height;
  const double t = (j + 0.5) / height;
  return t < vLowFraction ? vMin * t / vLowFraction : vMin + (vMax - vMin) * (t - vLowFraction) / (1.0 - vLowFraction);
}

void checkLutRange(double uMin, double uMax, double vMin, double vMax, double vLowFraction) {
  if (!(uMin >= 0.0 && uMin < uMax && uMax <= 1.0 && vMin >= 0.0 && vMin < vMax && vMax <= 1.0 &&
        vLowFraction >= 0.0 && vLowFraction < 1.0 && (vLowFraction == 0.0 || vMin > 0.0)))
    throw std::invalid_argument("shadow LuT ranges must satisfy 0 <= min < max <= 1 in u and v, "
                                "0 <= vLowFraction < 1 (> 0 only with vMin > 0)");
}

LutRange lutRangeForDistances(const SunOccluderSystem& s, double minDistanceM, double maxDistanceM, bool darkUmbra,
                              int height) {
  if (!(minDistanceM > 0.0 && minDistanceM <= maxDistanceM && std::isfinite(maxDistanceM)))
    throw std::invalid_argument("distance range must satisfy 0 < min <= max");
  if (!(maxDistanceM < s.sunOccluderDistanceM - s.sunRadiusM))
    throw std::invalid_argument("distance range reaches the Sun");
  // u = phi_sun / (phi_occ + phi_sun) grows with the distance from the occluder and with
  // the Sun's apparent size, i.e. as the distance from the Sun shrinks.
  auto u = [&](double occluderDistanceM, double sunDistanceM) {
    const double phiSun = angularRadiusRad(s.sunRadiusM, sunDistanceM);
    return phiSun / (angularRadiusRad(s.occluderRadiusM, occluderDistanceM) + phiSun);
  };
  const double uMin = std::max(u(minDistanceM, s.sunOccluderDistanceM + minDistanceM), 0.0);
  double uMax = std::min(u(maxDistanceM, s.sunOccluderDistanceM - maxDistanceM), 1.0);
  if (!(uMin < uMax)) uMax = std::min(1.0, uMin + 1e-9);
  return lutRangeForU(uMin, uMax, darkUmbra, height);
}

LutRange lutRangeForU(double uMin, double uMax, bool darkUmbra, int height) {
  if (!(uMin >= 0.0 && uMin < uMax && uMax <= 1.0)) throw std::invalid_argument("u range must satisfy 0 <= min < max <= 1");
  LutRange r{uMin, uMax};
  r.vMax = 1.0;
  const double edge = 1.0 - 2.0 * r.uMax, half = 0.5 / std::max(height, 2);
  if (darkUmbra) {
    // Row 0's centre vMin + (1 - vMin) / (2 height) at or below the umbra's edge.
    r.vMin = edge > half ? (edge - half) / (1.0 - half) : 0.0;
  } else if (edge > 0.0) {
    r.vMin = edge, r.vLowFraction = 0.25;
  }
  return r;
}

bool rangedLutPays(const LutRange& range, int height) { return 2.0 * range.uMax * height < 16.0; }

ShadowLut buildAirlessShadowLut(const ShadowLutParams& p, const Progress& progress, const TexelShare& share) {
  if (p.width < 2 || p.height < 2) throw std::invalid_argument("shadow LuT size must be at least 2x2");
  if (share.count < 1 || share.index < 0 || share.index >= share.count)
    throw std::invalid_argument("texel share: index outside 0..count-1");
  checkLutRange(p.uMin, p.uMax, p.vMin, p.vMax, p.vLowFraction);
  ShadowLut lut;
  lut.width = p.width;
  lut.height = p.height;
  lut.uMin = p.uMin;
  lut.uMax = p.uMax;
  lut.vMin = p.vMin;
  lut.vMax = p.vMax;
  lut.vLowFraction = p.vLowFraction;
  lut.rgb.assign(3 * static_cast<std::size_t>(p.width) * p.height, 0.0f);
  std::atomic<int> rowsDone{0};
  std::atomic<bool> cancelled{false};

  ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1)
  for (int j = 0; j < p.height; ++j) {
    if (cancelled.load()) continue;
    errors.run([&] {
      for (int i = 0; i < p.width; ++i) {
        if (!share.owns(static_cast<long long>(j) * p.width + i)) continue;
        const LutCoords c{lut.texelU(i), lut.texelV(j)};
        const float value = static_cast<float>(airlessShadow(c, p.limbDarkening, p.relativeTolerance));
        float* t = &lut.rgb[3 * (static_cast<std::size_t>(j) * p.width + i)];
        t[0] = t[1] = t[2] = value;
      }
    });
    const int done = ++rowsDone;
    // Report from whichever thread finishes a row; callers see a monotone sequence
    // only approximately, which is all a progress bar needs.
#pragma omp critical(umbra_progress)
    if (progress && !progress(static_cast<double>(done) / p.height)) cancelled = true;
  }
  errors.rethrow();
  if (cancelled) return {};
  return lut;
}

double lightTimeToSurfaceS(const glm::dvec3& pointM, const glm::dvec3& centreM, double radiusM) {
  return std::max(0.0, glm::length(centreM - pointM) - radiusM) / kLightSpeedMps;
}

Occluder seenFromCamera(const Occluder& body, const glm::dvec3& cameraM) {
  Occluder seen = body;
  seen.lightDelayS = lightTimeToSurfaceS(cameraM, body.centreM, body.radiusM);
  seen.centreM -= body.velocityMps * seen.lightDelayS;
  return seen;
}

Occluder occluderSeenBy(const Occluder& o, const glm::dvec3& receiverCentreM, double receiverRadiusM,
                        double receiverDelayS) {
  const double delayS = receiverDelayS + lightTimeToSurfaceS(o.centreM, receiverCentreM, receiverRadiusM);
  Occluder seen = o;
  seen.centreM -= o.velocityMps * (delayS - o.lightDelayS);
  seen.lightDelayS = delayS;
  return seen;
}

glm::dvec3 eclipseFactor(const glm::dvec3& p, const glm::dvec3& sun, double sunRadiusM,
                         const Occluder& occ, const ShadowLut* lut, double limbDarkening) {
  if (!occluderInFront(p, sun, occ.centreM)) return glm::dvec3(1.0);
  const LutCoords c = lutCoords(shadowAngles(p, sun, sunRadiusM, occ.centreM, occ.radiusM, occ.figure));
  if (c.v >= 1.0) return glm::dvec3(1.0);
  return lut ? lut->sample(c) : glm::dvec3(airlessShadow(c, limbDarkening));
}

std::vector<ProfileSample> shadowProfile(const SunOccluderSystem& s, double distanceBehindM,
                                         double maxOffsetM, int samples, const ShadowLut* lut,
                                         double limbDarkening) {
  if (samples < 2) throw std::invalid_argument("a shadow profile needs at least 2 samples");
  // Sun at (-d, 0, 0), occluder at the origin, the shadow axis along +x.
  const glm::dvec3 sun(-s.sunOccluderDistanceM, 0.0, 0.0);
  const Occluder occ{{0.0, 0.0, 0.0}, s.occluderRadiusM};
  std::vector<ProfileSample> out(samples);
  ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 16)
  for (int k = 0; k < samples; ++k) errors.run([&] {
    const double offset = maxOffsetM * k / (samples - 1);
    const glm::dvec3 rgb = eclipseFactor({distanceBehindM, offset, 0.0}, sun, s.sunRadiusM, occ, lut, limbDarkening);
    out[k] = {offset, rgb, colour::luminance(rgb)};
  });
  errors.rethrow();
  return out;
}

} // namespace umbra::eclipse
