#include "Spectrum.hpp"

#include <glm/vec2.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

using namespace umbra::atmosphere;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A hand-built set with a sample at every whole nm of 360-830 nm and 1 nm bins: the point
/// rule on it is the CIE's own 1 nm summation, the reference for the coarse sets.
WavelengthSet everyNanometre() {
  WavelengthSet set;
  for (int nm = 360; nm <= 830; ++nm) {
    set.nm.push_back(nm);
    set.binWidthNm.push_back(1.0);
  }
  return set;
}

std::vector<double> sampleSpectrum(const WavelengthSet& set, double (*f)(double)) {
  std::vector<double> v;
  for (double nm : set.nm) v.push_back(f(nm));
  return v;
}

double sun(double nm) { return solarIrradianceWm2PerNm(nm); }
double rayleighSky(double nm) { return solarIrradianceWm2PerNm(nm) * std::pow(nm / 550.0, -4.0); }
double flat(double) { return 1.0; }

glm::dvec2 chromaticity(const glm::dvec3& xyz) {
  const double s = xyz.x + xyz.y + xyz.z;
  return {xyz.x / s, xyz.y / s};
}

glm::dvec3 normalisedToMax(const glm::dvec3& c) { return c / std::max({c.x, c.y, c.z}); }

} // namespace

// ---- CIE 1931 colour-matching functions ----------------------------------------------------

TEST(Cie1931, TableSumsAreTheCieCheckSums) {
  // Column sums of the CIE 1 nm table (360-830 nm): catch any transcription slip.
  glm::dvec3 sum(0.0);
  for (int nm = 360; nm <= 830; ++nm) sum += cie1931(nm);
  EXPECT_NEAR(sum.x, 106.865469, 1e-6);
  EXPECT_NEAR(sum.y, 106.856917, 1e-6);
  EXPECT_NEAR(sum.z, 106.892251, 1e-6);
}

TEST(Cie1931, PeaksWhereTheCieTablesPutThem) {
  EXPECT_DOUBLE_EQ(cie1931(555.0).y, 1.0);
  glm::dvec3 peak(0.0), peakNm(0.0);
  for (double nm = 360.0; nm <= 830.0; nm += 0.5) {
    const glm::dvec3 c = cie1931(nm);
    for (int k = 0; k < 3; ++k) {
      if (c[k] > peak[k]) { peak[k] = c[k]; peakNm[k] = nm; }
    }
  }
  EXPECT_NEAR(peak.x, 1.0629, 1e-4);  // at 599 nm
  EXPECT_GE(peakNm.x, 595.0);
  EXPECT_LE(peakNm.x, 600.0);
  EXPECT_EQ(peak.y, 1.0);
  EXPECT_EQ(peakNm.y, 555.0);
  EXPECT_NEAR(peak.z, 1.7830, 1e-4);  // at 446 nm
  EXPECT_GE(peakNm.z, 445.0);
  EXPECT_LE(peakNm.z, 450.0);
}

TEST(Cie1931, InterpolatesLinearlyAndIsZeroOutside360To830) {
  const glm::dvec3 a = cie1931(600.0), b = cie1931(601.0), mid = cie1931(600.25);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(mid[k], 0.75 * a[k] + 0.25 * b[k], 1e-15);
  EXPECT_NEAR(a.x, 1.0622, 1e-12);          // table values at whole nm
  EXPECT_NEAR(cie1931(360.0).x, 0.0001299, 1e-12);
  EXPECT_NEAR(cie1931(830.0).y, 4.5181e-7, 1e-15);
  EXPECT_EQ(cie1931(359.99), glm::dvec3(0.0));
  EXPECT_EQ(cie1931(830.01), glm::dvec3(0.0));
  EXPECT_EQ(cie1931(std::nan("")), glm::dvec3(0.0));
  EXPECT_EQ(cie1931(700.0).z, 0.0);          // zbar ends at 650 nm
  EXPECT_GT(cie1931(649.5).z, 0.0);
}

TEST(Cie1931, EqualEnergyWhiteHasEqualIntegralsAndChromaticityOneThird) {
  const WavelengthSet fine = everyNanometre();
  const glm::dvec3 xyz = spectralRadianceToXyz(fine, sampleSpectrum(fine, flat));
  EXPECT_NEAR(xyz.x / xyz.y, 1.0, 1e-3);
  EXPECT_NEAR(xyz.z / xyz.y, 1.0, 1e-3);
  const glm::dvec2 xy = chromaticity(xyz);
  EXPECT_NEAR(xy.x, 1.0 / 3.0, 1e-4);
  EXPECT_NEAR(xy.y, 1.0 / 3.0, 1e-4);
}

// ---- XYZ, luminance, sRGB ------------------------------------------------------------------

TEST(Srgb, D65WhitePointIsWhiteAndPrimariesComeBack) {
  const glm::dvec3 white = xyzToLinearSrgb({0.9505, 1.0, 1.089});
  EXPECT_NEAR(white.r, 1.0, 1e-3);
  EXPECT_NEAR(white.g, 1.0, 1e-3);
  EXPECT_NEAR(white.b, 1.0, 1e-3);
  // XYZ of the sRGB primaries (IEC 61966-2-1's RGB-to-XYZ matrix columns).
  const glm::dvec3 red = xyzToLinearSrgb({0.4124, 0.2126, 0.0193});
  const glm::dvec3 green = xyzToLinearSrgb({0.3576, 0.7152, 0.1192});
  const glm::dvec3 blue = xyzToLinearSrgb({0.1805, 0.0722, 0.9505});
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(red[k], k == 0 ? 1.0 : 0.0, 1e-3);
    EXPECT_NEAR(green[k], k == 1 ? 1.0 : 0.0, 1e-3);
    EXPECT_NEAR(blue[k], k == 2 ? 1.0 : 0.0, 1e-3);
  }
  // The converse: white to D65's XYZ, and the round trip within the 4 decimals.
  const glm::dvec3 d65 = linearSrgbToXyz({1.0, 1.0, 1.0});
  EXPECT_NEAR(d65.x, 0.9505, 1e-4);
  EXPECT_NEAR(d65.y, 1.0, 1e-4);
  EXPECT_NEAR(d65.z, 1.089, 1e-4);
  const glm::dvec3 colour(0.7, 0.2, 0.05), back = xyzToLinearSrgb(linearSrgbToXyz(colour));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[k], colour[k], 2e-4);
}

TEST(Luminance, OneNanometreLineAt555nmGives683CdM2) {
  WavelengthSet line;  // hand-built: point rule
  line.nm = {555.0};
  line.binWidthNm = {1.0};
  EXPECT_NEAR(luminanceCdM2(line, {1.0}), 683.0, 1e-9);
  const glm::dvec3 xyz = spectralRadianceToXyz(line, {1.0});
  EXPECT_NEAR(xyz.x, 683.0 * 0.5120501, 1e-6);
  EXPECT_NEAR(xyz.z, 683.0 * 0.005749999, 1e-6);
  EXPECT_NEAR(luminanceCdM2(line, {2.0}), 2.0 * 683.0, 1e-9);  // linear
  line.nm = {700.0};                                            // ybar(700) = 0.004102
  EXPECT_NEAR(luminanceCdM2(line, {1.0}), 683.0 * 0.004102, 1e-9);
}

TEST(Luminance, SizesMustMatch) {
  const WavelengthSet set = WavelengthSet::uniform(15);
  EXPECT_THROW(spectralRadianceToXyz(set, std::vector<double>(14, 1.0)), std::invalid_argument);
  WavelengthSet bad;
  bad.nm = {500.0, 600.0};
  bad.binWidthNm = {1.0};
  EXPECT_THROW(luminanceCdM2(bad, {1.0, 1.0}), std::invalid_argument);
}

// ---- solar spectrum ------------------------------------------------------------------------

TEST(SolarSpectrum, BandIntegralIsItsShareOfTheSolarConstant) {
  // 360-830 nm holds 734.9 W m^-2 of the ASTM G173 spectrum (whole: 1366.1 W m^-2), i.e.
  // 54 % of the 1361 W m^-2 solar constant. A 5772 K black body scaled to 1361 W m^-2 puts
  // 717 W m^-2 (52.7 %) there; the real Sun is a little brighter in the visible and darker
  // in the near UV than the black body.
  double integral = 0.0;
  const double step = 0.01;
  for (double nm = 360.0 + 0.5 * step; nm < 830.0; nm += step) integral += solarIrradianceWm2PerNm(nm) * step;
  EXPECT_NEAR(integral, 734.9, 0.5);
  double binSum = 0.0;  // the bins [360, 370) ... [820, 830) exactly
  for (int k = 0; k < 47; ++k) binSum += 10.0 * umbra::atmosphere::detail::kSolarBinMeanWm2PerNm[k];
  EXPECT_NEAR(integral, binSum, 0.1);
  EXPECT_NEAR(integral / 1361.0, 0.527, 0.02);
}

TEST(SolarSpectrum, PeaksAt455nmNear2WPerM2PerNm) {
  double peak = 0.0, peakNm = 0.0;
  for (double nm = 360.0; nm <= 830.0; nm += 0.5) {
    if (solarIrradianceWm2PerNm(nm) > peak) { peak = solarIrradianceWm2PerNm(nm); peakNm = nm; }
  }
  EXPECT_GE(peakNm, 450.0);
  EXPECT_LE(peakNm, 500.0);
  EXPECT_NEAR(peak, 2.03, 0.01);
  EXPECT_NEAR(solarIrradianceWm2PerNm(550.0), 1.851, 0.002);
  EXPECT_NEAR(solarIrradianceWm2PerNm(800.0), 1.135, 0.005);
}

TEST(SolarSpectrum, IlluminanceIsTheLuminousSolarConstant) {
  // Darula, Kittler & Gueymard (2005, Solar Energy 79:559) derive a luminous solar constant
  // of 133 334 lx from the same Gueymard spectrum that ASTM G173 tabulates.
  const WavelengthSet fine = everyNanometre();
  EXPECT_NEAR(luminanceCdM2(fine, sampleSpectrum(fine, sun)), 133334.0, 0.005 * 133334.0);
}

TEST(SolarSpectrum, HeldAtTheTableEndsAndZeroOutside) {
  EXPECT_EQ(solarIrradianceWm2PerNm(360.0), solarIrradianceWm2PerNm(365.0));
  EXPECT_NEAR(solarIrradianceWm2PerNm(365.0), 1.11776, 1e-12);  // the [360, 370) bin mean
  EXPECT_NEAR(solarIrradianceWm2PerNm(370.0), 0.5 * (1.11776 + 1.14259), 1e-12);
  EXPECT_EQ(solarIrradianceWm2PerNm(840.0), solarIrradianceWm2PerNm(835.0));
  EXPECT_EQ(solarIrradianceWm2PerNm(359.9), 0.0);
  EXPECT_EQ(solarIrradianceWm2PerNm(840.1), 0.0);
}

// ---- wavelength sets -----------------------------------------------------------------------

TEST(WavelengthSet, UniformSamplesBinCentresWithWidthsSummingToTheBand) {
  const WavelengthSet set = WavelengthSet::uniform();
  ASSERT_EQ(set.size(), 15u);
  ASSERT_EQ(set.binWidthNm.size(), 15u);
  ASSERT_EQ(set.xyzWeightLmNmPerW.size(), 15u);
  EXPECT_NEAR(set.nm.front(), 360.0 + 470.0 / 30.0, 1e-12);
  EXPECT_NEAR(set.nm.back(), 830.0 - 470.0 / 30.0, 1e-12);
  EXPECT_TRUE(std::is_sorted(set.nm.begin(), set.nm.end()));
  double sum = 0.0;
  for (double w : set.binWidthNm) {
    EXPECT_NEAR(w, 470.0 / 15.0, 1e-12);
    sum += w;
  }
  EXPECT_NEAR(sum, 830.0 - 360.0, 1e-9);
  // sampled() at the same wavelengths computes the same widths from the interpolant.
  const WavelengthSet again = WavelengthSet::sampled(set.nm, 360.0, 830.0);
  for (std::size_t i = 0; i < set.size(); ++i) EXPECT_NEAR(again.binWidthNm[i], set.binWidthNm[i], 1e-9);
}

TEST(WavelengthSet, UniformQuadratureConvergesForSmoothFunctions) {
  // A Gaussian of 60 nm width at 550 nm, integrated over 360-830 nm (closed form with erf).
  auto f = [](double nm) { return std::exp(-std::pow((nm - 550.0) / 60.0, 2)); };
  const double exact = 60.0 * std::sqrt(kPi) * 0.5 * (std::erf(280.0 / 60.0) + std::erf(190.0 / 60.0));
  double previousError = 1e300;
  for (int count : {15, 30, 60, 120}) {
    const WavelengthSet set = WavelengthSet::uniform(count);
    double q = 0.0;
    for (std::size_t i = 0; i < set.size(); ++i) q += set.binWidthNm[i] * f(set.nm[i]);
    const double error = std::abs(q - exact);
    EXPECT_LT(error, 0.5 * previousError) << count;  // midpoint rule: about / 4 per doubling
    previousError = error;
  }
  EXPECT_LT(previousError, 1e-7 * exact);
}

TEST(WavelengthSet, RgbIsRedGreenBlueWithInterpolantWidths) {
  const WavelengthSet set = WavelengthSet::rgb();
  ASSERT_EQ(set.size(), 3u);
  EXPECT_EQ(set.nm, (std::vector<double>{680.0, 550.0, 440.0}));
  // Linear interpolation held constant to 360 and 830 nm: 680 nm owns 615-830 nm,
  // 550 nm owns 495-615 nm, 440 nm owns 360-495 nm.
  EXPECT_NEAR(set.binWidthNm[0], 215.0, 1e-12);
  EXPECT_NEAR(set.binWidthNm[1], 120.0, 1e-12);
  EXPECT_NEAR(set.binWidthNm[2], 135.0, 1e-12);
  // Each sample feeds mostly the channel it stands for.
  const glm::dvec3 r = xyzToLinearSrgb(set.xyzWeightLmNmPerW[0]);
  const glm::dvec3 b = xyzToLinearSrgb(set.xyzWeightLmNmPerW[2]);
  EXPECT_GT(r.r, std::abs(r.b));
  EXPECT_GT(b.b, std::abs(b.r));
}

TEST(WavelengthSet, SampledRejectsWhatItCannotInterpolate) {
  EXPECT_THROW(WavelengthSet::sampled({}), std::invalid_argument);
  EXPECT_THROW(WavelengthSet::sampled({500.0, 500.0}), std::invalid_argument);
  EXPECT_THROW(WavelengthSet::sampled({350.0, 500.0}), std::invalid_argument);
  EXPECT_THROW(WavelengthSet::sampled({500.0}, 600.0, 400.0), std::invalid_argument);
  EXPECT_THROW(WavelengthSet::uniform(0), std::invalid_argument);
  const WavelengthSet one = WavelengthSet::sampled({550.0}, 400.0, 700.0);
  EXPECT_NEAR(one.binWidthNm[0], 300.0, 1e-12);
}

// ---- colour of sampled spectra -------------------------------------------------------------

TEST(Colour, SunWithoutAtmosphereIsWarmWhiteFromAnySampleCount) {
  // Reference: the 1 nm point rule. The Sun's chromaticity is (0.3236, 0.3331), about 5900 K;
  // in linear sRGB normalised to its largest channel it is (1, 0.891, 0.856).
  const WavelengthSet fine = everyNanometre();
  const glm::dvec3 reference = spectralRadianceToXyz(fine, sampleSpectrum(fine, sun));
  const glm::dvec2 xy = chromaticity(reference);
  EXPECT_NEAR(xy.x, 0.3236, 5e-4);
  EXPECT_NEAR(xy.y, 0.3331, 5e-4);
  const glm::dvec3 rgb = normalisedToMax(xyzToLinearSrgb(reference));
  EXPECT_EQ(rgb.r, 1.0);                 // warm: red strongest ...
  EXPECT_GT(rgb.g, rgb.b);               // ... blue weakest
  EXPECT_GT(rgb.b, 0.85);                // ... and all within 15 %
  EXPECT_NEAR(rgb.g, 0.891, 2e-3);
  EXPECT_NEAR(rgb.b, 0.856, 2e-3);
  // The solar-ratio rule reproduces the Sun exactly from 15 and from 3 samples (up to the
  // reference's own 1 nm summation), where the point rule on 3 samples would be far off.
  for (const WavelengthSet& set : {WavelengthSet::uniform(15), WavelengthSet::rgb(), WavelengthSet::uniform(4)}) {
    const glm::dvec3 xyz = spectralRadianceToXyz(set, sampleSpectrum(set, sun));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(xyz[k] / reference[k], 1.0, 2e-4) << set.size();
  }
  // The weights are integrated exactly: against a 0.01 nm midpoint sum of the Sun they
  // agree to 1e-6.
  WavelengthSet hundredth;
  for (int i = 0; i < 47000; ++i) {
    hundredth.nm.push_back(360.005 + 0.01 * i);
    hundredth.binWidthNm.push_back(0.01);
  }
  const glm::dvec3 exact = spectralRadianceToXyz(hundredth, sampleSpectrum(hundredth, sun));
  const WavelengthSet fifteen = WavelengthSet::uniform(15);
  const glm::dvec3 xyz15 = spectralRadianceToXyz(fifteen, sampleSpectrum(fifteen, sun));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(xyz15[k] / exact[k], 1.0, 1e-6);
  WavelengthSet pointRule = WavelengthSet::rgb();
  pointRule.xyzWeightLmNmPerW.clear();
  EXPECT_GT(std::abs(chromaticity(spectralRadianceToXyz(pointRule, sampleSpectrum(pointRule, sun))).x - xy.x), 0.05);
}

TEST(Colour, RayleighSkyFromFewSamplesIsCloseToTheFineSpectrum) {
  // Sunlight times lambda^-4: 15 samples give its chromaticity to 5e-4; 3 samples overstate
  // green (interpolating lambda^-4 linearly between 440 and 550 nm lies above the curve), by
  // 0.003 in x and 0.010 in y.
  const WavelengthSet fine = everyNanometre();
  const glm::dvec2 reference = chromaticity(spectralRadianceToXyz(fine, sampleSpectrum(fine, rayleighSky)));
  EXPECT_NEAR(reference.x, 0.2345, 5e-4);
  EXPECT_NEAR(reference.y, 0.2348, 5e-4);
  const WavelengthSet fifteen = WavelengthSet::uniform(15);
  const glm::dvec2 xy15 = chromaticity(spectralRadianceToXyz(fifteen, sampleSpectrum(fifteen, rayleighSky)));
  EXPECT_NEAR(xy15.x, reference.x, 5e-4);
  EXPECT_NEAR(xy15.y, reference.y, 5e-4);
  const WavelengthSet three = WavelengthSet::rgb();
  const glm::dvec2 xy3 = chromaticity(spectralRadianceToXyz(three, sampleSpectrum(three, rayleighSky)));
  EXPECT_NEAR(xy3.x, reference.x, 0.005);
  EXPECT_NEAR(xy3.y, reference.y, 0.015);
  const glm::dvec3 rgb3 = normalisedToMax(spectralRadianceToLinearSrgb(three, sampleSpectrum(three, rayleighSky)));
  EXPECT_EQ(rgb3.b, 1.0);                // still sky blue
  EXPECT_LT(rgb3.r, 0.3);
}

TEST(Colour, SolarRatioRuleOnAFineGridAgreesWithThePointRule) {
  std::vector<double> nm;
  for (int w = 360; w <= 830; w += 5) nm.push_back(w);
  const WavelengthSet interpolated = WavelengthSet::sampled(nm);
  WavelengthSet pointRule = interpolated;
  pointRule.xyzWeightLmNmPerW.clear();
  pointRule.binWidthNm.assign(nm.size(), 5.0);
  pointRule.binWidthNm.front() = pointRule.binWidthNm.back() = 2.5;  // trapezoid ends
  const std::vector<double> l = sampleSpectrum(interpolated, rayleighSky);
  const glm::dvec3 a = spectralRadianceToXyz(interpolated, l), b = spectralRadianceToXyz(pointRule, l);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k] / b[k], 1.0, 3e-3) << k;
  // Weights are never negative, so non-negative samples never give negative X, Y, Z.
  for (const glm::dvec3& w : interpolated.xyzWeightLmNmPerW) EXPECT_GE(std::min({w.x, w.y, w.z}), 0.0);
  EXPECT_NEAR(luminanceCdM2(interpolated, l), a.y, 1e-9 * a.y);
}
