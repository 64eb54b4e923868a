// The sky of a solar eclipse in the render pass (AtmosphereRendering::SetEclipsingBodies):
// from inside the Moon's shadow the composite's sky pixels are the eclipsed-sky quadrature
// (atmosphere/EclipsedSky.hpp) looked up on its sky-view grid; against the CPU quadrature
// at the pixels' own directions, against the same view without the Moon (totality 3 to 4
// orders of magnitude darker), in a partial phase (the sky dims as the Sun at the camera),
// and the ground lit by the eclipsed sky.
#include "AtmosphereTestSupport.hpp"

#include "EclipsedSky.hpp"
#include "ShadowLut.hpp"
#include "ShadowLutData.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <memory>

namespace umbra::render::test {
namespace {

constexpr double kMoonRadiusM = 1737.4e3;
constexpr double kDeg = kPi / 180.0;

/// The observer 2 m above the fixture's north pole, the Sun 26.1 deg from the zenith
/// towards +x, the Moon `offsetM` off the observer-Sun line (towards -x, up the Sun's
/// vertical) at the distance that makes the umbra 114.7 km across through the observer
/// (2017-08-21); the Moon's visible fraction from a 256 x 256 LuT over the air's distances,
/// for the renderer's Sun (SunLight's radius).
struct EclipseSkyScene {
  double sunRadiusM = SunLight().radiusM;
  glm::dvec3 observer, sunM, moonM;
  std::shared_ptr<const eclipse::ShadowLut> lut;
  vtkSmartPointer<vtkImageData> lutImage;

  explicit EclipseSkyScene(double offsetM) {
    const double rb = atmosphereFixture().tables.bottomRadiusM;
    observer = {0.0, 0.0, rb + 2.0};
    const glm::dvec3 toSun = directionFromAngles(90.0 - 26.1, 0.0);
    sunM = observer + kAu * toSun;
    const double moonDistance = eclipse::occluderDistanceForUmbraM(kAu, sunRadiusM, kMoonRadiusM, 57.35e3);
    moonM = observer + moonDistance * toSun + offsetM * directionFromAngles(-26.1, 0.0) * -1.0;
    const eclipse::SunOccluderSystem system{sunRadiusM, kMoonRadiusM, glm::length(sunM - moonM)};
    const eclipse::LutRange range = eclipse::lutRangeForDistances(system, moonDistance - 3e6, moonDistance + 3e6, true);
    eclipse::ShadowLutParams p;
    p.uMin = range.uMin, p.uMax = range.uMax, p.vMin = range.vMin, p.vMax = range.vMax, p.vLowFraction = range.vLowFraction;
    lut = std::make_shared<const eclipse::ShadowLut>(eclipse::buildAirlessShadowLut(p));
    lutImage = filters::toImageData(*lut);
  }
  double visibleAt(const glm::dvec3& p) const {
    return eclipse::eclipseFactor(p, sunM, sunRadiusM, {moonM, kMoonRadiusM}, lut.get()).g;
  }
};

struct Rendered {
  std::vector<float> hdr;
  bool usedEclipsedSky = false;
};

/// Earth and its air (the fixture), the Sun, and the Moon when `withMoon`, seen from the
/// observer by `camera` (size x size).
Rendered render(const EclipseSkyScene& s, const ViewCamera& camera, int size, bool withMoon) {
  BodyView view(size, size, true);
  useSharedDisplay(view.GetRenderWindow());
  const AtmosphereFixture& f = atmosphereFixture();
  SunLight sun;
  sun.positionM = s.sunM;
  const SphereBody earth{"Earth", {0.0, 0.0, 0.0}, f.tables.bottomRadiusM, {0.1, 0.1, 0.1}};
  const SphereBody moon{"Moon", s.moonM, kMoonRadiusM, {0.12, 0.12, 0.12}};
  view.SetBodies(sun, withMoon ? std::vector<SphereBody>{earth, moon} : std::vector<SphereBody>{earth}, s.lutImage);
  AtmosphereRendering& atmo = view.GetAtmosphere();
  atmo.SetAtmosphere(f.model, f.tables, earth.centreM, earth.albedoRgb);
  atmo.SetEclipsedSkyOptions(atmosphere::draftEclipsedSkyOptions());
  Rendered out;
  out.hdr = renderHdr(view, camera);
  out.usedEclipsedSky = atmo.GetLastDrawUsedEclipsedSky();
  if (out.usedEclipsedSky) std::printf("  the eclipsed sky's grid: %.2f s\n", atmo.GetLastEclipsedSkySeconds());
  return out;
}

/// The frame's value of a sky radiance per unit irradiance (table channels): M E_sun L.
glm::dvec3 frameValue(const std::vector<double>& perUnit) {
  const glm::dmat3 m = atmosphereToDisplayMatrix(atmosphere::WavelengthSet::rgb().nm);
  const SunLight sun;
  return m * (glm::dvec3(perUnit[0], perUnit[1], perUnit[2]) * sun.irradianceAtWm2(kAu));
}

glm::dvec3 pixel(const std::vector<float>& hdr, int size, int i, int j) {
  const float* p = &hdr[3 * (static_cast<std::size_t>(j) * size + i)];
  return {p[0], p[1], p[2]};
}

TEST(EclipsedSkyRender, InTotalityTheSkyPixelsAreTheQuadratures) {
  // Pixels from 5 to 85 deg up, away from the Sun: the composite's value against the CPU
  // quadrature in the pixel's own direction (the grid's bilinear lookup and float: within
  // 2 %), and the same view without the Moon 3 to 4 orders of magnitude brighter overhead.
  const EclipseSkyScene s(0.0);
  ASSERT_EQ(s.visibleAt(s.observer), 0.0);
  const int size = 48;
  const ViewCamera camera = [&] {
    ViewCamera c = groundCamera(2.0, 45.0, 84.0);
    c.targetM = c.positionM + directionFromAngles(45.0, 180.0);
    return c;
  }();
  const Rendered eclipsed = render(s, camera, size, true);
  const Rendered clear = render(s, camera, size, false);
  EXPECT_TRUE(eclipsed.usedEclipsedSky);
  EXPECT_FALSE(clear.usedEclipsedSky);

  std::vector<glm::dvec3> directions;
  std::vector<std::pair<int, int>> at;
  for (int j = 2; j < size; j += 11)
    for (int i = 2; i < size; i += 11) {
      directions.push_back(pixelRay(camera, size, size, i, j).dir);
      at.emplace_back(i, j);
    }
  const AtmosphereFixture& f = atmosphereFixture();
  const atmosphere::SunVisibility visibility = [&](const glm::dvec3& p) { return s.visibleAt(p); };
  const atmosphere::EclipsedSky cpu = atmosphere::eclipsedSkyRadiance(
      f.tables, f.model, s.observer, directions, glm::normalize(s.sunM - s.observer), visibility, atmosphere::draftEclipsedSkyOptions());
  for (std::size_t k = 0; k < directions.size(); ++k) {
    const glm::dvec3 gpu = pixel(eclipsed.hdr, size, at[k].first, at[k].second);
    const glm::dvec3 expected = frameValue(cpu.radiance[k]);
    const double elevation = std::asin(directions[k].z) / kDeg;
    std::printf("  %.1f deg up: GPU %.4g %.4g %.4g, CPU %.4g %.4g %.4g\n", elevation, gpu.r, gpu.g, gpu.b, expected.r,
                expected.g, expected.b);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(gpu[c], expected[c], 0.02 * expected[c]) << elevation << " deg, channel " << c;
    const double ratio = pixel(clear.hdr, size, at[k].first, at[k].second).g / gpu.g;
    if (elevation > 60.0) {
      EXPECT_GT(ratio, 1e3) << elevation;
      EXPECT_LT(ratio, 3e4) << elevation;
    }
  }
}

TEST(EclipsedSkyRender, InAPartialPhaseTheSkyDimsAsTheSunAndTheGroundIsLitByIt) {
  // 1500 km off the axis the Moon leaves about half the Sun: the sky away from the Sun is
  // the uneclipsed sky times the visible fraction at the camera (within 10 %, as the
  // Monte-Carlo reference found), the ground in front by as much.
  const EclipseSkyScene s(1500e3);
  const double v = s.visibleAt(s.observer);
  ASSERT_GT(v, 0.2);
  ASSERT_LT(v, 0.8);
  const int size = 32;
  ViewCamera camera = groundCamera(2.0, 0.0, 60.0);
  camera.targetM = camera.positionM + directionFromAngles(0.0, 180.0);
  const Rendered partial = render(s, camera, size, true);
  const Rendered clear = render(s, camera, size, false);
  EXPECT_TRUE(partial.usedEclipsedSky);
  for (int j : {2, 8, 23, 29})  // sky rows 26, 16, ground rows
    for (int i : {4, 16, 28}) {
      const glm::dvec3 p = pixel(partial.hdr, size, i, j), c = pixel(clear.hdr, size, i, j);
      std::printf("  pixel %d,%d: partial / clear / visible fraction %.3f %.3f %.3f\n", i, j, p.r / c.r / v,
                  p.g / c.g / v, p.b / c.b / v);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(p[k] / c[k] / v, 1.0, 0.1) << i << "," << j << " channel " << k;
    }
}

TEST(EclipsedSkyRender, OutsideTheShadowOrAboveTheAirTheTablesDrawTheSky) {
  // The Moon's shadow far away: the tables' sky (the grid not used), the same image as
  // without the Moon.
  const EclipseSkyScene s(2.0e7);
  ASSERT_EQ(s.visibleAt(s.observer), 1.0);
  const ViewCamera camera = groundCamera(2.0, 20.0, 60.0);
  const Rendered far = render(s, camera, 16, true);
  const Rendered none = render(s, camera, 16, false);
  EXPECT_FALSE(far.usedEclipsedSky);
  for (std::size_t k = 0; k < far.hdr.size(); ++k) ASSERT_EQ(far.hdr[k], none.hdr[k]) << k;
}

}  // namespace
}  // namespace umbra::render::test
