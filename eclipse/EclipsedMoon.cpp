#include "EclipsedMoon.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace umbra::eclipse {
namespace {
constexpr double kPi = 3.14159265358979323846;
}

double EarthOutline::radiusM(double fromEquatorRad) const {
  const double s = std::sin(fromEquatorRad);
  return equatorialRadiusM * ellipseRadius(projectedPolarRadiusM / equatorialRadiusM, s * s);
}

EarthOutline earthOutline(double a, double f, double declinationRad, double profileRadiusM) {
  // The axis' declination: the sine of it is the view's cosine to the pole.
  return {a, a * outlinePolarRatio(std::sin(declinationRad), f), profileRadiusM};
}

double profileLuminanceAt(const std::vector<ProfileSample>& profile, double offsetM) {
  if (offsetM <= profile.front().offsetM) return profile.front().luminance;
  if (offsetM >= profile.back().offsetM) return profile.back().luminance;
  const auto above = std::upper_bound(profile.begin(), profile.end(), offsetM,
                                      [](double r, const ProfileSample& s) { return r < s.offsetM; });
  const ProfileSample& hi = *above;
  const ProfileSample& lo = *(above - 1);
  const double w = (offsetM - lo.offsetM) / (hi.offsetM - lo.offsetM);
  return lo.luminance + w * (hi.luminance - lo.luminance);
}

EclipsedMoonLight eclipsedMoonLight(const std::vector<ProfileSample>& profile, glm::dvec2 moonCentreM,
                                    double moonRadiusM, const EarthOutline& outline, int rings) {
  if (profile.size() < 2) throw std::invalid_argument("eclipsed Moon: the shadow profile has fewer than 2 samples");
  for (size_t i = 1; i < profile.size(); ++i)
    if (!(profile[i].offsetM > profile[i - 1].offsetM))
      throw std::invalid_argument("eclipsed Moon: the shadow profile's offsets do not increase");
  if (!(moonRadiusM > 0.0) || !(rings >= 1) || !std::isfinite(moonCentreM.x) || !std::isfinite(moonCentreM.y))
    throw std::invalid_argument("eclipsed Moon: the disc needs a radius > 0, a finite centre and rings >= 1");
  const auto at = [&](glm::dvec2 p) {
    const double r = glm::length(p);
    const double theta = r > 0.0 ? std::atan2(p.y, p.x) : 0.0;
    return profileLuminanceAt(profile, std::max(0.0, r - (outline.radiusM(theta) - outline.profileRadiusM)));
  };
  EclipsedMoonLight light;
  double sum = 0.0, area = 0.0;
  const int sectors = 4 * rings;
  for (int i = 0; i < rings; ++i) {
    const double r = (i + 0.5) / rings * moonRadiusM;
    const double ringArea = 2.0 * kPi * r * (moonRadiusM / rings) / sectors;
    for (int j = 0; j < sectors; ++j) {
      const double phi = (j + 0.5) / sectors * 2.0 * kPi;
      sum += ringArea * at(moonCentreM + r * glm::dvec2(std::cos(phi), std::sin(phi)));
      area += ringArea;
    }
  }
  light.mean = sum / area;
  light.centre = at(moonCentreM);
  const double d = glm::length(moonCentreM);
  const glm::dvec2 out = d > 0.0 ? moonCentreM / d : glm::dvec2(0.0, 1.0);
  light.nearLimb = at(moonCentreM - moonRadiusM * out);
  light.farLimb = at(moonCentreM + moonRadiusM * out);
  return light;
}

double danjonMagnitude(double danjonL) { return 4.2 - 3.0 * danjonL + 0.25 * danjonL * danjonL; }

double danjonLFromMagnitude(double magnitudeV) {
  // L^2 / 4 - 3 L + (4.2 - V) = 0, the root below the parabola's vertex (L = 6).
  return std::clamp(2.0 * (3.0 - std::sqrt(std::max(0.0, 4.8 + magnitudeV))), 0.0, 4.0);
}

EclipsedMoonMagnitudes eclipsedMoonMagnitudes(double uneclipsedV, double moonAngularRadiusRad,
                                              const EclipsedMoonLight& light) {
  const auto dimming = [](double factor) { return -2.5 * std::log10(std::max(factor, 1e-30)); };
  EclipsedMoonMagnitudes m;
  m.v = uneclipsedV + dimming(light.mean);
  m.danjonL = danjonLFromMagnitude(m.v);
  m.fullSurface = meanSurfaceBrightness(uneclipsedV, moonAngularRadiusRad);
  m.centreSurface = m.fullSurface + dimming(light.centre);
  m.nearLimbSurface = m.fullSurface + dimming(light.nearLimb);
  m.farLimbSurface = m.fullSurface + dimming(light.farLimb);
  return m;
}

double meanSurfaceBrightness(double magnitude, double angularRadiusRad) {
  const double radiusArcsec = angularRadiusRad * 180.0 / kPi * 3600.0;
  return magnitude + 2.5 * std::log10(kPi * radiusArcsec * radiusArcsec);
}

double steepestLogRiseOffsetM(const std::vector<ProfileSample>& profile) {
  if (profile.size() < 2) throw std::invalid_argument("umbra's edge: the shadow profile has fewer than 2 samples");
  double best = -1.0, at = profile.front().offsetM;
  for (size_t i = 1; i < profile.size(); ++i) {
    const ProfileSample &a = profile[i - 1], &b = profile[i];
    if (!(a.luminance > 0.0 && b.luminance > 0.0 && b.offsetM > a.offsetM))
      throw std::invalid_argument("umbra's edge: the shadow profile needs luminances > 0 at increasing offsets");
    const double rise = std::log(b.luminance / a.luminance) / (b.offsetM - a.offsetM);
    if (rise > best) best = rise, at = 0.5 * (a.offsetM + b.offsetM);
  }
  return at;
}

double umbraEdgeEnlargementM(const std::vector<ProfileSample>& profile, const SunOccluderSystem& system,
                             double distanceBehindM) {
  const double geometric = shadowConeRadii(system, distanceBehindM).umbraRadiusM;
  return (steepestLogRiseOffsetM(profile) - geometric) / (1.0 + distanceBehindM / system.sunOccluderDistanceM);
}

}  // namespace umbra::eclipse
