// Phase functions (Phase.hpp): normalisation, asymmetry, symmetry, the tabulated hook.
#include "ModelTestSupport.hpp"
#include "Phase.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

using namespace umbra::atmosphere;
using umbra::test::integrateSphere;
using umbra::test::kPi;

namespace {

std::vector<PhaseFunction> everyKind() {
  std::vector<double> mu, values;
  for (int i = 0; i <= 200; ++i) {
    const double m = -1.0 + 2.0 * i / 200.0;
    mu.push_back(m);
    values.push_back(std::exp(3.0 * m) + 0.2);  // forward-peaked, not normalised
  }
  return {PhaseFunction::isotropic(),
          PhaseFunction::rayleigh(),
          PhaseFunction::penndorf(),
          PhaseFunction::henyeyGreenstein(0.0),
          PhaseFunction::henyeyGreenstein(0.8),
          PhaseFunction::henyeyGreenstein(-0.5),
          PhaseFunction::henyeyGreenstein(0.95),
          PhaseFunction::doubleHenyeyGreenstein(0.85, -0.3, 0.7),
          PhaseFunction::doubleHenyeyGreenstein(0.4, 0.89, 0.04),  // Mars at 550 nm, Costa Table 1
          PhaseFunction::cornetteShanks(0.8),
          PhaseFunction::cornetteShanks(-0.3),
          PhaseFunction::tabulated(mu, values)};
}

}  // namespace

TEST(ModelPhase, EveryKindIntegratesToOneOverTheSphere) {
  for (const PhaseFunction& p : everyKind()) {
    const double total = integrateSphere(p, [](double) { return 1.0; });
    EXPECT_NEAR(total, 1.0, 1e-6) << p.describe();
  }
}

TEST(ModelPhase, AsymmetryMatchesTheMeanCosine) {
  for (const PhaseFunction& p : everyKind()) {
    const double meanCosine = integrateSphere(p, [](double mu) { return mu; });
    EXPECT_NEAR(p.asymmetry(), meanCosine, 1e-9) << p.describe();
  }
}

TEST(ModelPhase, HenyeyGreensteinMeanCosineEqualsG) {
  for (double g : {-0.7, -0.2, 0.0, 0.3, 0.76, 0.9}) {
    const PhaseFunction p = PhaseFunction::henyeyGreenstein(g);
    EXPECT_NEAR(integrateSphere(p, [](double mu) { return mu; }), g, 1e-9) << g;
  }
  // the double HG's mean cosine is the weighted mean of its lobes'
  const PhaseFunction dhg = PhaseFunction::doubleHenyeyGreenstein(0.67, 0.099, 0.01);
  EXPECT_NEAR(integrateSphere(dhg, [](double mu) { return mu; }), 0.01 * 0.67 + 0.99 * 0.099, 1e-9);
  // Cornette-Shanks: <mu> = 3 g (4 + g^2) / (5 (2 + g^2)), 0.7178... for Bruneton's g = 0.8
  EXPECT_NEAR(PhaseFunction::cornetteShanks(0.8).asymmetry(), 3 * 0.8 * 4.64 / (5 * 2.64), 1e-15);
}

TEST(ModelPhase, RayleighAndPenndorfAreSymmetricWithZeroAsymmetry) {
  for (const PhaseFunction& p : {PhaseFunction::rayleigh(), PhaseFunction::penndorf()}) {
    EXPECT_NEAR(integrateSphere(p, [](double mu) { return mu; }), 0.0, 1e-15) << p.describe();
    for (double mu : {0.0, 0.1, 0.5, 0.9, 1.0}) EXPECT_DOUBLE_EQ(p(mu), p(-mu)) << p.describe();
  }
  // Eq. 9: 3/(16 pi) (1 + mu^2); forward twice as strong as sideways
  EXPECT_NEAR(PhaseFunction::rayleigh()(1.0), 3.0 / (8.0 * kPi), 1e-17);
  EXPECT_NEAR(PhaseFunction::rayleigh()(1.0) / PhaseFunction::rayleigh()(0.0), 2.0, 1e-15);
  // Eq. 10: 0.7629 (1 + 0.932 mu^2) / (4 pi), to the 4 digits Penndorf gives
  const PhaseFunction penndorf = PhaseFunction::penndorf();
  EXPECT_NEAR(penndorf(0.0) * 4.0 * kPi, 0.7629, 1e-4);
  EXPECT_NEAR(penndorf(1.0) / penndorf(0.0), 1.932, 1e-12);
}

TEST(ModelPhase, TabulatedInterpolatesLinearlyAndIsRenormalised) {
  // a table of the HG function, in degrees, scaled by 7: renormalised back to 1
  std::vector<double> angles, values;
  const PhaseFunction hg = PhaseFunction::henyeyGreenstein(0.5);
  for (int i = 0; i <= 1800; ++i) {
    angles.push_back(i * 0.1);
    values.push_back(7.0 * hg(std::cos(i * 0.1 * kPi / 180.0)));
  }
  const PhaseFunction t = PhaseFunction::tabulatedDegrees(angles, values);
  EXPECT_NEAR(integrateSphere(t, [](double) { return 1.0; }), 1.0, 1e-6);
  for (double mu : {-1.0, -0.5, 0.0, 0.5, 0.99, 1.0}) EXPECT_NEAR(t(mu) / hg(mu), 1.0, 2e-4) << mu;
  EXPECT_NEAR(t.asymmetry(), 0.5, 1e-4);

  // two samples: a straight line in mu, exactly normalised
  const PhaseFunction line = PhaseFunction::tabulated({-1.0, 1.0}, {1.0, 3.0});
  EXPECT_NEAR(line(0.0), 1.0 / (4.0 * kPi), 1e-15);  // p = (2 + mu) / (8 pi)
  EXPECT_NEAR(line(0.5) - line(0.0), (line(1.0) - line(0.0)) / 2.0, 1e-15);
}

// A tabulated function's interval gives operator()'s value to the bit, also read from
// another table on the same samples (one search for the tables of every wavelength), and at
// the ends and outside the samples; a closed form has no samples to search.
TEST(ModelPhase, TheIntervalOfASampleIsSharedByTablesOnTheSameSamples) {
  std::vector<double> angles, a, b;
  for (int i = 0; i <= 360; ++i) {
    angles.push_back(i * 0.5);
    const double mu = std::cos(i * 0.5 * kPi / 180.0);
    a.push_back(PhaseFunction::henyeyGreenstein(0.7)(mu));
    b.push_back(PhaseFunction::henyeyGreenstein(0.2)(mu) + 0.01 * i);
  }
  const PhaseFunction ta = PhaseFunction::tabulatedDegrees(angles, a), tb = PhaseFunction::tabulatedDegrees(angles, b);
  for (double mu : {-2.0, -1.0, -0.999, -0.3, 0.0, 0.123456, 0.9, 0.99996, 1.0, 3.0}) {
    const PhaseFunction::Interval s = ta.interval(mu);
    EXPECT_EQ(ta.valueIn(s), ta(mu)) << mu;
    EXPECT_EQ(tb.valueIn(s), tb(mu)) << mu;
  }
  EXPECT_GT(tb(0.5), 0.0);
  EXPECT_THROW(PhaseFunction::rayleigh().interval(0.5), std::logic_error);
}

// A mixture's phase function is the weighted mean of its parts': normalised, its asymmetry
// the weighted mean of theirs (g is linear in p), on the parts' own samples when they share them.
TEST(ModelPhase, MixtureIsTheWeightedMeanOfItsParts) {
  std::vector<double> angles, a, b;
  const PhaseFunction hgA = PhaseFunction::henyeyGreenstein(0.7), hgB = PhaseFunction::henyeyGreenstein(-0.2);
  for (int i = 0; i <= 360; ++i) {
    angles.push_back(i * 0.5);
    a.push_back(hgA(std::cos(i * 0.5 * kPi / 180.0)));
    b.push_back(hgB(std::cos(i * 0.5 * kPi / 180.0)));
  }
  const PhaseFunction ta = PhaseFunction::tabulatedDegrees(angles, a), tb = PhaseFunction::tabulatedDegrees(angles, b);
  const PhaseFunction mix = PhaseFunction::mixture({ta, tb}, {3.0, 1.0});
  EXPECT_EQ(mix.cosThetaSamples(), ta.cosThetaSamples());
  EXPECT_NEAR(integrateSphere(mix, [](double) { return 1.0; }), 1.0, 1e-12);
  EXPECT_NEAR(mix.asymmetry(), 0.75 * ta.asymmetry() + 0.25 * tb.asymmetry(), 1e-12);
  for (double mu : {-1.0, 0.0, 0.7, 1.0}) EXPECT_NEAR(mix(mu), 0.75 * ta(mu) + 0.25 * tb(mu), 1e-12 * ta(1.0));
  // Parts of other kinds: sampled every 0.25 degrees.
  const PhaseFunction other = PhaseFunction::mixture({PhaseFunction::rayleigh(), hgB}, {1.0, 1.0});
  EXPECT_EQ(other.cosThetaSamples().size(), 721u);
  EXPECT_NEAR(other.asymmetry(), 0.5 * (0.0 - 0.2), 1e-4);
  EXPECT_THROW(PhaseFunction::mixture({ta}, {0.0}), std::invalid_argument);
  EXPECT_THROW(PhaseFunction::mixture({ta, tb}, {1.0}), std::invalid_argument);
}

TEST(ModelPhase, InvalidParametersAreRefused) {
  EXPECT_THROW(PhaseFunction::henyeyGreenstein(1.0), std::invalid_argument);
  EXPECT_THROW(PhaseFunction::henyeyGreenstein(-1.0), std::invalid_argument);
  EXPECT_THROW(PhaseFunction::henyeyGreenstein(std::nan("")), std::invalid_argument);
  EXPECT_THROW(PhaseFunction::cornetteShanks(1.5), std::invalid_argument);
  EXPECT_THROW(PhaseFunction::doubleHenyeyGreenstein(0.5, 0.2, 1.5), std::invalid_argument);
  EXPECT_THROW(PhaseFunction::tabulated({-1.0, 0.5}, {1.0, 1.0}), std::invalid_argument);      // not up to 1
  EXPECT_THROW(PhaseFunction::tabulated({-1.0, 0.5, 0.2, 1.0}, {1, 1, 1, 1}), std::invalid_argument);  // unsorted
  EXPECT_THROW(PhaseFunction::tabulated({-1.0, 1.0}, {1.0, -1.0}), std::invalid_argument);     // negative
  EXPECT_THROW(PhaseFunction::tabulated({-1.0, 1.0}, {0.0, 0.0}), std::invalid_argument);      // zero integral
  try {
    PhaseFunction::henyeyGreenstein(1.2);
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "g: expected a number in [-0.999999, 0.999999], got 1.2");
  }
}
