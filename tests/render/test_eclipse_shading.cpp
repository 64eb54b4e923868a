// The eclipse shadow as the GPU renders it (EclipseShading + eclipse/glsl/EclipseShadow.glsl)
// against the CPU reference (eclipse/ShadowLut.cpp eclipseFactor with the same LuT), pixel
// by pixel: the shadow factors must agree within 1e-3.
#include "RenderTestSupport.hpp"

#include <vtkLight.h>
#include <vtkNew.h>
#include <vtkRenderer.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace umbra;
using namespace umbra::render;
using namespace umbra::render::test;

namespace {

struct AgreementStats {
  int samples = 0, umbra = 0, penumbra = 0, outside = 0;
  double maxDiff = 0.0;
};

// Renders `bodies` seen by `camera` and compares the shadow factor of `receiver` at every
// `step`-th pixel with the CPU. Pixels near the receiver's limb (cos of the view angle
// < 0.3, where the polygonal silhouette differs from the sphere) and pixels where the
// Sun grazes (cos i < 0.05) are skipped.
AgreementStats compareWithCpu(const SunLight& sun, const std::vector<SphereBody>& bodies,
                              const SphereBody& receiver, const ViewCamera& camera, int size, int step,
                              bool withVtkLight = false, const eclipse::ShadowLut& lut = testLut(),
                              double bound = 1e-3) {
  BodyView view(size, size, true);
  useSharedDisplay(view.GetRenderWindow());
  view.SetBodies(sun, bodies, filters::toImageData(lut));
  if (withVtkLight) {  // VTK then builds the lit variant of the receiver's shaders
    vtkNew<vtkLight> light;
    light->SetLightTypeToHeadlight();
    view.GetRenderer()->AddLight(light);
  }
  const std::vector<float> hdr = renderHdr(view, camera);
  const int w = size, h = size;
  EXPECT_EQ(hdr.size(), 3u * static_cast<std::size_t>(w) * h);

  std::vector<eclipse::Occluder> occluders;
  for (const SphereBody& b : bodies) {
    if (b.name != receiver.name) occluders.push_back({b.centreM, b.radiusM});
  }
  AgreementStats s;
  for (int j = step / 2; j < h; j += step) {
    for (int i = step / 2; i < w; i += step) {
      const Ray ray = pixelRay(camera, w, h, i, j);
      const auto hit = hitSphere(ray, receiver.centreM, receiver.radiusM);
      if (!hit) continue;
      const glm::dvec3 n = glm::normalize(*hit - receiver.centreM);
      if (-glm::dot(n, ray.dir) < 0.3) continue;
      double cosi = 0.0;
      const double unshadowed = unshadowedRadiance(*hit, receiver.centreM, receiver.albedoRgb.r, sun, &cosi);
      if (cosi < 0.05) continue;
      double expected = 1.0;
      for (const auto& occ : occluders) {
        expected *= eclipse::eclipseFactor(*hit, sun.positionM, sun.radiusM, occ, &lut).r;
      }
      const double gpu = hdr[3 * (static_cast<std::size_t>(j) * w + i)] / unshadowed;
      const double diff = std::abs(gpu - expected);
      s.maxDiff = std::max(s.maxDiff, diff);
      EXPECT_LT(diff, bound) << "pixel (" << i << ", " << j << "): GPU factor " << gpu << ", CPU " << expected;
      ++s.samples;
      if (expected < 0.05) ++s.umbra;
      else if (expected < 0.95) ++s.penumbra;
      else if (expected > 0.999) ++s.outside;
    }
  }
  std::printf("  %d samples (umbra %d, penumbra %d, outside %d), max |GPU - CPU| = %.3g\n", s.samples,
              s.umbra, s.penumbra, s.outside, s.maxDiff);
  return s;
}

SunLight sunAtMinusOneAu() {
  SunLight sun;
  sun.positionM = {-kAu, 0.0, 0.0};
  return sun;
}

SphereBody earth() { return {"Earth", {0.0, 0.0, 0.0}, kEarthRadius, {0.3, 0.3, 0.3}}; }

} // namespace

// The brief's scene: Earth's shadow on a screen across the axis at the Moon's distance
// (the sunward pole of a 20 000 km sphere at x = 384 400 km), parallel view along the axis.
TEST(EclipseShading, CpuGlslAgreementParallelAxisView) {
  const SunLight sun = sunAtMinusOneAu();
  const double screenR = 2.0e7;
  const SphereBody screen{"Screen", {kMoonDistance + screenR, 0.0, 0.0}, screenR, {0.5, 0.5, 0.5}};
  ViewCamera cam;
  cam.positionM = {kMoonDistance - 5.0e7, 0.0, 0.0};
  cam.targetM = screen.centreM;
  cam.up = {0.0, 0.0, 1.0};
  cam.parallel = true;
  cam.parallelScaleM = 1.0e7;
  const AgreementStats s = compareWithCpu(sun, {earth(), screen}, screen, cam, 256, 6);
  RecordProperty("max_abs_factor_difference", std::to_string(s.maxDiff));
  EXPECT_GE(s.samples, 200);
  EXPECT_GE(s.umbra, 20);
  EXPECT_GE(s.penumbra, 50);
  EXPECT_GE(s.outside, 20);
}

// The same screen in perspective, from inside the shadow 30 000 km in front of it,
// slightly off-axis.
TEST(EclipseShading, CpuGlslAgreementPerspective) {
  const SunLight sun = sunAtMinusOneAu();
  const double screenR = 2.0e7;
  const SphereBody screen{"Screen", {kMoonDistance + screenR, 0.0, 0.0}, screenR, {0.5, 0.5, 0.5}};
  ViewCamera cam;
  cam.positionM = {kMoonDistance - 3.0e7, 1.5e6, -1.0e6};
  cam.targetM = {kMoonDistance, 0.0, 0.0};
  cam.up = {0.0, 0.0, 1.0};
  cam.fovDeg = 40.0;
  const AgreementStats s = compareWithCpu(sun, {earth(), screen}, screen, cam, 256, 6);
  RecordProperty("max_abs_factor_difference", std::to_string(s.maxDiff));
  EXPECT_GE(s.samples, 200);
  EXPECT_GE(s.umbra, 20);
  EXPECT_GE(s.penumbra, 50);
  EXPECT_GE(s.outside, 20);
}

// A Moon across the umbra's edge at the zenith of an observer 1 km above Earth's night
// side, 3.8e8 m away through a 0.6 degree field: float precision must hold with the
// camera far from the receiver.
TEST(EclipseShading, CpuGlslAgreementMoonFromEarth) {
  const SunLight sun = sunAtMinusOneAu();
  const SphereBody moon{"Moon", {kMoonDistance, 5.0e6, 0.0}, 1.7374e6, {0.12, 0.12, 0.12}};
  ViewCamera cam;
  cam.positionM = {kEarthRadius + 1000.0, 0.0, 0.0};
  cam.targetM = moon.centreM;
  cam.up = {0.0, 0.0, 1.0};
  cam.fovDeg = 0.6;
  const AgreementStats s = compareWithCpu(sun, {earth(), moon}, moon, cam, 256, 4);
  RecordProperty("max_abs_factor_difference", std::to_string(s.maxDiff));
  EXPECT_GE(s.samples, 200);
  EXPECT_GE(s.umbra, 20);
  EXPECT_GE(s.penumbra, 50);
}

// Several occluders multiply: a second, smaller body between Earth and the screen.
TEST(EclipseShading, CpuGlslAgreementTwoOccluders) {
  const SunLight sun = sunAtMinusOneAu();
  const double screenR = 2.0e7;
  const SphereBody screen{"Screen", {kMoonDistance + screenR, 0.0, 0.0}, screenR, {0.5, 0.5, 0.5}};
  const SphereBody rock{"Rock", {2.0e8, 6.0e6, 0.0}, 1.2e6, {0.2, 0.2, 0.2}};
  ViewCamera cam;
  cam.positionM = {kMoonDistance - 5.0e7, 0.0, 0.0};
  cam.targetM = screen.centreM;
  cam.up = {0.0, 0.0, 1.0};
  cam.parallel = true;
  cam.parallelScaleM = 1.0e7;
  const AgreementStats s = compareWithCpu(sun, {earth(), rock, screen}, screen, cam, 256, 6);
  EXPECT_GE(s.samples, 200);
  EXPECT_GE(s.penumbra, 50);
}

// VTK's lights play no part in the receiver's shading, but they change the shader VTK
// builds around it (lit actors declare more camera matrices): same result with a light.
TEST(EclipseShading, CpuGlslAgreementWithVtkLightInRenderer) {
  const SunLight sun = sunAtMinusOneAu();
  const double screenR = 2.0e7;
  const SphereBody screen{"Screen", {kMoonDistance + screenR, 0.0, 0.0}, screenR, {0.5, 0.5, 0.5}};
  ViewCamera cam;
  cam.positionM = {kMoonDistance - 3.0e7, 1.5e6, -1.0e6};
  cam.targetM = {kMoonDistance, 0.0, 0.0};
  cam.up = {0.0, 0.0, 1.0};
  cam.fovDeg = 40.0;
  const AgreementStats s = compareWithCpu(sun, {earth(), screen}, screen, cam, 128, 4, true);
  EXPECT_GE(s.samples, 200);
  EXPECT_GE(s.penumbra, 50);
}

// A ranged LuT (u over Phobos' distances, v from the umbra's edge: lutRangeForDistances)
// read by the renderer through its field data (umbraShadowLutURange, VRange): Mars' shadow
// on Phobos as the CPU's eclipse factor with the same LuT, within 1e-3. Phobos is put at
// the shadow's edge (Mars' radius off the axis), 9376 km behind Mars, seen from the Sun's side.
TEST(EclipseShading, RangedLutAtPhobosAgreesWithTheCpu) {
  SunLight sun;
  sun.positionM = {-2.2794e11, 0.0, 0.0};
  const double marsRadiusM = 3389.5e3, phobosRadiusM = 11.1e3, phobosDistanceM = 9376e3;
  const SphereBody mars{"Mars", {0.0, 0.0, 0.0}, marsRadiusM, {0.25, 0.25, 0.25}};
  const SphereBody phobos{"Phobos", {phobosDistanceM, marsRadiusM, 0.0}, phobosRadiusM, {0.07, 0.07, 0.07}};
  const eclipse::LutRange r = eclipse::lutRangeForDistances({sun.radiusM, marsRadiusM, -sun.positionM.x},
                                                            phobosDistanceM - phobosRadiusM,
                                                            1.01 * (phobosDistanceM + phobosRadiusM), true, 64);
  ASSERT_GT(r.uMin, 0.0);
  const eclipse::ShadowLut lut =
      eclipse::buildAirlessShadowLut({64, 64, eclipse::kDefaultLimbDarkening, 1e-10, r.uMin, r.uMax, r.vMin, r.vMax});
  ViewCamera cam;
  cam.positionM = phobos.centreM + glm::dvec3(-200e3, 0.0, 0.0);
  cam.targetM = phobos.centreM;
  cam.up = {0.0, 0.0, 1.0};
  cam.fovDeg = 2.0 * std::atan(phobosRadiusM / 200e3) * 180.0 / 3.14159265358979 * 1.1;
  const AgreementStats s = compareWithCpu(sun, {mars, phobos}, phobos, cam, 128, 4, false, lut, 1e-3);
  RecordProperty("max_abs_factor_difference", std::to_string(s.maxDiff));
  EXPECT_GE(s.samples, 200);
  EXPECT_GE(s.penumbra + s.umbra, 50);  // the shadow crosses Phobos
}
