// The atmosphere in the render pass at the extremes (camera 1 m above the ground, on the
// top boundary, 1 au away; the Sun on the horizon, the Sun behind the planet) and what a
// sky must look like (bluer at the zenith than at the horizon at noon, a reddened Sun
// low down), on the HDR frame with the display colour matrix.
#include "DiscExtent.hpp"
#include "Colour.hpp"
#include "AtmosphereTestSupport.hpp"

#include "Refraction.hpp"
#include "SightLines.hpp"

#include "vtkUmbraRenderPass.h"

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>
#include <vtk_glew.h>

#include <cmath>

#include <algorithm>
#include <cstdio>

using namespace umbra::pipeline;  // the scene glue (app/pipeline)

using namespace umbra;
using namespace umbra::render;
using namespace umbra::render::test;
using umbra::colour::luminance;

namespace {

struct Frame {
  std::vector<float> rgb;
  int w = 0, h = 0;
  glm::dvec3 at(int i, int j) const {  // j from the top
    const float* p = &rgb[3 * (static_cast<std::size_t>(j) * w + i)];
    return {p[0], p[1], p[2]};
  }
  /// Rows (or columns) that are black in every channel from edge to edge.
  int blackRows() const {
    int n = 0;
    for (int j = 0; j < h; ++j) {
      bool black = true;
      for (int i = 0; i < w && black; ++i) black = glm::length(at(i, j)) == 0.0;
      n += black;
    }
    return n;
  }
};

// Renders; ReadHdr throws on any non-finite value.
Frame renderFrame(const ViewCamera& cam, const glm::dvec3& sunDir, int size = 64) {
  AtmosphereScene scene(size, cam, sunDir);
  scene.view.Render();
  Frame f;
  scene.view.ReadHdr(f.rgb, f.w, f.h);
  return f;
}

double blueOverRed(const glm::dvec3& c) { return c.b / c.r; }

} // namespace

// 1 m above the ground, the Sun's centre exactly on the (geometric) horizon, looking at it.
TEST(AtmosphereRender, OneMetreUpSunOnTheHorizon) {
  const Frame f = renderFrame(groundCamera(1.0, 0.0, 4.0), directionFromAngles(0.0, 0.0));
  EXPECT_EQ(f.blackRows(), 0);
  for (int j = 0; j < f.h / 2 - 1; ++j)  // the sky, above the horizon
    for (int i = 0; i < f.w; ++i) EXPECT_GT(f.at(i, j).r, 0.0) << i << ", " << j;
  // The Sun's half disc at the centre outshines the sky beside it.
  EXPECT_GT(luminance(f.at(f.w / 2, f.h / 2 - 1)), 10.0 * luminance(f.at(f.w / 8, f.h / 2 - 1)));
}

// On the top boundary, looking down at the limb 20 degrees below the horizontal.
TEST(AtmosphereRender, CameraOnTheTopBoundary) {
  const double top = atmosphereFixture().tables.topRadiusM - atmosphereFixture().tables.bottomRadiusM;
  const Frame f = renderFrame(groundCamera(top, -15.0, 30.0), directionFromAngles(40.0, 30.0));
  EXPECT_EQ(f.blackRows(), 0);
  EXPECT_GT(luminance(f.at(f.w / 2, f.h - 1)), 0.0);  // the lit ground below
}

// 1 au from Earth (the Sun beside the camera): Earth is a few pixels wide and lit.
TEST(AtmosphereRender, CameraOneAuAway) {
  ViewCamera cam;
  cam.positionM = {kAu, 0.0, 0.0};
  cam.targetM = {0.0, 0.0, 0.0};
  cam.up = {0.0, 0.0, 1.0};
  cam.fovDeg = 0.02;  // Earth's diameter: 0.0049 degrees
  const Frame f = renderFrame(cam, directionFromAngles(0.0, 10.0));
  const glm::dvec3 centre = f.at(f.w / 2, f.h / 2);
  EXPECT_GT(luminance(centre), 1.0);
  EXPECT_LT(luminance(centre), 1361.0 / kPi);
  EXPECT_EQ(luminance(f.at(0, 0)), 0.0);  // space
}

// The Sun exactly behind Earth, seen from 30 000 km on the night side, zoomed on the
// limb (0.4 degrees: 210 km): the ground below (just past the terminator) is dark, the
// atmosphere's ring is lit by forward scattering, space above is black. The rays enter the
// atmosphere with the Sun ~110 degrees from the zenith and meet sunlit air only past the
// tangent point: the ring's brightest is ~0.03 W m^-2 sr^-1 (the brute-force single
// scattering of such rays agrees, tests/atmosphere Precompute.*Limb*; reading the tables'
// lowest Sun at the entry point made it 100-400 times brighter).
TEST(AtmosphereRender, SunExactlyBehindEarth) {
  const double b = atmosphereFixture().tables.bottomRadiusM;
  ViewCamera cam;
  cam.positionM = {-3.0e7, 0.0, 0.0};
  const double limb = std::asin((b + 40e3) / 3.0e7);  // grazing 40 km up
  cam.targetM = cam.positionM + glm::dvec3(std::cos(limb), 0.0, std::sin(limb));
  cam.up = {0.0, 0.0, 1.0};
  cam.fovDeg = 0.4;
  const Frame f = renderFrame(cam, directionFromAngles(0.0, 0.0), 96);
  double ringMax = 0.0;
  for (int j = 0; j < f.h; ++j) ringMax = std::max(ringMax, luminance(f.at(f.w / 2, j)));
  const double ground = luminance(f.at(f.w / 2, f.h - 1)), space = luminance(f.at(f.w / 2, 0));
  std::printf("  night ground %.3g, brightest in the ring %.3g, space %.3g W m^-2 sr^-1\n", ground, ringMax, space);
  EXPECT_LT(ground, 1e-2 * ringMax);  // near the limb: the twilit ground under the terminator
  EXPECT_GT(ringMax, 1e-2);
  EXPECT_LT(ringMax, 0.3);
  EXPECT_EQ(space, 0.0);
}

// Noon-ish (Sun 60 degrees up): the zenith is bluer than the horizon.
TEST(AtmosphereRender, ZenithBluerThanHorizonNearNoon) {
  const Frame f = renderFrame(groundCamera(10.0, 45.0, 90.0), directionFromAngles(60.0, 180.0), 64);
  const glm::dvec3 zenith = f.at(f.w / 2, 0), horizon = f.at(f.w / 2, f.h - 1);
  std::printf("  zenith (%.4g, %.4g, %.4g), horizon (%.4g, %.4g, %.4g)\n", zenith.r, zenith.g, zenith.b, horizon.r,
              horizon.g, horizon.b);
  EXPECT_GT(zenith.b, zenith.r);
  EXPECT_GT(blueOverRed(zenith), 1.2 * blueOverRed(horizon));
}

// The render pass's stage timestamps (the benches' Table 1-2 columns): none unless asked
// for; then every stage's GPU time is finite and not negative, the atmosphere and glare
// stages take time when they draw, and the receivers' and atmosphere's together are no
// longer than the whole frame on the GL timer.
TEST(AtmosphereRender, StageTimesOfTheRenderPass) {
  AtmosphereScene scene(64, groundCamera(10.0, 45.0, 90.0), directionFromAngles(60.0, 180.0));
  vtkUmbraRenderPass* pass = scene.view.GetRenderPass();
  vtkUmbraRenderPass::StageTimes t;
  scene.view.Render();
  EXPECT_FALSE(pass->GetLastStageTimes(t));
  pass->SetStageTiming(true);
  pass->SetGlareStrength(1.0);
  scene.view.GetRenderWindow()->MakeCurrent();
  GLuint frameQuery = 0;
  glGenQueries(1, &frameQuery);
  glBeginQuery(GL_TIME_ELAPSED, frameQuery);
  scene.view.Render();
  scene.view.GetRenderWindow()->MakeCurrent();
  glEndQuery(GL_TIME_ELAPSED);
  GLuint64 frameNs = 0;
  glGetQueryObjectui64v(frameQuery, GL_QUERY_RESULT, &frameNs);
  glDeleteQueries(1, &frameQuery);
  ASSERT_TRUE(pass->GetLastStageTimes(t));
  std::printf("  receivers %.3f ms, atmosphere %.3f ms, glare %.3f ms, tone map %.3f ms; frame %.3f ms\n", t.receiversMs,
              t.atmosphereMs, t.glareMs, t.toneMapMs, frameNs * 1e-6);
  for (double ms : {t.receiversMs, t.atmosphereMs, t.glareMs, t.toneMapMs}) {
    EXPECT_TRUE(std::isfinite(ms));
    EXPECT_GE(ms, 0.0);
  }
  EXPECT_GT(t.atmosphereMs, 0.0);
  EXPECT_GT(t.glareMs, 0.0);
  EXPECT_LE(t.receiversMs + t.atmosphereMs, frameNs * 1e-6);
  pass->SetStageTiming(false);
  scene.view.Render();
  EXPECT_FALSE(pass->GetLastStageTimes(t));
}

// The Sun's disc 2 degrees up is redder than 60 degrees up (its light crosses ~25 air masses).
TEST(AtmosphereRender, LowSunIsReddened) {
  const Frame low = renderFrame(groundCamera(10.0, 2.0, 4.0), directionFromAngles(2.0, 0.0));
  const Frame high = renderFrame(groundCamera(10.0, 60.0, 4.0), directionFromAngles(60.0, 0.0));
  const glm::dvec3 l = low.at(low.w / 2, low.h / 2), hi = high.at(high.w / 2, high.h / 2);
  std::printf("  Sun at 2 deg (%.4g, %.4g, %.4g), at 60 deg (%.4g, %.4g, %.4g)\n", l.r, l.g, l.b, hi.r, hi.g, hi.b);
  EXPECT_GT(l.r, l.b * 2.0);
  EXPECT_LT(blueOverRed(l), 0.5 * blueOverRed(hi));
  EXPECT_GT(luminance(hi), luminance(l));
}

// ---- refraction (eclipse paper, section 4.2) --------------------------------------------

namespace {

// The fixture's atmosphere with refracted paths and the refraction table (256 x 128).
struct RefractionFixture {
  atmosphere::AtmosphereTables tables;
  vtkSmartPointer<vtkImageData> refraction;
};
const RefractionFixture& refractionFixture() {
  static const RefractionFixture f = [] {
    vtkNew<vtkAtmosphereTablesSource> source;
    source->SetAtmosphere("earth");
    useSmallAtmosphereTables(source);
    source->SetTables(vtkAtmosphereTablesSource::Bruneton | vtkAtmosphereTablesSource::Refraction);
    source->SetRefractedPaths(true);
    source->SetRefractionWidth(256);
    source->SetRefractionHeight(128);
    source->UseCacheOff();
    source->Update();
    RefractionFixture out;
    out.tables = umbra::filters::tablesFromBlocks(source->GetOutput(), atmosphereFixture().model);
    vtkMultiBlockDataSet* blocks = source->GetOutput();
    out.refraction = vtkImageData::SafeDownCast(blocks->GetBlock(blocks->GetNumberOfBlocks() - 1));
    return out;
  }();
  return f;
}

// The pixels whose red channel exceeds 5 % of the brightest one: the Sun's disc.
umbra::test::DiscExtent discOf(const Frame& f) {
  return umbra::test::discOf(f.w, f.h, [&](int i, int j) { return f.at(i, j).r; }, 0.05);
}

// A frame with or without refraction (the refracted-path tables and the refraction table,
// or the plain ones).
Frame renderRefracted(const ViewCamera& cam, const glm::dvec3& sunDir, int size, bool refraction,
                      const std::vector<StarPoint>& stars = {}) {
  const RefractionFixture& rf = refractionFixture();
  const AtmosphereFixture& f = atmosphereFixture();
  AtmosphereScene scene(size, cam, sunDir);
  scene.view.SetStars(stars);
  scene.view.GetAtmosphere().SetAtmosphere(f.model, refraction ? rf.tables : f.tables, glm::dvec3(0.0),
                                           scene.earth.albedoRgb);
  scene.view.GetAtmosphere().SetRefraction(refraction ? rf.refraction.Get() : nullptr);
  scene.view.Render();
  Frame out;
  scene.view.ReadHdr(out.rgb, out.w, out.h);
  return out;
}

} // namespace

// A sunset seen from 2 m, the Sun's centre 0.3 degrees above the geometric horizon: with
// refraction its disc is flattened (height / width < 0.9) and each edge is lifted by the
// deviation of the ray through it (traced on the CPU, the refraction table's source).
TEST(AtmosphereRender, RefractionLiftsAndFlattensTheSettingSun) {
  const AtmosphereFixture& f = atmosphereFixture();
  const ViewCamera cam = groundCamera(2.0, 0.5, 2.5);
  const double sunElevationDeg = 0.3;
  const glm::dvec3 sunDir = directionFromAngles(sunElevationDeg, 0.0);
  const Frame bent = renderRefracted(cam, sunDir, 200, true), straight = renderRefracted(cam, sunDir, 200, false);
  const umbra::test::DiscExtent d = discOf(bent), s = discOf(straight);
  const double flattening = double(d.height()) / d.width();
  std::printf("  disc %d x %d px with refraction (height / width %.3f), %d x %d px without\n", d.width(),
              d.height(), flattening, s.width(), s.height());
  EXPECT_LT(flattening, 0.9);
  EXPECT_GT(double(s.height()) / s.width(), 0.95);
  EXPECT_LT(d.bottom, s.bottom);  // lifted

  // Each edge's apparent elevation minus the deviation of its ray is the geometric edge.
  const atmosphere::RefractiveMedium medium =
      atmosphere::refractiveMedium(f.model, f.model.refractivityReferenceWavelengthNm);
  const double r = glm::length(cam.positionM), pxDeg = 2.5 / bent.h;
  const double sunRadiusDeg = std::asin(6.957e8 / kAu) * 180.0 / kPi;
  auto check = [&](int row, double edgeSign) {
    const Ray ray = pixelRay(cam, bent.w, bent.h, bent.w / 2, row);
    const double mu = glm::dot(ray.dir, glm::normalize(cam.positionM));
    const double apparentDeg = std::asin(mu) * 180.0 / kPi;
    const double deviationDeg = atmosphere::traceRay(medium, r, mu).deviationRad * 180.0 / kPi;
    const double geometricDeg = apparentDeg - deviationDeg, expected = sunElevationDeg + edgeSign * sunRadiusDeg;
    std::printf("  edge row %d: apparent %.4f deg, deviation %.4f deg, geometric %.4f deg (expected %.4f)\n", row,
                apparentDeg, deviationDeg, geometricDeg, expected);
    EXPECT_NEAR(geometricDeg, expected, 1.5 * pxDeg);
  };
  check(d.top, 1.0);
  check(d.bottom, -1.0);
}

// A star 2 degrees above the geometric horizon at night is lifted by refraction as the
// Sun is: its rendered centroid's apparent elevation minus the deviation of the ray
// through it is its geometric elevation within 1.5 pixels (0.0125 deg each); without
// refraction it stays where it is.
TEST(AtmosphereRender, RefractionLiftsAStar) {
  const AtmosphereFixture& f = atmosphereFixture();
  const ViewCamera cam = groundCamera(2.0, 2.0, 2.5);
  const double starElevationDeg = 2.0;
  const std::vector<StarPoint> star = {{directionFromAngles(starElevationDeg, 0.0), glm::dvec3(1e-6)}};
  const glm::dvec3 sunDir = directionFromAngles(-40.0, 180.0);
  const int size = 200;
  auto centroidRow = [&](const Frame& fr) {
    double sum = 0.0, rows = 0.0;
    for (int j = 0; j < fr.h; ++j)
      for (int i = 0; i < fr.w; ++i) {
        const double g = fr.at(i, j).g;
        sum += g;
        rows += g * (j + 0.5);
      }
    return rows / sum;
  };
  const double bentRow = centroidRow(renderRefracted(cam, sunDir, size, true, star));
  const double straightRow = centroidRow(renderRefracted(cam, sunDir, size, false, star));
  const double pxDeg = 2.5 / size;
  auto directionOfRow = [&](double row) {  // the pixel rows' centres are at j + 0.5
    const double t = std::tan(0.5 * cam.fovDeg * kPi / 180.0);
    const double y = (1.0 - 2.0 * row / size) * t;
    const glm::dvec3 fwd = glm::normalize(cam.targetM - cam.positionM);
    const glm::dvec3 right = glm::normalize(glm::cross(fwd, cam.up)), up = glm::cross(right, fwd);
    const glm::dvec3 d = glm::normalize(fwd + y * up);
    return d;
  };
  const glm::dvec3 bentDir = directionOfRow(bentRow);
  const double mu = glm::dot(bentDir, glm::normalize(cam.positionM));
  const atmosphere::RefractiveMedium medium =
      atmosphere::refractiveMedium(f.model, f.model.refractivityReferenceWavelengthNm);
  const double deviationDeg = atmosphere::traceRay(medium, glm::length(cam.positionM), mu).deviationRad * 180.0 / kPi;
  const double apparentDeg = std::asin(mu) * 180.0 / kPi;
  const double straightDeg = std::asin(glm::dot(directionOfRow(straightRow), glm::normalize(cam.positionM))) * 180.0 / kPi;
  std::printf("  star at %.2f deg: apparent %.4f deg with refraction (deviation %.4f deg), %.4f deg without\n",
              starElevationDeg, apparentDeg, deviationDeg, straightDeg);
  EXPECT_NEAR(apparentDeg - deviationDeg, starElevationDeg, 1.5 * pxDeg);
  EXPECT_NEAR(straightDeg, starElevationDeg, 1.5 * pxDeg);
  EXPECT_GT(deviationDeg, 0.1);
}

// Stars setting through refraction keep their light whatever their place within a pixel:
// 20 stars from 1.5 to 3.5 degrees up (every phase across the pixel rows, 8 pixels apart
// across) each come through with E T / J, T the transmittance along its refracted ray
// (atmosphere::transmittanceToTop at its apparent elevation) and J = 1 + d(deviation) /
// d(zenith angle) (rays traced on the CPU: refraction packs J rows of the sky into one,
// and radiance is kept along a ray), within 3 %; and each image is where its ray's deviation
// puts it, within 0.3 pixel. Read at the nearest pixel, a star whose light sat in a row that
// refraction skips came through dim or not at all, and the others J too bright.
TEST(AtmosphereRender, RefractionKeepsEveryStarsLight) {
  const AtmosphereFixture& f = atmosphereFixture();
  const RefractionFixture& rf = refractionFixture();
  const double fovDeg = 2.5;
  const ViewCamera cam = groundCamera(2.0, 2.7, fovDeg);
  const int size = 200, count = 20;
  std::vector<StarPoint> stars;
  std::vector<double> elevationsDeg;
  for (int k = 0; k < count; ++k) {
    elevationsDeg.push_back(1.5 + 2.0 * k / (count - 1) + 0.0037 * k);  // a phase of its own in every row
    stars.push_back({directionFromAngles(elevationsDeg.back(), -0.95 + 0.1 * k), glm::dvec3(1e-6)});
  }
  const glm::dvec3 sunDir = directionFromAngles(-40.0, 180.0);
  const Frame with = renderRefracted(cam, sunDir, size, true, stars), without = renderRefracted(cam, sunDir, size, true);
  const glm::dvec3 fwd = glm::normalize(cam.targetM - cam.positionM);
  const glm::dvec3 right = glm::normalize(glm::cross(fwd, cam.up)), up = glm::cross(right, fwd);
  const double t = std::tan(0.5 * fovDeg * kPi / 180.0), pxRad = 2.0 * t / size;
  auto rayOf = [&](double col, double row) {  // at pixel coordinates (centres at i + 0.5)
    return fwd + (2.0 * col / size - 1.0) * t * right + (1.0 - 2.0 * row / size) * t * up;
  };
  const atmosphere::RefractiveMedium medium =
      atmosphere::refractiveMedium(f.model, f.model.refractivityReferenceWavelengthNm);
  const double r = glm::length(cam.positionM);
  auto deviationRad = [&](double elevationRad) { return atmosphere::traceRay(medium, r, std::sin(elevationRad)).deviationRad; };
  double worst = 0.0, worstPlace = 0.0, lowestJ = 1e9, highestJ = 0.0;
  for (int k = 0; k < count; ++k) {
    const glm::dvec3 d = stars[k].direction;
    const int col = static_cast<int>(std::floor((dot(d, right) / dot(d, fwd) / t + 1.0) * 0.5 * size));
    glm::dvec3 flux(0.0);
    double light = 0.0, rows = 0.0;
    for (int j = 0; j < size; ++j)
      for (int i = std::max(col - 3, 0); i <= std::min(col + 3, size - 1); ++i) {
        const glm::dvec3 ray = rayOf(i + 0.5, j + 0.5);
        const double omega = (2.0 * t / size) * (2.0 * t / size) / std::pow(glm::length(ray), 3.0);
        const glm::dvec3 star = with.at(i, j) - without.at(i, j);
        flux += star * omega;
        light += star.g;
        rows += star.g * (j + 0.5);
      }
    ASSERT_GT(light, 0.0) << "star " << k << " at " << elevationsDeg[k] << " deg: not drawn";
    const glm::dvec3 seen = glm::normalize(rayOf(col + 0.5, rows / light));
    const double apparentRad = std::asin(dot(seen, glm::normalize(cam.positionM)));
    const double dz = 0.5 * pxRad;
    const double J = 1.0 + (deviationRad(apparentRad - dz) - deviationRad(apparentRad + dz)) / (2.0 * dz);
    const std::vector<double> T = atmosphere::transmittanceToTop(rf.tables, r, std::sin(apparentRad));
    const double placePx = (apparentRad - deviationRad(apparentRad) - elevationsDeg[k] * kPi / 180.0) / pxRad;
    for (int c = 0; c < 3; ++c) {
      const double ratio = flux[c] / (1e-6 * T[c] / J);
      if (std::abs(ratio - 1.0) > std::abs(worst)) worst = ratio - 1.0;
      EXPECT_NEAR(ratio, 1.0, 0.03) << "star " << k << " at " << elevationsDeg[k] << " deg, channel " << c << ", J " << J;
    }
    worstPlace = std::max(worstPlace, std::abs(placePx));
    lowestJ = std::min(lowestJ, J);
    highestJ = std::max(highestJ, J);
    EXPECT_NEAR(placePx, 0.0, 0.3) << "star " << k << " at " << elevationsDeg[k] << " deg";
  }
  std::printf("  %d stars from 1.5 to 3.5 deg (J %.3f to %.3f): light within %.2f %% of E T / J, place within %.3f px\n",
              count, highestJ, lowestJ, 100.0 * worst, worstPlace);
}

// A solar eclipse seen from space: the Moon's shadow on the ground survives the
// atmosphere (the direct sunlight there is dimmed by the frame's eclipse factor), and the
// ground far from it is as without the Moon.
TEST(AtmosphereRender, EclipseShadowOnTheGroundThroughTheAtmosphere) {
  const AtmosphereFixture& f = atmosphereFixture();
  ViewCamera cam;
  cam.positionM = {1.0e8, -2.0e7, 1.0e7};
  cam.targetM = {0.0, 0.0, 0.0};
  cam.up = {0.0, 0.0, 1.0};
  cam.fovDeg = 8.0;
  auto frameWith = [&](bool moon, const std::string& groundMap = "") {
    AtmosphereScene scene(96, cam, directionFromAngles(0.0, 0.0));
    std::vector<SphereBody> bodies{scene.earth};
    if (moon) bodies.push_back({"Moon", {kMoonDistance, 0.0, 0.0}, 1.7374e6, {0.1, 0.1, 0.1}});
    scene.view.SetBodies(scene.sun, bodies, testLutImage());
    scene.view.GetAtmosphere().SetAtmosphere(f.model, f.tables, glm::dvec3(0.0), scene.earth.albedoRgb);
    scene.view.GetAtmosphere().SetGroundAlbedoMap(groundMap.empty() ? nullptr : mapTexels(groundMap, MapKind::Reflectance));
    scene.view.SetCamera(cam);
    scene.view.Render();
    Frame out;
    scene.view.ReadHdr(out.rgb, out.w, out.h);
    return out;
  };
  const Frame eclipsed = frameWith(true), clear = frameWith(false);
  // The pixel of the sub-solar point (1, 0, 0) R, and one 40 degrees north of it.
  auto pixelOf = [&](const glm::dvec3& p) {
    const glm::dvec3 fwd = glm::normalize(cam.targetM - cam.positionM);
    const glm::dvec3 right = glm::normalize(glm::cross(fwd, cam.up)), up = glm::cross(right, fwd);
    const glm::dvec3 d = glm::normalize(p - cam.positionM);
    const double t = std::tan(0.5 * cam.fovDeg * kPi / 180.0);
    const double x = glm::dot(d, right) / glm::dot(d, fwd) / t, y = glm::dot(d, up) / glm::dot(d, fwd) / t;
    return std::pair<int, int>(static_cast<int>((x + 1.0) * 0.5 * eclipsed.w),
                               static_cast<int>((1.0 - y) * 0.5 * eclipsed.h));
  };
  const double R = f.tables.bottomRadiusM;
  const auto [i0, j0] = pixelOf({R, 0.0, 0.0});
  const auto [i1, j1] = pixelOf({R * std::cos(0.7), 0.0, R * std::sin(0.7)});
  const double inShadow = luminance(eclipsed.at(i0, j0)) / luminance(clear.at(i0, j0));
  const double far = luminance(eclipsed.at(i1, j1)) / luminance(clear.at(i1, j1));
  std::printf("  eclipsed / clear: %.3f at the sub-solar point, %.4f 40 degrees north\n", inShadow, far);
  EXPECT_LT(inShadow, 0.6);  // 0.50: the default sky's haze, sunlit above the shadow, adds its light
  EXPECT_NEAR(far, 1.0, 1e-3);
  // The same under a ground of a reflectance map of the receiver's albedo (sRGB 89: 0.0999),
  // the receiver keeping its uniform one.
  const std::string map = writeRgbPng(64, 32, [](int, int) { return glm::dvec3(89.0 / 255.0); }, "eclipse-ground.png");
  const Frame eclipsedMap = frameWith(true, map), clearMap = frameWith(false, map);
  const double inShadowMap = luminance(eclipsedMap.at(i0, j0)) / luminance(clearMap.at(i0, j0));
  std::printf("  with a ground map: %.3f at the sub-solar point\n", inShadowMap);
  EXPECT_NEAR(inShadowMap, inShadow, 0.01);
}

// From the Moon's distance, the Sun exactly behind Earth (a total lunar eclipse seen from
// the Moon), zoomed on the limb: refraction bends rays around the planet onto the Sun's
// disc (reconstructed along the exit ray), so the ring outshines the scattered light
// alone by far; the rays bent into the ground stay dark.
TEST(AtmosphereRender, RefractionShowsTheSunThroughTheLimbFromTheMoon) {
  const double b = atmosphereFixture().tables.bottomRadiusM;
  ViewCamera cam;
  cam.positionM = {-kMoonDistance, 0.0, 0.0};
  const double limb = std::asin((b + 20e3) / kMoonDistance);
  cam.targetM = cam.positionM + glm::dvec3(std::cos(limb), 0.0, std::sin(limb));
  cam.up = {0.0, 0.0, 1.0};
  cam.fovDeg = 0.02;  // 134 km across
  auto brightest = [&](bool refraction) {
    const Frame out = renderRefracted(cam, directionFromAngles(0.0, 0.0), 64, refraction);
    double m = 0.0;
    for (int j = 0; j < out.h; ++j) m = std::max(m, luminance(out.at(out.w / 2, j)));
    return m;
  };
  const double bent = brightest(true), straight = brightest(false);
  std::printf("  brightest limb pixel: %.4g with refraction, %.4g without (W m^-2 sr^-1)\n", bent, straight);
  EXPECT_GT(bent, 10.0 * straight);
}

// SetCentre (the GUI's time slider: the body moves, the tables stay) draws the same frame
// as SetAtmosphere with the new centre, and not the frame of the old one.
TEST(AtmosphereRender, SetCentreMovesTheAtmosphereLikeSetAtmosphere) {
  const ViewCamera cam = groundCamera(2.0, 5.0, 60.0);
  const glm::dvec3 sunDir = directionFromAngles(20.0, 0.0);
  const AtmosphereFixture& f = atmosphereFixture();
  auto frame = [&](bool viaSetCentre, const glm::dvec3& centre) {
    AtmosphereScene scene(48, cam, sunDir);
    SphereBody moved = scene.earth;
    moved.centreM = centre;
    scene.view.SetBodies(scene.sun, {moved}, testLutImage());
    if (viaSetCentre) scene.view.GetAtmosphere().SetCentre(centre);
    else scene.view.GetAtmosphere().SetAtmosphere(f.model, f.tables, centre, moved.albedoRgb);
    scene.view.SetCamera(cam);
    scene.view.Render();
    Frame out;
    scene.view.ReadHdr(out.rgb, out.w, out.h);
    return out;
  };
  const glm::dvec3 down(0.0, 0.0, -10e3);  // the camera 10 km higher above the ground
  const Frame a = frame(true, down), b = frame(false, down), still = frame(false, glm::dvec3(0.0));
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_NE(a.rgb, still.rgb);
  EXPECT_THROW(AtmosphereRendering().SetCentre(glm::dvec3(NAN, 0.0, 0.0)), std::invalid_argument);
}

// The ground's albedo from a reflectance map: a map of one sRGB value renders the ground as
// the uniform albedo of its decoded value does (within 1 %); a map bright east of the
// body-fixed prime meridian and dark west of it, in a frame turned 30 deg about the pole,
// renders the ground 10 deg east of the meridian with the bright albedo and 10 deg west of it
// with the dark one (each within 5 %: the ground's light over the uniform map's, the air's
// own light taken out).
TEST(AtmosphereRender, GroundAlbedoMapLiesInTheBodyFixedFrame) {
  const AtmosphereFixture& f = atmosphereFixture();
  const double R = f.tables.bottomRadiusM;
  ViewCamera cam;
  cam.positionM = {4.0 * R, 0.0, 0.0};
  cam.targetM = {0.0, 0.0, 0.0};
  cam.up = {0.0, 0.0, 1.0};
  cam.fovDeg = 32.0;
  const glm::dvec3 sunDir(1.0, 0.0, 0.0);
  auto decode = [](double byte) { return std::pow((byte / 255.0 + 0.055) / 1.055, 2.4); };
  const glm::dmat3 turn = glm::dmat3(glm::rotate(glm::dmat4(1.0), 30.0 * kPi / 180.0, glm::dvec3(0, 0, 1)));
  // The ground of a map, or of a uniform albedo (the receiver's then; with a map the
  // receiver keeps the scene's 0.1).
  auto render = [&](const std::string& map, const glm::dvec3& albedo) {
    AtmosphereScene scene(128, cam, sunDir);
    if (map.empty()) {
      scene.earth.albedoRgb = albedo;
      scene.view.SetBodies(scene.sun, {scene.earth}, testLutImage());
    }
    scene.view.GetAtmosphere().SetAtmosphere(f.model, f.tables, glm::dvec3(0.0), scene.earth.albedoRgb);
    scene.view.GetAtmosphere().SetGroundAlbedoMap(map.empty() ? nullptr : mapTexels(map, MapKind::Reflectance), turn);
    scene.view.Render();
    Frame out;
    scene.view.ReadHdr(out.rgb, out.w, out.h);
    return out;
  };
  const std::string uniformMap =
      writeRgbPng(64, 32, [](int, int) { return glm::dvec3(160.0 / 255.0); }, "ground-uniform.png");
  const Frame mapped = render(uniformMap, glm::dvec3(0.0)), uniform = render("", glm::dvec3(decode(160.0)));
  const Frame black = render("", glm::dvec3(0.0));
  double worst = 0.0;
  for (int j = 0; j < mapped.h; ++j)
    for (int i = 0; i < mapped.w; ++i) {
      const Ray ray = pixelRay(cam, mapped.w, mapped.h, i, j);
      const auto hit = hitSphere(ray, glm::dvec3(0.0), R);
      if (!hit || glm::dot(glm::normalize(*hit), sunDir) < 0.2 || -glm::dot(glm::normalize(*hit), ray.dir) < 0.3) continue;
      worst = std::max(worst, std::abs(luminance(mapped.at(i, j)) / luminance(uniform.at(i, j)) - 1.0));
    }
  std::printf("  a uniform map against its albedo %.4f: within %.2g\n", decode(160.0), worst);
  EXPECT_LT(worst, 0.01);

  // Bright (byte 200) east of the body-fixed prime meridian, dark (byte 40) west of it.
  const std::string halves = writeRgbPng(
      64, 32, [](int i, int) { return glm::dvec3(i >= 32 ? 200.0 / 255.0 : 40.0 / 255.0); }, "ground-halves.png");
  const Frame split = render(halves, glm::dvec3(0.0));
  const glm::dvec3 fwd(-1.0, 0.0, 0.0), right = glm::normalize(glm::cross(fwd, cam.up)), up = glm::cross(right, fwd);
  auto albedoAtLon = [&](double lonDeg) {  // on the equator, body-fixed east longitude
    const double l = lonDeg * kPi / 180.0;
    const glm::dvec3 d = glm::normalize(turn * glm::dvec3(R * std::cos(l), R * std::sin(l), 0.0) - cam.positionM);
    const double t = std::tan(0.5 * cam.fovDeg * kPi / 180.0);
    const int i = static_cast<int>((glm::dot(d, right) / glm::dot(d, fwd) / t + 1.0) * 0.5 * split.w);
    const int j = static_cast<int>((1.0 - glm::dot(d, up) / glm::dot(d, fwd) / t) * 0.5 * split.h);
    const double air = luminance(black.at(i, j));
    return decode(160.0) * (luminance(split.at(i, j)) - air) / (luminance(uniform.at(i, j)) - air);
  };
  const double east = albedoAtLon(10.0), west = albedoAtLon(-10.0);
  std::printf("  albedo 10 deg east / west of the turned meridian: %.4f / %.4f (map %.4f / %.4f)\n", east, west,
              decode(200.0), decode(40.0));
  EXPECT_NEAR(east / decode(200.0), 1.0, 0.05);
  EXPECT_NEAR(west / decode(40.0), 1.0, 0.05);
}
