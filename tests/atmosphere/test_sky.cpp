// The sky seen from the ground (Sky.hpp): the CIE standard general sky formula, and the
// Earth preset's relative luminance against the CIE standard clear sky (type 12), its
// zenith luminance and colour. Small tables (docs/sky-validation.md has the numbers at the
// command's default sizes).
#include "Sky.hpp"

#include "ModelTestSupport.hpp"
#include "PrecomputeTestSupport.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>

namespace umbra::atmosphere {
namespace {

using umbra::test::kPi;
constexpr double kDeg = kPi / 180.0;

TEST(CieSky, Type12ParametersAreTheStandardClearSky) {
  // ISO 15469:2004 table 1: type 12 = gradation group V (a = -1, b = -0.32) with
  // indicatrix group 4 (c = 10, d = -3, e = 0.45).
  EXPECT_EQ(kCieClearSkyType12.a, -1.0);
  EXPECT_EQ(kCieClearSkyType12.b, -0.32);
  EXPECT_EQ(kCieClearSkyType12.c, 10.0);
  EXPECT_EQ(kCieClearSkyType12.d, -3.0);
  EXPECT_EQ(kCieClearSkyType12.e, 0.45);
}

TEST(CieSky, RelativeLuminanceIsOneAtTheZenithAndSymmetricInAzimuth) {
  const CieSkyParameters& p = kCieClearSkyType12;
  for (double zs : {0.0, 20.0, 45.0, 70.0, 89.0}) {
    EXPECT_NEAR(cieRelativeLuminance(p, 0.0, 0.7, zs * kDeg), 1.0, 1e-14) << zs;
    for (double z : {10.0, 50.0, 85.0})
      for (double a : {15.0, 90.0, 160.0})
        EXPECT_NEAR(cieRelativeLuminance(p, z * kDeg, a * kDeg, zs * kDeg),
                    cieRelativeLuminance(p, z * kDeg, -a * kDeg, zs * kDeg), 1e-14);
  }
  EXPECT_EQ(cieGradation(p, kPi / 2), 1.0);
}

TEST(CieSky, KnownValues) {
  const CieSkyParameters& p = kCieClearSkyType12;
  // By hand: phi(0) = 1 - exp(-0.32) = 0.2738510; f(45 deg) = 1 + 10 (exp(-3 pi/4) -
  // exp(-3 pi/2)) + 0.45 / 2 = 2.0829700; at the horizon opposite the Sun chi = 135 deg,
  // f = 1 + 10 (exp(-9 pi/4) - exp(-3 pi/2)) + 0.225 = 1.1436825, phi(90) = 1:
  // L/L_z = 1.1436825 / (2.0829700 * 0.2738510) = 2.004970.
  EXPECT_NEAR(cieGradation(p, 0.0), 0.27385096, 1e-8);
  EXPECT_NEAR(cieIndicatrix(p, 0.0), 11.3601671, 1e-6);
  EXPECT_NEAR(cieRelativeLuminance(p, 90 * kDeg, 180 * kDeg, 45 * kDeg), 2.0049703, 1e-6);
  // Sun at 30 deg, view at 45 deg, 90 deg from the Sun's azimuth.
  EXPECT_NEAR(cieRelativeLuminance(p, 45 * kDeg, 90 * kDeg, 30 * kDeg), 0.6903524, 1e-6);
  // Looking at a Sun 60 deg from the zenith: the circumsolar peak, 13.48 times the zenith.
  EXPECT_NEAR(cieRelativeLuminance(p, 60 * kDeg, 0.0, 60 * kDeg), 13.479005, 1e-5);
}

TEST(Sky, SolarIlluminanceAtOneAu) {
  // 683 lm/W * int E ybar over the ASTM G173 extraterrestrial spectrum: the "solar
  // illuminance constant" is about 1.33e5 lx (e.g. 133 334 lx in Darula, Kittler &
  // Gueymard 2005, Solar Energy 79, 559).
  const double e = solarIlluminanceLux();
  EXPECT_GT(e, 1.30e5);
  EXPECT_LT(e, 1.36e5);
  // The solar-ratio colour rule is exact for the Sun itself.
  std::vector<double> sun;
  const WavelengthSet set = WavelengthSet::uniform(15);
  for (double nm : set.nm) sun.push_back(solarIrradianceWm2PerNm(nm));
  EXPECT_NEAR(luminanceCdM2(set, sun) / e, 1.0, 2e-3);
}

// ---- Earth with Bruneton's thin haze, earth-bruneton (small tables, 3 wavelengths, 3 orders)

class EarthSky : public ::testing::Test {
protected:
  static void SetUpTestSuite() { setUpPreset("earth-bruneton"); }
  static void setUpPreset(const char* preset) {
    wavelengths = std::make_unique<WavelengthSet>(WavelengthSet::rgb());
    atmosphere = std::make_unique<Atmosphere>(loadAtmosphere(preset, wavelengths->nm));
    PrecomputeOptions o = umbra::test::smallPrecomputeOptions();
    o.orders = 3;
    tables = std::make_unique<AtmosphereTables>(precompute(*atmosphere, o));
  }
  static void TearDownTestSuite() {
    tables.reset();
    atmosphere.reset();
    wavelengths.reset();
  }
  static SkyGrid grid(double sunZenithDeg) {
    return skyLuminance(*tables, *atmosphere, *wavelengths, sunZenithDeg * kDeg, 0.0, 5 * kDeg, 10 * kDeg);
  }
  static std::unique_ptr<WavelengthSet> wavelengths;
  static std::unique_ptr<Atmosphere> atmosphere;
  static std::unique_ptr<AtmosphereTables> tables;
};
std::unique_ptr<WavelengthSet> EarthSky::wavelengths;
std::unique_ptr<Atmosphere> EarthSky::atmosphere;
std::unique_ptr<AtmosphereTables> EarthSky::tables;

TEST_F(EarthSky, GridShapeAndValues) {
  const SkyGrid g = grid(45.0);
  EXPECT_EQ(g.zenithCount, 19);
  EXPECT_EQ(g.azimuthCount, 19);
  ASSERT_EQ(g.samples.size(), 19u * 19u);
  EXPECT_NEAR(g.at(18, 0).viewZenithRad, kPi / 2, 1e-12);
  EXPECT_NEAR(g.at(0, 18).azimuthRad, kPi, 1e-12);
  for (const SkySample& s : g.samples) {
    EXPECT_TRUE(std::isfinite(s.luminanceCdM2));
    EXPECT_GT(s.luminanceCdM2, 0.0);
  }
  // brighter towards the Sun than away from it, at the Sun's height
  EXPECT_GT(g.at(9, 0).luminanceCdM2, 2.0 * g.at(9, 18).luminanceCdM2);
}

TEST_F(EarthSky, ZenithLuminanceForASunAt30Degrees) {
  // Measured clear skies at a solar elevation of 60 degrees have zenith luminances of some
  // 3-10 kcd/m^2 (Preetham et al. 1999's fit gives 5.9 kcd/m^2 at turbidity 2), but those
  // skies have aerosol optical depths of 0.1-0.3. The Earth preset has Bruneton's aerosols,
  // vertical optical depth 4.44e-6 1/m * 1200 m = 0.005: a nearly pure Rayleigh sky. Its
  // single-scattering estimate at 550 nm, E_v tau_R P_R(30 deg) T = 133 klx * 0.097 *
  // 0.1044 / sr * 0.9 ~ 1.2 kcd/m^2, plus multiple scattering (+20-40 %), is the range
  // below (docs/sky-validation.md): the model gives 1.5-1.6 kcd/m^2.
  const SkyGrid g = grid(30.0);
  const double lz = g.at(0, 0).luminanceCdM2;
  std::printf("zenith luminance, Sun at 30 deg: %.0f cd/m^2 (illuminance %.0f lx)\n", lz, g.solarIlluminanceLux);
  EXPECT_GT(lz, 1200.0);
  EXPECT_LT(lz, 2500.0);
}

TEST_F(EarthSky, ZenithIsBlueForAHighSun) {
  for (double zs : {0.0, 30.0, 45.0}) {
    const glm::dvec3 c = grid(zs).at(0, 0).linearSrgb;
    EXPECT_GT(c.b, c.g) << zs;
    EXPECT_GT(c.g, c.r) << zs;
    EXPECT_GT(c.r, 0.0) << zs;
  }
}

// ---- the Mars preset (small tables, 3 wavelengths, 3 orders) ---------------------------
// Published colours of the Martian sky (Mars Pathfinder, Spirit and Curiosity imaging;
// Ehlers et al. 2014): by day a butterscotch sky, reddest and brightest near the horizon;
// at sunset a blue glow around the Sun within a reddish sky. Costa's Table 1 dust phase
// function (only green forward-peaked) gave a yellow-green day sky (G > B away from the
// Sun fails) and a green glow.

class MarsSky : public EarthSky {
protected:
  static void SetUpTestSuite() { setUpPreset("mars"); }
};

TEST_F(MarsSky, DaySkyNearTheHorizonIsButterscotch) {
  const SkyGrid g = grid(45.0);  // Sun 45 deg high
  for (int ia = 0; ia < g.azimuthCount; ++ia) {
    const glm::dvec3 c = g.at(17, ia).linearSrgb;  // 85 deg from the zenith
    EXPECT_GT(c.r, 1.2 * c.g) << "azimuth " << g.at(17, ia).azimuthRad / kDeg;
    EXPECT_GT(c.g, 1.2 * c.b) << "azimuth " << g.at(17, ia).azimuthRad / kDeg;
  }
}

TEST_F(MarsSky, SunsetGlowAroundTheSunIsBlue) {
  const SkyGrid g = grid(88.0);  // Sun 2 deg high
  const glm::dvec3 glow = g.at(17, 0).linearSrgb;   // 3 deg from the Sun
  const glm::dvec3 away = g.at(17, 9).linearSrgb;   // 90 deg from it in azimuth
  std::printf("Mars sunset: glow rgb %.0f %.0f %.0f, away %.0f %.0f %.0f cd/m^2\n", glow.r, glow.g, glow.b, away.r,
              away.g, away.b);
  EXPECT_GT(glow.b, glow.r);
  EXPECT_GT(away.r, away.b);
  EXPECT_GT(glow.b / glow.r, 3.0 * away.b / away.r);
}

void printComparison(const char* what, const SkyGrid& g) {
  for (double maxZ : {85.0, 70.0}) {
    SkyComparisonOptions zo, mo;
    zo.maxViewZenithRad = mo.maxViewZenithRad = maxZ * kDeg;
    mo.normalisation = SkyNormalisation::Mean;
    const SkyComparison z = compareWithCie(g, kCieClearSkyType12, zo);
    const SkyComparison m = compareWithCie(g, kCieClearSkyType12, mo);
    std::printf("%s Sun zenith %2.0f, Z <= %2.0f: zenith-normalised rms %.3f max %.3f (Z %.0f A %.0f) bias %+.3f; "
                "mean-normalised rms %.3f max %.3f; %d samples\n",
                what, g.sunZenithRad / kDeg, maxZ, z.rmsRelativeError, z.maxRelativeError, z.maxErrorZenithRad / kDeg,
                z.maxErrorAzimuthRad / kDeg, z.meanRelativeError, m.rmsRelativeError, m.maxRelativeError, z.samples);
  }
}

TEST_F(EarthSky, RelativeLuminanceAgainstCieClearSky) {
  // Zenith-normalised (Costa et al., Fig. 7), over Z <= 85 degrees and 5 degrees from the
  // Sun. The model (Bruneton's nearly aerosol-free Earth) is much brighter near the horizon
  // than the CIE clear sky, as Zotti et al. 2007 found for Bruneton's model: the error is
  // mostly there (docs/sky-validation.md). Measured: rms 1.21, 0.73, 0.51.
  struct Case {
    double sunZenithDeg, rmsBound;
  };
  for (const Case c : {Case{30.0, 1.35}, Case{45.0, 0.85}, Case{60.0, 0.60}}) {
    const SkyGrid g = grid(c.sunZenithDeg);
    printComparison("small tables, 3 wavelengths, 3 orders:", g);
    const SkyComparison z = compareWithCie(g);
    EXPECT_LT(z.rmsRelativeError, c.rmsBound) << c.sunZenithDeg;
    // The relative sky is too bright, not too dark, away from the zenith.
    EXPECT_GT(z.meanRelativeError, 0.0) << c.sunZenithDeg;
  }
}

TEST(EarthSkyCommandTables, RelativeLuminanceAgainstCieClearSky) {
  // The command's tables and defaults (15 wavelengths, 4 orders): about 1 s; the same
  // bounds hold (the numbers differ from the small tables' by a few per cent).
  const WavelengthSet set = WavelengthSet::uniform(15);
  const Atmosphere atm = loadAtmosphere("earth-bruneton", set.nm);
  const AtmosphereTables tables = precompute(atm, skyPrecomputeOptions(atm, 4));
  const double bounds[] = {1.35, 0.85, 0.60};
  int k = 0;
  for (double zs : {30.0, 45.0, 60.0}) {
    const SkyGrid g = skyLuminance(tables, atm, set, zs * kDeg, 0.0, 5 * kDeg, 10 * kDeg);
    printComparison("command tables, 15 wavelengths, 4 orders:", g);
    EXPECT_LT(compareWithCie(g).rmsRelativeError, bounds[k++]) << zs;
  }
}

// A real clear sky: the earth preset (OPAC's continental average aerosol, vertical optical
// depth 0.1 at 550 nm, over OPAC's stratospheric background) with the command's tables, against the CIE
// standard clear sky (type 12) over view zenith <= 70 degrees, 5 degrees around the Sun
// left out, both divided by their zenith luminance: RMS within 0.30 at Sun zenith 30, 45,
// 60 degrees (measured 0.06-0.14); types 11 and 13 printed beside it. The zenith at a Sun
// 30 degrees from it is several kcd/m^2, as real clear skies have (Bruneton's Earth: 1.5).
TEST(EarthClearSky, RelativeLuminanceAgainstCieClearSkies) {
  const WavelengthSet set = WavelengthSet::uniform(15);
  const Atmosphere atm = loadAtmosphere("earth", set.nm);
  const AtmosphereTables tables = precompute(atm, skyPrecomputeOptions(atm, 4));
  SkyComparisonOptions o;
  o.maxViewZenithRad = 70.0 * kDeg;
  for (double zs : {30.0, 45.0, 60.0}) {
    const SkyGrid g = skyLuminance(tables, atm, set, zs * kDeg, 0.0, 5 * kDeg, 10 * kDeg);
    const double type11 = compareWithCie(g, kCieSkyType11, o).rmsRelativeError;
    const double type12 = compareWithCie(g, kCieClearSkyType12, o).rmsRelativeError;
    const double type13 = compareWithCie(g, kCieSkyType13, o).rmsRelativeError;
    std::printf("earth, Sun zenith %2.0f, Z <= 70: zenith-normalised rms against CIE type 11 %.3f, "
                "12 %.3f, 13 %.3f; zenith %.0f cd/m^2\n",
                zs, type11, type12, type13, g.at(0, 0).luminanceCdM2);
    EXPECT_LT(type12, 0.30) << zs;
    if (zs == 30.0) { EXPECT_GT(g.at(0, 0).luminanceCdM2, 3000.0); }
  }
}

// The default sky's light on the ground against published clear skies, at the command's
// tables (15 wavelengths, 4 orders):
// - the IES daylight-availability model for a clear sky (IES RP-21, "Recommended practice
//   for the calculation of daylight availability", J. IES 13 (4), 1984): the Sun's direct
//   normal illuminance 127.5 klx exp(-0.21 m), m = 1 / sin(altitude), and the sky's on a
//   horizontal surface 0.8 + 15.5 sqrt(sin(altitude)) klx: mean design values fitted to
//   measured clear skies;
// - the zenith luminance of Preetham, Shirley & Smits (1999, "A practical analytic model
//   for daylight", Appendix A.2) at turbidity 2, the default sky's ((tau_Rayleigh +
//   tau_aerosol) / tau_Rayleigh at 550 nm = (0.097 + 0.1) / 0.097).
// Measured (Sun zenith 20 / 30 / 45 / 60 / 75 deg): direct normal +3 / +3 / +3 / +2 / +1 %,
// sky +5 / +6 / +8 / +10 / +6 %, global +3 / +3 / +4 / +4 / +3 %; zenith -1 / -19 / -39 /
// -51 / -60 % (Preetham's fit keeps a bright zenith down to a low Sun; earth-bruneton's
// sky is -41..-55 % of the IES one, its zenith -72..-75 % of Preetham's).
TEST(EarthClearSky, LightOnTheGroundAgainstPublishedClearSkies) {
  const WavelengthSet set = WavelengthSet::uniform(15);
  for (const std::string preset : {"earth", "earth-bruneton"}) {
    const bool clear = preset == "earth";  // the bounds below are the default sky's
    const Atmosphere atm = loadAtmosphere(preset, set.nm);
    const AtmosphereTables t = precompute(atm, skyPrecomputeOptions(atm, 4));
    std::vector<double> sun(set.size());
    for (std::size_t l = 0; l < sun.size(); ++l) sun[l] = solarIrradianceWm2PerNm(set.nm[l]);
    auto illuminance = [&](std::vector<double> perUnitSun) {
      for (std::size_t l = 0; l < sun.size(); ++l) perUnitSun[l] *= sun[l];
      return luminanceCdM2(set, perUnitSun);  // of an irradiance spectrum: lux
    };
    const double b = t.bottomRadiusM;
    for (double zs : {20.0, 30.0, 45.0, 60.0, 75.0}) {
      const double muS = std::cos(zs * kDeg), sinAltitude = muS, airMass = 1.0 / sinAltitude;
      const double directNormal = illuminance(directIrradiance(t, b, muS)) / muS;
      const double sky = illuminance(indirectIrradiance(t, b, muS));
      const double iesDirectNormal = 127.5e3 * std::exp(-0.21 * airMass);
      const double iesSky = 1e3 * (0.8 + 15.5 * std::sqrt(sinAltitude));
      const double turbidity = 2.0, chi = (4.0 / 9.0 - turbidity / 120.0) * (kPi - 2.0 * zs * kDeg);
      const double preethamZenith =
          1e3 * ((4.0453 * turbidity - 4.9710) * std::tan(chi) - 0.2155 * turbidity + 2.4192);
      const double zenith = skyLuminanceAt(t, atm, set, zs * kDeg, 0.0, 0.0, 0.0).luminanceCdM2;
      std::printf("%s, Sun zenith %2.0f: direct normal %.0f lx (IES %.0f), sky %.0f lx (IES %.0f), global %.0f lx "
                  "(IES %.0f); zenith %.0f cd/m^2 (Preetham T 2: %.0f)\n",
                  preset.c_str(), zs, directNormal, iesDirectNormal, sky, iesSky, directNormal * muS + sky,
                  iesDirectNormal * muS + iesSky, zenith, preethamZenith);
      if (clear) {
        EXPECT_NEAR(directNormal / iesDirectNormal, 1.0, 0.10) << zs;
        EXPECT_NEAR(sky / iesSky, 1.0, 0.20) << zs;
        EXPECT_NEAR((directNormal * muS + sky) / (iesDirectNormal * muS + iesSky), 1.0, 0.10) << zs;
        if (zs <= 30.0) { EXPECT_NEAR(zenith / preethamZenith, 1.0, 0.25) << zs; }
      } else {  // Bruneton's thin haze: too little skylight, too much sunlight
        EXPECT_LT(sky, 0.7 * iesSky) << zs;
        EXPECT_GT(directNormal, 1.1 * iesDirectNormal) << zs;
      }

      // The zenith's colour: CIE 1931 (x, y) against Preetham's fit at turbidity 2 (measured:
      // 0.02-0.03 whiter in x and y from a Sun 20 to 60 deg from the zenith, within 0.005 at
      // 75), and bluer than the Sun's own white.
      const double th = zs * kDeg, th2 = th * th, th3 = th2 * th, T = turbidity, T2 = T * T;
      const double px = (0.00166 * th3 - 0.00375 * th2 + 0.00209 * th) * T2 +
                        (-0.02903 * th3 + 0.06377 * th2 - 0.03202 * th + 0.00394) * T +
                        (0.11693 * th3 - 0.21196 * th2 + 0.06052 * th + 0.25886);
      const double py = (0.00275 * th3 - 0.00610 * th2 + 0.00317 * th) * T2 +
                        (-0.04214 * th3 + 0.08970 * th2 - 0.04153 * th + 0.00516) * T +
                        (0.15346 * th3 - 0.26756 * th2 + 0.06670 * th + 0.26688);
      const glm::dvec3 xyz = spectralRadianceToXyz(set, skyRadiance(t, atm, b, 1.0, muS, muS, sun));
      const glm::dvec3 white = solarXyzLux();
      const double x = xyz.x / (xyz.x + xyz.y + xyz.z), y = xyz.y / (xyz.x + xyz.y + xyz.z);
      std::printf("  zenith colour x %.4f y %.4f (Preetham T 2: %.4f %.4f; the Sun: %.4f %.4f)\n", x, y, px, py,
                  white.x / (white.x + white.y + white.z), white.y / (white.x + white.y + white.z));
      EXPECT_NEAR(x, px, 0.04) << preset << " " << zs;
      EXPECT_NEAR(y, py, 0.04) << preset << " " << zs;
      EXPECT_LT(x, white.x / (white.x + white.y + white.z) - 0.03) << preset << " " << zs;
      EXPECT_LT(y, white.y / (white.x + white.y + white.z) - 0.03) << preset << " " << zs;
    }
  }
}

// The aureole: along the Sun's almucantar (the view as high as the Sun), the luminance at
// chi from the Sun over that at 90 deg, against the CIE indicatrix f(chi) / f(90 deg) of the
// clear skies (at one view zenith their gradation cancels). The default sky lies between
// type 12 (low turbidity) and type 13 (polluted) from 5 to 40 deg (measured, Sun 60 deg
// from the zenith: 10.7, 8.2, 5.5, 2.6 against 9.1-13.5, 7.3-10.6, 4.8-6.7, 2.4-3.0); nearer
// the Sun it rises above both (18.2 at 2 deg: the forward peak of Lorenz-Mie particles,
// which the CIE formula flattens). earth-bruneton's has almost none (3.7 at 5 deg, 1.45 at
// 40); earth-turbid's is brighter than the default's at every angle.
TEST(EarthClearSky, AureoleBetweenTheCieClearSkies) {
  const WavelengthSet set = WavelengthSet::uniform(15);
  std::map<std::string, std::map<double, double>> ratios;  // preset -> chi -> ratio (Sun zenith 60)
  for (const std::string preset : {"earth", "earth-bruneton", "earth-turbid"}) {
    const Atmosphere atm = loadAtmosphere(preset, set.nm);
    const AtmosphereTables t = precompute(atm, skyPrecomputeOptions(atm, 4));
    for (double zs : {45.0, 60.0}) {
      if (preset != "earth" && zs != 60.0) continue;
      const double Z = zs * kDeg;
      auto along = [&](double chiDeg) {
        const double cosA = (std::cos(chiDeg * kDeg) - std::cos(Z) * std::cos(Z)) / (std::sin(Z) * std::sin(Z));
        return skyLuminanceAt(t, atm, set, Z, 0.0, Z, std::acos(std::clamp(cosA, -1.0, 1.0))).luminanceCdM2;
      };
      const double side = along(90.0);
      for (double chi : {2.0, 5.0, 10.0, 20.0, 40.0}) {
        const double ratio = along(chi) / side;
        auto cie = [&](const CieSkyParameters& p) { return cieIndicatrix(p, chi * kDeg) / cieIndicatrix(p, kPi / 2); };
        std::printf("%s, Sun zenith %.0f, %2.0f deg from the Sun: %.2f (CIE 12 %.2f, 13 %.2f)\n", preset.c_str(), zs,
                    chi, ratio, cie(kCieClearSkyType12), cie(kCieSkyType13));
        if (zs == 60.0) ratios[preset][chi] = ratio;
        if (preset == "earth" && chi >= 5.0) {
          EXPECT_GT(ratio, cie(kCieClearSkyType12)) << zs << " " << chi;
          EXPECT_LT(ratio, cie(kCieSkyType13)) << zs << " " << chi;
        } else if (preset == "earth") {
          EXPECT_GT(ratio, cie(kCieSkyType13)) << zs << " " << chi;
        } else if (preset == "earth-bruneton") {
          EXPECT_LT(ratio, 0.7 * cie(kCieClearSkyType12)) << chi;  // almost no aureole
        }
      }
    }
  }
  for (const auto& [chi, ratio] : ratios["earth"]) {  // more haze, a brighter aureole
    EXPECT_GT(ratios["earth-turbid"][chi], ratio) << chi;
    EXPECT_LT(ratios["earth-bruneton"][chi], ratio) << chi;
  }
}

}  // namespace
}  // namespace umbra::atmosphere
