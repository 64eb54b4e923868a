#include "ShadowMapping.hpp"
#include "SolarDisc.hpp"
#include "ShadowLut.hpp"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace umbra::eclipse;

namespace {
constexpr double kAu = 149597870700.0;

struct NamedSystem {
  std::string name;
  SunOccluderSystem system;
};

// From the smallest occluder to the largest distance: Phobos at Mars, Moon and Earth at
// 1 au, Mars, Jupiter at its distance, and a Phobos-sized rock at Jupiter's distance.
std::vector<NamedSystem> systems() {
  return {{"Phobos", {kSunRadiusM, 11.08e3, 1.523679 * kAu}},
          {"Moon", {kSunRadiusM, 1737.4e3, kAu}},
          {"Earth", {kSunRadiusM, 6371.0084e3, kAu}},
          {"Mars", {kSunRadiusM, 3389.5e3, 1.523679 * kAu}},
          {"Jupiter", {kSunRadiusM, 69911e3, 5.2038 * kAu}},
          {"rock at Jupiter", {kSunRadiusM, 11.08e3, 5.2038 * kAu}}};
}

// u reachable from behind the occluder, estimated independently (small angles): at the
// occluder's surface phi_occ = pi/2, phi_sun = R_sun / d; far away phi_occ/phi_sun ->
// R_occ / R_sun.
bool clearlyReachable(double u, const SunOccluderSystem& s) {
  const double phiSun = s.sunRadiusM / s.sunOccluderDistanceM;
  const double uSurface = phiSun / (1.5707963267948966 + phiSun);
  const double uInfinity = s.sunRadiusM / (s.sunRadiusM + s.occluderRadiusM);
  return u > 1.01 * uSurface && u < uInfinity - 1e-4 * (1.0 - uInfinity);
}
} // namespace

TEST(ShadowMapping, AngleBetweenIsAccurateForTinyAngles) {
  for (double a : {1e-12, 1e-7, 1e-3, 1.0, 3.0}) {
    EXPECT_NEAR(angleBetweenRad({1, 0, 0}, {std::cos(a), std::sin(a), 0}), a, 1e-15 + 1e-13 * a);
  }
}

TEST(ShadowMapping, Equation4OnTheAxisBehindTheMoon) {
  // A point on the axis 384 400 km behind Earth.
  const double d = kAu, x = 384400e3, rOcc = 6371e3;
  const ShadowAngles a = shadowAngles({x, 0, 0}, {-d, 0, 0}, kSunRadiusM, {0, 0, 0}, rOcc);
  EXPECT_NEAR(a.sunAngularRadiusRad, std::asin(kSunRadiusM / (d + x)), 1e-15);
  EXPECT_NEAR(a.occluderAngularRadiusRad, std::asin(rOcc / x), 1e-15);
  EXPECT_EQ(a.separationRad, 0.0);
  const LutCoords c = lutCoords(a);
  EXPECT_NEAR(c.u, 1.0 / (a.occluderAngularRadiusRad / a.sunAngularRadiusRad + 1.0), 1e-15);
  EXPECT_EQ(c.v, 0.0);
  const NormalisedDiscs n = normalisedDiscs(c);
  EXPECT_NEAR(n.occluderRadius, a.occluderAngularRadiusRad / a.sunAngularRadiusRad, 1e-12);
}

TEST(ShadowMapping, InverseRoundTripAtTheExtremes) {
  for (const auto& [name, sys] : systems()) {
    for (double u : {1e-6, 0.01, 0.5, 0.99, 1.0 - 1e-6}) {
      for (double v : {0.0, 0.5, 1.0}) {
        SCOPED_TRACE(name + " u=" + std::to_string(u) + " v=" + std::to_string(v));
        const InverseMapping m = inverseLutCoords({u, v}, sys);
        // never NaN, always a point in front of the occluder's surface
        ASSERT_TRUE(std::isfinite(m.occluderDistanceM) && std::isfinite(m.sunDistanceM));
        ASSERT_TRUE(std::isfinite(m.reached.u) && std::isfinite(m.reached.v));
        EXPECT_GE(m.occluderDistanceM, sys.occluderRadiusM);
        EXPECT_TRUE(m.converged) << m.iterations << " iterations";
        EXPECT_LT(m.iterations, 200);
        EXPECT_NEAR(m.reached.v, v, 1e-9 * (v > 0.0 ? v : 1.0));
        if (clearlyReachable(u, sys)) {
          EXPECT_FALSE(m.clamped);
          EXPECT_NEAR(m.reached.u, u, 1e-9 * u);
        } else if (m.clamped) {
          // the nearest reachable u: closer to the requested one than any other point's
          const InverseMapping inner = inverseLutCoords({0.5 * (m.reached.u + 0.5), v}, sys);
          EXPECT_FALSE(inner.clamped);
        }
      }
    }
  }
}

TEST(ShadowMapping, InverseConvergesInFewIterationsAwayFromTheLimits) {
  // The paper reports at most four iterations "to a sufficient precision"; to 1e-12 the
  // plain Eq. 5-6 iteration needs more where it contracts slowly (u -> 1).
  const SunOccluderSystem earth{kSunRadiusM, 6371e3, kAu};
  for (double u : {0.003, 0.05, 0.2, 0.5}) {
    const InverseMapping coarse = inverseLutCoords({u, 0.5}, earth, 1e-6);
    EXPECT_TRUE(coarse.converged);
    EXPECT_LE(coarse.iterations, 4) << "u=" << u;
  }
  for (double u : {0.003, 0.05, 0.2, 0.5, 0.8, 0.9, 0.99}) {
    const InverseMapping fine = inverseLutCoords({u, 0.5}, earth, 1e-12);
    EXPECT_TRUE(fine.converged);
    EXPECT_LE(fine.iterations, 15) << "u=" << u;
  }
}

TEST(ShadowMapping, UmbraConeSurfaceIsWhereTheDiscsTouchInside) {
  for (const auto& [name, sys] : systems()) {
    const ShadowConeRadii r = shadowConeRadii(sys, 0.25 * shadowConeRadii(sys, 0).umbraLengthM);
    const double x = 0.25 * r.umbraLengthM;
    const ShadowAngles onUmbra = shadowAngles({x, r.umbraRadiusM, 0}, {-sys.sunOccluderDistanceM, 0, 0},
                                              sys.sunRadiusM, {0, 0, 0}, sys.occluderRadiusM);
    EXPECT_NEAR(onUmbra.separationRad, onUmbra.occluderAngularRadiusRad - onUmbra.sunAngularRadiusRad,
                1e-9 * onUmbra.sunAngularRadiusRad) << name;
    const ShadowAngles onPenumbra = shadowAngles({x, r.penumbraRadiusM, 0}, {-sys.sunOccluderDistanceM, 0, 0},
                                                 sys.sunRadiusM, {0, 0, 0}, sys.occluderRadiusM);
    EXPECT_NEAR(onPenumbra.separationRad, onPenumbra.occluderAngularRadiusRad + onPenumbra.sunAngularRadiusRad,
                1e-9 * onPenumbra.sunAngularRadiusRad) << name;
  }
}

TEST(ShadowMapping, AntumbraBeyondTheUmbrasTipIsWhereTheSunRingsTheOccluder) {
  // The Moon's shadow on Earth at the Moon's mean distance: the umbra ends ~374 000 km
  // behind the Moon, short of Earth's surface, so an annular eclipse is seen there.
  const SunOccluderSystem moon{kSunRadiusM, 1737.4e3, kAu};
  const double x = 384400e3 - 6371e3;
  const ShadowConeRadii r = shadowConeRadii(moon, x);
  EXPECT_NEAR(r.umbraLengthM, 374e6, 2e6);
  EXPECT_EQ(r.umbraRadiusM, 0.0);
  ASSERT_GT(r.antumbraRadiusM, 0.0);
  // On the antumbra's edge the occluder just fits inside the solar disc.
  const ShadowAngles a = shadowAngles({x, r.antumbraRadiusM, 0}, {-kAu, 0, 0}, kSunRadiusM, {0, 0, 0}, 1737.4e3);
  EXPECT_NEAR(a.separationRad, a.sunAngularRadiusRad - a.occluderAngularRadiusRad, 1e-9 * a.sunAngularRadiusRad);
  EXPECT_EQ(shadowConeRadii(moon, 0.5 * r.umbraLengthM).antumbraRadiusM, 0.0);
}

TEST(ShadowMapping, EarthShadowAtTheMoonMatchesTheClassicalFigures) {
  // Small-angle textbook values: umbra R_E - x (R_S - R_E)/d, penumbra R_E + x (R_S + R_E)/d
  const SunOccluderSystem earth{kSunRadiusM, 6371e3, kAu};
  const ShadowConeRadii r = shadowConeRadii(earth, 384400e3);
  EXPECT_NEAR(r.umbraRadiusM, 6371e3 - 384400e3 * (kSunRadiusM - 6371e3) / kAu, 2e3);
  EXPECT_NEAR(r.penumbraRadiusM, 6371e3 + 384400e3 * (kSunRadiusM + 6371e3) / kAu, 2e3);
  EXPECT_NEAR(r.umbraLengthM, 1.384e9, 0.01e9);  // ~1.38 million km
}

// The expansion of Eq. 3 over a receiver (AngularRadiusExpansion): its coefficients are
// the derivatives of asin(r / d) in e = d0 / d - 1 (central differences), its error bound
// holds between the sampled points (1000 distances across the receiver), and it is exact
// to float for the Moon behind Earth, Phobos by Mars and the Sun seen from 0.1 au, not for
// a receiver that nearly touches its occluder.
TEST(ShadowMapping, AngularRadiusExpansionOverAReceiver) {
  struct Case {
    double radiusM, distanceM, halfWidthM;
    bool exactToFloat;
  };
  for (const Case& c : {Case{6371e3, 384400e3, 1737.4e3, true}, Case{3389.5e3, 9376e3, 11.1e3, true},
                        Case{kSunRadiusM, 0.1 * kAu, 2439.7e3, true}, Case{6371e3, 30000e3, 20000e3, false}}) {
    const AngularRadiusExpansion x = angularRadiusExpansion(c.radiusM, c.distanceM, c.halfWidthM);
    EXPECT_EQ(x.exactToFloat(), c.exactToFloat) << c.distanceM << ": max error " << x.maxErrorRad;
    EXPECT_NEAR(x.phi0Rad, std::asin(c.radiusM / c.distanceM), 1e-16);
    EXPECT_NEAR(x.maxPhiRad, std::asin(c.radiusM / (c.distanceM - c.halfWidthM)), 1e-16);
    const double h = 1e-4;
    auto phiAt = [&](double e) { return std::asin(c.radiusM / (c.distanceM / (1.0 + e))); };
    EXPECT_NEAR(x.c1Rad, (phiAt(h) - phiAt(-h)) / (2 * h), 1e-7 * x.c1Rad);
    EXPECT_NEAR(x.c2Rad, (phiAt(h) - 2 * phiAt(0.0) + phiAt(-h)) / (2 * h * h), 1e-4 * x.c2Rad + 1e-9);
    double worst = 0.0;
    for (int k = 0; k <= 1000; ++k) {
      const double d = c.distanceM - c.halfWidthM + 2.0 * c.halfWidthM * k / 1000;
      worst = std::max(worst, std::abs(std::asin(c.radiusM / d) - x.at(d)));
    }
    EXPECT_LE(worst, 1.01 * x.maxErrorRad + 1e-18);
  }
  // A receiver reaching into the occluder's sphere: no expansion.
  EXPECT_FALSE(angularRadiusExpansion(6371e3, 7000e3, 1000e3).exactToFloat());
}

// The series of asin to s^7 is exact to 2^-26 up to kSmallAngleSeriesMaxRad.
TEST(ShadowMapping, SmallAngleSeriesIsExactToFloatUpToItsLimit) {
  for (double a = 1e-6; a <= kSmallAngleSeriesMaxRad; a *= 1.1) {
    const double s = std::sin(a), t = s * s;
    const double series = s * (1.0 + t * (1.0 / 6.0 + t * (3.0 / 40.0 + t * (5.0 / 112.0))));
    EXPECT_LE(std::abs(series - a), 0x1p-26 * a) << a;
  }
}

TEST(ShadowMapping, OccluderDistanceForAnUmbraGivesThatUmbraBack) {
  // A point with the Sun D away and the occluder x in front of it on the same line: the
  // umbra's cross-section through the point, from the cones' tangents (shadowConeRadii),
  // is the radius asked for (to the tangent's cosine, 1e-5 of it for the Moon at 1 au).
  for (const auto& [name, sys] : systems())
    for (double fraction : {0.0, 0.01, 0.3, 0.9}) {
      const double D = sys.sunOccluderDistanceM, r = fraction * sys.occluderRadiusM;
      const double x = occluderDistanceForUmbraM(D, sys.sunRadiusM, sys.occluderRadiusM, r);
      ASSERT_GT(x, 0.0);
      const ShadowConeRadii cone = shadowConeRadii({sys.sunRadiusM, sys.occluderRadiusM, D - x}, x);
      EXPECT_NEAR(cone.umbraRadiusM, r, 2e-5 * sys.occluderRadiusM) << name << " " << fraction;
    }
}

TEST(ShadowMapping, AnAnnularEclipseLeavesTheRingOutsideTheOccludersDisc) {
  // On the axis, the Moon 400 000 km away in front of a Sun 1 au away: what shows is the
  // limb-darkened Sun outside the Moon's radius (eclipseFactor, exact); 360 000 km away it
  // hides the Sun whole; behind the point it hides nothing.
  const glm::dvec3 sun(kAu, 0, 0);
  const double moonR = 1737.4e3;
  const double ring = eclipseFactor({0, 0, 0}, sun, kSunRadiusM, {{400000e3, 0, 0}, moonR}, nullptr).g;
  const double phiSun = std::asin(kSunRadiusM / kAu), phiMoon = std::asin(moonR / 400000e3);
  EXPECT_NEAR(ring, 1.0 - limbDarkenedFluxInside(phiMoon / phiSun, kDefaultLimbDarkening), 1e-9);
  EXPECT_GT(ring, 0.05);
  EXPECT_EQ(eclipseFactor({0, 0, 0}, sun, kSunRadiusM, {{360000e3, 0, 0}, moonR}, nullptr).g, 0.0);
  EXPECT_EQ(eclipseFactor({0, 0, 0}, sun, kSunRadiusM, {{-380000e3, 0, 0}, moonR}, nullptr).g, 1.0);
}

namespace {
// Where the line through `centre + s t` along `view` meets a spheroid (centre 0, mean
// radius R, figure `o`): the stretched line meets the sphere of the equatorial radius.
bool lineMeetsSpheroid(const glm::dvec3& through, const glm::dvec3& view, double meanRadiusM, const Oblateness& o) {
  const double a = meanRadiusM / std::cbrt(1.0 - o.flattening), k = 1.0 / (1.0 - o.flattening);
  const auto st = [&](const glm::dvec3& v) { return v + (k - 1.0) * glm::dot(v, o.pole) * o.pole; };
  const glm::dvec3 p = st(through), d = st(view);
  const double b = glm::dot(p, d), dd = glm::dot(d, d), c = glm::dot(p, p) - a * a;
  return b * b - dd * c >= 0.0;
}
} // namespace

// The outline's radius (outlineRadiusFactor) against the spheroid's own: the farthest line
// of sight along t that still meets it, found by bisection, for poles at every tilt to the
// view and directions at every angle to the projected pole, flattening up to Saturn's.
TEST(ShadowMapping, OutlineRadiusIsTheSpheroidsOwn) {
  const double meanR = 6371.0e3;
  for (double f : {1.0 / 298.257, 1.0 / 170.0, 0.0980}) {
    for (double tilt : {0.0, 0.3, 0.9, 1.5707963267948966}) {
      const Oblateness o{{std::sin(tilt), 0.0, std::cos(tilt)}, f};
      const glm::dvec3 view(1.0, 0.0, 0.0);
      for (double th = 0.0; th < 3.2; th += 0.4) {
        const glm::dvec3 t(0.0, std::sin(th), std::cos(th));
        double lo = 0.0, hi = 2.0 * meanR;
        for (int i = 0; i < 200; ++i) {
          const double mid = 0.5 * (lo + hi);
          (lineMeetsSpheroid(mid * t, view, meanR, o) ? lo : hi) = mid;
        }
        const double a = meanR / std::cbrt(1.0 - f);
        EXPECT_NEAR(outlineRadiusFactor(view, t + 0.3 * view, o), lo / a, 1e-12) << f << " " << tilt << " " << th;
      }
    }
  }
  // A sphere's outline is its radius; along the view the factor is 1; along the pole seen
  // from the equator's plane it is 1 - f.
  const Oblateness earth{{0.0, 0.0, 1.0}, 1.0 / 298.257};
  EXPECT_EQ(outlineRadiusTowardsSunM({0, 0, 0}, {1, 2, 3}, {4, 5, 6}, 7.0, {}), 7.0);
  EXPECT_EQ(outlineRadiusFactor({1, 0, 0}, {2, 0, 0}, earth), 1.0);
  EXPECT_NEAR(outlineRadiusFactor({1, 0, 0}, {0, 0, 1}, earth), 1.0 - 1.0 / 298.257, 1e-15);
}

// The Earth's shadow at the Moon's distance cast by the oblate Earth (eclipseFactor with
// its figure: the circle of the outline's radius towards the Sun) against the spheroid
// sampled ray by ray over the limb-darkened Sun (visibleFractionPastSpheroid), across the
// penumbra towards the projected pole, the equator and between: within 3.5e-4 everywhere,
// where the sphere of the mean radius errs by 2.5e-3 to 4e-3 towards the pole and the
// equator (the circle is rounder than the ellipse at the pole, which lets more light by).
TEST(ShadowMapping, OblateEarthsPenumbraAgreesWithTheSpheroidRayByRay) {
  const double meanR = 6371.0084e3, f = 1.0 / 298.257, eps = 0.4091;
  const glm::dvec3 sun(-kAu, 0.0, 0.0);
  const Oblateness earth{{-std::sin(eps), 0.0, std::cos(eps)}, f};
  for (double th : {0.0, 0.7853981633974483, 1.5707963267948966}) {
    double maxOblate = 0.0, maxSphere = 0.0;
    for (double r = 4300e3; r <= 8300e3; r += 250e3) {
      const glm::dvec3 p(384400e3, r * std::sin(th), r * std::cos(th));
      const double ref = visibleFractionPastSpheroid(p, sun, kSunRadiusM, {0, 0, 0}, meanR, earth, kDefaultLimbDarkening, 1500);
      const double oblate = eclipseFactor(p, sun, kSunRadiusM, {{0, 0, 0}, meanR, earth}, nullptr).g;
      const double sphere = eclipseFactor(p, sun, kSunRadiusM, {{0, 0, 0}, meanR}, nullptr).g;
      // The rays themselves, against the sphere's exact value.
      EXPECT_NEAR(visibleFractionPastSpheroid(p, sun, kSunRadiusM, {0, 0, 0}, meanR, {}, kDefaultLimbDarkening, 1500),
                  sphere, 2e-5);
      maxOblate = std::max(maxOblate, std::abs(oblate - ref));
      maxSphere = std::max(maxSphere, std::abs(sphere - ref));
    }
    std::printf("  %.0f deg from the projected pole: max |oblate - rays| %.2e, |sphere - rays| %.2e\n",
                th * 57.29577951308232, maxOblate, maxSphere);
    EXPECT_LT(maxOblate, 3.5e-4) << th;
    if (th != 0.7853981633974483) {
      EXPECT_GT(maxSphere, 2.5e-3) << th;
      EXPECT_LT(maxOblate, 0.1 * maxSphere) << th;
    }
  }
}
