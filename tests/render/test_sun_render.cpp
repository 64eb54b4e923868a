// The Sun in a scene without an atmosphere (StarRendering's Sun stage, glsl/SunDisc.glsl):
// the disc's centre radiance is Eq. 1's limb-darkened profile times E / (pi alpha^2), its
// pixels times their solid angles give back the irradiance at the camera, a body in front
// hides the limb-darkened fraction eclipse::visibleFractionLimbDarkened says, and a Sun
// smaller than two pixels keeps its irradiance and its place.
#include "RenderTestSupport.hpp"

#include "Corona.hpp"
#include "SolarDisc.hpp"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace umbra;
using namespace umbra::render;
using namespace umbra::render::test;

namespace {

constexpr int kSize = 256;

/// A camera `distanceM` from the Sun (at the origin), looking at it through a `fovDeg`
/// field, from -x.
ViewCamera cameraOnTheSun(double distanceM, double fovDeg) {
  ViewCamera c;
  c.positionM = {-distanceM, 0.0, 0.0};
  c.targetM = {0.0, 0.0, 0.0};
  c.up = {0.0, 0.0, 1.0};
  c.fovDeg = fovDeg;
  return c;
}

/// The solid angle of pixel (i, j) of a square view of `fovDeg`, at its centre.
double pixelSolidAngle(int i, int j, double fovDeg) {
  const double s = 2.0 * std::tan(0.5 * fovDeg * kPi / 180.0) / kSize;
  const double u = (i + 0.5 - 0.5 * kSize) * s, v = (0.5 * kSize - (j + 0.5)) * s;
  return s * s / std::pow(1.0 + u * u + v * v, 1.5);
}

struct SunImage {
  std::vector<float> rgb;
  double irradiance = 0.0;  // sum of G radiance x solid angle
  double x = 0.0, y = 0.0;  // its centroid, pixels from the top-left
  double maxRgbSpread = 0.0;
};

SunImage renderSun(BodyView& view, const ViewCamera& camera, const std::vector<SphereBody>& bodies = {}) {
  SunLight sun;  // at the origin, 1361 W m^-2 at 1 au
  view.SetBodies(sun, bodies, testLutImage());
  view.SetCamera(camera);
  view.Render();
  SunImage out;
  int w = 0, h = 0;
  view.ReadHdr(out.rgb, w, h);
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      const float* p = &out.rgb[(static_cast<std::size_t>(j) * kSize + i) * 3];
      const double e = p[1] * pixelSolidAngle(i, j, camera.fovDeg);
      out.irradiance += e;
      out.x += e * (i + 0.5);
      out.y += e * (j + 0.5);
      out.maxRgbSpread = std::max({out.maxRgbSpread, std::abs(double(p[0]) - p[1]), std::abs(double(p[2]) - p[1])});
    }
  if (out.irradiance > 0.0) out.x /= out.irradiance, out.y /= out.irradiance;
  return out;
}

}  // namespace

TEST(SunRender, DiscRadianceAndIrradianceFromSpace) {
  // 0.67 au from the Sun, a 2 degree field: the disc 0.80 degrees across, 51 pixels in radius.
  BodyView view(kSize, kSize, true);
  useSharedDisplay(view.GetRenderWindow());
  const double d = 0.67 * kAu;
  const SunImage image = renderSun(view, cameraOnTheSun(d, 2.0));
  const double E = 1361.0 / (0.67 * 0.67), alpha = std::asin(SunLight{}.radiusM / d);
  const double centre = E / (kPi * alpha * alpha) * eclipse::limbDarkenedLuminance(0.0, eclipse::kDefaultLimbDarkening);
  // The four pixels around the image centre lie within 0.3 % of the disc's radius of it.
  const float* p = &image.rgb[(static_cast<std::size_t>(kSize / 2) * kSize + kSize / 2) * 3];
  std::printf("centre %.6e (model %.6e), irradiance %.3f W/m^2 (model %.3f), centroid %.3f %.3f\n", p[1], centre,
              image.irradiance, E, image.x, image.y);
  EXPECT_NEAR(p[1], centre, 0.01 * centre);
  EXPECT_NEAR(image.irradiance, E, 0.01 * E);
  EXPECT_NEAR(image.x, 0.5 * kSize, 0.05);
  EXPECT_NEAR(image.y, 0.5 * kSize, 0.05);
  EXPECT_EQ(image.maxRgbSpread, 0.0);  // white, as the frame's convention has the Sun
  // The limb: at 0.95 of the radius Eq. 1 gives 0.544 of the centre's radiance.
  const int limb = static_cast<int>(std::lround(0.5 * kSize - 0.5 + 0.95 * alpha / (2.0 * kPi / 180.0 / kSize)));
  const float* q = &image.rgb[(static_cast<std::size_t>(kSize / 2) * kSize + limb) * 3];
  EXPECT_NEAR(q[1] / p[1], eclipse::limbDarkenedLuminance(0.95, 0.6) / eclipse::limbDarkenedLuminance(0.0, 0.6), 0.03);
}

TEST(SunRender, ABodyInFrontHidesTheLimbDarkenedFractionItCovers) {
  // A dark sphere between the camera (1 au out) and the Sun, its disc 0.8 of the Sun's in
  // radius, its centre 0.9 solar radii off the Sun's: the pixels' light against Eq. 1's
  // visible fraction (the body's night side faces the camera: it adds nothing).
  BodyView view(kSize, kSize, true);
  useSharedDisplay(view.GetRenderWindow());
  const ViewCamera camera = cameraOnTheSun(kAu, 1.5);
  const double alpha = std::asin(SunLight{}.radiusM / kAu);
  const double bodyDistanceM = 1.0e9, bodyRadiusM = bodyDistanceM * std::tan(0.8 * alpha);
  const glm::dvec3 centre = camera.positionM + glm::dvec3(bodyDistanceM, bodyDistanceM * std::tan(0.9 * alpha), 0.0);
  const SphereBody body{"Blocker", centre, bodyRadiusM, {0.0, 0.0, 0.0}};
  const SunImage clear = renderSun(view, camera);
  const SunImage covered = renderSun(view, camera, {body});
  const eclipse::ShadowAngles angles = eclipse::shadowAngles(camera.positionM, glm::dvec3(0.0), SunLight{}.radiusM, centre, bodyRadiusM);
  const eclipse::NormalisedDiscs n = eclipse::normalisedDiscs(angles);
  const double expected = eclipse::visibleFractionLimbDarkened(n.occluderRadius, n.separation).value;
  std::printf("visible %.4f of the Sun (Eq. 1: %.4f)\n", covered.irradiance / clear.irradiance, expected);
  EXPECT_GT(expected, 0.2);
  EXPECT_LT(expected, 0.8);
  EXPECT_NEAR(covered.irradiance / clear.irradiance, expected, 0.01);
  EXPECT_NEAR(clear.irradiance, 1361.0, 0.01 * 1361.0);
}

TEST(SunRender, ASunSmallerThanTwoPixelsKeepsItsIrradianceAndPlace) {
  // From 40 au the Sun is 0.85 pixels in radius in a 2 degree field; off the centre.
  BodyView view(kSize, kSize, true);
  useSharedDisplay(view.GetRenderWindow());
  ViewCamera camera = cameraOnTheSun(40.0 * kAu, 2.0);
  const double offDeg = 0.3;  // the Sun 0.3 degrees left of the image centre
  camera.targetM = camera.positionM + glm::dvec3(std::cos(offDeg * kPi / 180.0), -std::sin(offDeg * kPi / 180.0), 0.0);
  const SunImage image = renderSun(view, camera);
  const double E = 1361.0 / (40.0 * 40.0);
  const double s = 2.0 * std::tan(1.0 * kPi / 180.0) / kSize;
  std::printf("irradiance %.5f W/m^2 (model %.5f), at %.3f %.3f\n", image.irradiance, E, image.x, image.y);
  EXPECT_NEAR(image.irradiance, E, 0.01 * E);
  EXPECT_NEAR(image.x, 0.5 * kSize - std::tan(offDeg * kPi / 180.0) / s, 0.1);
  EXPECT_NEAR(image.y, 0.5 * kSize, 0.1);
}

TEST(SunRender, NoSunBehindTheCamera) {
  BodyView view(kSize, kSize, true);
  useSharedDisplay(view.GetRenderWindow());
  ViewCamera camera = cameraOnTheSun(kAu, 30.0);
  camera.targetM = camera.positionM - glm::dvec3(1.0, 0.0, 0.0);
  EXPECT_EQ(renderSun(view, camera).irradiance, 0.0);
}

TEST(SunRender, TheCoronaAroundAHiddenDiscIsBaumbachs) {
  // A dark sphere hides the disc whole (1.05 times its angular radius, centred), 1 au out:
  // around it the corona at 1.5, 2 and 3 solar radii against sky/Corona.hpp times the
  // disc's mean radiance E / (pi alpha^2).
  BodyView view(kSize, kSize, true);
  useSharedDisplay(view.GetRenderWindow());
  const ViewCamera camera = cameraOnTheSun(kAu, 2.0);
  const double alpha = std::asin(SunLight{}.radiusM / kAu);
  const double bodyDistanceM = 1.0e9;
  const SphereBody body{"Blocker", camera.positionM + glm::dvec3(bodyDistanceM, 0.0, 0.0),
                        bodyDistanceM * std::tan(1.05 * alpha), {0.0, 0.0, 0.0}};
  const SunImage image = renderSun(view, camera, {body});
  const double mean = 1361.0 / (kPi * alpha * alpha);
  const double pixelRad = 2.0 * std::tan(1.0 * kPi / 180.0) / kSize;  // at the centre
  for (double rho : {1.5, 2.0, 3.0}) {
    // The pixel whose centre lies nearest rho solar radii right of the Sun's centre.
    const int i = static_cast<int>(std::lround(0.5 * kSize - 0.5 + std::tan(rho * alpha) / pixelRad));
    const double x = (i + 0.5 - 0.5 * kSize) * pixelRad;
    const double rhoAt = std::atan(x) / alpha;
    const float* p = &image.rgb[(static_cast<std::size_t>(kSize / 2) * kSize + i) * 3];
    const double expected = mean * sky::coronaRelativeRadiance(rhoAt);
    std::printf("corona at %.3f solar radii: %.4e W m^-2 sr^-1 (Baumbach %.4e)\n", rhoAt, p[1], expected);
    EXPECT_NEAR(p[1], expected, 0.02 * expected) << rho;
  }
  const float* centre = &image.rgb[(static_cast<std::size_t>(kSize / 2) * kSize + kSize / 2) * 3];
  EXPECT_EQ(centre[1], 0.0f);  // the body
}
