// The eclipse through Earth's atmosphere in the renderer (eclipse paper, 5.4): the Moon in
// Earth's umbra shaded with the atmospheric shadow LuT (AtmosphereShadow + EclipseShading),
// computed only for the u columns the Moon can be in. The GPU's factor per channel against
// the CPU lookup (eclipse/ShadowLut.cpp eclipseFactor) in a table holding only those
// columns (the others NaN: a lookup that strays outside them fails), and the colour of
// the umbra: copper (R > G > B).
#include "AtmosphereShadow.h"
#include "AtmosphericShadow.hpp"
#include "Corona.hpp"
#include "EclipseAtmosphere.hpp"
#include "Precompute.hpp"
#include "SolarDisc.hpp"
#include "RenderTestSupport.hpp"
#include "SceneInputs.h"

#include "Atmosphere.hpp"
#include "Spectrum.hpp"
#include "AtmosphereRendering.h"
#include "AtmosphereTablesBlocks.h"
#include "vtkAtmosphereTablesSource.h"
#include "vtkEclipseShadowLutSource.h"
#include "vtkLimbLuminanceSource.h"
#include "ShadowLutData.h"

#include <vtkMultiBlockDataSet.h>
#include <vtkInformation.h>

#include <vtkNew.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <vector>

using namespace umbra::pipeline;  // the scene glue (app/pipeline)

using namespace umbra;
using namespace umbra::render;
using namespace umbra::render::test;

namespace {

constexpr int kLutWidth = 64, kLutHeight = 32;

double earthBottomRadius() {
  static const double r = atmosphere::loadAtmosphere("earth", atmosphere::WavelengthSet::rgb().nm).bottomRadiusM;
  return r;
}

void configureSmall(vtkEclipseShadowLutSource* s) {
  useSmallEclipseShadowTables(s);
  ASSERT_EQ(s->GetWidth(), kLutWidth);
  ASSERT_EQ(s->GetHeight(), kLutHeight);
  s->UseCacheOff();
}

// The part of the table the source computed, in a whole-size CPU table (NaN elsewhere);
// a ranged table (the scene path's near the occluder: sceneLutRange) is whole already.
eclipse::ShadowLut cpuTable(vtkImageData* image) {
  const eclipse::LutRange range = filters::lutRangeOf(filters::fieldParameters(image), "atmospheric LuT");
  if (range != eclipse::LutRange{}) return filters::fromImageData(image);
  eclipse::ShadowLut lut;
  lut.width = kLutWidth;
  lut.height = kLutHeight;
  lut.rgb.assign(3 * kLutWidth * kLutHeight, std::numeric_limits<float>::quiet_NaN());
  int ext[6];
  image->GetExtent(ext);
  vtkDataArray* values = image->GetPointData()->GetScalars();
  for (int j = ext[2]; j <= ext[3]; ++j) {
    for (int i = ext[0]; i <= ext[1]; ++i) {
      int ijk[3] = {i, j, 0};
      const vtkIdType id = image->ComputePointId(ijk);
      for (int c = 0; c < 3; ++c) lut.rgb[3 * (j * kLutWidth + i) + c] = float(values->GetComponent(id, c));
    }
  }
  return lut;
}

struct MoonInUmbra {
  SceneInputs in;
  SphereBody moon;
  vtkNew<vtkEclipseShadowLutSource> source;
  std::vector<float> hdr;
  int width = 0, height = 0;
  int columns[2] = {0, 0};

  // The Moon `offsetM` off the shadow's axis, seen from 1 km above Earth's night side.
  MoonInUmbra(double offsetM, int size) {
    in.sun.positionM = {-kAu, 0.0, 0.0};
    const SphereBody earth{"Earth", {0.0, 0.0, 0.0}, earthBottomRadius(), {0.3, 0.3, 0.3}};
    moon = {"Moon", {kMoonDistance, offsetM, 0.0}, 1.7374e6, {0.12, 0.12, 0.12}};
    in.bodies = {earth, moon};
    in.atmosphere = SceneAtmosphere{"Earth", atmosphere::AtmosphereModel::load("earth")};
    in.camera.positionM = {earth.radiusM + 1000.0, 0.0, 0.0};
    in.camera.targetM = moon.centreM;
    in.camera.up = {0.0, 0.0, 1.0};
    in.camera.fovDeg = 0.6;
    configureSmall(source);

    BodyView view(size, size, true);
    useSharedDisplay(view.GetRenderWindow());
    view.SetBodies(in.sun, in.bodies, testLutImage());
    applySceneAtmosphereShadow(view.GetShading(), in, source);
    int ext[6];
    source->GetOutput()->GetExtent(ext);
    columns[0] = ext[0];
    columns[1] = ext[1];
    view.SetCamera(in.camera);
    view.SetExposureEV(0.0);
    view.Render();
    view.ReadHdr(hdr, width, height);
  }
};

// The receiver's factor per channel in the rendered HDR image (every 4th pixel facing the
// camera and the Sun) against the CPU lookup in `cpu`: relative (the umbra spans orders of
// magnitude) within 2 % (GL's filter weights are 8-bit). The CPU factors of the samples
// and the largest relative difference.
struct FactorAgreement {
  std::vector<glm::dvec3> expected;
  double maxRel = 0.0;
};
FactorAgreement compareFactors(const SceneInputs& in, const SphereBody& body, const SphereBody& occluder,
                               const std::vector<float>& hdr, int width, int height, const eclipse::ShadowLut& cpu) {
  FactorAgreement out;
  const eclipse::Occluder occ{occluder.centreM, occluder.radiusM};
  for (int j = 2; j < height; j += 4) {
    for (int i = 2; i < width; i += 4) {
      const Ray ray = pixelRay(in.camera, width, height, i, j);
      const auto hit = hitSphere(ray, body.centreM, body.radiusM);
      if (!hit) continue;
      const glm::dvec3 n = glm::normalize(*hit - body.centreM);
      if (-glm::dot(n, ray.dir) < 0.3) continue;
      double cosi = 0.0;
      const double unshadowed = unshadowedRadiance(*hit, body.centreM, body.albedoRgb.r, in.sun, &cosi);
      if (cosi < 0.05) continue;
      const glm::dvec3 expected = eclipse::eclipseFactor(*hit, in.sun.positionM, in.sun.radiusM, occ, &cpu);
      for (int c = 0; c < 3; ++c) {
        EXPECT_TRUE(std::isfinite(expected[c])) << "the CPU lookup left the computed columns at pixel " << i << ", " << j;
        const double gpu = hdr[3 * (static_cast<std::size_t>(j) * width + i) + c] / unshadowed;
        const double rel = std::abs(gpu - expected[c]) / std::max(expected[c], 1e-7);
        out.maxRel = std::max(out.maxRel, rel);
        EXPECT_LT(rel, 0.02) << "pixel (" << i << ", " << j << ") channel " << c << ": GPU " << gpu << ", CPU "
                             << expected[c];
      }
      out.expected.push_back(expected);
    }
  }
  return out;
}

} // namespace

// The columns asked for are only those around the Moon's u (Eq. 4 at 384 400 km: ~0.22).
TEST(EclipseAtmosphereRender, ShadowLutColumnsCoverTheReceiverOnly) {
  SunLight sun;
  sun.positionM = {-kAu, 0.0, 0.0};
  const SphereBody earth{"Earth", {0.0, 0.0, 0.0}, earthBottomRadius(), {0.3, 0.3, 0.3}};
  const SphereBody moon{"Moon", {kMoonDistance, 0.0, 0.0}, 1.7374e6, {0.12, 0.12, 0.12}};
  const auto cols = shadowLutColumns(sun, earth, moon, 256);
  const double phiSun = std::asin(sun.radiusM / (kAu + kMoonDistance));
  const double u = phiSun / (phiSun + std::asin(earth.radiusM / kMoonDistance));
  EXPECT_LE(cols[0], u * 256 - 0.5);
  EXPECT_GE(cols[1], u * 256 - 0.5);
  EXPECT_LE(cols[1] - cols[0], 3);
  // A body touching the occluder reaches down to u = 0.
  const SphereBody near{"Near", {1.0e7, 0.0, 0.0}, 4.0e6, {0.1, 0.1, 0.1}};
  EXPECT_EQ(shadowLutColumns(sun, earth, near, 256)[0], 0);
}

TEST(EclipseAtmosphereRender, CpuGlslAgreementMoonInEarthsUmbra) {
  const double umbraEdgeM = 4.4e6;  // roughly, at the Moon: the Moon straddles it
  MoonInUmbra s(umbraEdgeM - 0.5e6, 128);
  EXPECT_LE(s.columns[1] - s.columns[0], 3) << "columns " << s.columns[0] << ".." << s.columns[1];
  const eclipse::ShadowLut cpu = cpuTable(s.source->GetOutput());
  const FactorAgreement f = compareFactors(s.in, s.moon, s.in.bodies[0], s.hdr, s.width, s.height, cpu);
  const int samples = int(f.expected.size());
  const int umbra = int(std::count_if(f.expected.begin(), f.expected.end(), [](const glm::dvec3& e) { return e.r < 0.01; }));
  const double maxRel = f.maxRel;
  std::printf("  columns %d..%d of %d, %d samples (%d in the umbra), max relative |GPU - CPU| = %.3g\n",
              s.columns[0], s.columns[1], kLutWidth, samples, umbra, maxRel);
  RecordProperty("max_rel_factor_difference", std::to_string(maxRel));
  EXPECT_GE(samples, 200);
  EXPECT_GE(umbra, 50);
}

// A ranged atmospheric LuT (u over Phobos' distances, v split at the umbra's edge: the
// scene path's own choice, sceneLutRange; field data read by SetAtmosphereShadowLut into
// umbraAtmosphereLutURange, VRange, VLowFraction): Mars' shadow through its atmosphere on
// Phobos, put at the shadow's edge (Mars' radius off the axis) and seen from the Sun's
// side, as the CPU's eclipse factor with the same table, within 2 % (compareFactors).
// Read through the whole-table ranges [0, 1] instead, the same pixels are off by a factor
// of up to ~160.
TEST(EclipseAtmosphereRender, RangedLutAtPhobosAgreesWithTheCpu) {
  SceneInputs in;
  in.sun.positionM = {-2.2794e11, 0.0, 0.0};
  const double marsRadiusM = atmosphere::loadAtmosphere("mars", atmosphere::WavelengthSet::rgb().nm).bottomRadiusM;
  const double phobosRadiusM = 11.1e3, phobosDistanceM = 9376e3;
  const SphereBody mars{"Mars", {0.0, 0.0, 0.0}, marsRadiusM, {0.25, 0.25, 0.25}};
  const SphereBody phobos{"Phobos", {phobosDistanceM, marsRadiusM, 0.0}, phobosRadiusM, {0.07, 0.07, 0.07}};
  in.bodies = {mars, phobos};
  in.atmosphere = SceneAtmosphere{"Mars", atmosphere::AtmosphereModel::load("mars")};
  in.camera.positionM = phobos.centreM + glm::dvec3(-200e3, 0.0, 0.0);
  in.camera.targetM = phobos.centreM;
  in.camera.up = {0.0, 0.0, 1.0};
  in.camera.fovDeg = 2.0 * std::atan(phobosRadiusM / 200e3) * 180.0 / 3.14159265358979 * 1.1;
  vtkNew<vtkEclipseShadowLutSource> source;
  configureSmall(source);
  BodyView view(128, 128, true);
  useSharedDisplay(view.GetRenderWindow());
  view.SetBodies(in.sun, in.bodies, testLutImage());
  applySceneAtmosphereShadow(view.GetShading(), in, source);  // ranged by itself
  const eclipse::ShadowLut cpu = filters::fromImageData(source->GetOutput());
  const eclipse::LutRange r = cpu.range();
  ASSERT_GT(r.uMin, 0.0);
  ASSERT_GT(r.vLowFraction, 0.0);  // the umbra is not dark: a split v axis
  view.SetCamera(in.camera);
  view.SetExposureEV(0.0);
  view.Render();
  std::vector<float> hdr;
  int width = 0, height = 0;
  view.ReadHdr(hdr, width, height);

  const FactorAgreement f = compareFactors(in, phobos, mars, hdr, width, height, cpu);
  const int samples = int(f.expected.size());
  const int shadowed = int(std::count_if(f.expected.begin(), f.expected.end(), [](const glm::dvec3& e) { return e.g < 0.99; }));
  const double maxRel = f.maxRel;
  std::printf("  u %.4f..%.4f, v %.4f..%.4f (low fraction %.3f), %d samples (%d shadowed), max relative |GPU - CPU| = %.3g\n",
              r.uMin, r.uMax, r.vMin, r.vMax, r.vLowFraction, samples, shadowed, maxRel);
  RecordProperty("max_rel_factor_difference", std::to_string(maxRel));
  EXPECT_GE(samples, 200);
  EXPECT_GE(shadowed, 50);  // the shadow crosses Phobos
}

// The Moon on the shadow's axis: copper, R > G > B at its centre, and not black (the
// airless umbra would be 0 there).
TEST(EclipseAtmosphereRender, MoonInTheUmbraIsCopper) {
  MoonInUmbra s(0.0, 64);
  const std::size_t centre = 3 * (static_cast<std::size_t>(s.height / 2) * s.width + s.width / 2);
  const double r = s.hdr[centre], g = s.hdr[centre + 1], b = s.hdr[centre + 2];
  std::printf("  umbra centre radiance R G B = %.3g %.3g %.3g W m^-2 sr^-1\n", r, g, b);
  const double unshadowed = unshadowedRadiance(s.moon.centreM - glm::dvec3(s.moon.radiusM, 0, 0), s.moon.centreM,
                                               s.moon.albedoRgb.r, s.in.sun);
  EXPECT_GT(r, g);
  EXPECT_GT(g, b);
  EXPECT_GT(r / unshadowed, 1e-5);  // red light bent into the umbra
  EXPECT_LT(r / unshadowed, 1e-2);  // but the umbra is still dark
  EXPECT_GT(r, 3.0 * b);
}

// ---- the limb ring from the limb-luminance LuT (eclipse paper, 5.4) ---------------------

namespace {

constexpr int kLimbWidth = 8, kLimbHeight = 8;

// Earth's tables with refraction (small sizes) and its limb-luminance LuT (8 x 8 x 16,
// views of 512 rows: 195 m of the limb, finer than the ~2 km band through which the Sun
// lights the umbra), made once.
struct RingFixture {
  atmosphere::Atmosphere model;
  atmosphere::AtmosphereTables tables;
  vtkSmartPointer<vtkImageData> refraction, limb;
};
// The ring tests' eclipse tables: Earth's atmosphere with Bruneton's thin haze (small
// tables, refraction), the Sun at 1 au; kLimbWidth x kLimbHeight texels. (The ring's light
// passes 1.8-3.9 km up, across the default sky's 2 km mixing-layer top, where its aerosol
// density steps twelvefold: there the 16-column LuT and the ray marching part by up to
// 40 % in G and B.)
void configureRingTables(vtkEclipseAtmosphereSource* s, double bottomRadiusM) {
  s->SetOccluderName("Earth");
  s->SetOccluderRadiusM(bottomRadiusM);
  s->SetSunOccluderDistanceM(kAu);
  s->SetAtmosphere("earth-bruneton");
  s->SetOrders(3);
  s->SetTransmittanceSize(64, 16);
  s->SetScatteringSize(8, 32, 8, 4);
  s->SetIrradianceSize(16, 4);
  s->SetRefractionSize(128, 64);
  s->UseCacheOff();
}
// The limb-luminance LuT of the ring tests: 16 columns, views of 512 rows, 4x4 cells.
void configureRingLimb(vtkLimbLuminanceSource* limb, double bottomRadiusM) {
  configureRingTables(limb, bottomRadiusM);
  limb->SetWidth(kLimbWidth);
  limb->SetHeight(kLimbHeight);
  limb->SetColumns(16);
  limb->SetLimbRows(512);
  limb->SetScatteringCells(4);
}

const RingFixture& ringFixture() {
  static const RingFixture f = [] {
    RingFixture out;
    out.model = atmosphere::loadAtmosphere("earth-bruneton", atmosphere::WavelengthSet::rgb().nm);
    vtkNew<vtkAtmosphereTablesSource> tables;
    tables->SetAtmosphere("earth-bruneton");
    useSmallAtmosphereTables(tables);
    tables->SetTables(vtkAtmosphereTablesSource::Bruneton | vtkAtmosphereTablesSource::Refraction);
    tables->SetRefractedPaths(true);
    tables->SetRefractionWidth(128);
    tables->SetRefractionHeight(64);
    tables->UseCacheOff();
    tables->Update();
    vtkMultiBlockDataSet* blocks = tables->GetOutput();
    out.tables = umbra::filters::tablesFromBlocks(blocks, out.model);
    out.refraction = vtkImageData::SafeDownCast(blocks->GetBlock(blocks->GetNumberOfBlocks() - 1));

    vtkNew<vtkLimbLuminanceSource> limb;
    configureRingLimb(limb, out.tables.bottomRadiusM);
    limb->Update();
    out.limb = vtkSmartPointer<vtkImageData>::New();
    out.limb->DeepCopy(limb->GetOutput());
    return out;
  }();
  return f;
}

// The camera at the point of the shadow whose (u, v) is the centre of LuT texel (i, j),
// with the Sun at -1 au on x and Earth at the origin (the LuT's lookup is then exact).
glm::dvec3 cameraAtTexel(int i, int j) {
  const SunLight sun;
  const eclipse::InverseMapping m = eclipse::inverseLutCoords(
      {(i + 0.5) / kLimbWidth, (j + 0.5) / kLimbHeight}, {sun.radiusM, ringFixture().tables.bottomRadiusM, kAu});
  return m.pointM;  // occluder at the origin, the Sun at (-d, 0, 0)
}

struct RingFrame {
  std::vector<float> rgb;
  int subsamples = 0;
  int w = 0, h = 0;
  double ringWidthPx = 0.0;
  bool usedLut = false;
  double pixelSolidAngleSr = 0.0;
  glm::dvec3 flux() const {  // sum of radiance x solid angle (the background is black)
    glm::dvec3 f(0.0);
    for (std::size_t k = 0; k < rgb.size() / 3; ++k) f += glm::dvec3(rgb[3 * k], rgb[3 * k + 1], rgb[3 * k + 2]);
    return f * pixelSolidAngleSr;
  }
};

// Earth seen from `camera` towards `target`, with refraction, ray marched or from the LuT.
// `lut`: that limb-luminance LuT instead of the fixture's.
RingFrame renderRing(const glm::dvec3& camera, const glm::dvec3& target, double fovDeg, int size, bool useLut,
                     double thresholdPx, vtkImageData* lut = nullptr) {
  const RingFixture& f = ringFixture();
  SunLight sun;
  sun.positionM = {-kAu, 0.0, 0.0};
  const SphereBody earth{"Earth", {0.0, 0.0, 0.0}, f.tables.bottomRadiusM, {0.1, 0.1, 0.1}};
  BodyView view(size, size, true);
  useSharedDisplay(view.GetRenderWindow());
  view.SetBodies(sun, {earth}, testLutImage());
  AtmosphereRendering& atmo = view.GetAtmosphere();
  atmo.SetAtmosphere(f.model, f.tables, earth.centreM, earth.albedoRgb);
  atmo.SetRefraction(f.refraction);
  atmo.SetTerrainMeanElevation(eclipse::defaultTerrain("Earth").meanElevationM);
  if (useLut) atmo.SetLimbLuminance(lut ? lut : f.limb.Get());
  atmo.SetLimbRingThresholdPixels(thresholdPx);
  ViewCamera cam;
  cam.positionM = camera;
  cam.targetM = target;
  cam.up = {0.0, 0.0, 1.0};
  cam.fovDeg = fovDeg;
  view.SetCamera(cam);
  view.SetExposureEV(0.0);
  view.Render();
  RingFrame out;
  view.ReadHdr(out.rgb, out.w, out.h);
  // No channel below 0: light outside the display's gamut (the deep red ring's blue through
  // the colour matrix) is clipped to 0, as the sky command writes it.
  EXPECT_EQ(std::count_if(out.rgb.begin(), out.rgb.end(), [](float v) { return v < 0.0f; }), 0);
  out.ringWidthPx = atmo.GetLastRingWidthPixels();
  out.usedLut = atmo.GetLastDrawUsedLimbLuminance();
  out.subsamples = atmo.GetLastLimbSubsamples();
  const double pixel = 2.0 * std::tan(0.5 * fovDeg * kPi / 180.0) / size;
  out.pixelSolidAngleSr = pixel * pixel;
  return out;
}

} // namespace

// Earth from the Moon's distance in its umbra, whole in a 128 px view: the ring is under
// a pixel wide, so the LuT draws it: a thin ring, finite, red-dominant.
TEST(EclipseAtmosphereRender, ThinRingFromTheLimbLuminanceLut) {
  const glm::dvec3 camera = cameraAtTexel(1, 0);  // u = 0.1875 (~316 000 km), v = 0.0625
  const RingFrame f = renderRing(camera, {0.0, 0.0, 0.0}, 2.6, 128, true, 5.0);
  std::printf("  camera %.0f km behind Earth, ring %.2f px wide, LuT used: %d\n", glm::length(camera) / 1e3,
              f.ringWidthPx, f.usedLut);
  ASSERT_TRUE(f.usedLut);
  EXPECT_LT(f.ringWidthPx, 1.0);
  int lit = 0;
  glm::dvec3 sum(0.0), ringFlux(0.0);
  for (std::size_t k = 0; k < f.rgb.size(); ++k) ASSERT_TRUE(std::isfinite(f.rgb[k]));
  // Off the ring the Sun's corona shows round Earth (sky/Corona.hpp, out to 16 solar radii):
  // no brighter than its profile at the pixel's centre, grey.
  const SunLight sunLight;
  const double dSun = kAu + glm::length(camera), alpha = std::asin(sunLight.radiusM / dSun);
  const double discMean = sunLight.irradianceAtWm2(dSun) / (kPi * alpha * alpha);
  const double pixelRad = 2.0 * std::tan(0.5 * 2.6 * kPi / 180.0) / f.h;
  const double rPx = std::asin(ringFixture().tables.bottomRadiusM / glm::length(camera)) / pixelRad;
  // The Sun's centre lies off the view's centre (the camera is off the shadow's axis): the
  // bound takes a pixel that much nearer the Sun.
  const glm::dvec3 toSun = glm::normalize(glm::dvec3(-kAu, 0.0, 0.0) - camera), forward = glm::normalize(-camera);
  const double sunOffsetPx = std::acos(std::min(1.0, glm::dot(toSun, forward))) / pixelRad;
  int corona = 0;
  for (int j = 0; j < f.h; ++j)
    for (int i = 0; i < f.w; ++i) {
      const float* p = &f.rgb[3 * (static_cast<std::size_t>(j) * f.w + i)];
      if (p[0] <= 0.0f) continue;
      const double x = i + 0.5 - 0.5 * f.w, y = j + 0.5 - 0.5 * f.h;
      if (std::abs(std::hypot(x, y) - rPx) > 1.5) {
        const double rho = std::atan(std::max(0.0, std::hypot(x, y) - sunOffsetPx - 0.5) * pixelRad) / alpha;
        EXPECT_LE(p[0], 1.01 * sky::coronaRelativeRadiance(rho) * discMean) << "pixel " << i << ", " << j;
        EXPECT_NEAR(p[0], p[2], 1e-3 * p[0]) << "pixel " << i << ", " << j;
        ++corona;
        continue;
      }
      // Every other lit pixel lies on the ring: at Earth's angular radius from the centre.
      ++lit;
      sum += glm::dvec3(p[0], p[1], p[2]);
    }
  ringFlux = sum * f.pixelSolidAngleSr;
  std::printf("  %d pixels of corona round the ring\n", corona);
  EXPECT_GT(corona, 1000);
  std::printf("  %d ring pixels, summed R G B = %.3g %.3g %.3g\n", lit, sum.r, sum.g, sum.b);
  EXPECT_GT(lit, 300);  // a closed ring: ~ 2 pi 60 px
  EXPECT_GT(sum.r, sum.g);
  EXPECT_GT(sum.g, sum.b);

  // Energy: the ring's flux over the Sun's irradiance is the illuminance the atmospheric
  // shadow LuT holds at the same (u, v) (in the umbra all of it comes through the ring).
  vtkNew<vtkEclipseShadowLutSource> shadow;
  configureRingTables(shadow, ringFixture().tables.bottomRadiusM);
  shadow->SetWidth(kLimbWidth);
  shadow->SetHeight(kLimbHeight);
  shadow->SetLimbSize(512);
  shadow->SetScatteringCells(4);
  const int texel[6] = {1, 1, 0, 0, 0, 0};
  shadow->UpdateExtent(texel);
  vtkDataArray* iOverSun = shadow->GetOutput()->GetPointData()->GetScalars();
  const glm::dvec3 ringOverSun = ringFlux / SunLight().irradianceAt1AuWm2;
  std::printf("  ring flux / E_sun R G = %.3g %.3g, shadow LuT I / I_sun = %.3g %.3g\n", ringOverSun.r, ringOverSun.g,
              iOverSun->GetComponent(0, 0), iOverSun->GetComponent(0, 1));
  EXPECT_NEAR(ringOverSun.r / iOverSun->GetComponent(0, 0), 1.0, 0.02);  // measured 0.2 %
  EXPECT_NEAR(ringOverSun.g / iOverSun->GetComponent(0, 1), 1.0, 0.02);
}

// Where both are valid, at the switch (the ring 5 px wide, the default threshold) and at
// 48 px (a piece of the ring across a 256 px view): the LuT's flux against ray marching's.
// The light of the ring seen from the umbra comes through a band ~2 km high (rays bent by
// ~0.9-1 degree, 1.8-3.9 km above the ground at their periapsis), so ray marching averages
// the Sun over sub-rays 250 m apart across each pixel (up to 64), the pixels of the ground
// next to the ring included, with the transmittance along the refracted path and Earth's
// terrain (the CPU limb views' formulas; test below); the LuT's limb views have 512 rows
// (195 m). Measured (llvmpipe): LuT / ray marched R G B = 0.987 0.985 0.943 at 5 px,
// 0.981 0.977 0.955 at 48 px (before: 0.51 0.32 0.88 at 48 px). Tolerance 10 %.
TEST(EclipseAtmosphereRender, LimbLuminanceLutAndRayMarchingAgreeInFlux) {
  const glm::dvec3 camera = cameraAtTexel(1, 0);
  const RingFixture& f = ringFixture();
  const double d = glm::length(camera);
  const double ringMid = 0.5 * (f.tables.bottomRadiusM + f.tables.topRadiusM);
  const double widthRad = std::asin(f.tables.topRadiusM / d) - std::asin(f.tables.bottomRadiusM / d);
  const int size = 256;
  const glm::dvec3 target{0.0, 0.0, ringMid};
  for (const double widthPx : {5.0, 48.0}) {
    const double fovDeg = widthRad / widthPx * size * 180.0 / kPi;
    const RingFrame lut = renderRing(camera, target, fovDeg, size, true, 1000.0);
    const RingFrame marched = renderRing(camera, target, fovDeg, size, false, 0.0);
    ASSERT_TRUE(lut.usedLut);
    ASSERT_FALSE(marched.usedLut);
    const glm::dvec3 a = lut.flux(), b = marched.flux();
    std::printf("  ring %.1f px wide (%d sub-rays); flux LuT R G B = %.3g %.3g %.3g, ray marched = %.3g %.3g %.3g W m^-2; "
                "LuT / ray marched = %.3f %.3f %.3f\n",
                lut.ringWidthPx, marched.subsamples, a.r, a.g, a.b, b.r, b.g, b.b, a.r / b.r, a.g / b.g, a.b / b.b);
    RecordProperty(widthPx < 10.0 ? "flux_ratio_red_5px" : "flux_ratio_red_48px", std::to_string(a.r / b.r));
    for (int c = 0; c < 3; ++c) {
      ASSERT_GT(b[c], 0.0);
      EXPECT_NEAR(a[c] / b[c], 1.0, 0.10) << "channel " << c << ", ring " << widthPx << " px";
    }
  }
}


namespace {

// The ring fixture's tables as a CPU limb model (eclipse/atmospheric: the limb ray profile
// along refracted paths, Earth's terrain), the reference of the ray-marched ring.
const eclipse::EclipseAtmosphere& ringCpuModel() {
  static const std::unique_ptr<eclipse::EclipseAtmosphere> e = [] {
    const RingFixture& f = ringFixture();
    vtkNew<vtkMultiBlockDataSet> blocks;
    blocks->SetNumberOfBlocks(1);
    blocks->SetBlock(0, f.refraction);
    blocks->GetMetaData(0u)->Set(vtkCompositeDataSet::NAME(), "refraction");
    eclipse::EclipseAtmosphereOptions o;
    o.tables = f.tables.options;
    o.refractionWidth = 128, o.refractionHeight = 64;
    return eclipse::prepareEclipseAtmosphere(f.model, f.tables, umbra::filters::refractionFromBlocks(blocks, f.model),
                                             "earth", kAu, o);
  }();
  return *e;
}

// The Sun's disc seen along `dir` (AtmosphereComposite.glsl's umbraSunDisc, in double).
double sunDiscRadiance(const glm::dvec3& dir, const glm::dvec3& sunDir, double alpha, double irradiance) {
  const double angle = 2.0 * std::atan2(glm::length(dir - sunDir), glm::length(dir + sunDir));
  if (angle >= alpha) return 0.0;
  return eclipse::limbDarkenedLuminance(angle / alpha, eclipse::kDefaultLimbDarkening) * irradiance / (kPi * alpha * alpha);
}

} // namespace

// The ray-marched ring (camera outside the atmosphere, in Earth's umbra, with refraction)
// against the CPU limb rays of eclipse/atmospheric at the same directions: per ring pixel
// the Sun's disc along the exit ray (deviation, contact altitude and transmittance along
// the refracted path from limbRayProfile, Earth's terrain: the quantities the limb views
// and the LuTs are made of), averaged over the same sub-rays across the pixel as the
// shader, plus the in-scattered radiance (skyRadiance) of the pixel's centre. Measured
// (llvmpipe): ring flux GPU / CPU R G B = 1.0003 1.0006 1.0000; of the 468 pixels lit by
// the Sun, red differs by 0.2 % (median), 1.3 % (90th percentile). Tolerance 2 % (flux),
// 5 % (90th percentile).
TEST(EclipseAtmosphereRender, RayMarchedRingMatchesTheCpuLimbRays) {
  const glm::dvec3 camera = cameraAtTexel(1, 0);
  const RingFixture& f = ringFixture();
  const eclipse::AtmosphericShadowModel& m = ringCpuModel().model;
  const double d = glm::length(camera);
  const double top = f.tables.topRadiusM, bottom = f.tables.bottomRadiusM;
  const double widthRad = std::asin(top / d) - std::asin(bottom / d);
  const int size = 256;
  const double fovDeg = widthRad / 48.0 * size * 180.0 / kPi;  // 48 px across the ring
  const glm::dvec3 target{0.0, 0.0, 0.5 * (bottom + top)};
  const RingFrame marched = renderRing(camera, target, fovDeg, size, false, 1000.0);
  ASSERT_FALSE(marched.usedLut);
  const int n = marched.subsamples;
  EXPECT_EQ(n, 9);  // 2.1 km of the limb per pixel, 250 m apart

  const SunLight sun;
  const glm::dvec3 sunPos{-kAu, 0.0, 0.0};
  const glm::dvec3 sunDir = glm::normalize(sunPos - camera), sunFromEarth = glm::normalize(sunPos);
  const double alpha = std::asin(sun.radiusM / kAu), E = sun.irradianceAt1AuWm2;
  const glm::dvec3 F = glm::normalize(target - camera);
  const glm::dvec3 X = glm::normalize(glm::cross(F, glm::dvec3(0.0, 0.0, 1.0)));
  const glm::dvec3 Y = glm::cross(X, F);
  const double tanHalf = std::tan(0.5 * fovDeg * kPi / 180.0), pixel = 2.0 * tanHalf / size;
  const glm::dmat3 M = atmosphereToDisplayMatrix(f.tables.wavelengthsNm);
  const glm::dvec3 toCentre = -camera;
  glm::dvec3 gpuSum(0.0), cpuSum(0.0);
  int compared = 0;
  std::vector<glm::dvec3> gpu, cpu;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const double nx = 2.0 * (i + 0.5) / size - 1.0, ny = 2.0 * (j + 0.5) / size - 1.0;
      const glm::dvec3 dir = glm::normalize(F + nx * tanHalf * X + ny * tanHalf * Y);
      const glm::dvec3 perp = toCentre - glm::dot(toCentre, dir) * dir;
      const double b = glm::length(perp);
      if (b >= top || b <= bottom) continue;  // the pixel's centre in the ring
      const glm::dvec3 x = -perp - std::sqrt(top * top - b * b) * dir;  // entry, from Earth's centre
      const std::vector<double> L = atmosphere::skyRadiance(f.tables, f.model, top, glm::dot(x, dir) / top,
                                                            glm::dot(x, sunFromEarth) / top, glm::dot(dir, sunFromEarth));
      glm::dvec3 value = M * glm::dvec3(L[0], L[1], L[2]) * E;
      const glm::dvec3 radial = glm::normalize(perp);
      for (int k = 0; k < n; ++k) {
        const glm::dvec3 dk = glm::normalize(dir + ((k + 0.5) / n - 0.5) * pixel * radial);
        const glm::dvec3 pk = toCentre - glm::dot(toCentre, dk) * dk;
        const double bk = glm::length(pk);
        if (bk >= top) value += glm::dvec3(sunDiscRadiance(dk, sunDir, alpha, E) / n);
        if (bk >= top || bk <= bottom) continue;
        double deviation = 0.0, contact = 0.0, T[3];
        m.rays.at(bk, deviation, contact, T);
        const glm::dvec3 exit = std::cos(deviation) * dk + std::sin(deviation) * glm::normalize(pk);
        value += glm::dvec3(T[0], T[1], T[2]) *
                 (sunDiscRadiance(exit, sunDir, alpha, E) * m.terrain.transmission(contact) / n);
      }
      const float* p = &marched.rgb[3 * (static_cast<std::size_t>(size - 1 - j) * size + i)];  // rows top down
      const glm::dvec3 g(p[0], p[1], p[2]);
      gpu.push_back(g), cpu.push_back(value);
      gpuSum += g, cpuSum += value;
    }
  double maxR = 0.0;
  for (const glm::dvec3& c : cpu) maxR = std::max(maxR, c.r);
  std::vector<double> redDifference;
  for (std::size_t k = 0; k < cpu.size(); ++k) {
    if (cpu[k].r < 1e-2 * maxR) continue;  // the Sun's light, not the faint scattered glow
    ++compared;
    redDifference.push_back(std::abs(gpu[k].r / cpu[k].r - 1.0));
  }
  std::sort(redDifference.begin(), redDifference.end());
  const double medianRed = redDifference.empty() ? 1.0 : redDifference[redDifference.size() / 2];
  const double p90Red = redDifference.empty() ? 1.0 : redDifference[redDifference.size() * 9 / 10];
  std::printf("  red per pixel: median %.3f, 90th percentile %.3f\n", medianRed, p90Red);
  std::printf("  %zu ring pixels, %d sub-rays; GPU / CPU ring flux R G B = %.4f %.4f %.4f; %d pixels lit by the Sun\n",
              cpu.size(), n, gpuSum.r / cpuSum.r, gpuSum.g / cpuSum.g, gpuSum.b / cpuSum.b, compared);
  EXPECT_GT(compared, 100);
  EXPECT_LT(p90Red, 0.05);  // single pixels: the float geometry moves the Sun's edge by ~30 m of the limb
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(gpuSum[c] / cpuSum[c], 1.0, 0.02) << "channel " << c;
}

// A ranged limb-luminance LuT (u, v ranges as the shadow LuT's: pointLutRange of a camera
// 200 000 km behind Earth, as applySceneLimbLuminance asks for one): the camera at the
// centre of a texel of it in the umbra, the ring drawn from it (read through the ranges:
// umbraLimbUv) carries the illuminance that a ranged shadow LuT holds at the same (u, v),
// within 5 % as above. (Nearer, e.g. 30 000 km, the ring is 12 deg off the view's axis,
// where the pixels' solid angle is cos^3 of the centre's: 11 % off, a flaw of the flux sum.)
TEST(EclipseAtmosphereRender, RangedLimbLuminanceLutRingMatchesTheShadowLut) {
  const RingFixture& f = ringFixture();
  SunLight sun;
  sun.positionM = {-kAu, 0.0, 0.0};
  const SphereBody earth{"Earth", {0.0, 0.0, 0.0}, f.tables.bottomRadiusM, {0.1, 0.1, 0.1}};
  const auto range = pointLutRange(sun, earth, {2.0e8, 0.0, 0.0}, false, kLimbHeight);
  ASSERT_TRUE(range);
  ASSERT_GT(range->vLowFraction, 0.0);
  const int width = rangedLutWidth(*range, kLimbWidth);
  const int row = 1;  // in the umbra: v < vMin
  const eclipse::LutCoords uv{range->texelU(0, width), range->texelV(row, kLimbHeight)};
  ASSERT_LT(uv.v, range->vMin);
  const glm::dvec3 camera = eclipse::inverseLutCoords(uv, {sun.radiusM, f.tables.bottomRadiusM, kAu}).pointM;

  vtkNew<vtkLimbLuminanceSource> limb;
  configureRingLimb(limb, f.tables.bottomRadiusM);
  limb->SetLutRange(*range);
  limb->SetWidth(width);
  limb->Update();
  int dims[3];
  limb->GetOutput()->GetDimensions(dims);
  ASSERT_EQ(dims[0], width);
  const eclipse::LutRange back = filters::lutRangeOf(filters::fieldParameters(limb->GetOutput()), "limb LuT");
  EXPECT_EQ(back, *range);

  // The ring from it: all of Earth in view, under 2 px wide at 128 px.
  const double phi = std::asin(f.tables.topRadiusM / glm::length(camera));
  const double fovDeg = 2.2 * phi * 180.0 / kPi;
  const RingFrame frame = renderRing(camera, earth.centreM, fovDeg, 128, true, 5.0, limb->GetOutput());
  ASSERT_TRUE(frame.usedLut);

  vtkNew<vtkEclipseShadowLutSource> shadow;
  configureRingTables(shadow, f.tables.bottomRadiusM);
  shadow->SetWidth(width);
  shadow->SetHeight(kLimbHeight);
  shadow->SetLimbSize(512);
  shadow->SetScatteringCells(4);
  shadow->SetLutRange(*range);
  const int column[6] = {0, 0, 0, kLimbHeight - 1, 0, 0};  // (a split v axis: all rows)
  shadow->UpdateExtent(column);
  vtkDataArray* iOverSun = shadow->GetOutput()->GetPointData()->GetScalars();
  ASSERT_NE(iOverSun, nullptr);
  ASSERT_EQ(iOverSun->GetNumberOfTuples(), kLimbHeight);
  const glm::dvec3 lutOverSun{iOverSun->GetComponent(row, 0), iOverSun->GetComponent(row, 1), 0.0};
  const glm::dvec3 ringOverSun = frame.flux() / SunLight().irradianceAt1AuWm2;
  std::printf("  u %.6f v %.4f (%.0f km behind Earth), ring %.2f px: flux / E_sun R G = %.3g %.3g, shadow LuT = %.3g %.3g\n",
              uv.u, uv.v, glm::length(camera) / 1e3, frame.ringWidthPx, ringOverSun.r, ringOverSun.g, lutOverSun.r,
              lutOverSun.g);
  EXPECT_NEAR(ringOverSun.r / lutOverSun.r, 1.0, 0.05);
  EXPECT_NEAR(ringOverSun.g / lutOverSun.g, 1.0, 0.05);
}
