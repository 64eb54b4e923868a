// Soft shadows on curved terrain: closed forms (flat sphere, straight ridge), the extremes
// (Sun below the horizon, at the zenith, over the pole, DEM edges, no data) and the
// agreement of the dynamic-programming search with the reference.
#include "CraterField.hpp"
#include "SolarDisc.hpp"
#include "TerrainTestSupport.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>

using namespace umbra;
using namespace umbra::terrain;
using umbra::test::kDeg;

namespace {

const ShadowMethod kMethods[] = {ShadowMethod::DynamicProgramming, ShadowMethod::Uniform, ShadowMethod::Cells,
                                 ShadowMethod::Reference};

void expectFiniteFractions(const std::vector<double>& v) {
  for (double x : v) {
    ASSERT_TRUE(std::isfinite(x));
    ASSERT_GE(x, 0.0);
    ASSERT_LE(x, 1.0);
  }
}

HeightField smallCraters(int size = 96, std::uint64_t seed = 3) {
  CraterFieldOptions o;
  o.size = size;
  o.seed = seed;
  return makeCraterField(o);
}

/// The bare sphere and a crater field, with their mipmaps.
struct FlatAndCraters {
  HeightField flat = test::flatField(41), craters = smallCraters();
  MaximumMipmap flatMip{flat}, mip{craters};
};

} // namespace

TEST(SoftShadow, FlatSphereShowsTheSegmentAboveTheGeometricHorizon) {
  // On the bare sphere the horizon of a point on the surface is its own horizontal; the
  // Sun's elevation there differs from the grid centre's by the curvature (up to 0.07 deg here).
  const HeightField f = test::flatField(81);
  const MaximumMipmap mip(f);
  SunDisc sun;
  const double r = sun.angularRadiusRad;
  for (double eDeg = -0.5; eDeg <= 0.5001; eDeg += 0.05)
    for (double azDeg : {0.0, 131.0}) {
      sun.direction = sunDirectionFromElevationAzimuth(eDeg * kDeg, azDeg * kDeg);
      for (auto [i, j] : {std::pair{40, 40}, {10, 70}, {75, 5}})
        for (ShadowMethod m : kMethods) {
          const double expected = test::segmentFraction(test::localElevation(f, i, j, sun.direction) / r);
          EXPECT_NEAR(visibleFraction(f, mip, i, j, sun, test::method(m)), expected, 1e-3)
              << shadowMethodName(m) << " e=" << eDeg << " az=" << azDeg << " at " << i << "," << j;
        }
    }
}

TEST(SoftShadow, LimbDarkenedFlatSphereMatchesTheClosedForm) {
  const HeightField f = test::flatField(33);
  const MaximumMipmap mip(f);
  SunDisc sun;
  sun.limbDarkening = 0.6;
  for (double eDeg : {-0.2, 0.0, 0.1, 0.25}) {
    sun.direction = sunDirectionFromElevationAzimuth(eDeg * kDeg, 0.3);
    const double d = eDeg * kDeg / sun.angularRadiusRad;
    for (ShadowMethod m : kMethods)
      EXPECT_NEAR(visibleFraction(f, mip, 16, 16, sun, test::method(m)),
                  eclipse::visibleFractionAboveHorizonLimbDarkened(d, 0.6), 1e-3) << shadowMethodName(m) << " " << eDeg;
  }
}

namespace {
/// A straight ridge (a great circle: a grid row) of crest height H with triangular
/// flanks of half-width w texels, on the bare sphere.
HeightField ridgeField(int size, int crestRow, double crestM, int halfWidth) {
  HeightField f = test::flatField(size);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i)
      f.heightsM[j * size + i] = crestM * std::max(0.0, 1.0 - std::abs(j - crestRow) / double(halfWidth));
  return f;
}

/// Ground distance [texels] behind the crest where the crest stands at elevation e, on the
/// sphere: solve atan2((R+H) cos phi - R, (R+H) sin phi) = e for phi (bisection).
double distanceWhereCrestIsAt(double e, double crestM, double R, double spacingM) {
  double lo = 1e-9, hi = 0.2;
  for (int k = 0; k < 200; ++k) {
    const double phi = 0.5 * (lo + hi);
    const double el = std::atan2((R + crestM) * std::cos(phi) - R, (R + crestM) * std::sin(phi));
    (el > e ? lo : hi) = phi;
  }
  return 0.5 * (lo + hi) * R / spacingM;  // arc length on the sphere ~ plane length (1e-6 here)
}
} // namespace

TEST(SoftShadow, StraightRidgeCastsShadowAndPenumbraOfTheGeometricLength) {
  // Sun due "north" (+y) at 1.5 deg behind a 200 m ridge: the shadow reaches ~255 texels
  // (7.6 km) south of the crest, its penumbra spans ~ H (1/tan(e-r) - 1/tan(e+r)).
  const int size = 400, crest = 360;
  const double H = 200.0, e = 1.5 * kDeg;
  const HeightField f = ridgeField(size, crest, H, 6);
  const MaximumMipmap mip(f);
  SunDisc sun;
  sun.direction = sunDirectionFromElevationAzimuth(e, 0.0);
  const double r = sun.angularRadiusRad;
  const int column = size / 2;
  for (ShadowMethod m : kMethods) {
    ShadowOptions o = test::method(m);
    o.uniformSteps = 2048;
    // The fraction along the column south of the ridge, with its crossings of 1%, 50% and 99%.
    auto crossing = [&](double level) {
      double prev = visibleFraction(f, mip, column, crest - 7, sun, o);
      for (int j = crest - 8; j >= 0; --j) {
        const double now = visibleFraction(f, mip, column, j, sun, o);
        if (prev < level && now >= level) return (crest - (j + 1)) + (level - prev) / (now - prev);
        prev = now;
      }
      return -1.0;
    };
    // The Sun's elevation at the receivers differs from the centre's by the curvature;
    // the expected distances use the elevation seen along this column.
    auto expectedAt = [&](double edgeOffset, int jNear) {
      const double eLocal = test::localElevation(f, column, jNear, sun.direction);
      return distanceWhereCrestIsAt(eLocal + edgeOffset, H, f.bodyRadiusM, f.spacingM);
    };
    // Uniform stepping cuts the crest between its samples: a shorter shadow, within 2 texels here.
    const double tol = m == ShadowMethod::Uniform ? 2.0 : 1.0;
    const double half = crossing(0.5);
    EXPECT_NEAR(half, expectedAt(0.0, crest - int(half)), tol) << shadowMethodName(m);
    // Penumbra: 1% where the disc's top just shows, 99% where its bottom just clears
    // (the segment reaches 1% / 99% at d = -+0.9...; compute those elevations exactly).
    auto dFor = [](double level) {
      double lo = -1.0, hi = 1.0;
      for (int k = 0; k < 100; ++k) {
        const double mid = 0.5 * (lo + hi);
        (test::segmentFraction(mid) < level ? lo : hi) = mid;
      }
      return lo;
    };
    const double d01 = dFor(0.01), d99 = dFor(0.99);
    const double lit01 = crossing(0.01), lit99 = crossing(0.99);
    // Fraction f needs the crest at e - d r: nearer the ridge (deeper) for small f.
    const double exp01 = expectedAt(-d01 * r, crest - int(lit01)), exp99 = expectedAt(-d99 * r, crest - int(lit99));
    EXPECT_NEAR(lit01, exp01, tol) << shadowMethodName(m);
    EXPECT_NEAR(lit99, exp99, tol) << shadowMethodName(m);
    // The penumbra's width (about 90 texels, 2.7 km, a third of the shadow at 1.5 deg).
    EXPECT_NEAR(lit99 - lit01, exp99 - exp01, tol) << shadowMethodName(m);
    EXPECT_GT(exp99 - exp01, 80.0);
  }
}

TEST(SoftShadow, SunBelowTheHorizonGivesFiniteZero) {
  // On the bare sphere the Sun 1 deg below the horizon is hidden everywhere; on craters,
  // whose walls slope by up to ~40 deg, 60 deg below is.
  const FlatAndCraters fields;
  const HeightField &flat = fields.flat, &f = fields.craters;
  const MaximumMipmap &flatMip = fields.flatMip, &mip = fields.mip;
  SunDisc sun;
  for (ShadowMethod m : kMethods) {
    sun.direction = sunDirectionFromElevationAzimuth(-1.0 * kDeg, 1.0);
    const auto v = visibleFractionMap(flat, flatMip, sun, test::method(m));
    expectFiniteFractions(v);
    EXPECT_EQ(*std::max_element(v.begin(), v.end()), 0.0) << shadowMethodName(m);
    sun.direction = sunDirectionFromElevationAzimuth(-60.0 * kDeg, 1.0);
    const auto c = visibleFractionMap(f, mip, sun, test::method(m));
    expectFiniteFractions(c);
    EXPECT_EQ(*std::max_element(c.begin(), c.end()), 0.0) << shadowMethodName(m);
  }
  sun.direction = {0.0, 0.0, -1.0};  // nadir
  expectFiniteFractions(visibleFractionMap(f, mip, sun, test::method(ShadowMethod::DynamicProgramming)));
  EXPECT_EQ(visibleFraction(f, mip, 48, 48, sun, ShadowOptions{}), 0.0);
}

TEST(SoftShadow, SunAtTheZenithLightsEverything) {
  SunDisc sun;
  sun.direction = {0.0, 0.0, 1.0};  // zenith of the grid's centre: no azimuth there
  const HeightField flat = test::flatField(33);
  const MaximumMipmap flatMip(flat);
  const HeightField f = smallCraters();
  const MaximumMipmap mip(f);
  for (ShadowMethod m : kMethods) {
    const auto v = visibleFractionMap(flat, flatMip, sun, test::method(m));
    expectFiniteFractions(v);
    EXPECT_EQ(*std::min_element(v.begin(), v.end()), 1.0) << shadowMethodName(m);
    const auto c = visibleFractionMap(f, mip, sun, test::method(m));
    expectFiniteFractions(c);
    // Crater walls are at most ~40 deg steep: nothing is shadowed at noon overhead.
    EXPECT_GT(*std::min_element(c.begin(), c.end()), 0.999) << shadowMethodName(m);
  }
}

TEST(SoftShadow, SunOverThePoleFromABodyFixedDirection) {
  // A grid tangent at the south pole; the Sun 0.2 deg south of the equator (body-fixed)
  // stands 0.2 deg above the pole's horizon whatever its longitude.
  const glm::dmat3 toTangent = bodyFixedToTangent(-90.0, 0.0);
  EXPECT_NEAR(glm::determinant(toTangent), 1.0, 1e-14);
  EXPECT_NEAR(glm::length(toTangent * glm::dvec3(0, 0, -1) - glm::dvec3(0, 0, 1)), 0.0, 1e-15);  // up = -z
  const FlatAndCraters fields;
  const HeightField &flat = fields.flat, &f = fields.craters;
  const MaximumMipmap &flatMip = fields.flatMip, &mip = fields.mip;
  for (double lonDeg : {0.0, 77.0, 200.0}) {
    const double dec = -0.2 * kDeg, lon = lonDeg * kDeg;
    SunDisc sun;
    sun.direction = toTangent * glm::dvec3(std::cos(dec) * std::cos(lon), std::cos(dec) * std::sin(lon), std::sin(dec));
    EXPECT_NEAR(std::asin(sun.direction.z), 0.2 * kDeg, 1e-12);
    for (ShadowMethod m : kMethods) {
      EXPECT_NEAR(visibleFraction(flat, flatMip, 20, 20, sun, test::method(m)),
                  test::segmentFraction(0.2 * kDeg / sun.angularRadiusRad), 1e-3) << shadowMethodName(m);
      if (m != ShadowMethod::Reference) expectFiniteFractions(visibleFractionMap(f, mip, sun, test::method(m)));
    }
    for (int j = 0; j < f.height; j += 7)  // the reference is slow: every 7th sample
      for (int i = 0; i < f.width; i += 7) {
        const double v = visibleFraction(f, mip, i, j, sun, test::method(ShadowMethod::Reference));
        ASSERT_TRUE(std::isfinite(v) && v >= 0.0 && v <= 1.0);
      }
  }
  // Away from the poles the frame is east, north, up.
  const glm::dmat3 m = bodyFixedToTangent(0.0, 90.0);
  EXPECT_NEAR(glm::length(m * glm::dvec3(0, 1, 0) - glm::dvec3(0, 0, 1)), 0.0, 1e-15);
  EXPECT_NEAR(glm::length(m * glm::dvec3(0, 0, 1) - glm::dvec3(0, 1, 0)), 0.0, 1e-15);
}

TEST(SoftShadow, DemEdgesFacingOutwardSeeOnlyTheirOwnSlope) {
  // Receivers on the edges with the Sun beyond the edge: nothing of the grid lies towards
  // the Sun, so the flat sphere's segment; on craters, finite.
  const FlatAndCraters fields;
  const HeightField &flat = fields.flat, &f = fields.craters;
  const MaximumMipmap &flatMip = fields.flatMip, &mip = fields.mip;
  SunDisc sun;
  const int last = flat.width - 1;
  const struct {
    double azDeg;
    int i, j;
  } edges[] = {{0.0, 20, last}, {90.0, last, 20}, {180.0, 20, 0}, {270.0, 0, 20}, {45.0, last, last}};
  for (const auto& e : edges) {
    sun.direction = sunDirectionFromElevationAzimuth(0.1 * kDeg, e.azDeg * kDeg);
    for (ShadowMethod m : kMethods) {
      EXPECT_NEAR(visibleFraction(flat, flatMip, e.i, e.j, sun, test::method(m)),
                  test::segmentFraction(test::localElevation(flat, e.i, e.j, sun.direction) / sun.angularRadiusRad), 1e-3)
          << shadowMethodName(m) << " az " << e.azDeg;
      const int ci = e.i == last ? f.width - 1 : e.i, cj = e.j == last ? f.height - 1 : e.j;
      const double v = visibleFraction(f, mip, ci, cj, sun, test::method(m));
      EXPECT_TRUE(std::isfinite(v) && v >= 0.0 && v <= 1.0);
    }
  }
}

TEST(SoftShadow, NoDataCellsCastNoShadowAndReceiveFiniteLight) {
  // The ridge of the ridge test, blanked out: the ground behind it is lit as on the bare sphere.
  HeightField f = ridgeField(200, 160, 200.0, 6);
  for (int j = 150; j <= 170; ++j)
    for (int i = 0; i < f.width; ++i) f.heightsM[j * f.width + i] = std::numeric_limits<double>::quiet_NaN();
  const MaximumMipmap mip(f);
  SunDisc sun;
  sun.direction = sunDirectionFromElevationAzimuth(0.1 * kDeg, 0.0);
  for (ShadowMethod m : kMethods) {
    if (m != ShadowMethod::Reference) expectFiniteFractions(visibleFractionMap(f, mip, sun, test::method(m)));
    for (int j : {20, 100, 149})
      EXPECT_NEAR(visibleFraction(f, mip, 100, j, sun, test::method(m)),
                  test::segmentFraction(test::localElevation(f, 100, j, sun.direction) / sun.angularRadiusRad), 1e-3)
          << shadowMethodName(m) << " row " << j;
  }
  // Holes in a crater field: finite everywhere, including inside the holes.
  HeightField c = smallCraters();
  for (int j = 30; j < 40; ++j)
    for (int i = 0; i < c.width; i += 3) c.heightsM[j * c.width + i] = std::numeric_limits<double>::quiet_NaN();
  const MaximumMipmap cmip(c);
  sun.direction = sunDirectionFromElevationAzimuth(2.0 * kDeg, 2.0);
  for (ShadowMethod m : {ShadowMethod::DynamicProgramming, ShadowMethod::Uniform, ShadowMethod::Cells})
    expectFiniteFractions(visibleFractionMap(c, cmip, sun, test::method(m)));
  for (int j = 28; j < 42; ++j)  // the reference is slow: the rows of the holes only
    for (int i = 0; i < c.width; i += 2) {
      const double v = visibleFraction(c, cmip, i, j, sun, test::method(ShadowMethod::Reference));
      ASSERT_TRUE(std::isfinite(v) && v >= 0.0 && v <= 1.0) << i << "," << j;
    }
}

TEST(SoftShadow, DynamicProgrammingFindsTheSameHorizonAsDenseStepping) {
  // Within the prism model the mipmap search must not lose the horizon: wherever the
  // horizon matters (inside the disc), uniform stepping at ~1/10 texel never finds it
  // higher than DP does, beyond DP's tolerance (2e-6 rad), for any N'.
  const HeightField f = smallCraters(128, 11);
  const MaximumMipmap mip(f);
  SunDisc sun;
  sun.direction = sunDirectionFromElevationAzimuth(2.0 * kDeg, 0.7);
  ShadowOptions dense = test::method(ShadowMethod::Uniform);
  dense.uniformSteps = 1600;
  int relevant = 0;
  for (int levels : {1, 3, 6, 12}) {
    ShadowOptions dp;
    dp.levels = levels;
    double worst = 0.0, sumAbs = 0.0;
    int n = 0;
    for (int j = 2; j < f.height; j += 5)
      for (int i = 2; i < f.width; i += 5) {
        const Horizon a = horizonTowardsSun(f, mip, i, j, sun, dp), b = horizonTowardsSun(f, mip, i, j, sun, dense);
        const double e = a.sunElevationRad, r = sun.angularRadiusRad;
        if (b.horizonElevationRad > e - r && b.horizonElevationRad < e + r) {
          worst = std::max(worst, b.horizonElevationRad - a.horizonElevationRad);
          ++relevant;
        }
        sumAbs += std::abs(discFractionAboveHorizon(a, sun) - discFractionAboveHorizon(b, sun));
        ++n;
      }
    EXPECT_LE(worst, 2e-6) << "N' = " << levels;
    EXPECT_LT(sumAbs / n, 0.003) << "N' = " << levels;
  }
  EXPECT_GT(relevant, 40);  // enough receivers in the penumbra for this to mean something
}

TEST(SoftShadow, TheCellSearchFindsTheBilinearSurfacesHighestPoint) {
  // The cell-by-cell search takes each cell's highest point in closed form: never below
  // dense stepping (1/10 texel: points of the same surface), and the same horizon as the
  // DP within the DP's tolerance (2e-6 rad) wherever the horizon is on the disc.
  const HeightField f = smallCraters(128, 11);
  const MaximumMipmap mip(f);
  SunDisc sun;
  sun.direction = sunDirectionFromElevationAzimuth(2.0 * kDeg, 0.7);
  ShadowOptions dense = test::method(ShadowMethod::Uniform), cells = test::method(ShadowMethod::Cells), dp;
  dense.uniformSteps = 1600;
  double belowDense = 0.0, vsDp = 0.0;
  int relevant = 0;
  for (int j = 2; j < f.height; j += 3)
    for (int i = 2; i < f.width; i += 3) {
      const Horizon c = horizonTowardsSun(f, mip, i, j, sun, cells), d = horizonTowardsSun(f, mip, i, j, sun, dense),
                    m = horizonTowardsSun(f, mip, i, j, sun, dp);
      const double e = c.sunElevationRad, r = sun.angularRadiusRad;
      if (d.horizonElevationRad > e - r && d.horizonElevationRad < e + r) {
        belowDense = std::max(belowDense, d.horizonElevationRad - c.horizonElevationRad);
        vsDp = std::max(vsDp, std::abs(m.horizonElevationRad - c.horizonElevationRad));
        ++relevant;
      }
    }
  std::printf("  %d receivers with the horizon on the disc: dense stepping above the cells' by %.2g rad at most, "
              "|DP - cells| %.2g rad at most\n", relevant, belowDense, vsDp);
  EXPECT_GT(relevant, 40);
  EXPECT_LE(belowDense, 1e-9);
  EXPECT_LE(vsDp, 2e-6);
}

TEST(SoftShadow, DynamicProgrammingAgreesWithTheReferenceOnCraters) {
  const HeightField f = smallCraters(128, 5);
  const MaximumMipmap mip(f);
  SunDisc sun;
  sun.direction = sunDirectionFromElevationAzimuth(1.5 * kDeg, 2.3);
  std::vector<double> err;
  for (int j = 1; j < f.height; j += 4)
    for (int i = 1; i < f.width; i += 4)
      err.push_back(std::abs(visibleFraction(f, mip, i, j, sun, ShadowOptions{}) -
                             visibleFraction(f, mip, i, j, sun, test::method(ShadowMethod::Reference))));
  std::sort(err.begin(), err.end());
  const double mean = std::accumulate(err.begin(), err.end(), 0.0) / err.size();
  const double p99 = err[static_cast<std::size_t>(0.99 * (err.size() - 1))];
  EXPECT_LT(mean, 0.01);
  EXPECT_LT(p99, 0.15);
}
