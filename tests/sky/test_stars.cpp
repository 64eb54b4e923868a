// The star catalogue (sky/StarCatalogue) on real rows of kstars-data's stars.dat typed in
// here, and the closed forms of sky/StarLight.
#include "StarCatalogue.hpp"
#include "StarLight.hpp"

#include "Sky.hpp"
#include "Spectrum.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace umbra::sky;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kArcsecRad = kPi / 180.0 / 3600.0;

// Rows of /usr/share/kstars/stars.dat (kstars-data 3.6.2), as they are in the file.
const char* const kSirius =
    "064508.92 -164258.0 -000546.0-001223.100379.2 -1.4400.01A0 1            , alp CMa, Sirius";
const char* const kVega =
    "183656.34 +384701.3 +000201.0+000287.500128.9 00.03-0.00A0 0            , alp Lyr, Vega";
const char* const kPolaris =
    "023149.09 +891550.8 +000044.2-000011.700007.6 01.9700.64F7 0 0.04   3.97, alp UMi, Polaris";
const char* const kFaint = "191157.63 -201446.3 -000076.4+000009.700020.4 08.9902.02M? 0";

double hms(double h, double m, double s) { return (h + m / 60.0 + s / 3600.0) * kPi / 12.0; }
double dms(double sign, double d, double m, double s) { return sign * (d + m / 60.0 + s / 3600.0) * kPi / 180.0; }

std::string writeFile(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST(StarCatalogue, ReadsAKStarsRow) {
  const auto sirius = parseKStarsLine(kSirius);
  ASSERT_TRUE(sirius.has_value());
  EXPECT_NEAR(sirius->raRad, hms(6, 45, 8.92), 0.001 * kArcsecRad);
  EXPECT_NEAR(sirius->decRad, dms(-1, 16, 42, 58.0), 0.001 * kArcsecRad);
  EXPECT_DOUBLE_EQ(sirius->pmRaCosDecMasPerYear, -546.0);
  EXPECT_DOUBLE_EQ(sirius->pmDecMasPerYear, -1223.1);
  EXPECT_DOUBLE_EQ(sirius->parallaxMas, 379.2);
  EXPECT_DOUBLE_EQ(sirius->vMag, -1.44);
  EXPECT_DOUBLE_EQ(sirius->bMinusV, 0.01);
  EXPECT_EQ(sirius->name, "Sirius");

  const auto vega = parseKStarsLine(kVega);
  ASSERT_TRUE(vega.has_value());
  EXPECT_DOUBLE_EQ(vega->bMinusV, 0.0);  // "-0.00"
  EXPECT_NEAR(vega->decRad, dms(+1, 38, 47, 1.3), 0.001 * kArcsecRad);

  const auto polaris = parseKStarsLine(kPolaris);  // with a variability amplitude and period
  ASSERT_TRUE(polaris.has_value());
  EXPECT_EQ(polaris->name, "Polaris");
  EXPECT_NEAR(polaris->decRad, dms(+1, 89, 15, 50.8), 0.001 * kArcsecRad);

  const auto faint = parseKStarsLine(kFaint);  // no name
  ASSERT_TRUE(faint.has_value());
  EXPECT_EQ(faint->name, "");
  EXPECT_DOUBLE_EQ(faint->vMag, 8.99);

  EXPECT_FALSE(parseKStarsLine("#  RA        DEC      pmRA").has_value());
  EXPECT_FALSE(parseKStarsLine("   ").has_value());
}

TEST(StarCatalogue, BadRowsNameTheColumn) {
  const auto messageOf = [](const std::string& line) {
    try {
      parseKStarsLine(line);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  std::string row = kSirius;
  EXPECT_NE(messageOf(row.substr(0, 40)).find("parallax: the line ends before column 45"), std::string::npos);
  row[47] = 'x';
  EXPECT_NE(messageOf(row).find("magnitude: expected a number in columns 47-51"), std::string::npos);
  row = kSirius;
  row[10] = ' ';
  EXPECT_NE(messageOf(row).find("Dec: expected a sign in column 11"), std::string::npos);
  row = kSirius;
  row.replace(0, 2, "25");
  EXPECT_NE(messageOf(row).find("RA: '254508.92' is not hhmmss.ss"), std::string::npos);
  row = kSirius;
  row.replace(11, 2, "91");
  EXPECT_NE(messageOf(row).find("is not sddmmss.s"), std::string::npos);
}

TEST(StarCatalogue, ReadsAFileToTheFaintestMagnitudeAndNamesBadLines) {
  const std::string path = writeFile("umbra-stars-test.dat", std::string("# comment\n") + kSirius + "\n" + kVega +
                                                                 "\n" + kPolaris + "\n" + kFaint + "\n");
  EXPECT_EQ(readKStarsCatalogue(path).size(), 4u);
  const auto bright = readKStarsCatalogue(path, 2.0);
  ASSERT_EQ(bright.size(), 3u);
  EXPECT_EQ(bright.back().name, "Polaris");

  const std::string bad = writeFile("umbra-stars-bad.dat", std::string(kSirius) + "\n" + "064508.92 -16\n");
  try {
    readKStarsCatalogue(bad);
    ADD_FAILURE() << "no error";
  } catch (const StarCatalogueError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(bad + ":2: ", 0), 0u) << e.what();
  }
  try {
    readKStarsCatalogue("/nonexistent/stars.dat");
    ADD_FAILURE() << "no error";
  } catch (const StarCatalogueError& e) {
    EXPECT_NE(std::string(e.what()).find("kstars-data"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
  std::filesystem::remove(bad);
}

// The whole packaged catalogue, where kstars-data is installed: its size and brightest star.
TEST(StarCatalogue, ThePackagedCatalogue) {
  if (!std::filesystem::exists(kKStarsCatalogue)) GTEST_SKIP() << "kstars-data is not installed";
  const auto stars = readKStarsCatalogue(kKStarsCatalogue);
  EXPECT_EQ(stars.size(), 125982u);
  EXPECT_EQ(stars.front().name, "Sirius");
  EXPECT_DOUBLE_EQ(stars.back().vMag, 8.99);
  EXPECT_EQ(readKStarsCatalogue(kKStarsCatalogue, 6.0).back().vMag <= 6.0, true);
}

TEST(StarLight, IrradianceFollowsTheMagnitudeScale) {
  EXPECT_DOUBLE_EQ(irradianceRelativeToSun(kSunMagnitudeV), 1.0);
  EXPECT_NEAR(irradianceRelativeToSun(kSunMagnitudeV + 5.0), 0.01, 1e-15);
  EXPECT_NEAR(irradianceRelativeToSun(0.0) / irradianceRelativeToSun(1.0), std::pow(10.0, 0.4), 1e-12);
}

// Ballesteros' formula gives the Sun's effective temperature (5772 K, IAU 2015 B3) for
// the Sun's B-V of 0.65 within 0.5 %, 10 125 K for B-V 0, and falls monotonically.
TEST(StarLight, TemperatureFromBMinusV) {
  EXPECT_NEAR(ballesterosTemperatureK(0.65), 5772.0, 0.005 * 5772.0);
  EXPECT_NEAR(ballesterosTemperatureK(0.0), 4600.0 * (1.0 / 1.7 + 1.0 / 0.62), 1e-9);
  double last = ballesterosTemperatureK(-0.4);
  for (double bv = -0.35; bv <= 2.0; bv += 0.05) {
    const double t = ballesterosTemperatureK(bv);
    EXPECT_LT(t, last) << "B-V " << bv;
    last = t;
  }
  EXPECT_TRUE(std::isfinite(ballesterosTemperatureK(-0.6739)));  // clamped, no division by zero
  EXPECT_EQ(ballesterosTemperatureK(5.0), ballesterosTemperatureK(2.0));
}

// The Planckian locus: CIE 1931 chromaticities of blackbodies from the CIE's tables
// (CIE 15:2004; illuminant A is a 2856 K blackbody: x 0.44757, y 0.40745).
TEST(StarLight, BlackbodyChromaticityOnThePlanckianLocus) {
  const auto xy = [](double t) {
    const glm::dvec3 c = blackbodyXyz(t);
    return std::pair<double, double>(c.x / (c.x + c.y + c.z), c.y / (c.x + c.y + c.z));
  };
  EXPECT_NEAR(xy(2856.0).first, 0.44757, 5e-4);
  EXPECT_NEAR(xy(2856.0).second, 0.40745, 5e-4);
  EXPECT_NEAR(xy(5000.0).first, 0.3451, 5e-4);
  EXPECT_NEAR(xy(5000.0).second, 0.3516, 5e-4);
  EXPECT_DOUBLE_EQ(blackbodyXyz(5000.0).y, 1.0);
  EXPECT_THROW(blackbodyXyz(0.0), std::invalid_argument);
}

// A star of the Sun's B-V (0.65) has the Sun's colour: the rgb chromaticity of the ASTM
// G173 solar spectrum umbra lights its scenes with, within 0.01. Bluer stars (B-V 0) are
// bluer, redder (1.5) redder, monotonically.
TEST(StarLight, ColourFromBMinusV) {
  glm::dvec3 sunXyz(0.0);
  for (int nm = 360; nm <= 830; ++nm)
    sunXyz += umbra::atmosphere::solarIrradianceWm2PerNm(nm) * umbra::atmosphere::cie1931(nm);
  const glm::dvec3 sun = umbra::atmosphere::xyzToLinearSrgb(sunXyz / sunXyz.y);
  const auto chroma = [](const glm::dvec3& c) { return c / (c.r + c.g + c.b); };
  const glm::dvec3 star = starLinearSrgb(0.65);
  EXPECT_NEAR(chroma(star).r, chroma(sun).r, 0.01);
  EXPECT_NEAR(chroma(star).g, chroma(sun).g, 0.01);
  EXPECT_NEAR(chroma(star).b, chroma(sun).b, 0.01);

  double lastRedOverBlue = 0.0;
  for (double bv = 0.0; bv <= 1.5 + 1e-9; bv += 0.1) {
    const glm::dvec3 c = starLinearSrgb(bv);
    EXPECT_GT(c.r / c.b, lastRedOverBlue) << "B-V " << bv;
    lastRedOverBlue = c.r / c.b;
  }
  EXPECT_GT(starLinearSrgb(0.0).b, starLinearSrgb(0.0).r);
  EXPECT_GT(starLinearSrgb(1.5).r, starLinearSrgb(1.5).b);
}

// A star's illuminance: V = 0 gives 2.54e-6 lx by the relation V = -13.98 - 2.5 log10(E / lx)
// (Allen's Astrophysical Quantities) within 0.1 mag, through the Sun's spectrum and
// V_sun = -26.74; the frames' irradiance of a star, its white balance undone, has that
// illuminance as its luminance (sunlight's lux per W m^-2).
TEST(StarLight, IlluminanceOfAZeroMagnitudeStar) {
  EXPECT_NEAR(-13.98 - 2.5 * std::log10(starIlluminanceLux(0.0)), 0.0, 0.1);
  EXPECT_NEAR(starIlluminanceLux(-1.44) / starIlluminanceLux(6.0), std::pow(10.0, 0.4 * 7.44), 1e-9 * std::pow(10.0, 2.976));
  const glm::dvec3 sirius = starFrameIrradianceWm2(-1.44, 0.01, kSolarConstantWm2) * sunLinearSrgb() *
                            (umbra::atmosphere::solarIlluminanceLux() / kSolarConstantWm2);
  EXPECT_NEAR(0.2126 * sirius.r + 0.7152 * sirius.g + 0.0722 * sirius.b, starIlluminanceLux(-1.44),
              2e-3 * starIlluminanceLux(-1.44));
}

// The frames' white balance: the Sun's own colour (the G173 spectrum through the CIE
// functions, summed here independently) divides each star's; a star of B-V 0.65 is then
// white within 0.01 in chromaticity, undoing the balance gives back unit luminance, the
// table is exact at the catalogue's 0.01 steps and linear between them.
TEST(StarLight, FrameColourIsBalancedToTheSun) {
  glm::dvec3 sunXyz(0.0);
  for (int nm = 360; nm <= 830; ++nm)
    sunXyz += umbra::atmosphere::solarIrradianceWm2PerNm(nm) * umbra::atmosphere::cie1931(nm);
  const glm::dvec3 sun = umbra::atmosphere::xyzToLinearSrgb(sunXyz / sunXyz.y);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sunLinearSrgb()[c], sun[c], 1e-3);

  const glm::dvec3 solarTwin = starFrameColour(0.65);
  const auto chroma = [](const glm::dvec3& c) { return c / (c.r + c.g + c.b); };
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(chroma(solarTwin)[c], 1.0 / 3.0, 0.01);
  for (double bv : {-0.4, -0.12, 0.0, 0.65, 1.5, 2.0}) {
    const glm::dvec3 f = starFrameColour(bv), expected = starLinearSrgb(bv) / sunLinearSrgb();
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], expected[c], 1e-12) << "B-V " << bv;
    const glm::dvec3 unbalanced = f * sunLinearSrgb();
    EXPECT_NEAR(0.2126 * unbalanced.r + 0.7152 * unbalanced.g + 0.0722 * unbalanced.b, 1.0, 2e-3) << "B-V " << bv;
  }
  const glm::dvec3 mid = starFrameColour(0.655), lo = starFrameColour(0.65), hi = starFrameColour(0.66);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mid[c], 0.5 * (lo[c] + hi[c]), 1e-12);
  // Outside the Ballesteros range the colour is that of its ends.
  EXPECT_EQ(starFrameColour(3.0), starFrameColour(2.0));
  EXPECT_THROW(starFrameColour(std::nan("")), std::invalid_argument);

  const glm::dvec3 e = starFrameIrradianceWm2(6.0, 0.65, 1361.0);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c] / (1361.0 * std::pow(10.0, -0.4 * (6.0 + 26.74))), lo[c], 1e-12);
}

// A planet's tint: the Sun's own B-V reflects white; redder B-V redder light (red over blue
// rising with B-V through the planets' values); the V-band luminance kept within 3 % (the
// magnitudes set it), undoing the white balance.
TEST(StarLight, ReflectedColourIsTheSunsTintedByTheReflectance) {
  const glm::dvec3 grey = reflectedFrameColour(0.653, 0.653);
  for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(grey[c], 1.0);
  double lastRedOverBlue = 0.0;
  for (double bv : {0.81, 0.87, 0.97, 1.09, 1.43}) {  // Venus, Jupiter, Mercury, Saturn, Mars
    const glm::dvec3 f = reflectedFrameColour(bv, 0.653);
    EXPECT_GT(f.r / f.b, lastRedOverBlue) << "B-V " << bv;
    lastRedOverBlue = f.r / f.b;
    const glm::dvec3 unbalanced = f * sunLinearSrgb();
    const double y = 0.2126 * unbalanced.r + 0.7152 * unbalanced.g + 0.0722 * unbalanced.b;
    std::printf("  B-V %.2f: frame colour %.3f %.3f %.3f, luminance %.4f of the Sun's\n", bv, f.r, f.g, f.b, y);
    EXPECT_NEAR(y, 1.0, 0.03) << "B-V " << bv;
  }
  EXPECT_GT(lastRedOverBlue, 1.5);  // Mars: clearly red
}

// The air mass: 1 at the zenith, 2 at 60 deg (1.994 by Kasten & Young's own table), 38 at
// the horizon.
TEST(StarLight, AirMass) {
  EXPECT_NEAR(airMass(0.0), 1.0, 1e-3);
  EXPECT_NEAR(airMass(60.0 * kPi / 180.0), 1.994, 2e-3);
  EXPECT_NEAR(airMass(kPi / 2.0), 38.0, 0.1);
  EXPECT_THROW(airMass(-0.1), std::invalid_argument);
}

// Scintillation keeps the mean (log-normal with mean 1) within the sampling error of 200 000
// stars; the log's spread is sigma X^(3/2) (0.05 at the zenith, 0.26 at X = 3); the same
// (seed, index) gives the same factor, another seed another; sigma 0 gives 1.
TEST(StarLight, ScintillationKeepsTheMean) {
  for (double x : {1.0, 3.0}) {
    const double s = 0.05 * std::pow(x, 1.5);
    double sum = 0.0, sumLog = 0.0, sumLog2 = 0.0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const double f = scintillationFactor(0.05, x, 42, static_cast<std::uint64_t>(i));
      sum += f;
      sumLog += std::log(f);
      sumLog2 += std::log(f) * std::log(f);
    }
    const double mean = sum / n, meanLog = sumLog / n, sdLog = std::sqrt(sumLog2 / n - meanLog * meanLog);
    EXPECT_NEAR(mean, 1.0, 4.0 * s / std::sqrt(n)) << "X " << x;
    EXPECT_NEAR(sdLog, s, 0.01 * s) << "X " << x;
    EXPECT_NEAR(meanLog, -0.5 * s * s, 4.0 * s / std::sqrt(n)) << "X " << x;
  }
  EXPECT_EQ(scintillationFactor(0.1, 2.0, 7, 123), scintillationFactor(0.1, 2.0, 7, 123));
  EXPECT_NE(scintillationFactor(0.1, 2.0, 7, 123), scintillationFactor(0.1, 2.0, 8, 123));
  EXPECT_EQ(scintillationFactor(0.0, 5.0, 7, 123), 1.0);
  EXPECT_THROW(scintillationFactor(-0.1, 1.0, 1, 1), std::invalid_argument);
  EXPECT_THROW(scintillationFactor(0.1, 0.5, 1, 1), std::invalid_argument);
}

// Rows of /usr/share/xplanet/stars/BSC (xplanet 1.3.1), as they are in the file.
namespace {
const char* const kBscHeader = "# From the Bright Star Catalogue, 5th Revised Ed.,\n\n#    Dec      RA   Mag         Name  BSN     HD    SAO\n";
const char* const kBscSirius = "-16.7161  6.7525 -1.46 \"  9Alp CMa\" 2491  48915 151881";
const char* const kBscVega = " 38.7836 18.6156  0.03 \"  3Alp Lyr\" 7001 172167  67174";
}  // namespace

// The Yale catalogue of xplanet: Dec in degrees, RA in hours, V; no colour (the Sun's B-V);
// readCatalogue tells it from the KStars format by its quoted names and names a bad line.
TEST(StarCatalogue, ReadsXplanetsYaleCatalogue) {
  const std::optional<CatalogueStar> s = parseXplanetLine(kBscSirius);
  ASSERT_TRUE(s);
  EXPECT_NEAR(s->decRad, -16.7161 * kPi / 180.0, 1e-12);
  EXPECT_NEAR(s->raRad, 6.7525 * kPi / 12.0, 1e-12);
  EXPECT_EQ(s->vMag, -1.46);
  EXPECT_EQ(s->bMinusV, kColourlessBMinusV);
  EXPECT_EQ(s->pmRaCosDecMasPerYear, 0.0);
  EXPECT_EQ(s->name, "9Alp CMa");
  // The same star in the two catalogues: within 1 arcsec (the Yale file's 4 decimals).
  const CatalogueStar k = *parseKStarsLine(kSirius);
  EXPECT_NEAR(s->decRad, k.decRad, 1.0 * kArcsecRad);
  EXPECT_NEAR(s->raRad, k.raRad, 3.0 * kArcsecRad);

  const std::string bsc = writeFile("umbra-bsc-test.dat", std::string(kBscHeader) + kBscSirius + "\n" + kBscVega + "\n");
  const std::vector<CatalogueStar> stars = readCatalogue(bsc);
  ASSERT_EQ(stars.size(), 2u);
  EXPECT_EQ(stars[1].vMag, 0.03);
  EXPECT_EQ(readCatalogue(bsc, 0.0).size(), 1u);
  const std::string kstars = writeFile("umbra-kstars-test.dat", std::string(kSirius) + "\n" + kVega + "\n");
  EXPECT_EQ(readCatalogue(kstars)[0].bMinusV, 0.01);
  const std::string bad = writeFile("umbra-bsc-bad.dat", std::string(kBscSirius) + "\n 95.0 1.0 2.0 \"x\"\n");
  try {
    readCatalogue(bad);
    ADD_FAILURE() << "no error for a Dec beyond a pole";
  } catch (const StarCatalogueError& e) {
    EXPECT_EQ(std::string(e.what()), bad + ":2: Dec (deg): beyond a pole");
  }
  EXPECT_THROW(parseXplanetLine("-16.7161 six -1.46 \"x\""), std::invalid_argument);
  std::filesystem::remove(bsc);
  std::filesystem::remove(kstars);
  std::filesystem::remove(bad);
}
