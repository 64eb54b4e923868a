// The Moon's shadow on Earth as the receivers' shading draws it (the airless shadow LuT the
// scene path asks for: sceneLutRange): the 2024-04-08 example scene from 150 000 km over the
// greatest eclipse, without its atmosphere, Lambert's law; per pixel the GPU's factor
// (radiance over the unshadowed radiance) against eclipse::eclipseFactor computed exactly
// at the same ground point, and the umbra's pixels (factor below 1e-3) counted both ways, at the
// LuT sizes a scene can ask for. The umbra is 197 km wide there: 18 pixels of this 240-pixel
// view. The scene's ranged LuT resolves it from 256 rows (the example's size): the factor
// within 2e-4 of the exact one everywhere, the pixels darker than 1e-3 the same to 4 % (those at the umbra's edge within the
// factor's 2e-4 of the threshold go either way);
// at 64 rows the factor is within 5e-3 but the umbra is not black (a quarter of its
// pixels below 1e-3).
#include "AtmosphereShadow.h"
#include "RenderTestSupport.hpp"
#include "SceneInputs.h"

#include "ShadowLut.hpp"
#include "scene/Scene.hpp"
#include "vtkEclipseShadowLutSource.h"

#include <vtkImageData.h>
#include <vtkNew.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

using namespace umbra::pipeline;

using namespace umbra;
using namespace umbra::render;
using namespace umbra::render::test;

namespace {

constexpr int kImage = 240;

struct UmbraAgreement {
  int pixels = 0, umbraGpu = 0, umbraExact = 0, penumbra = 0;
  double maxDiff = 0.0;
};

UmbraAgreement renderAndCompare(int lutSize) {
  const scene::Scene s = scene::loadScene(UMBRA_SOURCE_DIR "/examples/scenes/solar-eclipse-2024-04-08-from-space.json");
  SceneInputs in = sceneInputs(s);
  for (SphereBody& b : in.bodies) b.photometry = {};
  const auto earthIt = std::find_if(in.bodies.begin(), in.bodies.end(), [](const SphereBody& b) { return b.name == "Earth"; });
  const auto moonIt = std::find_if(in.bodies.begin(), in.bodies.end(), [](const SphereBody& b) { return b.name == "Moon"; });
  const SphereBody earth = *earthIt, moon = *moonIt;
  const auto range = sceneLutRange(in.sun, in.bodies, in.bodies, true, lutSize);
  vtkNew<vtkEclipseShadowLutSource> source;
  source->UseCacheOff();
  source->SetHeight(lutSize);
  source->SetWidth(range ? rangedLutWidth(*range, lutSize) : lutSize);
  if (range) source->SetLutRange(*range);
  source->Update();

  BodyView view(kImage, kImage, true);
  useSharedDisplay(view.GetRenderWindow());
  view.SetBodies(in.sun, in.bodies, source->GetOutput());
  const ViewCamera& camera = in.camera;
  const std::vector<float> hdr = renderHdr(view, camera);
  const int w = kImage, h = kImage;

  UmbraAgreement a;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const Ray ray = pixelRay(camera, w, h, i, j);
      const auto hit = hitSphere(ray, earth.centreM, earth.radiusM);
      if (!hit) continue;
      double cosi = 0.0;
      const double unshadowed = unshadowedRadiance(*hit, earth.centreM, 1.0, in.sun, &cosi);
      if (cosi < 0.2) continue;
      const double exact = eclipse::eclipseFactor(*hit, in.sun.positionM, in.sun.radiusM, occluderOf(occluderSeenBy(moon, earth)), nullptr).g;
      const double gpu = hdr[3 * (static_cast<std::size_t>(j) * w + i) + 1] / (earth.albedoRgb.g * unshadowed);
      ++a.pixels;
      if (gpu < 1e-3) ++a.umbraGpu;
      if (exact < 1e-3) ++a.umbraExact;
      if (exact > 0.0 && exact < 1.0) ++a.penumbra;
      a.maxDiff = std::max(a.maxDiff, std::abs(gpu - exact));
    }
  return a;
}

}  // namespace

TEST(SceneMoonShadow, TheUmbraOnEarthThroughTheLutAgainstTheExactFactor) {
  for (int size : {64, 256, 1024}) {
    const UmbraAgreement a = renderAndCompare(size);
    std::printf("  LuT %4d: %d pixels on the ground, umbra %d (exact %d), max |GPU - exact| %.4f\n", size, a.pixels,
                a.umbraGpu, a.umbraExact, a.maxDiff);
    EXPECT_GT(a.pixels, 40000);
    EXPECT_GT(a.umbraExact, 200);
    EXPECT_GT(a.penumbra, 40000);
    if (size >= 256) {
      EXPECT_LT(a.maxDiff, 5e-4) << size;
      EXPECT_NEAR(a.umbraGpu, a.umbraExact, 0.04 * a.umbraExact) << size;
    } else {
      EXPECT_LT(a.maxDiff, 1e-2);
      EXPECT_LT(a.umbraGpu, a.umbraExact / 2);
    }
  }
}
