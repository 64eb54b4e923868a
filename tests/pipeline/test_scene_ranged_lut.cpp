// The scene path asks for ranged eclipse LuTs by itself (AtmosphereShadow: sceneLutRange,
// applySceneAtmosphereShadow): Phobos by Mars, where a whole LuT gives Mars' penumbra only
// 2u = 1.6 % of its rows. The two example scenes (examples/scenes/phobos-in-mars-shadow.json,
// phobos-in-mars-umbra-atmosphere.json) rendered with small tables: the shading on Phobos
// (GPU factor = radiance / unshadowed radiance) against the CPU's exact factor at the same
// points (no LuT: eclipse::eclipseFactor without a table; through the atmosphere
// illuminanceAt with the LuT's limb views). The ranged LuT is within the bound, the whole
// LuT of the same size is not (both asserted).
#include "AtmosphereShadow.h"
#include "RenderTestSupport.hpp"
#include "SceneInputs.h"

#include "AtmosphericShadow.hpp"
#include "EclipseAtmosphere.hpp"
#include "ShadowLutData.h"
#include "scene/Scene.hpp"
#include "scene/Time.hpp"
#include "vtkEclipseShadowLutSource.h"
#include "vtkLimbLuminanceSource.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

using namespace umbra::pipeline;  // the scene glue (app/pipeline)

using namespace umbra;
using namespace umbra::render;
using namespace umbra::render::test;

namespace {

constexpr int kSize = 64;  // the LuTs' rows (and the whole LuTs' columns)
constexpr int kImage = 96;

// The scene's bodies with Lambert's law: the tests read the shadow as the GPU's radiance
// over Lambert's unshadowed one (the photometry itself: test_moon_render.cpp).
SceneInputs loadPhobosScene(const std::string& file) {
  const scene::Scene s = scene::loadScene(UMBRA_SOURCE_DIR "/examples/scenes/" + file);
  SceneInputs in = sceneInputs(s);
  for (SphereBody& b : in.bodies) b.photometry = {};
  return in;
}

const SphereBody& body(const SceneInputs& in, const std::string& name) {
  return *std::find_if(in.bodies.begin(), in.bodies.end(), [&](const SphereBody& b) { return b.name == name; });
}

// Phobos' shading in a rendered view: per sampled pixel (facing the camera and the Sun) the
// GPU's factor per channel and `exact`'s; the largest |GPU - exact| (absolute, or relative
// to exact with `relative`).
struct Agreement {
  int samples = 0, shadowed = 0;
  double maxDiff = 0.0;
};
Agreement compare(const SceneInputs& in, const std::vector<float>& hdr, int w, int h,
                  const std::function<glm::dvec3(const glm::dvec3&)>& exact, bool relative) {
  const SphereBody& phobos = body(in, "Phobos");
  Agreement a;
  for (int j = 1; j < h; j += 3)
    for (int i = 1; i < w; i += 3) {
      const Ray ray = pixelRay(in.camera, w, h, i, j);
      const auto hit = hitSphere(ray, phobos.centreM, phobos.radiusM);
      if (!hit) continue;
      if (-glm::dot(glm::normalize(*hit - phobos.centreM), ray.dir) < 0.3) continue;
      double cosi = 0.0;
      const double unshadowed = unshadowedRadiance(*hit, phobos.centreM, 1.0, in.sun, &cosi);  // x albedo
      if (cosi < 0.1) continue;
      const glm::dvec3 e = exact(*hit);
      ++a.samples;
      if (e.g < 0.99) ++a.shadowed;
      for (int c = 0; c < 3; ++c) {
        const double gpu = hdr[3 * (static_cast<std::size_t>(j) * w + i) + c] / (phobos.albedoRgb[c] * unshadowed);
        const double d = std::abs(gpu - e[c]) / (relative ? std::max(e[c], 1e-9) : 1.0);
        EXPECT_TRUE(std::isfinite(gpu)) << "pixel " << i << ", " << j;
        a.maxDiff = std::max(a.maxDiff, d);
      }
    }
  return a;
}

std::vector<float> renderPhobos(const SceneInputs& in, vtkImageData* airless,
                                const std::function<void(EclipseShading&)>& atmosphere = {}) {
  BodyView view(kImage, kImage * 3 / 4, true);
  useSharedDisplay(view.GetRenderWindow());
  view.SetBodies(in.sun, in.bodies, airless);
  if (atmosphere) atmosphere(view.GetShading());
  return renderHdr(view, in.camera);
}

vtkSmartPointer<vtkImageData> airlessLut(const std::optional<eclipse::LutRange>& range) {
  vtkNew<vtkEclipseShadowLutSource> s;
  s->UseCacheOff();
  s->SetHeight(kSize);
  s->SetWidth(range ? rangedLutWidth(*range, kSize) : kSize);
  if (range) s->SetLutRange(*range);
  s->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(s->GetOutput());
  return out;
}

} // namespace

// Who can be in whose penumbra, and the ranges the scene asks for.
TEST(SceneRangedLut, RangesCoverPhobosOnly) {
  const SceneInputs in = loadPhobosScene("phobos-in-mars-shadow.json");
  const SphereBody &mars = body(in, "Mars"), &phobos = body(in, "Phobos");
  EXPECT_TRUE(canBeInPenumbra(in.sun, mars, phobos));
  EXPECT_FALSE(canBeInPenumbra(in.sun, phobos, mars));  // Phobos' shadow points away from Mars
  const auto r = sceneLutRange(in.sun, in.bodies, in.bodies, true, kSize);
  ASSERT_TRUE(r);
  // Every point of Phobos has u (Eq. 4) inside the range.
  for (const double dx : {-phobos.radiusM, phobos.radiusM}) {
    const glm::dvec3 p = phobos.centreM + glm::dvec3(dx, 0.0, 0.0);
    const eclipse::LutCoords c =
        eclipse::lutCoords(eclipse::shadowAngles(p, in.sun.positionM, in.sun.radiusM, mars.centreM, mars.radiusM));
    EXPECT_GE(c.u, r->uMin);
    EXPECT_LE(c.u, r->uMax);
  }
  EXPECT_LT(r->uMax - r->uMin, 1e-4);
  EXPECT_GT(r->vMin, 0.95);  // the umbra's edge 1 - 2u
  EXPECT_EQ(rangedLutWidth(*r, kSize), 2);
  // The Moon in Earth's shadow: a whole 256-row LuT resolves it (no range), a 32-row one not.
  SunLight sun;
  sun.positionM = {-kAu, 0.0, 0.0};
  const SphereBody earth{"Earth", {0.0, 0.0, 0.0}, 6.371e6, {0.3, 0.3, 0.3}};
  const SphereBody moon{"Moon", {kMoonDistance, 0.0, 0.0}, 1.7374e6, {0.12, 0.12, 0.12}};
  EXPECT_FALSE(sceneLutRange(sun, {earth}, {moon}, true, 256));
  EXPECT_TRUE(sceneLutRange(sun, {earth}, {moon}, true, 32));
}

// Airless: Phobos across the umbra's edge. Ranged 64-row LuT (2 columns) vs whole 64².
TEST(SceneRangedLut, AirlessPhobosMatchesTheExactFactor) {
  const SceneInputs in = loadPhobosScene("phobos-in-mars-shadow.json");
  const SphereBody& mars = body(in, "Mars");
  const auto range = sceneLutRange(in.sun, in.bodies, in.bodies, true, kSize);
  ASSERT_TRUE(range);
  const eclipse::Occluder occ{mars.centreM, mars.radiusM};
  const auto exact = [&](const glm::dvec3& p) {
    return eclipse::eclipseFactor(p, in.sun.positionM, in.sun.radiusM, occ, nullptr);
  };
  const int w = kImage, h = kImage * 3 / 4;
  const Agreement ranged = compare(in, renderPhobos(in, airlessLut(range)), w, h, exact, false);
  const Agreement whole = compare(in, renderPhobos(in, airlessLut(std::nullopt)), w, h, exact, false);
  std::printf("  %d samples (%d shadowed); max |GPU - exact| of I/I_sun: ranged %.3g, whole %.3g\n", ranged.samples,
              ranged.shadowed, ranged.maxDiff, whole.maxDiff);
  RecordProperty("ranged_max_abs", std::to_string(ranged.maxDiff));
  RecordProperty("whole_max_abs", std::to_string(whole.maxDiff));
  EXPECT_GE(ranged.samples, 200);
  EXPECT_GE(ranged.shadowed, 50);
  constexpr double kBound = 5e-3;
  EXPECT_LT(ranged.maxDiff, kBound);
  EXPECT_GT(whole.maxDiff, kBound);
}

// Through Mars' atmosphere: Phobos 1500 km off the axis in the umbra, lit by the
// atmosphere's ring. The scene path (applySceneAtmosphereShadow, small tables: 64 x 32,
// limb views of 32 rows) ranges the table itself; the whole table's columns (the path
// before) for comparison. Relative differences: the umbra there is 1e-5 to 1e-4 of I_sun
// and falls steeply towards the axis (x 10 in a tenth of the umbra's radius), which the
// ranged table's 32 rows follow within a few per cent; the whole table's rows do not.
TEST(SceneRangedLut, AtmospherePhobosMatchesTheExactFactor) {
  const SceneInputs in = loadPhobosScene("phobos-in-mars-umbra-atmosphere.json");
  ASSERT_TRUE(in.atmosphere);
  const SphereBody &mars = body(in, "Mars"), &phobos = body(in, "Phobos");
  vtkNew<vtkEclipseShadowLutSource> source;
  useSmallEclipseShadowTables(source);
  source->UseCacheOff();
  const int width = source->GetWidth();

  vtkSmartPointer<vtkImageData> ranged;
  const std::vector<float> rangedHdr = renderPhobos(in, testLutImage(), [&](EclipseShading& shading) {
    applySceneAtmosphereShadow(shading, in, source);
    ranged = vtkSmartPointer<vtkImageData>::New();
    ranged->DeepCopy(source->GetOutput());
  });
  EXPECT_EQ(source->GetWidth(), width);  // given back
  const eclipse::LutRange r = filters::lutRangeOf(filters::fieldParameters(ranged), "ranged LuT");
  int dims[3];
  ranged->GetDimensions(dims);
  std::printf("  ranged table %dx%d: u %.6f..%.6f, v %.4f..%.4f (low fraction %.2f)\n", dims[0], dims[1], r.uMin,
              r.uMax, r.vMin, r.vMax, r.vLowFraction);
  EXPECT_GT(r.uMin, 0.0);
  EXPECT_GT(r.vLowFraction, 0.0);
  EXPECT_EQ(dims[0], 2);

  // The whole table's columns around Phobos (as before: ranges [0, 1]).
  const auto cols = shadowLutColumns(in.sun, mars, phobos, width);
  source->SetLutRange({});
  const int extent[6] = {cols[0], std::max(cols[1], cols[0] + 1), 0, source->GetHeight() - 1, 0, 0};
  source->UpdateExtent(extent);
  vtkNew<vtkImageData> whole;
  whole->DeepCopy(source->GetOutput());
  const std::vector<float> wholeHdr =
      renderPhobos(in, testLutImage(), [&](EclipseShading& shading) { shading.SetAtmosphereShadowLut("Mars", whole); });

  const auto prepared = source->GetPreparedAtmosphere();
  const eclipse::AtmosphericShadowModel& model = prepared->model;
  const eclipse::LimbViewParams limb{source->GetLimbSize(), source->GetLimbSize(), source->GetScatteringCells(),
                                     source->GetScatteringCells()};
  const auto exact = [&](const glm::dvec3& p) {
    const eclipse::LutCoords c =
        eclipse::lutCoords(eclipse::shadowAngles(p, in.sun.positionM, in.sun.radiusM, mars.centreM, mars.radiusM));
    const std::vector<double> t = eclipse::illuminanceAt(model, eclipse::limbPosition(model, c), limb).total();
    return eclipse::rgbOfSpectralRatio(model.rays.wavelengthsNm, t.data());
  };
  const int w = kImage, h = kImage * 3 / 4;
  const Agreement a = compare(in, rangedHdr, w, h, exact, true);
  const Agreement b = compare(in, wholeHdr, w, h, exact, true);
  std::printf("  %d samples (%d shadowed); max relative |GPU - exact|: ranged %.3g, whole %.3g\n", a.samples,
              a.shadowed, a.maxDiff, b.maxDiff);
  RecordProperty("ranged_max_rel", std::to_string(a.maxDiff));
  RecordProperty("whole_max_rel", std::to_string(b.maxDiff));
  EXPECT_GE(a.samples, 200);
  EXPECT_EQ(a.shadowed, a.samples);  // all in the umbra
  constexpr double kBound = 0.05;
  EXPECT_LT(a.maxDiff, kBound);
  EXPECT_GT(b.maxDiff, kBound);
}

// Tables of a scene in motion are asked for on grids (AtmosphereShadow: the Sun's
// distance, relative step 1e-4; the ends of a u range, relative step 1e-3), so that the
// frames of a while share one table. The grid's point is within half a step of the
// distance and maps to itself; a distance 2e-5 off it maps to it.
TEST(SceneRangedLut, SunDistanceOnTheGrid) {
  for (const double d : {1.0e9, kAu, 2.279e11, 4.5e12}) {
    const double g = sunDistanceOnGrid(d);
    EXPECT_LE(std::abs(g / d - 1.0), 0.5e-4 * (1.0 + 1e-9)) << d;
    EXPECT_EQ(sunDistanceOnGrid(g), g) << d;
    EXPECT_EQ(sunDistanceOnGrid(g * (1.0 + 2e-5)), g) << d;
    EXPECT_EQ(sunDistanceOnGrid(g * (1.0 - 2e-5)), g) << d;
    EXPECT_NE(sunDistanceOnGrid(g * (1.0 + 1.2e-4)), g) << d;  // the next point
  }
}

// The 2015-09-28 eclipse seen from the lunar north pole, 02:00 to 02:50 UTC: the camera's
// distance from Earth changes by a few km (the Moon at perigee, 01:46), the Sun's by
// ~1500 km; every frame asks for the same limb-luminance LuT (one table, one cache file;
// before the grids, one per frame): the whole 64-row LuT, and the ranged 8-row one (2 u
// 8 < 16: eclipse::rangedLutPays) whose u range holds the camera's u of each frame.
TEST(SceneRangedLut, AnEclipseInMotionKeepsItsLimbLuminanceLut) {
  scene::Scene s = scene::loadScene(UMBRA_SOURCE_DIR "/examples/scenes/earth-from-lunar-north-pole-2015-09-28.json");
  for (const int size : {64, 8}) {
    std::optional<LimbLuminanceRequest> first;
    double firstSunM = 0.0, lastSunM = 0.0;
    for (int minute = 0; minute <= 50; minute += 10) {
      scene::setTime(s, scene::parseUtc("2015-09-28T02:" + std::to_string(minute / 10) + "0:00Z"));
      const SceneInputs in = sceneInputs(s);
      const SphereBody& earth = body(in, "Earth");
      const auto r = sceneLimbLuminanceRequest(in, size, size, 5.0);
      ASSERT_TRUE(r) << minute;
      ASSERT_EQ(r->range.has_value(), size == 8) << size;
      const double sunM = glm::length(earth.centreM - in.sun.positionM);
      EXPECT_LE(std::abs(r->sunOccluderDistanceM / sunM - 1.0), 0.5e-4 * (1.0 + 1e-9)) << minute;
      const eclipse::LutCoords c = eclipse::lutCoords(
          eclipse::shadowAngles(in.camera.positionM, in.sun.positionM, in.sun.radiusM, earth.centreM, earth.radiusM));
      EXPECT_LT(c.v, 1.0) << minute;  // in the shadow
      if (r->range) {
        EXPECT_GE(c.u, r->range->uMin) << minute;
        EXPECT_LE(c.u, r->range->uMax) << minute;
      }
      if (!first) first = r, firstSunM = sunM;
      EXPECT_TRUE(*r == *first) << size << " at 02:" << minute;
      lastSunM = sunM;
    }
    EXPECT_GT(std::abs(lastSunM - firstSunM), 1.0e6);  // the exact distances differ
  }
}

// The copper Moon seen from Earth (the camera on Earth's ground, whose sphere sceneInputs
// shrinks to just below it: by ~5 m, with the camera's rounding at 1 AU from the origin,
// a radius different at every minute in its last digits): the atmospheric shadow LuT is
// made for the model's ground radius, and 02:30 to 03:20 ask for one table (the small
// ranged one, 64x32, and the whole 256x256 one's Moon columns).
TEST(SceneRangedLut, AnEclipseInMotionKeepsTheMoonsShadowLut) {
  scene::Scene s = scene::loadScene(UMBRA_SOURCE_DIR "/examples/scenes/lunar-eclipse-2015-09-28-moon.json");
  for (const int size : {32, 256}) {
    std::optional<AtmosphereShadowRequest> first;
    std::set<double> sphereRadii;
    for (int minute = 30; minute <= 80; minute += 10) {
      const int hour = 2 + minute / 60;
      char t[32];
      std::snprintf(t, sizeof t, "2015-09-28T%02d:%02d:00Z", hour, minute % 60);
      scene::setTime(s, scene::parseUtc(t));
      const SceneInputs in = sceneInputs(s);
      ASSERT_TRUE(in.atmosphere);
      const auto r = sceneAtmosphereShadowRequest(in, size == 32 ? 64 : size, size);
      ASSERT_TRUE(r) << t;
      EXPECT_EQ(r->range.has_value(), size == 32) << t;
      EXPECT_EQ(r->occluderRadiusM, in.atmosphere->bottomRadiusM) << t;
      sphereRadii.insert(body(in, "Earth").radiusM);
      EXPECT_LT(body(in, "Earth").radiusM, in.atmosphere->bottomRadiusM) << t;  // shrunk below the camera
      if (!first) first = r;
      EXPECT_TRUE(*r == *first) << size << " at " << t;
    }
    EXPECT_GT(sphereRadii.size(), 1u);  // what the request no longer follows
  }
}

// What the Sun distance's grid costs: the small limb-luminance LuT made for the grid's
// distance and for the exact one (the example above at its time; were they equal, half a
// step off, the most the grid moves it) differ by < 1e-3 of each texel above 1e-3 of the
// largest (docs/accuracy-vs-speed/eclipse-luts.md, "Tables for a scene in motion").
TEST(SceneRangedLut, LimbLuminanceLutOnTheSunDistanceGrid) {
  scene::Scene s = scene::loadScene(UMBRA_SOURCE_DIR "/examples/scenes/earth-from-lunar-north-pole-2015-09-28.json");
  const SceneInputs in = sceneInputs(s);
  auto request = sceneLimbLuminanceRequest(in, 8, 8, 5.0);
  ASSERT_TRUE(request);
  const double exactM = glm::length(body(in, "Earth").centreM - in.sun.positionM);
  const auto lut = [&](double sunM) {
    vtkNew<vtkLimbLuminanceSource> source;
    useSmallLimbLuminanceTables(source);
    LimbLuminanceRequest r = *request;
    r.sunOccluderDistanceM = sunM;
    updateLimbLuminance(source, r);
    auto* a = source->GetOutput()->GetPointData()->GetScalars();
    std::vector<double> v(a->GetNumberOfTuples() * a->GetNumberOfComponents());
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
      for (int c = 0; c < a->GetNumberOfComponents(); ++c) v[i * a->GetNumberOfComponents() + c] = a->GetComponent(i, c);
    return v;
  };
  // The far side of the grid's half step, so that the two differ by the most the grid allows.
  const double gridM = request->sunOccluderDistanceM;
  const double otherM = exactM == gridM ? gridM * (1.0 + 0.5e-4) : exactM;
  const std::vector<double> a = lut(gridM), b = lut(otherM);
  ASSERT_EQ(a.size(), b.size());
  const double largest = *std::max_element(a.begin(), a.end());
  ASSERT_GT(largest, 0.0);
  double worst = 0.0;
  int compared = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_TRUE(std::isfinite(a[i]) && std::isfinite(b[i]));
    if (a[i] < 1e-3 * largest) continue;
    worst = std::max(worst, std::abs(b[i] / a[i] - 1.0));
    ++compared;
  }
  std::printf("  Sun %.6g m (grid) vs %.6g m: %d texels, largest relative difference %.3g\n", gridM, otherM, compared,
              worst);
  EXPECT_GT(compared, 50);
  EXPECT_GT(std::abs(otherM / gridM - 1.0), 1e-6);
  EXPECT_LT(worst, 1e-3);
}

// A scene with a time casts the Earth's shadow from its spheroid (scene::shadowFigure):
// the flattening of its radii about its pole of date, and the LuT's u range holds every
// point of the Moon for the outline's radius towards the Sun, which lies between the
// polar and the equatorial radius.
TEST(SceneRangedLut, TheOblateEarthsRangeHoldsTheMoon) {
  const scene::Scene s = scene::loadScene(UMBRA_SOURCE_DIR "/examples/scenes/lunar-eclipse-2015-09-28.json");
  const SceneInputs in = sceneInputs(s);
  const SphereBody &earth = body(in, "Earth"), &moon = body(in, "Moon");
  EXPECT_NEAR(earth.flattening, 1.0 / 298.257, 1e-6);
  EXPECT_EQ(moon.flattening, 0.0);
  const eclipse::Occluder occ = occluderOf(earth);
  EXPECT_GT(occ.figure.pole.z, 0.9999);  // the pole of date, 0.1 deg from the ICRS pole in 2015
  const auto r = sceneLutRange(in.sun, {earth}, {moon}, true, 32);
  ASSERT_TRUE(r);
  double least = 1.0, most = 0.0;
  for (const glm::dvec3 dir : {glm::dvec3(1, 0, 0), glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, -1, 0),
                               glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1)}) {
    const glm::dvec3 p = moon.centreM + moon.radiusM * dir;
    const double u = eclipse::lutCoords(eclipse::shadowAngles(p, in.sun.positionM, in.sun.radiusM, occ.centreM,
                                                              occ.radiusM, occ.figure)).u;
    least = std::min(least, u), most = std::max(most, u);
    EXPECT_GE(u, r->uMin);
    EXPECT_LE(u, r->uMax);
  }
  // For comparison, the sphere's u at the Moon's centre.
  const double sphereU = eclipse::lutCoords(eclipse::shadowAngles(moon.centreM, in.sun.positionM, in.sun.radiusM,
                                                                  earth.centreM, earth.radiusM)).u;
  std::printf("  u over the Moon %.6f..%.6f (sphere at its centre %.6f); range %.6f..%.6f\n", least, most, sphereU,
              r->uMin, r->uMax);
}
