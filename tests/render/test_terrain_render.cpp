// The terrain patch in the renderer (render::TerrainRendering): the pre-displaced mesh,
// the view-ray refinement and the GLSL DP search, against the CPU. For sampled pixels of
// the HDR buffer: the surface point the GPU found lies on the pixel's view ray (so the
// refinement found the bilinear surface, not the mesh facet); the visible fraction there
// equals terrain::horizonTowardsSunAt (the CPU DP at the same surface point); the
// radiance is albedo / pi * E * cos i * fraction. From orbit (30 km) and from 2 m.
#include "RenderTestSupport.hpp"
#include "TerrainRendering.h"
#include "vtkUmbraRenderPass.h"

#include "CraterField.hpp"
#include "scene/Scene.hpp"
#include "scene/Time.hpp"

#include <vtkActor.h>
#include <vtkActorCollection.h>
#include <vtkCamera.h>
#include <vtkMapper.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <gtest/gtest.h>

#include <cstdio>

using namespace umbra;
using render::test::kPi;

namespace {

struct Frame {
  std::vector<float> rgba;  // row 0 = bottom
  int width = 0, height = 0;
};

struct TerrainScene {
  terrain::HeightField field;
  render::SunLight sun;
  render::TerrainRendering terrain;

  TerrainScene(int meshStep) {
    terrain::CraterFieldOptions o;
    o.size = 129;
    o.seed = 11;
    field = terrain::makeCraterField(o);
    render::TerrainPatch patch;
    patch.field = field;
    patch.meshStep = meshStep;
    patch.albedoRgb = glm::dvec3(0.12, 0.11, 0.10);
    terrain.SetTerrain(patch);
    // The Sun 3 degrees above the tangent plane, from the south-east.
    const glm::dvec3 l = terrain::sunDirectionFromElevationAzimuth(3.0 * kPi / 180.0, 135.0 * kPi / 180.0);
    sun.positionM = glm::dvec3(0.0, 0.0, field.bodyRadiusM) + render::test::kAu * l;
    terrain.SetSun(sun);
  }

  /// The shadow table for the present Sun, rounded to the default step.
  void useShadowTable() {
    const terrain::SunDisc sun = terrain::roundedSun(terrain.GetSunDisc(), terrain::kDefaultSunStepRad);
    terrain.SetShadowTable(std::make_shared<terrain::ShadowTable>(
        terrain::makeShadowTable(field, terrain.GetMipmap(), sun, terrain::ShadowOptions{})));
  }

  /// World (= tangent frame here) surface point at grid coordinates g.
  glm::dvec3 surface(glm::dvec2 g) const { return (field.bodyRadiusM + field.bilinear(g.x, g.y)) * field.direction(g.x, g.y); }

  /// The two frames (GridAndFraction, Radiance) of one view, in one window.
  std::pair<Frame, Frame> render(const render::ViewCamera& c, int w, int h) {
    vtkNew<vtkRenderWindow> window;
    window->SetOffScreenRendering(1);
    window->SetSize(w, h);
    render::test::useSharedDisplay(window);
    vtkNew<vtkRenderer> renderer;
    window->AddRenderer(renderer);
    vtkNew<vtkUmbraRenderPass> pass;
    renderer->SetPass(pass);
    terrain.SetOrigin(c.positionM);  // camera-relative
    renderer->AddActor(terrain.GetActor());
    vtkCamera* cam = renderer->GetActiveCamera();
    cam->SetPosition(0.0, 0.0, 0.0);
    const glm::dvec3 f = c.targetM - c.positionM;
    cam->SetFocalPoint(f.x, f.y, f.z);
    cam->SetViewUp(c.up.x, c.up.y, c.up.z);
    cam->SetViewAngle(c.fovDeg);
    cam->SetClippingRange(0.1, 1e6);
    std::pair<Frame, Frame> frames;
    for (Frame* frame : {&frames.first, &frames.second}) {
      terrain.SetOutput(frame == &frames.first ? render::TerrainRendering::Output::GridAndFraction
                                               : render::TerrainRendering::Output::Radiance);
      window->Render();
      EXPECT_TRUE(pass->ReadHdrPixels(frame->rgba, frame->width, frame->height));
    }
    renderer->RemoveActor(terrain.GetActor());
    terrain.GetActor()->ReleaseGraphicsResources(window);
    return frames;
  }
};

struct Stats {
  int pixels = 0, umbra = 0, lit = 0, fractionOff = 0, radianceOff = 0;
  double maxRayGap = 0.0  /* relative to the distance */, meanFractionDiff = 0.0;
};

Stats check(TerrainScene& s, const render::ViewCamera& c) {
  const int W = 96, H = 72;
  // The facet point VTK rasterises is within the rasteriser's sub-pixel precision of the
  // pixel centre's ray (llvmpipe: ~1/100 pixel); the mesh vertices are metres off the
  // bilinear surface (mesh step 4, or between samples' rims), so only the refinement
  // brings the point this close to the ray.
  const double rayTolerance = 0.05 * (c.fovDeg * kPi / 180.0) / H;
  const auto [grid, radiance] = s.render(c, W, H);
  const terrain::SunDisc disc = s.terrain.GetSunDisc();
  const terrain::ShadowOptions dp;
  const double E = s.terrain.GetSunIrradiance();
  Stats st;
  for (int row = 0; row < H; ++row)
    for (int i = 0; i < W; ++i) {
      const float* p = &grid.rgba[4 * (static_cast<std::size_t>(row) * W + i)];
      const float* q = &radiance.rgba[4 * (static_cast<std::size_t>(row) * W + i)];
      EXPECT_TRUE(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]) && std::isfinite(q[0]));
      if (p[3] < 0.5f) continue;  // background
      ++st.pixels;
      const glm::dvec2 g(p[0], p[1]);
      // On the view ray through the pixel centre.
      const render::test::Ray ray = render::test::pixelRay(c, W, H, i, H - 1 - row);
      const glm::dvec3 d = s.surface(g) - ray.origin;
      st.maxRayGap = std::max(st.maxRayGap, glm::length(d - glm::dot(d, ray.dir) * ray.dir) / glm::length(d));
      // The CPU DP at that surface point, or the CPU's lookup in the same shadow table.
      const terrain::ShadowTable* table = s.terrain.GetShadowTable();
      const double cpu =
          table ? table->fractionAt(s.field, s.terrain.GetMipmap(), g)
                : terrain::discFractionAboveHorizon(
                      terrain::horizonTowardsSunAt(s.field, s.terrain.GetMipmap(), g, s.field.bilinear(g.x, g.y), disc, dp),
                      disc);
      const double diff = std::abs(cpu - p[2]);
      st.meanFractionDiff += diff;
      st.fractionOff += diff > 0.01;
      st.umbra += cpu < 0.01;
      st.lit += cpu > 0.99;
      // Lambertian radiance with the bilinear surface's normal (central differences).
      const glm::dvec3 n = glm::normalize(glm::cross(s.surface(g + glm::dvec2(0.5, 0)) - s.surface(g - glm::dvec2(0.5, 0)),
                                                     s.surface(g + glm::dvec2(0, 0.5)) - s.surface(g - glm::dvec2(0, 0.5))));
      const double cosi = std::max(0.0, glm::dot(n, glm::normalize(disc.direction)));
      const double expected = 0.12 / kPi * E * cosi * p[2];
      const bool off = std::abs(q[0] - expected) > 1e-3 * 0.12 / kPi * E + 1e-3 * expected;
      st.radianceOff += off;
    }
  st.meanFractionDiff /= std::max(1, st.pixels);
  std::printf("  %d terrain pixels (%d umbra, %d lit): max angle from the pixel's ray %.2g rad, fraction off by > 0.01 at %d "
              "(mean |GPU - CPU| %.2g), radiance off at %d\n",
              st.pixels, st.umbra, st.lit, st.maxRayGap, st.fractionOff, st.meanFractionDiff, st.radianceOff);
  EXPECT_GT(st.pixels, W * H / 3);
  EXPECT_LT(st.maxRayGap, rayTolerance);
  EXPECT_LE(st.fractionOff, st.pixels / 200);  // single against double precision at shadow edges
  EXPECT_LT(st.meanFractionDiff, 2e-3);
  EXPECT_LE(st.radianceOff, st.pixels / 200);
  return st;
}

/// 30 km up, looking down at the patch's centre at a slant.
render::ViewCamera orbitCamera(const TerrainScene& s) {
  render::ViewCamera c;
  const glm::dvec3 centre(0.0, 0.0, s.field.bodyRadiusM);
  c.positionM = centre + glm::dvec3(-8e3, -12e3, 26e3);
  c.targetM = centre;
  c.up = glm::dvec3(0.0, 0.0, 1.0);
  c.up = glm::normalize(c.up - glm::dot(c.up, glm::normalize(c.targetM - c.positionM)) * glm::normalize(c.targetM - c.positionM));
  c.fovDeg = 9.0;
  return c;
}

} // namespace

TEST(TerrainRender, FromOrbitTheGpuMatchesTheCpu) {
  TerrainScene s(4);  // a coarse mesh: the view-ray refinement must find the surface between its vertices
  const Stats st = check(s, orbitCamera(s));
  EXPECT_GT(st.umbra, 100);
  EXPECT_GT(st.lit, 100);
}

// With a shadow table, the GLSL lookup (the near search and the table's far horizon)
// against the CPU's (terrain::ShadowTable::fractionAt) at the same surface points.
TEST(TerrainRender, FromOrbitTheGpuTableLookupMatchesTheCpu) {
  TerrainScene s(4);
  s.useShadowTable();
  const Stats st = check(s, orbitCamera(s));
  EXPECT_GT(st.umbra, 100);
  EXPECT_GT(st.lit, 100);
}

TEST(TerrainRender, FromTwoMetresTheGpuMatchesTheCpu) {
  TerrainScene s(1);
  render::ViewCamera c;
  // Stand in the umbra, in a shadow that reaches on to the north.
  glm::dvec2 g0(-1.0);
  const terrain::ShadowOptions dp;
  for (int j = 20; j < 80 && g0.x < 0.0; ++j)
    for (int i = 30; i < 100 && g0.x < 0.0; ++i)
      if (terrain::visibleFraction(s.field, s.terrain.GetMipmap(), i, j, s.terrain.GetSunDisc(), dp) == 0.0 &&
          terrain::visibleFraction(s.field, s.terrain.GetMipmap(), i, j + 8, s.terrain.GetSunDisc(), dp) == 0.0)
        g0 = glm::dvec2(i + 0.3, j + 0.4);
  ASSERT_GE(g0.x, 0.0);
  const glm::dvec3 up = s.field.direction(g0.x, g0.y);
  c.positionM = s.surface(g0) + 2.0 * up;
  const glm::dvec3 north = glm::normalize(glm::dvec3(0.0, 1.0, 0.0) - up.y * up);
  const glm::dvec3 fwd = glm::normalize(north - 0.15 * up);
  c.targetM = c.positionM + 100.0 * fwd;
  c.up = glm::normalize(up - glm::dot(up, fwd) * fwd);
  c.fovDeg = 60.0;
  const Stats st = check(s, c);
  EXPECT_GT(st.umbra, 100);
  EXPECT_GT(st.lit, 100);
  // Below the horizon the ground fills the frame: none of it is lost because the camera,
  // 2 m up, is under a mesh interpolating steep 30 m cells (the mesh is lowered below the
  // surface).
  EXPECT_GT(st.pixels, 96 * 72 * 6 / 10);
}
