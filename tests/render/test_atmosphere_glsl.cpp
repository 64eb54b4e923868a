// The atmosphere as the GPU renders it (AtmosphereRendering + atmosphere/glsl/Atmosphere.glsl)
// against the CPU lookups of atmosphere/Precompute.hpp on the same tables (the blocks of
// vtkAtmosphereTablesSource, read back with tablesFromBlocks), pixel by pixel: the sky
// radiance must agree within 1 %. The colour matrix is the identity here, so the frame
// holds the tables' own channels (680, 550, 440 nm) times the solar irradiance.
#include "AtmosphereTestSupport.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

using namespace umbra;
using namespace umbra::render;
using namespace umbra::render::test;

namespace {

struct Agreement {
  int samples = 0;
  double maxRelative = 0.0;
};

// Sky pixels (rays that leave the atmosphere without meeting the ground, away from the
// Sun's disc and from the horizon, where the tables switch halves) against skyRadiance at
// the camera, or at the entry point for a camera outside the atmosphere.
Agreement compareSky(const ViewCamera& camera, const glm::dvec3& sunDir, int size, int step) {
  const AtmosphereFixture& f = atmosphereFixture();
  AtmosphereScene scene(size, camera, sunDir);
  scene.view.GetAtmosphere().SetColourMatrix(glm::dmat3(1.0));
  scene.view.Render();
  std::vector<float> hdr;
  int w = 0, h = 0;
  scene.view.ReadHdr(hdr, w, h);
  const double b = f.tables.bottomRadiusM, t = f.tables.topRadiusM;
  Agreement a;
  for (int j = step / 2; j < h; j += step) {
    for (int i = step / 2; i < w; i += step) {
      const Ray ray = pixelRay(camera, w, h, i, j);
      glm::dvec3 x = ray.origin;  // planet at the origin
      if (glm::length(x) > t) {   // move to the entry point
        const double tc = -glm::dot(x, ray.dir);
        const glm::dvec3 perp = x + tc * ray.dir;
        const double hgt = glm::length(perp);
        if (hgt >= t * 0.999 || tc <= 0.0) continue;
        x = perp - std::sqrt((t - hgt) * (t + hgt)) * ray.dir;
      }
      const double r = glm::length(x);
      const double mu = glm::dot(x, ray.dir) / r;
      if (atmosphere::rayIntersectsGround(b, r, mu)) continue;
      if (mu < atmosphere::horizonCosine(b, r) + 0.02) continue;
      const double nu = glm::dot(ray.dir, sunDir);
      if (nu > std::cos(0.02)) continue;  // the Sun's disc
      const double muS = glm::dot(x, sunDir) / r;
      const std::vector<double> cpu = atmosphere::skyRadiance(f.tables, f.model, r, mu, muS, nu);
      for (int c = 0; c < 3; ++c) {
        const double expected = cpu[c] * kSolarIrradiance;
        const double gpu = hdr[3 * (static_cast<std::size_t>(j) * w + i) + c];
        const double rel = std::abs(gpu - expected) / expected;
        a.maxRelative = std::max(a.maxRelative, rel);
        EXPECT_LT(rel, 0.01) << "pixel (" << i << ", " << j << ") channel " << c << ": GPU " << gpu << ", CPU "
                             << expected << " (r " << r << ", mu " << mu << ", mu_s " << muS << ", nu " << nu << ")";
      }
      ++a.samples;
    }
  }
  std::printf("  %d sky samples, max |GPU - CPU| / CPU = %.3g\n", a.samples, a.maxRelative);
  return a;
}

} // namespace

// An observer 1 km up looking 20 degrees above the horizon, the Sun 30 degrees high and
// 60 degrees to the side (single scattering of both components, their phases, multiple
// scattering).
TEST(AtmosphereGlsl, SkyRadianceFromTheGround) {
  const Agreement a = compareSky(groundCamera(1000.0, 20.0, 70.0), directionFromAngles(30.0, 60.0), 96, 4);
  EXPECT_GE(a.samples, 300);
}

// Looking towards a Sun 3 degrees above the horizon: the forward aerosol lobe.
TEST(AtmosphereGlsl, SkyRadianceTowardsALowSun) {
  const Agreement a = compareSky(groundCamera(10.0, 11.5, 60.0), directionFromAngles(3.0, 10.0), 96, 4);
  EXPECT_GE(a.samples, 300);
}

// From 20 000 km, the limb of the atmosphere: the entry point on the top boundary.
TEST(AtmosphereGlsl, SkyRadianceFromSpace) {
  const double t = atmosphereFixture().tables.topRadiusM;
  ViewCamera cam;
  cam.positionM = {2.0e7, 0.0, 0.0};
  const double grazing = std::asin((t - 30e3) / 2.0e7);  // grazing 30 km below the top
  cam.targetM = cam.positionM + glm::dvec3(-std::cos(grazing), 0.0, std::sin(grazing));
  cam.up = {0.0, 0.0, 1.0};
  cam.fovDeg = 1.0;
  const Agreement a = compareSky(cam, directionFromAngles(0.0, 80.0), 96, 3);
  EXPECT_GE(a.samples, 100);
}

namespace {

// Bruneton's transmittance between (r, mu) and the point at distance d (the CPU side of
// umbraAtmTransmittance): a ratio of transmittances to the top, upwards for ground rays;
// rd is the radius at that point.
std::vector<double> transmittanceBetween(const atmosphere::AtmosphereTables& t, double r, double mu, double d,
                                         bool ground, double rd) {
  const double mud = std::clamp((r * mu + d) / rd, -1.0, 1.0);
  const auto a = ground ? atmosphere::transmittanceToTop(t, rd, -mud) : atmosphere::transmittanceToTop(t, r, mu);
  const auto b = ground ? atmosphere::transmittanceToTop(t, r, -mu) : atmosphere::transmittanceToTop(t, rd, mud);
  std::vector<double> out(a.size());
  for (std::size_t c = 0; c < a.size(); ++c) out[c] = std::min(a[c] / b[c], 1.0);
  return out;
}

} // namespace

// The ground seen from 2 km up, 5 to 60 km away: T(x, y) albedo / pi (E_0 + E_ind)(y) plus
// the in-scattering S(x) - T(x, y) S(y) (aerial perspective), against the CPU.
TEST(AtmosphereGlsl, GroundAndAerialPerspective) {
  const AtmosphereFixture& f = atmosphereFixture();
  const ViewCamera cam = groundCamera(2000.0, -8.0, 12.0);
  const glm::dvec3 sunDir = directionFromAngles(25.0, 40.0);
  AtmosphereScene scene(96, cam, sunDir);
  scene.view.GetAtmosphere().SetColourMatrix(glm::dmat3(1.0));
  scene.view.Render();
  std::vector<float> hdr;
  int w = 0, h = 0;
  scene.view.ReadHdr(hdr, w, h);
  const double b = f.tables.bottomRadiusM;
  int samples = 0;
  double maxRel = 0.0, minD = 1e30, maxD = 0.0;
  for (int j = 2; j < h; j += 4) {
    for (int i = 2; i < w; i += 4) {
      const Ray ray = pixelRay(cam, w, h, i, j);
      const glm::dvec3 x = ray.origin;
      const double r = glm::length(x), mu = glm::dot(x, ray.dir) / r;
      if (!atmosphere::rayIntersectsGround(b, r, mu)) continue;
      const double d = atmosphere::distanceToBottomBoundaryM(b, r, mu);
      const glm::dvec3 y = x + d * ray.dir;
      const double muS = glm::dot(x, sunDir) / r, nu = glm::dot(ray.dir, sunDir);
      const double muSy = glm::dot(glm::normalize(y), sunDir);
      const double rd = b, mud = glm::dot(y, ray.dir) / rd, muSd = glm::dot(y, sunDir) / rd;
      const auto T = transmittanceBetween(f.tables, r, mu, d, true, rd);
      const auto Sx = atmosphere::skyRadiance(f.tables, f.model, r, mu, muS, nu);
      const auto Sy = atmosphere::skyRadiance(f.tables, f.model, rd, mud, muSd, nu);
      const auto E0 = atmosphere::directIrradiance(f.tables, b, muSy);
      const auto Ei = atmosphere::indirectIrradiance(f.tables, b, muSy);
      for (int c = 0; c < 3; ++c) {
        const double S = std::max(Sx[c] - T[c] * Sy[c], 0.0);
        const double expected = (T[c] * 0.1 / kPi * (E0[c] + Ei[c]) + S) * kSolarIrradiance;
        const double gpu = hdr[3 * (static_cast<std::size_t>(j) * w + i) + c];
        const double rel = std::abs(gpu - expected) / expected;
        maxRel = std::max(maxRel, rel);
        EXPECT_LT(rel, 0.01) << "pixel (" << i << ", " << j << ") channel " << c << ": GPU " << gpu << ", CPU "
                             << expected << " at " << d << " m; T " << T[c] << " ground " << T[c] * 0.1 / kPi * (E0[c] + Ei[c]) * kSolarIrradiance << " S " << S * kSolarIrradiance << " Sx " << Sx[c] * kSolarIrradiance << " Sy " << Sy[c] * kSolarIrradiance << " mud " << mud << " muS " << muS << " nu " << nu;
      }
      minD = std::min(minD, d);
      maxD = std::max(maxD, d);
      ++samples;
    }
  }
  std::printf("  %d ground samples %.0f..%.0f m away, max |GPU - CPU| / CPU = %.3g\n", samples, minD, maxD, maxRel);
  EXPECT_GE(samples, 300);
  EXPECT_LT(minD, 10e3);
  EXPECT_GT(maxD, 30e3);
}
