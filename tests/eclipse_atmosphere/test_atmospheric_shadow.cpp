// Eclipse shadows through an atmosphere (eclipse paper, 5.2-5.3, 6.1): the decomposition
// I = I_indirect + I_direct against the airless LuT, a transparent shell against the
// airless occluder, Earth's umbra colour and brightness at the Moon's distance (Fig. 12),
// ozone (Fig. 13), Calbuco, Mars at Phobos and Deimos (Fig. 12 right), the ends u -> 0 and u -> 1,
// and finite tables at every preset. Small tables throughout.
#include "AtmosphericShadow.hpp"
#include "Colour.hpp"
#include "EclipseAtmosphere.hpp"

#include "Atmosphere.hpp"
#include "PrecomputeTestSupport.hpp"
#include "Spectrum.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>

using namespace umbra;
using eclipse::AtmosphericShadowModel;

namespace {

constexpr double kMoonDistanceM = 384400e3;
constexpr double kPhobosDistanceM = 9376e3;
constexpr double kDeimosDistanceM = 23463e3;

/// One prepared atmosphere per preset (or JSON text), shared by the tests of a process.
const eclipse::EclipseAtmosphere& body(const std::string& preset, const std::string& json = {}) {
  static std::map<std::string, std::unique_ptr<eclipse::EclipseAtmosphere>> cache;
  auto& slot = cache[preset + json];
  if (slot) return *slot;
  const std::vector<double> nm = atmosphere::WavelengthSet::rgb().nm;
  const atmosphere::Atmosphere atm =
      json.empty() ? atmosphere::loadAtmosphere(preset, nm)
                   : atmosphere::parseAtmosphere(json, "test.json", nm, atmosphere::presetDirectory());
  eclipse::EclipseAtmosphereOptions o;
  o.tables = test::smallPrecomputeOptions();
  o.tables.orders = 2;
  o.refractionWidth = 128, o.refractionHeight = 64;
  o.profileSamples = 2048;
  const bool mars = preset == "mars";
  // Mars' dust is forward-peaked (Mie g up to 0.83): the multiple-scattering tables need 32
  // cells in nu, or the forward peak is interpolated out to the ~20 degrees at which the
  // umbra at Phobos is lit (docs/eclipse-shadows.md).
  if (mars) o.tables.scatteringNu = 32;
  slot = eclipse::prepareEclipseAtmosphere(atm, mars ? "mars" : "earth", mars ? 2.2794e11 : 1.496e11, o);
  return *slot;
}

eclipse::LimbViewParams smallLimb() { return {64, 128, 8, 16}; }

glm::dvec3 rgbAt(const AtmosphericShadowModel& m, double distanceM, double offsetM,
                 const eclipse::LimbViewParams& limb = smallLimb()) {
  const std::vector<double> t = eclipse::illuminanceAt(m, eclipse::limbPositionBehind(m, distanceM, offsetM), limb).total();
  return eclipse::rgbOfSpectralRatio(m.rays.wavelengthsNm, t.data());
}

double umbraRadiusM(const AtmosphericShadowModel& m, double distanceM) {
  return eclipse::shadowConeRadii(m.system, distanceM).umbraRadiusM;
}

} // namespace

TEST(AtmosphericShadow, TerrainIsLinearBetweenZeroAndTwiceTheMeanElevation) {
  const eclipse::TerrainModel earth = eclipse::defaultTerrain("earth");
  EXPECT_DOUBLE_EQ(earth.meanElevationM, 240.0);
  EXPECT_DOUBLE_EQ(earth.transmission(-10.0), 0.0);
  EXPECT_DOUBLE_EQ(earth.transmission(120.0), 0.25);
  EXPECT_DOUBLE_EQ(earth.transmission(240.0), 0.5);
  EXPECT_DOUBLE_EQ(earth.transmission(480.0), 1.0);
  const eclipse::TerrainModel flat = eclipse::defaultTerrain("mars");
  EXPECT_DOUBLE_EQ(flat.transmission(-1e-3), 0.0);
  EXPECT_DOUBLE_EQ(flat.transmission(0.0), 1.0);
}

TEST(AtmosphericShadow, SpectralRatioToRgbPicksTheRgbWavelengths) {
  const std::vector<double> rgbNm = atmosphere::WavelengthSet::rgb().nm;
  const double r[3] = {0.3, 0.2, 0.1};
  const glm::dvec3 c = eclipse::rgbOfSpectralRatio(rgbNm, r);
  EXPECT_DOUBLE_EQ(c.r, 0.3);
  EXPECT_DOUBLE_EQ(c.g, 0.2);
  EXPECT_DOUBLE_EQ(c.b, 0.1);
  const std::vector<double> ascending = {400.0, 500.0, 600.0, 700.0};
  const double lin[4] = {4.0, 5.0, 6.0, 7.0};  // ratio = lambda / 100
  const glm::dvec3 d = eclipse::rgbOfSpectralRatio(ascending, lin);
  EXPECT_NEAR(d.r, 6.8, 1e-12);
  EXPECT_NEAR(d.g, 5.5, 1e-12);
  EXPECT_NEAR(d.b, 4.4, 1e-12);
}

// Must show: with scattering and refraction off, the LuT is the airless LuT of r_atmo.
TEST(AtmosphericShadow, WithoutScatteringAndRefractionItIsTheAirlessLutOfTheAtmosphereRadius) {
  AtmosphericShadowModel m = body("earth").model;
  m.scattering = false;
  m.refractedSun = false;
  eclipse::AtmosphericShadowLutParams p;
  p.width = 12, p.height = 10;
  p.limb = smallLimb();
  const eclipse::ShadowLut lut = eclipse::buildAtmosphericShadowLut(m, p);
  ASSERT_EQ(lut.width, 12);
  double worst = 0.0;
  for (int j = 0; j < p.height; ++j)
    for (int i = 0; i < p.width; ++i) {
      const eclipse::LutCoords c{(i + 0.5) / p.width, (j + 0.5) / p.height};
      const eclipse::LimbPosition pos = eclipse::limbPosition(m, c);
      // The same point with the atmosphere's top as the occluder, Eq. 4.
      const eclipse::LutCoords ca = eclipse::lutCoords(
          {pos.sunAngularRadiusRad, pos.atmosphereAngularRadiusRad, pos.separationRad});
      const double airless = eclipse::airlessShadow(ca);
      const glm::dvec3 t = lut.texel(i, j);
      for (int q = 0; q < 3; ++q) worst = std::max(worst, std::abs(t[q] - airless));
    }
  EXPECT_LT(worst, 1e-5);
}

// A transparent, non-refracting shell: the Sun seen through the ring plus the direct light
// past r_atmo is the airless occluder of radius r_occ (checks the limb-view solid angles).
TEST(AtmosphericShadow, TransparentShellGivesTheAirlessOccluder) {
  AtmosphericShadowModel m = body("earth").model;
  m.rays = eclipse::transparentLimbProfile(m.system.occluderRadiusM, m.rays.atmosphereRadiusM, m.rays.wavelengthsNm);
  m.scattering = false;
  m.terrain = {};
  const eclipse::LimbViewParams limb{16, 1024, 1, 1};
  for (double u : {0.02, 0.2, 0.45, 0.6, 0.9})
    for (double v : {0.0, 0.3, 0.7, 0.9, 0.97}) {
      const eclipse::LimbPosition pos = eclipse::limbPosition(m, {u, v});
      const eclipse::Illuminance I = eclipse::illuminanceAt(m, pos, limb);
      const double airless = eclipse::airlessShadow(eclipse::lutCoordsOf(pos));
      EXPECT_NEAR(I.indirect[1] + I.direct, airless, 2e-4 + 1e-3 * airless) << "u " << u << " v " << v;
      EXPECT_DOUBLE_EQ(I.indirect[0], I.indirect[2]);
    }
}

// The shadow LuT is the sum over the limb view, pixel by pixel (the view is half the ring).
TEST(AtmosphericShadow, LimbViewSumsToTheIlluminance) {
  const AtmosphericShadowModel& m = body("earth").model;
  const eclipse::LimbViewParams limb{64, 128, 8, 16};
  for (double offset : {0.0, 3e6, 4.6e6}) {
    const eclipse::LimbPosition pos = eclipse::limbPositionBehind(m, kMoonDistanceM, offset);
    const eclipse::LimbView view = eclipse::renderLimbView(m, pos, limb);
    const eclipse::Illuminance I = eclipse::illuminanceAt(m, pos, limb);
    std::vector<double> sum(3, 0.0);
    // The view holds radiance; the illuminance also weighs by the cosine towards the Sun,
    // which is 1 - O(1e-4) here.
    for (int r = 0; r < view.rows; ++r)
      for (int c = 0; c < view.columns; ++c)
        for (int q = 0; q < 3; ++q) sum[q] += 2.0 * view.at(r, c, q) * view.solidAngleSr[r];
    for (int q = 0; q < 3; ++q) EXPECT_NEAR(sum[q], I.indirect[q], 1e-3 * I.indirect[q]) << offset << " " << q;
  }
}

// Must show: Earth's umbra at the Moon's mean distance is red-dominant and its centre
// between 1e-6 and 1e-2 of I_sun in red (Fig. 12 left).
TEST(AtmosphericShadow, EarthUmbraAtTheMoonIsRed) {
  const AtmosphericShadowModel& m = body("earth").model;
  const glm::dvec3 centre = rgbAt(m, kMoonDistanceM, 0.0);
  EXPECT_GT(centre.r, centre.g);
  EXPECT_GT(centre.g, centre.b);
  EXPECT_GT(centre.r, 1e-6);
  EXPECT_LT(centre.r, 1e-2);
  // The penumbra outside is far brighter and nearly grey.
  const double umbra = umbraRadiusM(m, kMoonDistanceM);
  const glm::dvec3 penumbra = rgbAt(m, kMoonDistanceM, umbra + 2.5e6);
  EXPECT_GT(penumbra.g, 100 * centre.g);
  EXPECT_NEAR(penumbra.b / penumbra.r, 1.0, 0.1);
}

// Must show: the Calbuco preset (three times the stratospheric sulphate) darkens the umbra
// against the atmosphere it is made from (earth), less than four times the sulphate does
// (earth-volcanic): the stratosphere's extinction along the grazing rays, monotonic.
TEST(AtmosphericShadow, CalbucoDarkensTheUmbra) {
  const glm::dvec3 clear = rgbAt(body("earth").model, kMoonDistanceM, 0.0);
  const glm::dvec3 calbuco = rgbAt(body("earth-2015-calbuco").model, kMoonDistanceM, 0.0);
  const glm::dvec3 volcanic = rgbAt(body("earth-volcanic").model, kMoonDistanceM, 0.0);
  EXPECT_LT(calbuco.r, 0.95 * clear.r);
  EXPECT_LT(colour::luminance(calbuco), 0.95 * colour::luminance(clear));
  EXPECT_GT(colour::luminance(calbuco), colour::luminance(volcanic));
}

// Must show: ozone absorbs green-orange (Chappuis band) and leaves blue: with ozone the
// umbra is less green relative to red, and its rim bluer (Fig. 13: the turquoise fringe).
TEST(AtmosphericShadow, OzoneChangesTheUmbraColour) {
  const std::string none = R"({"extends": "earth", "name": "no-ozone", "components": {"ozone": null}})";
  const std::string peak6 = R"({"extends": "earth", "name": "ozone-6e18",
      "components": {"ozone": {"optics": {"numberDensityPerM3": 6e18}}}})";
  const AtmosphericShadowModel& mNone = body("earth", none).model;
  const AtmosphericShadowModel& mDef = body("earth").model;
  const AtmosphericShadowModel& m6 = body("earth", peak6).model;
  const double rim = 0.9 * umbraRadiusM(mDef, kMoonDistanceM);
  const glm::dvec3 cNone = rgbAt(mNone, kMoonDistanceM, 0.0), cDef = rgbAt(mDef, kMoonDistanceM, 0.0),
                   c6 = rgbAt(m6, kMoonDistanceM, 0.0);
  const glm::dvec3 rNone = rgbAt(mNone, kMoonDistanceM, rim), rDef = rgbAt(mDef, kMoonDistanceM, rim),
                   r6 = rgbAt(m6, kMoonDistanceM, rim);
  EXPECT_GT(cNone.g / cNone.r, cDef.g / cDef.r);
  EXPECT_GT(cDef.g / cDef.r, c6.g / c6.r);
  EXPECT_LT(rNone.b / rNone.g, rDef.b / rDef.g);
  EXPECT_LT(rDef.b / rDef.g, r6.b / r6.g);
  EXPECT_GT(cNone.r, cDef.r);  // ozone absorbs some red too
}

// Must show: Mars' shadow at Phobos' and Deimos' distances is red in most of the shadow,
// grey near the penumbra's outer boundary (Fig. 12 right). Inside the umbra the light is
// the dust's scattering in the air that the Sun still reaches, seen through the limb:
// from Phobos only air high on the far side of the limb (the rays' entry points have the
// Sun 112-124 degrees from the zenith), 1e-9 to 1e-4 of I_sun from the axis to the
// umbra's edge; from Deimos the upper limb itself. R > G > B over the inner part of the
// umbra (at Phobos most of it, at Deimos its inner 40 %); towards the umbra's edge the
// view reaches the dust's diffraction peak and turns bluish (docs/eclipse-shadows.md).
TEST(AtmosphericShadow, MarsShadowAtPhobosAndDeimosIsRedThenGrey) {
  const AtmosphericShadowModel& m = body("mars").model;
  for (const double distanceM : {kPhobosDistanceM, kDeimosDistanceM}) {
    const eclipse::ShadowConeRadii cone = eclipse::shadowConeRadii(m.system, distanceM);
    const int n = 10;
    int red = 0;
    for (int k = 0; k < n; ++k) {
      const glm::dvec3 c = rgbAt(m, distanceM, cone.umbraRadiusM * k / n);
      std::printf("  Mars at %.0f km, %.1f umbra radii: rgb %.3e %.3e %.3e  R/B %.2f G/B %.2f\n", distanceM / 1e3,
                  double(k) / n, c.r, c.g, c.b, c.r / c.b, c.g / c.b);
      ASSERT_TRUE(std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b));
      if (c.r > 1.02 * c.g && c.g > 1.02 * c.b) ++red;
      if (k <= 4) {
        EXPECT_GT(c.r, 1.1 * c.b) << distanceM << " " << k;  // the inner half is red
      }
    }
    EXPECT_GE(red, distanceM == kPhobosDistanceM ? 7 : 4) << distanceM;
    // At the penumbra's outer boundary the Sun is seen through the thin upper atmosphere:
    // nearly grey, and far brighter than the umbra.
    const glm::dvec3 edge = rgbAt(m, distanceM, 0.999 * cone.penumbraRadiusM);
    EXPECT_NEAR(edge.b / edge.r, 1.0, 0.1) << distanceM;
    EXPECT_NEAR(edge.g / edge.r, 1.0, 0.1) << distanceM;
    EXPECT_GT(edge.r, 100 * rgbAt(m, distanceM, 0.0).r) << distanceM;
  }
}

// Mars' dust needs 32 nu cells (the test above; docs/eclipse-shadows.md): the default for
// Mars whatever the case of its name; other bodies keep the caller's value.
TEST(AtmosphericShadow, MarsDefaultsTo32NuCells) {
  EXPECT_EQ(eclipse::defaultScatteringNu("Mars", 8), 32);
  EXPECT_EQ(eclipse::defaultScatteringNu("mars", 4), 32);
  EXPECT_EQ(eclipse::defaultScatteringNu("Earth", 8), 8);
  EXPECT_EQ(eclipse::defaultScatteringNu("earth", 4), 4);
}

// Must show: positions at the occluder's surface (u -> 0) and far beyond the umbra (u -> 1).
TEST(AtmosphericShadow, EndsOfTheLutAreFiniteAndSensible) {
  const AtmosphericShadowModel& m = body("earth").model;
  for (double v : {0.0, 0.5, 0.999}) {
    const glm::dvec3 nearSurface = [&] {
      const std::vector<double> t = eclipse::illuminanceAt(m, eclipse::limbPosition(m, {1e-9, v}), smallLimb()).total();
      return eclipse::rgbOfSpectralRatio(m.rays.wavelengthsNm, t.data());
    }();
    for (int q = 0; q < 3; ++q) {
      EXPECT_TRUE(std::isfinite(nearSurface[q]));
      EXPECT_GE(nearSurface[q], 0.0);
      EXPECT_LT(nearSurface[q], 1.0);
    }
    // Far away the occluder is a speck in front of the Sun: almost all light arrives.
    const eclipse::LimbPosition far = eclipse::limbPosition(m, {1.0 - 1e-9, v});
    const std::vector<double> t = eclipse::illuminanceAt(m, far, smallLimb()).total();
    for (double x : t) {
      EXPECT_TRUE(std::isfinite(x));
      EXPECT_GT(x, 0.99);
      EXPECT_LE(x, 1.0 + 1e-6);
    }
  }
}

// Must show: no NaN anywhere, in either table, at any preset.
TEST(AtmosphericShadow, TablesAreFiniteAtEveryPreset) {
  for (const std::string preset : {"earth", "earth-2015-calbuco", "mars"}) {
    const AtmosphericShadowModel& m = body(preset).model;
    eclipse::AtmosphericShadowLutParams sp;
    sp.width = 10, sp.height = 8;
    sp.limb = smallLimb();
    const eclipse::ShadowLut s = eclipse::buildAtmosphericShadowLut(m, sp);
    ASSERT_EQ(s.rgb.size(), 10u * 8u * 3u);
    for (float x : s.rgb) {
      ASSERT_TRUE(std::isfinite(x)) << preset;
      ASSERT_GE(x, 0.0f) << preset;
      ASSERT_LE(x, 1.0f + 1e-5f) << preset;
    }
    eclipse::LimbLuminanceLutParams lp;
    lp.width = 6, lp.height = 5, lp.columns = 8, lp.layers = 2;
    lp.limb = {8, 32, 4, 8};
    const eclipse::LimbLuminanceLut l = eclipse::buildLimbLuminanceLut(m, lp);
    ASSERT_EQ(l.depth(), 16);
    ASSERT_EQ(l.rgb.size(), 6u * 5u * 16u * 3u);
    float brightest = 0.0f;
    for (float x : l.rgb) {
      ASSERT_TRUE(std::isfinite(x)) << preset;
      ASSERT_GE(x, 0.0f) << preset;
      brightest = std::max(brightest, x);
    }
    EXPECT_GT(brightest, 0.0f) << preset;
  }
}

// The limb-luminance LuT is the limb view averaged over each layer's rows by solid angle.
TEST(AtmosphericShadow, LimbLuminanceIsTheLayerAverageOfTheLimbView) {
  const AtmosphericShadowModel& m = body("earth").model;
  eclipse::LimbLuminanceLutParams lp;
  lp.width = 4, lp.height = 4, lp.columns = 8, lp.layers = 2;
  lp.limb = {8, 32, 4, 8};
  const eclipse::LimbLuminanceLut l = eclipse::buildLimbLuminanceLut(m, lp);
  const int i = 2, j = 1;
  const eclipse::LimbView view = eclipse::renderLimbView(m, eclipse::limbPosition(m, {(i + 0.5) / 4, (j + 0.5) / 4}), lp.limb);
  for (int layer = 0; layer < 2; ++layer)
    for (int col = 0; col < 8; ++col) {
      double s = 0.0, w = 0.0;
      for (int r = layer * 16; r < (layer + 1) * 16; ++r) s += view.at(r, col, 0) * view.solidAngleSr[r], w += view.solidAngleSr[r];
      EXPECT_NEAR(l.texel(i, j, layer * 8 + col).r, s / w, 1e-6 * s / w + 1e-30);
    }
}

// Single beta columns of the limb-luminance LuT converge with the limb-view rows. Halfway to
// the umbra's edge at the Moon, the far side of the ring sees the Sun through rays ~1-3 km up
// whose deviation changes by a good part of the Sun's diameter within one row of 256: a
// row's point sample either hits or misses the Sun's image at a given beta, and columns were
// off by 10-15 % (docs/accuracy-vs-speed/eclipse-luts.md, "Single columns of the limb ring"). Integrated
// by sub-rows (1/128 of the Sun's diameter each, the default), each column of a 256-row view
// (the LuT's default) is within 3 % of a 4096-row view with four times finer sub-rows: the
// sub-rows' midpoint rule is off by at most half a sub-row at each edge of the Sun's image
// (the limb-darkened disc's edge is a step to 0.4 of its centre), ~1 % for a column whose
// image spans a few sub-rows; measured 0.2-1 % with the default tables. The bound is
// checked to fail for the old point samples (subRowsPerSunDiameter 0).
TEST(AtmosphericShadow, LimbLuminanceColumnsConvergeWithTheRows) {
  const AtmosphericShadowModel& m = body("earth").model;
  auto columns = [&](const eclipse::LimbPosition& p, int rows, double sub) {
    eclipse::LimbViewParams limb{32, rows, 4, 4};
    limb.subRowsPerSunDiameter = sub;
    return eclipse::layerAverages(eclipse::renderLimbView(m, p, limb), 1);
  };
  const double defaultSub = eclipse::LimbViewParams{}.subRowsPerSunDiameter;
  double worstDefault = 0.0, worstPoint = 0.0;
  for (double f : {0.25, 0.5, 0.75}) {
    const eclipse::LimbPosition p = eclipse::limbPositionBehind(m, kMoonDistanceM, f * umbraRadiusM(m, kMoonDistanceM));
    const std::vector<double> ref = columns(p, 4096, 4.0 * defaultSub);
    const std::vector<double> v = columns(p, 256, defaultSub), point = columns(p, 256, 0.0);
    for (int c = 0; c < 3; ++c) {
      double top = 0.0;
      for (int col = 0; col < 32; ++col) top = std::max(top, ref[col * 3 + c]);
      for (int col = 0; col < 32; ++col) {
        const double r = ref[col * 3 + c];
        ASSERT_TRUE(std::isfinite(v[col * 3 + c])) << f << " " << col;
        if (r < 0.01 * top) continue;  // the dark ends of the Sun's image
        const double e = std::abs(v[col * 3 + c] / r - 1.0);
        EXPECT_LT(e, 0.03) << "offset " << f << " column " << col << " channel " << c;
        worstDefault = std::max(worstDefault, e);
        worstPoint = std::max(worstPoint, std::abs(point[col * 3 + c] / r - 1.0));
      }
    }
  }
  std::printf("largest column error, 256 rows: sub-rows %.3g, point samples %.3g\n", worstDefault, worstPoint);
  EXPECT_GT(worstPoint, 0.03);  // the check sees the old point sampling's error
}

// A requested extent computes exactly those texels of the full table.
TEST(AtmosphericShadow, ExtentComputesThatPartOfTheLut) {
  const AtmosphericShadowModel& m = body("earth").model;
  eclipse::AtmosphericShadowLutParams p;
  p.width = 8, p.height = 6;
  p.limb = smallLimb();
  const eclipse::ShadowLut full = eclipse::buildAtmosphericShadowLut(m, p);
  const eclipse::ShadowLut part = eclipse::buildAtmosphericShadowLut(m, p, {3, 6, 1, 5});
  ASSERT_EQ(part.width, 3);
  ASSERT_EQ(part.height, 4);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 3; ++i) EXPECT_EQ(part.texel(i, j), full.texel(3 + i, 1 + j));
  EXPECT_THROW(eclipse::buildAtmosphericShadowLut(m, p, {0, 9, 0, 2}), std::invalid_argument);
  int calls = 0;
  const eclipse::ShadowLut cancelled = eclipse::buildAtmosphericShadowLut(m, p, {}, [&](double) { return ++calls < 0; });
  EXPECT_TRUE(cancelled.rgb.empty());
}

// Near the occluder the shadow crowds into a corner of (u, v) (docs/eclipse-shadows.md): a
// 64^2 LuT over u, v in [0, 1] misses Mars' penumbra at Phobos; one over the ranges of
// Phobos' distances (eclipse::lutRangeForDistances: u range, v split at the umbra's edge
// with a quarter of the rows inside) resolves it. The same arcs as the
// airless test: nearest, mean and farthest distance, axis to 1.1 x the penumbra.
TEST(AtmosphericShadow, RangedLutResolvesMarsShadowAtPhobos) {
  const AtmosphericShadowModel& m = body("mars").model;
  const double radiusM = 11.1e3;
  eclipse::AtmosphericShadowLutParams whole;
  whole.width = whole.height = 64;
  whole.limb = smallLimb();
  eclipse::AtmosphericShadowLutParams ranged = whole, uOnly = whole;
  const eclipse::LutRange r =
      eclipse::lutRangeForDistances(m.system, kPhobosDistanceM - radiusM, kPhobosDistanceM + radiusM, false, 64);
  ASSERT_GT(r.vLowFraction, 0.0);  // the umbra's inside keeps rows of its own
  ranged.uMin = uOnly.uMin = r.uMin, ranged.uMax = uOnly.uMax = r.uMax;
  ranged.vMin = r.vMin, ranged.vLowFraction = r.vLowFraction;
  const eclipse::ShadowLut lutWhole = eclipse::buildAtmosphericShadowLut(m, whole);
  const eclipse::ShadowLut lutU = eclipse::buildAtmosphericShadowLut(m, uOnly);
  const eclipse::ShadowLut lutRanged = eclipse::buildAtmosphericShadowLut(m, ranged);
  double err[3] = {0, 0, 0}, umbraErr = 0.0;
  for (double d : {kPhobosDistanceM - radiusM, kPhobosDistanceM, kPhobosDistanceM + radiusM}) {
    const double maxAngle = 1.1 * std::asin(eclipse::shadowConeRadii(m.system, d).penumbraRadiusM / d);
    for (int k = 0; k <= 400; ++k) {
      const double a = maxAngle * k / 400;
      const eclipse::LimbPosition p = eclipse::limbPositionBehind(m, d * std::cos(a), d * std::sin(a));
      const eclipse::LutCoords c = eclipse::lutCoordsOf(p);
      if (c.v >= 1.0) continue;  // the LuT ends at v = 1
      const std::vector<double> t = eclipse::illuminanceAt(m, p, smallLimb()).total();
      const double exact = colour::luminance(eclipse::rgbOfSpectralRatio(m.rays.wavelengthsNm, t.data()));
      const eclipse::ShadowLut* luts[3] = {&lutWhole, &lutU, &lutRanged};
      for (int q = 0; q < 3; ++q) err[q] = std::max(err[q], std::abs(colour::luminance(luts[q]->sample(c)) - exact));
      if (c.v < r.vMin) umbraErr = std::max(umbraErr, std::abs(colour::luminance(lutRanged.sample(c)) - exact));
    }
  }
  std::printf("  Mars' atmosphere at Phobos, 64^2: max |LuT - exact| %.3g whole, %.3g u range only, %.3g u range "
              "and v split at %.6g (inside the umbra: %.3g)\n", err[0], err[1], err[2], r.vMin, umbraErr);
  EXPECT_LT(err[2], 1e-3);
  EXPECT_LT(err[2], err[0] / 10.0);
}

// The transmittance through the periapsis (eclipse::refractedTransmittanceToTop, the render
// pass's umbraRefractedTransmittanceToTop) for straight rays (contact = impact parameter -
// ground) against the optical depth integrated along the chord (Simpson, 20 000 intervals),
// and the tables' own lookup of the descending ray (Bruneton's T(r, mu) below the horizon,
// the render pass's old path) against the same. Small tables (64 x 16): the periapsis' row
// is finer near the ground than the top row's columns are across the limb. Bruneton's
// smooth haze (earth-bruneton): the default sky's mixing-layer top, blended over 1.75-2.25 km,
// puts the periapsis at 2 km 22 % off with these small tables.
TEST(AtmosphericShadow, TransmittanceThroughThePeriapsisMatchesTheStraightChord) {
  const std::vector<double> nm = atmosphere::WavelengthSet::rgb().nm;
  const atmosphere::Atmosphere atm = atmosphere::loadAtmosphere("earth-bruneton", nm);
  eclipse::EclipseAtmosphereOptions o;
  o.tables = test::smallPrecomputeOptions();
  o.tables.orders = 1;
  o.tables.refraction = false;
  o.refraction = false;
  o.refractionWidth = 8, o.refractionHeight = 8;
  const auto e = eclipse::prepareEclipseAtmosphere(atm, "earth", 1.496e11, o);
  const atmosphere::AtmosphereTables& t = e->tables;
  const double bottom = t.bottomRadiusM, top = t.topRadiusM;
  double worstThrough = 0.0, worstDescending = 0.0;
  for (const double r : {top, bottom + 40e3, bottom + 15e3})
    for (const double periapsisAltitudeM : {2e3, 5e3, 10e3}) {
      const double b = bottom + periapsisAltitudeM;
      if (b >= r) continue;
      const double mu = -std::sqrt(1.0 - (b / r) * (b / r));
      // The chord from r down through the periapsis and up to the top.
      const double length = -r * mu + std::sqrt(top * top - b * b);
      const int n = 20000;
      std::vector<double> depth(3, 0.0);
      for (int k = 0; k <= n; ++k) {
        const double sM = length * k / n;
        const double w = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
        const std::vector<double> ext = atm.extinctionPerM(std::sqrt(r * r + sM * sM + 2.0 * r * mu * sM) - bottom);
        for (int c = 0; c < 3; ++c) depth[c] += w * ext[c] * length / n / 3.0;
      }
      double through[3], descending[3];
      eclipse::refractedTransmittanceToTop(t, r, mu, periapsisAltitudeM, through);
      atmosphere::transmittanceToTop(t, r, mu, descending);
      for (int c = 0; c < 3; ++c) {
        worstThrough = std::max(worstThrough, std::abs(-std::log(through[c]) / depth[c] - 1.0));
        worstDescending = std::max(worstDescending, std::abs(-std::log(descending[c]) / depth[c] - 1.0));
      }
    }
  std::printf("  optical depth, largest relative difference from the chord's: through the periapsis %.3g, "
              "descending lookup %.3g\n",
              worstThrough, worstDescending);
  EXPECT_LT(worstThrough, 0.03);  // measured 0.0165 (the descending lookup: 0.107)
  // Rising rays: the table's T(r, mu); below the ground: 0.
  double up[3], ref[3], ground[3];
  eclipse::refractedTransmittanceToTop(t, bottom + 1e3, 0.3, 999.0, up);
  atmosphere::transmittanceToTop(t, bottom + 1e3, 0.3, ref);
  eclipse::refractedTransmittanceToTop(t, top, -0.2, -10.0, ground);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(up[c], ref[c]);
    EXPECT_EQ(ground[c], 0.0);
  }
}

// A cloud deck on the limb: the rays whose lowest point lies under the tops keep 1 - cover
// of their light, the others all of it; and the umbra's centre, lit by rays grazing a few
// km up, darkens by at most -2.5 log10(1 - cover).
TEST(AtmosphericShadow, CloudsScreenTheLowRays) {
  eclipse::LimbRayProfile rays = eclipse::transparentLimbProfile(6371e3, 6471e3, {680.0, 550.0, 440.0});
  ASSERT_EQ(rays.samples(), 2);  // contacts 0 and 100 km
  eclipse::screenByClouds(rays, 10e3, 0.4);
  for (int c = 0; c < 3; ++c) {
    EXPECT_DOUBLE_EQ(rays.transmittance[c], 0.6);
    EXPECT_DOUBLE_EQ(rays.transmittance[3 + c], 1.0);
  }
  EXPECT_THROW(eclipse::screenByClouds(rays, -1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(eclipse::screenByClouds(rays, 10e3, 1.5), std::invalid_argument);

  eclipse::AtmosphericShadowModel clear = body("earth").model, cloudy = clear;
  eclipse::screenByClouds(cloudy.rays, 10e3, 0.5);
  const double ratio = colour::luminance(rgbAt(cloudy, kMoonDistanceM, 0.0)) / colour::luminance(rgbAt(clear, kMoonDistanceM, 0.0));
  EXPECT_LT(ratio, 0.95);
  EXPECT_GE(ratio, 0.5 - 1e-9);
}
