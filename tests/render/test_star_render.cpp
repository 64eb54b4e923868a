// Stars in the render pass (StarRendering): with no atmosphere, each star's pixels times
// their solid angle give back its V magnitude, their centroid is its image point, its
// colour is the Sun's for the Sun's B-V, and a body in front hides it.
#include "RenderTestSupport.hpp"
#include "AtmosphereTestSupport.hpp"
#include "SceneInputs.h"
#include "StarCatalogue.hpp"
#include "StarCatalogueCache.h"
#include "Photometry.hpp"
#include "StarLight.hpp"
#include "PlanetMagnitudes.hpp"
#include "scene/Planets.hpp"
#include "scene/Scene.hpp"
#include "scene/Stars.hpp"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

using namespace umbra::pipeline;  // the scene glue (app/pipeline)

using namespace umbra;
using namespace umbra::render;
using namespace umbra::render::test;

namespace {

constexpr int kWidth = 320, kHeight = 240;
constexpr double kFovDeg = 40.0;

ViewCamera starCamera() {
  ViewCamera c;
  c.positionM = {0.0, 0.0, 0.0};
  c.targetM = {1.0, 0.0, 0.0};
  c.up = {0.0, 0.0, 1.0};
  c.fovDeg = kFovDeg;
  return c;
}

// The direction of the image point (x, y) in pixels from the top-left corner, by the
// pinhole model of the camera above (independent of the render pass's code).
glm::dvec3 directionAtPixel(double x, double y) {
  const double s = 2.0 * std::tan(0.5 * kFovDeg * kPi / 180.0) / kHeight;  // image plane units per pixel
  const double u = (x - 0.5 * kWidth) * s, v = (0.5 * kHeight - y) * s;
  // camera: forward +x, right = forward x up = -y, up +z
  return glm::normalize(glm::dvec3(1.0, -u, v));
}

// The solid angle of pixel (i, j) (row j from the top), at its centre: s^2 cos^3 of its
// angle off the axis.
double pixelSolidAngle(int i, int j) {
  const double s = 2.0 * std::tan(0.5 * kFovDeg * kPi / 180.0) / kHeight;
  const double u = (i + 0.5 - 0.5 * kWidth) * s, v = (0.5 * kHeight - (j + 0.5)) * s;
  return s * s / std::pow(1.0 + u * u + v * v, 1.5);
}

struct Measured {
  glm::dvec3 irradiance{0.0};  // sum of radiance * solid angle over the window
  double x = 0.0, y = 0.0;     // luminance-weighted centroid, pixels from the top-left
};

// Sums the window's pixels within `radius` of (cx, cy).
Measured measure(const std::vector<float>& rgb, double cx, double cy, int radius = 4) {
  Measured m;
  double wsum = 0.0;
  for (int j = int(cy) - radius; j <= int(cy) + radius; ++j)
    for (int i = int(cx) - radius; i <= int(cx) + radius; ++i) {
      if (i < 0 || j < 0 || i >= kWidth || j >= kHeight) continue;
      const float* p = &rgb[(static_cast<std::size_t>(j) * kWidth + i) * 3];
      const glm::dvec3 e = glm::dvec3(p[0], p[1], p[2]) * pixelSolidAngle(i, j);
      m.irradiance += e;
      const double w = e.g;
      m.x += w * (i + 0.5);
      m.y += w * (j + 0.5);
      wsum += w;
    }
  if (wsum > 0.0) {
    m.x /= wsum;
    m.y /= wsum;
  }
  return m;
}

// The V magnitude of a frame irradiance: its luminance once the Sun's white balance is
// undone, against the Sun's (1361 W m^-2 at 1 au, V = -26.74).
double vMagnitudeOf(const glm::dvec3& frameIrradiance) {
  const glm::dvec3 unbalanced = frameIrradiance * sky::sunLinearSrgb();
  const double y = 0.2126 * unbalanced.r + 0.7152 * unbalanced.g + 0.0722 * unbalanced.b;
  return sky::kSunMagnitudeV - 2.5 * std::log10(y / 1361.0);
}

std::vector<float> renderStars(BodyView& view, const std::vector<StarPoint>& stars,
                          const std::vector<SphereBody>& bodies = {}) {
  SunLight sun;
  sun.positionM = {-kAu, 0.0, 0.0};
  view.SetBodies(sun, bodies, testLutImage());
  view.SetCamera(starCamera());
  view.SetStars(stars);
  view.Render();
  std::vector<float> rgb;
  int w = 0, h = 0;
  view.ReadHdr(rgb, w, h);
  return rgb;
}

}  // namespace

// The zero point: Sirius (V = -1.46) and a V = 6 star, at the centre, off-centre at a
// sub-pixel position and near a corner (where a pixel's solid angle is 0.8 of the
// centre's), come back within 0.01 mag; their centroids within 0.1 pixel of their image
// points.
TEST(StarRender, ZeroPointAndCentroid) {
  BodyView view(kWidth, kHeight, true);
  useSharedDisplay(view.GetRenderWindow());
  struct Case {
    double x, y, vMag, bMinusV;
  };
  const Case cases[] = {{160.0, 120.0, -1.46, 0.00}, {41.3, 200.7, 6.0, 1.2}, {300.25, 15.6, -1.46, 0.00},
                        {230.5, 60.5, 6.0, 0.65}};
  std::vector<StarPoint> stars;
  for (const Case& c : cases)
    stars.push_back({directionAtPixel(c.x, c.y), sky::starFrameIrradianceWm2(c.vMag, c.bMinusV, 1361.0)});
  const std::vector<float> rgb = renderStars(view, stars);
  for (const Case& c : cases) {
    const Measured m = measure(rgb, c.x, c.y);
    std::printf("star V %.2f at (%.2f, %.2f): measured V %.4f at (%.3f, %.3f)\n", c.vMag, c.x, c.y,
                vMagnitudeOf(m.irradiance), m.x, m.y);
    EXPECT_NEAR(vMagnitudeOf(m.irradiance), c.vMag, 0.01) << "star at " << c.x << ", " << c.y;
    EXPECT_NEAR(m.x, c.x, 0.1) << "V " << c.vMag;
    EXPECT_NEAR(m.y, c.y, 0.1) << "V " << c.vMag;
  }
}

// Colour: a star of the Sun's B-V renders with the Sun's chromaticity in the frame (the
// bare Sun is (1, 1, 1)) within 0.01; B-V 0 is bluer, 1.5 redder.
TEST(StarRender, ColourFollowsBMinusV) {
  BodyView view(kWidth, kHeight, true);
  useSharedDisplay(view.GetRenderWindow());
  const double bvs[] = {0.0, 0.65, 1.5};
  std::vector<StarPoint> stars;
  for (int k = 0; k < 3; ++k)
    stars.push_back({directionAtPixel(80.0 + 80.0 * k, 120.0), sky::starFrameIrradianceWm2(2.0, bvs[k], 1361.0)});
  const std::vector<float> rgb = renderStars(view, stars);
  glm::dvec3 chroma[3];
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 e = measure(rgb, 80.0 + 80.0 * k, 120.0).irradiance;
    chroma[k] = e / (e.r + e.g + e.b);
  }
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(chroma[1][c], 1.0 / 3.0, 0.01);
  EXPECT_GT(chroma[0].b, chroma[1].b);
  EXPECT_LT(chroma[0].r, chroma[1].r);
  EXPECT_GT(chroma[2].r, chroma[1].r);
  EXPECT_LT(chroma[2].b, chroma[1].b);
}

// A body in front of a star hides it (the star is drawn only where the frame holds
// nothing); a star behind the camera is not drawn; the rest of the frame stays black.
TEST(StarRender, BodiesHideStars) {
  BodyView view(kWidth, kHeight, true);
  useSharedDisplay(view.GetRenderWindow());
  // A dark body (its night side faces the camera: the Sun is behind the camera... no, on
  // the far side) covering the image centre.
  const SphereBody blocker{"Blocker", {1.0e7, 0.0, 0.0}, 1.0e6, {0.0, 0.0, 0.0}};
  const std::vector<StarPoint> stars = {
      {directionAtPixel(160.0, 120.0), sky::starFrameIrradianceWm2(0.0, 0.65, 1361.0)},
      {directionAtPixel(20.0, 20.0), sky::starFrameIrradianceWm2(0.0, 0.65, 1361.0)},
      {glm::dvec3(-1.0, 0.0, 0.0), sky::starFrameIrradianceWm2(-1.0, 0.65, 1361.0)}};
  const std::vector<float> rgb = renderStars(view, stars, {blocker});
  EXPECT_EQ(measure(rgb, 160.0, 120.0).irradiance.g, 0.0);
  EXPECT_NEAR(vMagnitudeOf(measure(rgb, 20.0, 20.0).irradiance), 0.0, 0.01);
  double total = 0.0;
  for (float v : rgb) total += v;
  const Measured visible = measure(rgb, 20.0, 20.0);
  double visibleRadiance = 0.0;
  for (int j = 16; j <= 24; ++j)
    for (int i = 16; i <= 24; ++i)
      for (int c = 0; c < 3; ++c) visibleRadiance += rgb[(static_cast<std::size_t>(j) * kWidth + i) * 3 + c];
  EXPECT_NEAR(total, visibleRadiance, 1e-6 * visibleRadiance) << visible.x;
}

namespace {

// Rows of /usr/share/kstars/stars.dat (kstars-data 3.6.2), as they are in the file.
const char* const kCatalogueRows =
    "064508.92 -164258.0 -000546.0-001223.100379.2 -1.4400.01A0 1            , alp CMa, Sirius\n"
    "183656.34 +384701.3 +000201.0+000287.500128.9 00.03-0.00A0 0            , alp Lyr, Vega\n";

}  // namespace

// A scene's stars ("stars": a catalogue file and a limiting magnitude): Sirius, seen from
// the ground through a 1 degree field (15 arcsec a pixel), lands within a pixel of its
// apparent place for the scene's observer and time (aberration alone moves it 20 arcsec);
// a limiting magnitude of -1 leaves Vega out.
TEST(StarRender, SceneStarsAtTheirApparentPlaces) {
  const std::string catalogue =
      (std::filesystem::temp_directory_path() / ("umbra-stars-" + std::to_string(::getpid()) + ".dat")).string();
  std::ofstream(catalogue) << kCatalogueRows;
  const std::string text = R"({
    "time": "2024-03-20T22:00:00Z",
    "bodies": [{"preset": "Sun"}, {"preset": "Earth"}],
    "camera": {"observer": {"body": "Earth", "latDeg": 0.0, "lonDeg": 0.0, "altM": 2},
               "target": {"azimuthDeg": 240, "elevationDeg": 40}, "up": "zenith", "fovDeg": 1},
    "stars": {"catalogue": ")" + catalogue + R"(", "limitingMagnitude": 9}})";
  scene::Scene s = scene::parseScene(text, "stars.json");
  ASSERT_TRUE(s.stars.has_value());
  const std::vector<sky::CatalogueStar> rows = sky::readKStarsCatalogue(catalogue);
  const glm::dvec3 sirius = scene::apparentStarDirection(rows[0], s.time, scene::starObserverOf(s));
  // Aim 0.2 degrees right of and 0.1 degrees above Sirius.
  const glm::dvec3 right = glm::normalize(glm::cross(sirius, s.camera.up));
  const glm::dvec3 up = glm::cross(right, sirius);
  const glm::dvec3 aim = glm::normalize(sirius + std::tan(0.2 * kPi / 180.0) * right + std::tan(0.1 * kPi / 180.0) * up);
  s.camera.targetM = s.camera.positionM + 1.0e9 * aim;
  const SceneInputs in = sceneInputs(s);
  // The catalogue's two, then the planets (all brighter than V 9), at their places, in
  // sunlight tinted by their B-V (white-balanced to the Sun), as bright as their magnitudes.
  const std::vector<scene::PlanetSeen> planets = scene::planetsSeenFrom(in.camera.positionM, s.time);
  ASSERT_EQ(in.stars.size(), 2u + planets.size());
  for (std::size_t k = 0; k < planets.size(); ++k) {
    const StarPoint& p = in.stars[2 + k];
    EXPECT_NEAR(glm::dot(p.direction, planets[k].directionIcrs), 1.0, 1e-12) << planets[k].name;
    const glm::dvec3 e = in.sun.irradianceAt1AuWm2 * sky::irradianceRelativeToSun(planets[k].magnitudeV) *
                         sky::reflectedFrameColour(sky::planetBMinusV(planets[k].name), sky::kSunBMinusV);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(p.irradianceWm2[c], e[c], 1e-12 * e[c]) << planets[k].name;
    EXPECT_GT(p.irradianceWm2.r, p.irradianceWm2.b) << planets[k].name;  // every one redder than the Sun
  }

  BodyView view(kWidth, kHeight, true);
  useSharedDisplay(view.GetRenderWindow());
  view.SetBodies(in.sun, in.bodies, testLutImage());
  view.SetCamera(in.camera);
  view.SetStars(in.stars);
  view.Render();
  std::vector<float> rgb;
  int w = 0, h = 0;
  view.ReadHdr(rgb, w, h);

  // Sirius's image point by the pinhole model of the camera.
  const glm::dvec3 fwd = glm::normalize(in.camera.targetM - in.camera.positionM);
  const glm::dvec3 r = glm::normalize(glm::cross(fwd, in.camera.up)), u = glm::cross(r, fwd);
  const double t = std::tan(0.5 * kPi / 180.0);
  const double xNdc = glm::dot(sirius, r) / glm::dot(sirius, fwd) / (t * double(kWidth) / kHeight);
  const double yNdc = glm::dot(sirius, u) / glm::dot(sirius, fwd) / t;
  const double px = 0.5 * (xNdc + 1.0) * kWidth, py = 0.5 * (1.0 - yNdc) * kHeight;
  const Measured m = measure(rgb, px, py);
  std::printf("Sirius expected at (%.3f, %.3f), rendered at (%.3f, %.3f)\n", px, py, m.x, m.y);
  EXPECT_NEAR(m.x, px, 1.0);
  EXPECT_NEAR(m.y, py, 1.0);
  EXPECT_GT(m.irradiance.g, 0.0);

  s.stars->limitingMagnitude = -1.0;  // Sirius, and the planets as bright
  const auto brighter = std::count_if(planets.begin(), planets.end(), [](const scene::PlanetSeen& p) { return p.magnitudeV <= -1.0; });
  EXPECT_EQ(sceneInputs(s).stars.size(), 1u + static_cast<std::size_t>(brighter));
  std::filesystem::remove(catalogue);
}

// Extinction: through the Earth preset's air (small tables, night), a star at zenith angle
// 60 degrees is dimmer than the same star at the zenith by the preset's own extinction at
// 550 nm (the G channel): within 0.02 mag of its transmittance, and of the plane-parallel
// 1.086 tau (sec z - 1) of its exact vertical optical depth.
TEST(StarRender, ExtinctionIsTheAtmospheresTransmittance) {
  constexpr int kSize = 256;
  const ViewCamera camera = groundCamera(2.0, 60.0, 80.0);
  AtmosphereScene scene(kSize, camera, directionFromAngles(-60.0, 180.0));
  const glm::dvec3 zenith(0.0, 0.0, 1.0), low = directionFromAngles(30.0, 0.0);
  const glm::dvec3 e = sky::starFrameIrradianceWm2(1.0, 0.65, 1361.0);
  scene.view.SetStars({{zenith, e}, {low, e}});
  scene.view.Render();
  std::vector<float> rgb;
  int w = 0, h = 0;
  scene.view.ReadHdr(rgb, w, h);

  // Image points by the pinhole model; each star's G irradiance over the sky around it.
  const glm::dvec3 fwd = glm::normalize(camera.targetM - camera.positionM);
  const glm::dvec3 right = glm::normalize(glm::cross(fwd, camera.up)), up = glm::cross(right, fwd);
  const double t = std::tan(0.5 * camera.fovDeg * kPi / 180.0), s = 2.0 * t / kSize;
  auto starG = [&](const glm::dvec3& d) {
    const double px = 0.5 * kSize + glm::dot(d, right) / glm::dot(d, fwd) / s;
    const double py = 0.5 * kSize - glm::dot(d, up) / glm::dot(d, fwd) / s;
    double sum = 0.0, ring = 0.0;
    int ringCount = 0;
    for (int j = int(py) - 6; j <= int(py) + 6; ++j)
      for (int i = int(px) - 6; i <= int(px) + 6; ++i) {
        const double g = rgb[(static_cast<std::size_t>(j) * kSize + i) * 3 + 1];
        const double u = (i + 0.5 - 0.5 * kSize) * s, v = (0.5 * kSize - (j + 0.5)) * s;
        const double omega = s * s / std::pow(1.0 + u * u + v * v, 1.5);
        if (std::abs(i + 0.5 - px) <= 3.0 && std::abs(j + 0.5 - py) <= 3.0) {
          sum += g * omega;
        } else {
          ring += g * omega;
          ++ringCount;
        }
      }
    return sum - 49.0 * ring / ringCount;  // minus the sky's light under the 7 x 7 pixels
  };
  const double ratio = starG(low) / starG(zenith);
  const double dMag = -2.5 * std::log10(ratio);

  const AtmosphereFixture& f = atmosphereFixture();
  const double r = f.tables.bottomRadiusM + 2.0;
  const double expected = -2.5 * std::log10(atmosphere::transmittanceToTop(f.tables, r, 0.5)[1] /
                                            atmosphere::transmittanceToTop(f.tables, r, 1.0)[1]);
  const double tau = f.model.verticalOpticalDepth(2.0, f.model.thicknessM())[1];
  const double planeParallel = 2.5 / std::log(10.0) * tau * (2.0 - 1.0);
  std::printf("zenith angle 60 deg: %.4f mag fainter (tables %.4f, 1.086 tau (sec z - 1) %.4f; tau_550 %.4f)\n", dMag,
              expected, planeParallel, tau);
  EXPECT_NEAR(dMag, expected, 0.02);
  EXPECT_NEAR(dMag, planeParallel, 0.02);
  EXPECT_GT(dMag, 0.05);
}

// Day and night with no fade factor: stars of V -1.5, 1 and 3 at 60 degrees elevation in a
// 10 degree field of 256 pixels, shown when the star's irradiance is at least twice the
// sky's light on one pixel (E >= 2 L_sky Omega_pixel, G channel). The noon sky hides all
// three; as the Sun sinks they come out brightest first; the night shows all.
TEST(StarRender, TwilightRevealsStarsInOrderOfBrightness) {
  constexpr int kSize = 256;
  const ViewCamera camera = groundCamera(2.0, 60.0, 10.0);
  const double vMags[3] = {-1.5, 1.0, 3.0};
  const glm::dvec3 dirs[3] = {directionFromAngles(60.0, -3.0), directionFromAngles(60.0, 0.0),
                              directionFromAngles(60.0, 3.0)};
  const glm::dvec3 fwd = glm::normalize(camera.targetM - camera.positionM);
  const glm::dvec3 right = glm::normalize(glm::cross(fwd, camera.up)), up = glm::cross(right, fwd);
  const double s = 2.0 * std::tan(0.5 * camera.fovDeg * kPi / 180.0) / kSize;

  const std::vector<double> sunElevations = {45.0, 10.0, 0.0, -3.0, -6.0, -8.0, -10.0, -11.0, -12.0, -18.0};
  const int n = static_cast<int>(sunElevations.size());
  int firstShown[3] = {-1, -1, -1};
  for (int k = 0; k < n; ++k) {
    AtmosphereScene scene(kSize, camera, directionFromAngles(sunElevations[k], 180.0));
    std::vector<StarPoint> stars;
    for (int i = 0; i < 3; ++i) stars.push_back({dirs[i], sky::starFrameIrradianceWm2(vMags[i], 0.65, 1361.0)});
    scene.view.SetStars(stars);
    scene.view.Render();
    std::vector<float> rgb;
    int w = 0, h = 0;
    scene.view.ReadHdr(rgb, w, h);
    for (int i = 0; i < 3; ++i) {
      const glm::dvec3& d = dirs[i];
      const double px = 0.5 * kSize + glm::dot(d, right) / glm::dot(d, fwd) / s;
      const double py = 0.5 * kSize - glm::dot(d, up) / glm::dot(d, fwd) / s;
      // Pixels within 2 of the image point hold the star and the sky, those 3-5 away the sky.
      double inner = 0.0, sky = 0.0;
      int innerCount = 0, skyCount = 0;
      for (int j = int(py) - 5; j <= int(py) + 5; ++j)
        for (int c = int(px) - 5; c <= int(px) + 5; ++c) {
          const double g = rgb[(static_cast<std::size_t>(j) * kSize + c) * 3 + 1];
          const double far = std::max(std::abs(c + 0.5 - px), std::abs(j + 0.5 - py));
          if (far <= 2.0) {
            inner += g;
            ++innerCount;
          } else if (far >= 3.0) {
            sky += g;
            ++skyCount;
          }
        }
      sky /= skyCount;
      const double contrast = (inner - innerCount * sky) / std::max(sky, 1e-30);  // E / (L_sky Omega), Omega ~ constant here
      const bool shown = contrast >= 2.0;
      std::printf("Sun %+5.1f deg: star V %+.1f, sky %.3e W m^-2 sr^-1: E / (L_sky Omega_pixel) %.3g, %s\n",
                  sunElevations[k], vMags[i], sky, contrast, shown ? "shown" : "hidden");
      if (shown && firstShown[i] < 0) firstShown[i] = k;
      if (k == 0) { EXPECT_FALSE(shown) << "V " << vMags[i] << " at noon"; }
      if (k == n - 1) { EXPECT_TRUE(shown) << "V " << vMags[i] << " at night"; }
    }
  }
  EXPECT_GT(firstShown[0], 0);
  EXPECT_LT(firstShown[0], firstShown[1]);
  EXPECT_LT(firstShown[1], firstShown[2]);
}

namespace {

// The V surface brightness (mag per square arcsecond) of a frame radiance: its luminance
// once the Sun's white balance is undone, against sky::radianceOfSurfaceBrightnessWm2Sr.
double surfaceBrightnessOf(const glm::dvec3& frameRadiance) {
  const glm::dvec3 unbalanced = frameRadiance * sky::sunLinearSrgb();
  const double y = 0.2126 * unbalanced.r + 0.7152 * unbalanced.g + 0.0722 * unbalanced.b;
  return -2.5 * std::log10(y / sky::radianceOfSurfaceBrightnessWm2Sr(0.0, 1361.0));
}

// The mean frame radiance of the 9 x 9 pixels at the image centre.
glm::dvec3 centreRadiance(BodyView& view) {
  std::vector<float> rgb;
  int w = 0, h = 0;
  view.ReadHdr(rgb, w, h);
  glm::dvec3 sum(0.0);
  for (int j = h / 2 - 4; j <= h / 2 + 4; ++j)
    for (int i = w / 2 - 4; i <= w / 2 + 4; ++i)
      for (int c = 0; c < 3; ++c) sum[c] += rgb[(static_cast<std::size_t>(j) * w + i) * 3 + c];
  return sum / 81.0;
}

}  // namespace

// The night sky's glow: a moonless zenith at the ground shows the dark site's 22.0 V mag per
// square arcsecond within 0.02 (the glow set above the air as that over the zenith
// transmittance at 550 nm);
// towards the horizon it brightens (van Rhijn) but less than the bare layer would.
// The full Moon 45 degrees up lights the zenith to the brightness of Krisciunas & Schaefer's
// (1991) model with the preset's own extinction (k = 1.086 tau_550) within 0.5 mag.
TEST(StarRender, MoonlitAndMoonlessZenith) {
  const AtmosphereFixture& f = atmosphereFixture();
  const double tau = f.model.verticalOpticalDepth(0.0, f.model.thicknessM())[1];
  const double glowAboveAir = sky::nightGlowAboveAirWm2Sr(tau, 1361.0);
  AtmosphereScene zenith(64, groundCamera(2.0, 89.9, 5.0), directionFromAngles(-60.0, 180.0));
  zenith.view.GetAtmosphere().SetNightGlow(glowAboveAir);
  zenith.view.Render();
  const double moonless = surfaceBrightnessOf(centreRadiance(zenith.view));
  AtmosphereScene low(64, groundCamera(2.0, 10.0, 5.0), directionFromAngles(-60.0, 180.0));
  low.view.GetAtmosphere().SetNightGlow(glowAboveAir);
  low.view.Render();
  const double atTen = surfaceBrightnessOf(centreRadiance(low.view));

  // The full Moon: V -12.7 (0.0032 W m^-2), grey, 45 degrees up.
  const double moonV = -12.7;
  const double moonE = 1361.0 * sky::irradianceRelativeToSun(moonV);
  zenith.view.GetAtmosphere().SetMoonLight(4.0e8 * directionFromAngles(45.0, 90.0), glm::dvec3(moonE));
  zenith.view.GetAtmosphere().SetNightGlow(0.0);
  zenith.view.Render();
  const double moonlit = surfaceBrightnessOf(centreRadiance(zenith.view));
  // Krisciunas & Schaefer 1991 (PASP 103, 1033), Eq. 15-21, B in nanolamberts.
  const double k = 2.5 / std::log(10.0) * tau, rho = 45.0, alpha = 0.0;
  const double fRho = std::pow(10.0, 5.36) * (1.06 + std::pow(std::cos(rho * kPi / 180.0), 2)) +
                      std::pow(10.0, 6.15 - rho / 40.0);
  const double iStar = std::pow(10.0, -0.4 * (3.84 + 0.026 * alpha + 4e-9 * std::pow(alpha, 4)));
  const double xMoon = 1.0 / std::sqrt(1.0 - 0.96 * std::pow(std::sin(45.0 * kPi / 180.0), 2));
  const double bNl = fRho * iStar * std::pow(10.0, -0.4 * k * xMoon) * (1.0 - std::pow(10.0, -0.4 * k));
  const double ks = (20.7233 - std::log(bNl / 34.08)) / 0.92104;
  std::printf("zenith: moonless %.3f, 10 deg up %.3f; full Moon 45 deg up %.3f (Krisciunas & Schaefer %.3f, k %.3f) "
              "V mag/arcsec^2\n", moonless, atTen, moonlit, ks, k);
  EXPECT_NEAR(moonless, 22.0, 0.03);  // luminance over three channels, the glow set at 550 nm (the haze's
                                      // extinction differs per channel: 21.98)
  EXPECT_LT(atTen, moonless - 0.3);
  EXPECT_GT(atTen, 22.0 - 2.5 * std::log10(1.0 / std::sin(10.0 * kPi / 180.0)));
  EXPECT_NEAR(moonlit, ks, 0.5);
}

namespace {

// A scene of the Earth (with air), the Moon and the Sun, from (latDeg, lonDeg) at `time`.
scene::Scene groundScene(const std::string& time, double latDeg, double lonDeg) {
  return scene::parseScene(R"({"time": ")" + time + R"(",
    "bodies": [{"preset": "Sun"}, {"preset": "Earth", "atmosphere": "earth"}, {"preset": "Moon"}],
    "camera": {"observer": {"body": "Earth", "latDeg": )" + std::to_string(latDeg) +
                               R"(, "lonDeg": )" + std::to_string(lonDeg) + R"(, "altM": 10},
               "target": {"azimuthDeg": 0, "elevationDeg": 20}, "up": "zenith"}})",
                           "ground.json");
}

double moonMagnitudeOf(const SceneInputs& in) {
  const glm::dvec3 e = in.atmosphere->moonIrradianceWm2;
  return sky::magnitudeOfIrradiance(0.2126 * e.r + 0.7152 * e.g + 0.0722 * e.b);
}

}  // namespace

// The night's lights a scene asks for: the full Moon of 2026-10-26 from San Juan lights the
// sky with its own magnitude (V -12.7, `umbra moon` and Allen's phase law) and the glow is
// on; the same place by day has neither; the totally eclipsed Moon of 2015-09-28 (from the
// mid-Atlantic) lights nothing (the airless shadow at its centre).
TEST(StarRender, NightLightsOfAScene) {
  const SceneInputs night = sceneInputs(groundScene("2026-10-26T04:00:00Z", 18.47, -66.11));
  ASSERT_TRUE(night.atmosphere);
  EXPECT_NEAR(moonMagnitudeOf(night), -12.7, 0.1);
  EXPECT_GT(night.atmosphere->nightGlowWm2Sr, 0.0);
  const SceneInputs day = sceneInputs(groundScene("2026-10-26T16:00:00Z", 18.47, -66.11));
  EXPECT_EQ(day.atmosphere->moonIrradianceWm2, glm::dvec3(0.0));
  EXPECT_EQ(day.atmosphere->nightGlowWm2Sr, 0.0);
  const SceneInputs totality = sceneInputs(groundScene("2015-09-28T02:47:00Z", 1.33, -29.02));
  EXPECT_GT(totality.atmosphere->nightGlowWm2Sr, 0.0);
  EXPECT_LT(glm::length(totality.atmosphere->moonIrradianceWm2), 1e-12);
}

// Scintillation through the air ("stars": "scintillation", "seed"): each star's light is
// changed, the same time and seed give the same light, another time other light; a star
// below the horizon and a scene without air are left alone (the factors' mean:
// test_sky's StarLight.ScintillationKeepsTheMean).
TEST(StarRender, SceneScintillation) {
  const std::string catalogue =
      (std::filesystem::temp_directory_path() / ("umbra-twinkle-" + std::to_string(::getpid()) + ".dat")).string();
  std::ofstream(catalogue) << kCatalogueRows;
  auto sceneWith = [&](const std::string& time, double sigma, bool air) {
    return scene::parseScene(R"({"time": ")" + time + R"(",
      "bodies": [{"preset": "Sun"}, {"preset": "Earth")" + (air ? R"(, "atmosphere": "earth")" : "") + R"(}],
      "camera": {"observer": {"body": "Earth", "latDeg": 0.0, "lonDeg": 0.0, "altM": 2},
                 "target": {"azimuthDeg": 240, "elevationDeg": 40}, "up": "zenith"},
      "stars": {"catalogue": ")" + catalogue + R"(", "scintillation": )" + std::to_string(sigma) + R"(, "seed": 3}})",
                             "twinkle.json");
  };
  const std::string t0 = "2024-03-20T22:00:00Z", t1 = "2024-03-20T22:00:01Z";
  const SceneInputs still = sceneInputs(sceneWith(t0, 0.0, true));
  const SceneInputs a = sceneInputs(sceneWith(t0, 0.3, true)), b = sceneInputs(sceneWith(t0, 0.3, true));
  const SceneInputs later = sceneInputs(sceneWith(t1, 0.3, true));
  ASSERT_GE(a.stars.size(), 2u);  // the catalogue's two, then the planets
  EXPECT_NE(a.stars[0].irradianceWm2, still.stars[0].irradianceWm2);  // Sirius, 40 deg up
  EXPECT_EQ(a.stars[0].irradianceWm2, b.stars[0].irradianceWm2);
  EXPECT_NE(a.stars[0].irradianceWm2, later.stars[0].irradianceWm2);
  EXPECT_EQ(a.stars[1].irradianceWm2, still.stars[1].irradianceWm2);  // Vega, below the horizon
  const SceneInputs space = sceneInputs(sceneWith(t0, 0.3, false));
  EXPECT_EQ(space.stars[0].irradianceWm2, still.stars[0].irradianceWm2);
  std::filesystem::remove(catalogue);
}

// The catalogue's binary copy: the second read comes from it with every number exactly as
// the text gave it (names dropped); a truncated or foreign copy is read past (the text
// again, and the copy rewritten); a changed text file has another copy.
TEST(StarRender, CatalogueCopyRoundTrip) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("umbra-star-copy-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string catalogue = (dir / "few.dat").string(), cache = (dir / "cache").string();
  std::ofstream(catalogue) << kCatalogueRows;
  const std::vector<sky::CatalogueStar> text = sky::readKStarsCatalogue(catalogue);
  const std::vector<sky::CatalogueStar> first = readStarCatalogue(catalogue, cache);
  const std::string copy = starCatalogueCopyPath(catalogue, cache);
  ASSERT_TRUE(std::filesystem::exists(copy));
  auto same = [&](const std::vector<sky::CatalogueStar>& got) {
    ASSERT_EQ(got.size(), text.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].raRad, text[i].raRad);
      EXPECT_EQ(got[i].decRad, text[i].decRad);
      EXPECT_EQ(got[i].pmRaCosDecMasPerYear, text[i].pmRaCosDecMasPerYear);
      EXPECT_EQ(got[i].pmDecMasPerYear, text[i].pmDecMasPerYear);
      EXPECT_EQ(got[i].parallaxMas, text[i].parallaxMas);
      EXPECT_EQ(got[i].vMag, text[i].vMag);
      EXPECT_EQ(got[i].bMinusV, text[i].bMinusV);
      EXPECT_EQ(got[i].name, "");
    }
  };
  same(first);
  // From the copy: change the text's numbers in place would change its key, so corrupt the
  // copy's magnitudes instead and see them come back.
  {
    std::fstream f(copy, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(24 + 5 * 8);
    const double v = 42.0;
    f.write(reinterpret_cast<const char*>(&v), sizeof v);
  }
  EXPECT_EQ(readStarCatalogue(catalogue, cache)[0].vMag, 42.0);
  std::filesystem::resize_file(copy, 30);
  same(readStarCatalogue(catalogue, cache));
  EXPECT_EQ(std::filesystem::file_size(copy), 24u + 2u * 7u * 8u);
  std::ofstream(catalogue, std::ios::app) << "\n";
  EXPECT_NE(starCatalogueCopyPath(catalogue, cache), copy);
  std::filesystem::remove_all(dir);
}
