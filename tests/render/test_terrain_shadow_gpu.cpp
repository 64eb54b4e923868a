// The terrain soft shadow in GLSL (terrain/glsl/TerrainShadow.glsl, run by
// render::terrainShadowGpu) against the CPU DP search (terrain/SoftShadow.cpp), sample by
// sample on a synthetic crater field and on the bare sphere.
#include "RenderTestSupport.hpp"
#include "TerrainShadowGpu.h"

#include "CraterField.hpp"

#include <vtkNew.h>
#include <vtkRenderWindow.h>

#include <gtest/gtest.h>

#include <cstdio>

using namespace umbra;

namespace {

struct Agreement {
  int samples = 0, penumbra = 0;
  double maxDiff = 0.0, meanDiff = 0.0;
};

Agreement compare(const terrain::HeightField& f, const terrain::SunDisc& sun) {
  const terrain::MaximumMipmap mip(f);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(64, 64);
  render::test::useSharedDisplay(window);
  const render::GpuTerrainShadow gpu = render::terrainShadowGpu(window, f, mip, sun, 6);
  terrain::ShadowOptions dp;
  Agreement a;
  for (int j = 0; j < f.height; ++j)
    for (int i = 0; i < f.width; ++i) {
      const double cpu = terrain::visibleFraction(f, mip, i, j, sun, dp);
      const double diff = std::abs(gpu.fraction[j * f.width + i] - cpu);
      a.maxDiff = std::max(a.maxDiff, diff);
      a.meanDiff += diff;
      ++a.samples;
      a.penumbra += cpu > 0.01 && cpu < 0.99;
    }
  a.meanDiff /= a.samples;
  std::printf("  %d samples (%d in the penumbra): max |GPU - CPU| = %.3g, mean %.3g\n", a.samples, a.penumbra,
              a.maxDiff, a.meanDiff);
  return a;
}

} // namespace

TEST(TerrainShadowGpu, AgreesWithTheCpuOnACraterField) {
  terrain::CraterFieldOptions o;
  o.size = 96;
  o.seed = 5;
  const terrain::HeightField f = terrain::makeCraterField(o);
  for (double azimuthDeg : {30.0, 200.0}) {
    terrain::SunDisc sun;
    sun.direction = terrain::sunDirectionFromElevationAzimuth(2.0 * render::test::kPi / 180.0,
                                                              azimuthDeg * render::test::kPi / 180.0);
    const Agreement a = compare(f, sun);
    // Single precision against double: 4e-4 at most was measured (mean 6e-6).
    EXPECT_LT(a.maxDiff, 1e-3);
    EXPECT_LT(a.meanDiff, 1e-4);
    EXPECT_GT(a.penumbra, 200);
  }
}

TEST(TerrainShadowGpu, FlatSphereIsTheSegmentAboveTheHorizon) {
  terrain::HeightField f;
  f.width = f.height = 64;
  f.heightsM.assign(64 * 64, 0.0);
  for (double eDeg : {-0.2, 0.0, 0.15}) {
    terrain::SunDisc sun;
    sun.limbDarkening = 0.6;
    sun.direction = terrain::sunDirectionFromElevationAzimuth(eDeg * render::test::kPi / 180.0, 1.0);
    const Agreement a = compare(f, sun);
    EXPECT_LT(a.maxDiff, 1e-3) << eDeg;
  }
}
