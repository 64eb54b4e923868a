// The eclipse through Earth's atmosphere in the renderer (eclipse paper, 5.4): the Moon in
// Earth's umbra shaded with the atmospheric shadow LuT (AtmosphereShadow + EclipseShading),
// computed only for the u columns the Moon can be in. The GPU's factor per channel against
// the CPU lookup (eclipse/ShadowLut.cpp eclipseFactor) in a table holding only those
// columns (the others NaN: a lookup that strays outside them fails), and the colour of
// the umbra: copper (R > G > B).
#include "AtmosphereShadow.h"
#include "RenderTestSupport.hpp"
#include "SceneInputs.h"

#include "Atmosphere.hpp"
#include "Spectrum.hpp"
#include "vtkEclipseShadowLutSource.h"

#include <vtkNew.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <vector>

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

// The part of the table the source computed, in a whole-size CPU table (NaN elsewhere).
eclipse::ShadowLut cpuTable(vtkImageData* image) {
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
    in.atmosphere = SceneAtmosphere{"Earth", "earth"};
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
  const eclipse::Occluder earth{s.in.bodies[0].centreM, s.in.bodies[0].radiusM};
  int samples = 0, umbra = 0;
  double maxRel = 0.0;
  for (int j = 2; j < s.height; j += 4) {
    for (int i = 2; i < s.width; i += 4) {
      const Ray ray = pixelRay(s.in.camera, s.width, s.height, i, j);
      const auto hit = hitSphere(ray, s.moon.centreM, s.moon.radiusM);
      if (!hit) continue;
      const glm::dvec3 n = glm::normalize(*hit - s.moon.centreM);
      if (-glm::dot(n, ray.dir) < 0.3) continue;
      double cosi = 0.0;
      const double unshadowed = unshadowedRadiance(*hit, s.moon.centreM, s.moon.albedoRgb.r, s.in.sun, &cosi);
      if (cosi < 0.05) continue;
      const glm::dvec3 expected = eclipse::eclipseFactor(*hit, s.in.sun.positionM, s.in.sun.radiusM, earth, &cpu);
      for (int c = 0; c < 3; ++c) {
        ASSERT_TRUE(std::isfinite(expected[c])) << "the CPU lookup left the computed columns at pixel " << i << ", " << j;
        const double gpu = s.hdr[3 * (static_cast<std::size_t>(j) * s.width + i) + c] / unshadowed;
        // Relative (the umbra spans orders of magnitude); GL's filter weights are 8-bit.
        const double rel = std::abs(gpu - expected[c]) / std::max(expected[c], 1e-7);
        maxRel = std::max(maxRel, rel);
        EXPECT_LT(rel, 0.02) << "pixel (" << i << ", " << j << ") channel " << c << ": GPU " << gpu << ", CPU "
                             << expected[c];
      }
      ++samples;
      if (expected.r < 0.01) ++umbra;
    }
  }
  std::printf("  columns %d..%d of %d, %d samples (%d in the umbra), max relative |GPU - CPU| = %.3g\n",
              s.columns[0], s.columns[1], kLutWidth, samples, umbra, maxRel);
  RecordProperty("max_rel_factor_difference", std::to_string(maxRel));
  EXPECT_GE(samples, 200);
  EXPECT_GE(umbra, 50);
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
