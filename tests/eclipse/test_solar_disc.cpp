#include "ReferenceQuadrature.hpp"
#include "SolarDisc.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace umbra::eclipse;
using umbra::test::referenceVisibleFraction;

namespace {
constexpr double kPi = 3.14159265358979323846;

// (occluder radius, separation) pairs in solar radii covering small and large occluders,
// grazing contact, near-total and annular eclipses.
std::vector<std::pair<double, double>> partialCases() {
  std::vector<std::pair<double, double>> cases;
  for (double R : {1e-3, 0.1, 0.5, 0.99, 1.0, 1.01, 3.6, 100.0, 1e4}) {
    const double lo = std::abs(R - 1.0), hi = R + 1.0;
    for (double t : {1e-6, 0.01, 0.25, 0.5, 0.75, 0.99, 1.0 - 1e-6}) cases.emplace_back(R, lo + t * (hi - lo));
  }
  return cases;
}
} // namespace

TEST(SolarDisc, LimbDarkeningIsNormalisedToTheUniformDiscFlux) {
  for (double u : {0.0, 0.3, 0.6, 1.0}) {
    EXPECT_NEAR(limbDarkenedFluxInside(1.0, u), 1.0, 1e-15);
    EXPECT_DOUBLE_EQ(limbDarkenedFluxInside(0.0, u), 0.0);
    // Eq. 1: at the limb the luminance is (1 - u) of the centre's.
    EXPECT_NEAR(limbDarkenedLuminance(1.0, u), (1.0 - u) * limbDarkenedLuminance(0.0, u), 1e-15);
  }
  // mean 1 => centre luminance 1 / (1 - u/3)
  EXPECT_NEAR(limbDarkenedLuminance(0.0, 0.6), 1.0 / 0.8, 1e-15);
}

TEST(SolarDisc, OverlapAreaMatchesTheTextbookFormula) {
  for (auto [R, d] : partialCases()) {
    if (R > 10.0 || R < 0.01) continue;  // the textbook form cancels badly there
    // the textbook form itself loses ~1e-10 to acos near +-1
    EXPECT_NEAR(discOverlapArea(R, d), umbra::test::textbookLensArea(R, d), 1e-10) << R << " " << d;
  }
  EXPECT_DOUBLE_EQ(discOverlapArea(0.5, 0.2), kPi * 0.25);  // occluder inside
  EXPECT_DOUBLE_EQ(discOverlapArea(3.0, 1.0), kPi);          // Sun inside
  EXPECT_DOUBLE_EQ(discOverlapArea(1.0, 2.0), 0.0);          // touching
}

TEST(SolarDisc, UniformDiscFractionEqualsExactOverlapTo1e6) {
  // Against an independent quadrature (angle-first, radial integral in closed form).
  for (auto [R, d] : partialCases()) {
    const double exact = visibleFractionUniform(R, d);
    const double ref = referenceVisibleFraction(R, d, 0.0);
    EXPECT_NEAR(exact, ref, 1e-6 * std::max(std::min(exact, 1.0 - exact), 1e-3)) << R << " " << d;
    EXPECT_NEAR(exact, 1.0 - discOverlapArea(R, d) / kPi, 1e-12) << R << " " << d;
  }
}

TEST(SolarDisc, UniformFractionKeepsRelativeAccuracyNearTotality) {
  // Crescent of width w against a nearly straight edge (R large): area = (4 sqrt 2 / 3) w^1.5 + O(w^2.5)
  const double R = 1048576.0, w = 1.0 / 1048576.0;  // R - 1 + w is exact in double
  const double frac = visibleFractionUniform(R, R - 1.0 + w);
  const double crescent = 4.0 * std::sqrt(2.0) / 3.0 * std::pow(w, 1.5) / kPi;
  EXPECT_NEAR(frac, crescent, 1e-5 * crescent);
}

TEST(SolarDisc, LimbDarkenedFractionMatchesIndependentQuadratureTo1e6) {
  for (auto [R, d] : partialCases()) {
    const auto q = visibleFractionLimbDarkened(R, d, 0.6);
    const double ref = referenceVisibleFraction(R, d, 0.6);
    const double scale = std::max(std::min(ref, 1.0 - ref), 1e-9);
    EXPECT_NEAR(q.value, ref, 1e-6 * scale) << "R=" << R << " d=" << d;
    EXPECT_TRUE(std::isfinite(q.value));
  }
}

TEST(SolarDisc, LimbDarkenedWithoutDarkeningIsTheUniformDisc) {
  for (auto [R, d] : partialCases()) {
    EXPECT_NEAR(visibleFractionLimbDarkened(R, d, 0.0).value, visibleFractionUniform(R, d), 1e-9);
  }
}

TEST(SolarDisc, LimbDarkenedIntegralConverges) {
  for (auto [R, d] : partialCases()) {
    const double fine = visibleFractionLimbDarkened(R, d, 0.6, 1e-14).value;
    for (double tol : {1e-6, 1e-8, 1e-10}) {
      const auto q = visibleFractionLimbDarkened(R, d, 0.6, tol);
      const double scale = std::max(std::min(fine, 1.0 - fine), 1e-9);
      EXPECT_NEAR(q.value, fine, 1e-6 * scale) << "tol=" << tol << " R=" << R << " d=" << d;
      EXPECT_LE(q.errorEstimate, std::max(1e-6 * scale, tol));
    }
  }
}

TEST(SolarDisc, LimbDarkeningDeepensACentralTransit) {
  // A small occluder at the centre hides brighter-than-average light, at the limb dimmer.
  const double R = 0.05;
  const double uniformHidden = R * R;
  EXPECT_NEAR(visibleFractionLimbDarkened(R, 0.0, 0.6).value, referenceVisibleFraction(R, 0.0, 0.6), 1e-9);
  EXPECT_LT(1.0 - visibleFractionLimbDarkened(R, 0.94, 0.6).value, uniformHidden);
  EXPECT_GT(1.0 - visibleFractionLimbDarkened(R, 0.0, 0.6).value, uniformHidden);
}

TEST(SolarDisc, ContactsAndTotality) {
  EXPECT_EQ(visibleFractionLimbDarkened(2.0, 3.0).value, 1.0);
  EXPECT_EQ(visibleFractionLimbDarkened(2.0, 1.0).value, 0.0);
  EXPECT_EQ(visibleFractionUniform(2.0, 1.0), 0.0);
  EXPECT_NEAR(visibleFractionUniform(0.5, 0.0), 0.75, 1e-15);
}
