// The atmosphere as the GPU renders it (AtmosphereRendering + atmosphere/glsl/Atmosphere.glsl)
// against the CPU lookups of atmosphere/Precompute.hpp on the same tables (the blocks of
// vtkAtmosphereTablesSource, read back with tablesFromBlocks), pixel by pixel: the sky
// radiance must agree within 1 %. The colour matrix is the identity here, so the frame
// holds the tables' own channels (680, 550, 440 nm) times the solar irradiance.
#include "AtmosphereTestSupport.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

using namespace umbra::pipeline;  // the scene glue (app/pipeline)

using namespace umbra;
using namespace umbra::render;
using namespace umbra::render::test;

namespace {

struct Agreement {
  int samples = 0;
  double maxRelative = 0.0;
  double minDistanceM = 1e30, maxDistanceM = 0.0;  // to the ground (compareGround)
};

struct RawFrame {
  std::vector<float> hdr;
  int w = 0, h = 0;
  double at(int i, int j, int c) const { return hdr[3 * (static_cast<std::size_t>(j) * w + i) + c]; }
};

// The frame in the tables' own channels (identity colour matrix) times the irradiance.
RawFrame renderRaw(const ViewCamera& camera, const glm::dvec3& sunDir, int size,
                   const atmosphere::AtmosphereTables& tables) {
  AtmosphereScene scene(size, camera, sunDir);
  if (&tables != &atmosphereFixture().tables)
    scene.view.GetAtmosphere().SetAtmosphere(atmosphereFixture().model, tables, glm::dvec3(0.0), scene.earth.albedoRgb);
  scene.view.GetAtmosphere().SetColourMatrix(glm::dmat3(1.0));
  scene.view.Render();
  RawFrame f;
  scene.view.ReadHdr(f.hdr, f.w, f.h);
  return f;
}

// Where the ray starts in the atmosphere (planet at the origin): its origin inside the
// shell, else its entry point; nothing when it misses (or grazes within 0.1 %) the shell.
std::optional<glm::dvec3> startPoint(const Ray& ray, double top) {
  if (glm::length(ray.origin) <= top) return ray.origin;
  const double tc = -glm::dot(ray.origin, ray.dir);
  const glm::dvec3 perp = ray.origin + tc * ray.dir;
  const double h = glm::length(perp);
  if (h >= top * 0.999 || tc <= 0.0) return std::nullopt;
  return perp - std::sqrt((top - h) * (top + h)) * ray.dir;
}

// Sky pixels (rays that leave the atmosphere without meeting the ground, away from the
// Sun's disc and from the horizon, where the tables switch halves) against skyRadiance at
// the camera, or at the entry point for a camera outside the atmosphere. A CPU value below
// `floor` times the brightest sampled one (the night sky's dark part) is compared
// absolutely, within 1 % of that floor.
Agreement compareSky(const ViewCamera& camera, const glm::dvec3& sunDir, int size, int step, double floor = 0.0,
                     const atmosphere::AtmosphereTables& tables = atmosphereFixture().tables) {
  const atmosphere::Atmosphere& model = atmosphereFixture().model;
  const RawFrame frame = renderRaw(camera, sunDir, size, tables);
  const int w = frame.w, h = frame.h;
  const double b = tables.bottomRadiusM, t = tables.topRadiusM;
  struct Sample {
    int i, j;
    glm::dvec3 cpu;
    std::string where;
  };
  std::vector<Sample> samples;
  double brightest = 0.0;
  for (int j = step / 2; j < h; j += step) {
    for (int i = step / 2; i < w; i += step) {
      const Ray ray = pixelRay(camera, w, h, i, j);
      const auto start = startPoint(ray, t);
      if (!start) continue;
      const glm::dvec3 x = *start;
      const double r = glm::length(x);
      const double mu = glm::dot(x, ray.dir) / r;
      if (atmosphere::rayIntersectsGround(b, r, mu)) continue;
      if (mu < atmosphere::horizonCosine(b, r) + 0.02) continue;
      const double nu = glm::dot(ray.dir, sunDir);
      if (nu > std::cos(0.02)) continue;  // the Sun's disc
      const double muS = glm::dot(x, sunDir) / r;
      const std::vector<double> L = atmosphere::skyRadiance(tables, model, r, mu, muS, nu);
      const glm::dvec3 cpu = glm::dvec3(L[0], L[1], L[2]) * kSolarIrradiance;
      brightest = std::max({brightest, cpu.r, cpu.g, cpu.b});
      samples.push_back({i, j, cpu, "(r " + std::to_string(r) + ", mu " + std::to_string(mu) + ", mu_s " +
                                        std::to_string(muS) + ", nu " + std::to_string(nu) + ")"});
    }
  }
  Agreement a;
  int dark = 0;
  for (const Sample& s : samples) {
    bool lit = true;
    for (int c = 0; c < 3; ++c) {
      const double expected = s.cpu[c], gpu = frame.at(s.i, s.j, c);
      if (expected < floor * brightest) {
        lit = false;
        EXPECT_LT(std::abs(gpu - expected), 0.01 * floor * brightest)
            << "pixel (" << s.i << ", " << s.j << ") channel " << c << ": GPU " << gpu << ", CPU " << expected << " "
            << s.where;
        continue;
      }
      const double rel = std::abs(gpu - expected) / expected;
      a.maxRelative = std::max(a.maxRelative, rel);
      EXPECT_LT(rel, 0.01) << "pixel (" << s.i << ", " << s.j << ") channel " << c << ": GPU " << gpu << ", CPU "
                           << expected << " " << s.where;
    }
    if (lit) ++a.samples;
    else ++dark;
  }
  std::printf("  %d sky samples, max |GPU - CPU| / CPU = %.3g", a.samples, a.maxRelative);
  if (floor > 0.0) std::printf("; %d below %.3g of the brightest, compared absolutely", dark, floor);
  std::printf("\n");
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

// The night sky with the Sun 14 degrees below the horizon (below the tables' lowest Sun,
// 12 degrees): the twilight arch towards the Sun's azimuth, from the light of the first
// sunlit air along each ray (skyRadiance), and darkness elsewhere.
TEST(AtmosphereGlsl, SkyRadianceWithTheSunBelowTheTablesLowest) {
  const Agreement a = compareSky(groundCamera(10.0, 10.0, 40.0), directionFromAngles(-14.0, 0.0), 96, 3, 1e-3);
  EXPECT_GE(a.samples, 250);  // 288 of 736 lit above the floor (the arch)
}

// The twilight tables a scene asks for after sunset (pipeline::configureAtmosphereTables:
// 4x the mu_s cells, the Sun down to 120 deg here): the Sun 8 and 14 deg below the
// horizon, the whole sky in view, the zenith lit by the air in the Earth's shadow.
TEST(AtmosphereGlsl, SkyRadianceOnTwilightTables) {
  vtkNew<vtkAtmosphereTablesSource> source;
  source->SetAtmosphere("earth");
  configureAtmosphereTables(source, AtmosphereTableSizes::Small, {true, 120.0 * kPi / 180.0});
  source->UseCacheOff();
  source->Update();
  ASSERT_TRUE(source->GetLastError().empty()) << source->GetLastError();
  const atmosphere::AtmosphereTables tables = umbra::filters::tablesFromBlocks(source->GetOutput(), atmosphereFixture().model);
  ASSERT_NEAR(tables.options.muSMin, std::cos(120.0 * kPi / 180.0), 1e-12);
  for (double depressionDeg : {8.0, 14.0}) {
    const Agreement a = compareSky(groundCamera(10.0, 40.0, 90.0), directionFromAngles(-depressionDeg, 0.0), 96, 3,
                                   1e-4, tables);
    EXPECT_GE(a.samples, 300) << depressionDeg;
  }
}

// From 20 000 and 150 000 km, the limb of the atmosphere: the entry point on the top
// boundary (the same 200 km of limb in the frame).
TEST(AtmosphereGlsl, SkyRadianceFromSpace) {
  const double t = atmosphereFixture().tables.topRadiusM;
  for (double distance : {2.0e7, 1.5e8}) {
    ViewCamera cam;
    cam.positionM = {distance, 0.0, 0.0};
    const double grazing = std::asin((t - 30e3) / distance);  // grazing 30 km below the top
    cam.targetM = cam.positionM + glm::dvec3(-std::cos(grazing), 0.0, std::sin(grazing));
    cam.up = {0.0, 0.0, 1.0};
    cam.fovDeg = 2.0 * std::atan(1e5 / distance) * 180.0 / kPi;
    const Agreement a = compareSky(cam, directionFromAngles(0.0, 80.0), 96, 3);
    EXPECT_GE(a.samples, 100) << distance;
  }
}

namespace {

// Ground pixels: T(x, y) albedo / pi (E_0 + E_ind)(y) plus the in-scattering
// S(x) - T(x, y) S(y) (aerial perspective), against the CPU; x the camera or the entry point.
Agreement compareGround(const ViewCamera& cam, const glm::dvec3& sunDir, int size, int step) {
  const AtmosphereFixture& f = atmosphereFixture();
  const RawFrame frame = renderRaw(cam, sunDir, size, f.tables);
  const double b = f.tables.bottomRadiusM;
  Agreement a;
  for (int j = step / 2; j < frame.h; j += step) {
    for (int i = step / 2; i < frame.w; i += step) {
      const Ray ray = pixelRay(cam, frame.w, frame.h, i, j);
      const auto start = startPoint(ray, f.tables.topRadiusM);
      if (!start) continue;
      const glm::dvec3 x = *start;
      const double r = glm::length(x), mu = glm::dot(x, ray.dir) / r;
      if (!atmosphere::rayIntersectsGround(b, r, mu)) continue;
      const double d = atmosphere::distanceToBottomBoundaryM(b, r, mu);
      const glm::dvec3 y = x + d * ray.dir;
      const double muS = glm::dot(x, sunDir) / r, nu = glm::dot(ray.dir, sunDir);
      const double rd = b, mud = glm::dot(y, ray.dir) / rd, muSd = glm::dot(y, sunDir) / rd;
      const auto T = atmosphere::transmittanceAlong(f.tables, r, mu, d, true, true);  // umbraAtmTransmittance
      const auto Sx = atmosphere::skyRadiance(f.tables, f.model, r, mu, muS, nu);
      const auto Sy = atmosphere::skyRadiance(f.tables, f.model, rd, mud, muSd, nu);
      const auto E0 = atmosphere::directIrradiance(f.tables, b, muSd);
      const auto Ei = atmosphere::indirectIrradiance(f.tables, b, muSd);
      for (int c = 0; c < 3; ++c) {
        const double S = std::max(Sx[c] - T[c] * Sy[c], 0.0);
        const double expected = (T[c] * 0.1 / kPi * (E0[c] + Ei[c]) + S) * kSolarIrradiance;
        const double gpu = frame.at(i, j, c);
        if (expected == 0.0) {  // night ground past the tables' lowest Sun: black on both
          EXPECT_EQ(gpu, 0.0) << "pixel (" << i << ", " << j << ") channel " << c << " at " << d << " m";
          continue;
        }
        const double rel = std::abs(gpu - expected) / expected;
        a.maxRelative = std::max(a.maxRelative, rel);
        EXPECT_LT(rel, 0.01) << "pixel (" << i << ", " << j << ") channel " << c << ": GPU " << gpu << ", CPU "
                             << expected << " at " << d << " m";
      }
      a.minDistanceM = std::min(a.minDistanceM, d);
      a.maxDistanceM = std::max(a.maxDistanceM, d);
      ++a.samples;
    }
  }
  std::printf("  %d ground samples %.0f..%.0f m away, max |GPU - CPU| / CPU = %.3g\n", a.samples, a.minDistanceM,
              a.maxDistanceM, a.maxRelative);
  return a;
}

} // namespace

// The ground seen from 2 km up, 8 to 56 km away.
TEST(AtmosphereGlsl, GroundAndAerialPerspective) {
  const Agreement a = compareGround(groundCamera(2000.0, -8.0, 12.0), directionFromAngles(25.0, 40.0), 96, 4);
  EXPECT_GE(a.samples, 300);
  EXPECT_LT(a.minDistanceM, 10e3);
  EXPECT_GT(a.maxDistanceM, 30e3);
}

// The whole planet from 150 000 km: the day side through the atmosphere from its top.
// The Sun's disc setting over the ground (its centre 0.2 degrees below the camera's
// horizon; the ground 15-110 km away is tilted 0.1-1 degree towards it, so that the disc
// is partly up over its nearer half): E_0 from the transmittance times the disc's visible
// share, through its partial branch.
TEST(AtmosphereGlsl, GroundAsTheSunSets) {
  const Agreement a = compareGround(groundCamera(2000.0, -4.0, 8.0), directionFromAngles(-0.2, 0.0), 96, 4);
  EXPECT_GE(a.samples, 300);
}

// The ground 5 degrees after sunset, lit by the sky alone: the irradiance table's cells
// below the horizon, interpolated geometrically (lookupIrradiance), on both.
TEST(AtmosphereGlsl, GroundAfterSunset) {
  const Agreement a = compareGround(groundCamera(2000.0, -4.0, 8.0), directionFromAngles(-5.0, 0.0), 96, 4);
  EXPECT_GE(a.samples, 300);
}

TEST(AtmosphereGlsl, GroundFrom150000km) {
  ViewCamera cam;
  cam.positionM = {0.0, -1.5e8, 2.0e7};
  cam.targetM = {0.0, 0.0, 0.0};
  cam.up = {0.0, 0.0, 1.0};
  cam.fovDeg = 6.0;
  const Agreement a = compareGround(cam, directionFromAngles(10.0, -60.0), 96, 3);
  EXPECT_GE(a.samples, 200);
}

// The colour matrix keeps the bare Sun white: M (1, 1, 1) = (1, 1, 1); a Rayleigh-like
// spectrum (more blue than red) comes out blue.
TEST(AtmosphereGlsl, ColourMatrixKeepsTheSunWhite) {
  const glm::dmat3 m = atmosphereToDisplayMatrix(atmosphere::WavelengthSet::rgb().nm);
  const glm::dvec3 sun = m * glm::dvec3(1.0);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sun[c], 1.0, 1e-12);
  const glm::dvec3 sky = m * glm::dvec3(std::pow(550.0 / 680.0, 4), 1.0, std::pow(550.0 / 440.0, 4));
  EXPECT_GT(sky.b, 1.5 * sky.r);
  EXPECT_THROW(atmosphereToDisplayMatrix({500.0, 600.0}), std::invalid_argument);
}

// The phase lobes the shader evaluates reproduce every analytic phase function.
TEST(AtmosphereGlsl, PhaseLobesReproduceThePhaseFunctions) {
  using atmosphere::PhaseFunction;
  const PhaseFunction phases[] = {PhaseFunction::isotropic(), PhaseFunction::rayleigh(), PhaseFunction::penndorf(),
                                  PhaseFunction::henyeyGreenstein(0.7), PhaseFunction::cornetteShanks(0.8),
                                  PhaseFunction::doubleHenyeyGreenstein(0.8, -0.3, 0.9)};
  for (const PhaseFunction& p : phases) {
    PhaseLobe a, b;
    phaseLobes(p, a, b);
    for (double c = -1.0; c <= 1.0; c += 0.125) {
      auto lobe = [c](const PhaseLobe& l) { return l.a * (1.0 + l.b * c * c) / std::pow(1.0 + l.g * l.g - 2.0 * l.g * c, 1.5); };
      EXPECT_NEAR(lobe(a) + lobe(b), p(c), 1e-12 * std::max(1.0, p(c))) << p.describe() << " at " << c;
    }
  }
  // A table (e.g. Lorenz-Mie's) is drawn from the phase table: no lobes, and its row holds
  // the function at theta = pi i / (N - 1) per channel.
  std::vector<double> mu, v;
  for (int i = 0; i <= 2000; ++i) mu.push_back(-1.0 + i / 1000.0);
  for (double m : mu) v.push_back(PhaseFunction::henyeyGreenstein(0.6)(m));
  const PhaseFunction table = PhaseFunction::tabulated(mu, v);
  PhaseLobe a, b;
  phaseLobes(table, a, b);
  EXPECT_EQ(a.a, 0.0);
  EXPECT_EQ(b.a, 0.0);
  atmosphere::Component c;
  c.phases = {table, table, PhaseFunction::rayleigh()};
  std::vector<float> row;
  ASSERT_TRUE(phaseTableRow(c, row));
  ASSERT_EQ(row.size(), 3u * kPhaseTableSamples);
  for (int i : {0, 1, 100, kPhaseTableSamples / 2, kPhaseTableSamples - 1}) {
    const double cosTheta = std::cos(3.14159265358979323846 * i / (kPhaseTableSamples - 1));
    EXPECT_NEAR(row[3 * i], table(cosTheta), 1e-6 * table(cosTheta)) << i;
    EXPECT_NEAR(row[3 * i + 2], PhaseFunction::rayleigh()(cosTheta), 1e-6) << i;
  }
  c.phases = {PhaseFunction::rayleigh(), PhaseFunction::rayleigh(), PhaseFunction::rayleigh()};
  EXPECT_FALSE(phaseTableRow(c, row));
}
