// The eclipsed Moon's light: the shadow's profile averaged over the disc (closed forms),
// the oblate outline's shift, interpolation and bad input.
#include "EclipsedMoon.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace umbra::eclipse {
namespace {

/// A profile I = offset / scale (linear), samples every `step` metres to `maxM`.
std::vector<ProfileSample> linearProfile(double scaleM, double stepM = 1000.0, double maxM = 2e7) {
  std::vector<ProfileSample> p;
  for (double r = 0.0; r <= maxM; r += stepM) p.push_back({r, glm::dvec3(r / scaleM), r / scaleM});
  return p;
}

const EarthOutline kSphere{6371e3, 6371e3, 6371e3};

TEST(EclipsedMoon, AFlatProfileLeavesTheDiscAtItsValue) {
  std::vector<ProfileSample> flat{{0.0, glm::dvec3(0.25), 0.25}, {1e7, glm::dvec3(0.25), 0.25}};
  const EclipsedMoonLight l = eclipsedMoonLight(flat, {1.2e6, -0.4e6}, 1737.4e3, kSphere);
  EXPECT_NEAR(l.mean, 0.25, 1e-12);
  EXPECT_NEAR(l.centre, 0.25, 1e-12);
  EXPECT_NEAR(l.nearLimb, 0.25, 1e-12);
}

// Centred on the axis, a profile linear in the offset averages to 2a/3 over a disc of
// radius a (the mean distance from a disc's centre); off the axis by d >> a, to d (the
// linear term averages out, the curvature adds a^2 / 8d).
TEST(EclipsedMoon, ALinearProfileAveragesToTheDiscsMeanOffset) {
  const double a = 1737.4e3, scale = 1e6;
  const EclipsedMoonLight centred = eclipsedMoonLight(linearProfile(scale), {0.0, 0.0}, a, kSphere);
  EXPECT_NEAR(centred.mean, 2.0 * a / 3.0 / scale, 1e-4 * a / scale);
  EXPECT_NEAR(centred.centre, 0.0, 1e-12);
  EXPECT_NEAR(centred.nearLimb, a / scale, 1e-9);
  const double d = 8e6;
  const EclipsedMoonLight off = eclipsedMoonLight(linearProfile(scale), {0.0, d}, a, kSphere);
  EXPECT_NEAR(off.mean, (d + a * a / (8.0 * d)) / scale, 2e-3 * a * a / (8.0 * d) / scale + 1e-6);
  EXPECT_NEAR(off.nearLimb, (d - a) / scale, 1e-9);
  EXPECT_NEAR(off.farLimb, (d + a) / scale, 1e-9);
}

// The oblate outline: along the projected pole the limb lies lower, so the shadow's edge
// moves in: a point there sees the profile at its offset plus the outline's shortfall.
TEST(EclipsedMoon, TheOblateOutlineShiftsTheProfileAlongThePole) {
  const double a = 6378137.0, f = 1.0 / 298.257;
  const EarthOutline seenAlongTheEquator = earthOutline(a, f, 0.0, 6371e3);
  EXPECT_NEAR(seenAlongTheEquator.projectedPolarRadiusM, a * (1.0 - f), 1e-6);
  EXPECT_NEAR(earthOutline(a, f, 1.5707963267948966, 6371e3).projectedPolarRadiusM, a, 1e-6);  // pole-on: a circle
  EXPECT_NEAR(seenAlongTheEquator.radiusM(0.0), a, 1e-6);
  EXPECT_NEAR(seenAlongTheEquator.radiusM(1.5707963267948966), a * (1.0 - f), 1e-6);
  const double scale = 1e6, y = 2e6;
  const EclipsedMoonLight pole = eclipsedMoonLight(linearProfile(scale, 10.0, 4e6), {0.0, y}, 1000.0, seenAlongTheEquator);
  EXPECT_NEAR(pole.centre, (y - (a * (1.0 - f) - 6371e3)) / scale, 1e-9);
  const EclipsedMoonLight equator = eclipsedMoonLight(linearProfile(scale, 10.0, 4e6), {y, 0.0}, 1000.0, seenAlongTheEquator);
  EXPECT_NEAR(equator.centre, (y - (a - 6371e3)) / scale, 1e-9);
}

// The umbra's edge: a profile whose logarithm steps up 100 km outside the geometric umbra
// enlarges the occluder by 100 km / (1 + D / D_sun); the steepest rise of exp(r / H) + a
// step is the step.
TEST(EclipsedMoon, TheUmbrasEdgeIsWhereTheLogarithmRisesSteepest) {
  const SunOccluderSystem earth{696342e3, 6371e3, 1.495978707e11};
  const double distance = 384400e3;
  const double geometric = shadowConeRadii(earth, distance).umbraRadiusM;
  std::vector<ProfileSample> p;
  for (double r = 0.0; r < 9e6; r += 1000.0) {
    const double l = 1e-4 * std::exp(r / 2e6) * (r > geometric + 100e3 ? 100.0 : 1.0);
    p.push_back({r, glm::dvec3(l), l});
  }
  const double edge = steepestLogRiseOffsetM(p);
  EXPECT_NEAR(edge, geometric + 100e3, 1000.0);
  EXPECT_NEAR(umbraEdgeEnlargementM(p, earth, distance), (edge - geometric) / (1.0 + distance / earth.sunOccluderDistanceM),
              1e-6);
  EXPECT_NEAR(umbraEdgeEnlargementM(p, earth, distance), 100e3 / 1.00257, 1000.0);
  p[5].luminance = 0.0;
  EXPECT_THROW(steepestLogRiseOffsetM(p), std::invalid_argument);
}

// Vital's correlation: his own pairs (L 2.4 -> -1.56, L 3.0 -> -2.55), the round trip,
// and the scale's ends; the full Moon's mean surface brightness (V -12.73, 932.6") 3.36.
TEST(EclipsedMoon, DanjonScaleAndSurfaceBrightness) {
  EXPECT_NEAR(danjonMagnitude(2.4), -1.56, 1e-12);
  EXPECT_NEAR(danjonMagnitude(3.0), -2.55, 1e-12);
  for (double l = 0.0; l <= 4.0; l += 0.25) EXPECT_NEAR(danjonLFromMagnitude(danjonMagnitude(l)), l, 1e-12) << l;
  EXPECT_EQ(danjonLFromMagnitude(-6.0), 4.0);
  EXPECT_EQ(danjonLFromMagnitude(6.0), 0.0);
  EXPECT_NEAR(meanSurfaceBrightness(-12.73, 932.6 / 206264.806), 3.36, 0.01);
}

TEST(EclipsedMoon, InterpolationAndBadInput) {
  const std::vector<ProfileSample> p{{0.0, glm::dvec3(0.0), 0.0}, {10.0, glm::dvec3(1.0), 1.0}, {20.0, glm::dvec3(3.0), 3.0}};
  EXPECT_DOUBLE_EQ(profileLuminanceAt(p, 5.0), 0.5);
  EXPECT_DOUBLE_EQ(profileLuminanceAt(p, 15.0), 2.0);
  EXPECT_DOUBLE_EQ(profileLuminanceAt(p, -1.0), 0.0);
  EXPECT_DOUBLE_EQ(profileLuminanceAt(p, 99.0), 3.0);
  EXPECT_THROW(eclipsedMoonLight({p[0]}, {0.0, 0.0}, 1.0, kSphere), std::invalid_argument);
  EXPECT_THROW(eclipsedMoonLight({p[1], p[0]}, {0.0, 0.0}, 1.0, kSphere), std::invalid_argument);
  EXPECT_THROW(eclipsedMoonLight(p, {0.0, 0.0}, 0.0, kSphere), std::invalid_argument);
  EXPECT_THROW(eclipsedMoonLight(p, {std::nan(""), 0.0}, 1.0, kSphere), std::invalid_argument);
}

}  // namespace
}  // namespace umbra::eclipse

// The magnitudes from the shadow's light: unshadowed, the Moon's own; each factor of 100 in
// light five magnitudes; the Danjon L that of the V; the surface brightness the full Moon's
// plus the same dimming at each place.
TEST(EclipsedMoon, MagnitudesAddTheShadowsDimming) {
  const double fullV = -12.7, radiusRad = 0.0045;
  const umbra::eclipse::EclipsedMoonMagnitudes lit = umbra::eclipse::eclipsedMoonMagnitudes(fullV, radiusRad, umbra::eclipse::EclipsedMoonLight{});
  EXPECT_DOUBLE_EQ(lit.v, fullV);
  EXPECT_DOUBLE_EQ(lit.centreSurface, lit.fullSurface);
  EXPECT_DOUBLE_EQ(lit.fullSurface, umbra::eclipse::meanSurfaceBrightness(fullV, radiusRad));
  const umbra::eclipse::EclipsedMoonMagnitudes dark =
      umbra::eclipse::eclipsedMoonMagnitudes(fullV, radiusRad, umbra::eclipse::EclipsedMoonLight{1e-4, 1e-5, 1e-2, 1e-6});
  EXPECT_NEAR(dark.v, fullV + 10.0, 1e-12);
  EXPECT_NEAR(dark.centreSurface - dark.fullSurface, 12.5, 1e-12);
  EXPECT_NEAR(dark.nearLimbSurface - dark.fullSurface, 5.0, 1e-12);
  EXPECT_NEAR(dark.farLimbSurface - dark.fullSurface, 15.0, 1e-12);
  EXPECT_DOUBLE_EQ(dark.danjonL, umbra::eclipse::danjonLFromMagnitude(dark.v));
}
