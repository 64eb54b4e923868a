// The atmosphere tables a scene asks for (pipeline::atmosphereTableChoice,
// configureAtmosphereTables): the day's, or after sunset at the camera tables with finer
// mu_s cells that reach 20 deg below the Sun. What the twilight tables change is checked on
// the CPU lookups (the GPU draws the same, test_atmosphere_glsl): the zenith after sunset
// against the sky command's tables (atmosphere::skyPrecomputeOptions, within 20 % of brute
// force in Precompute.SecondOrderTwilightAtTheZenithMatchesBruteForce).
#include "AtmosphereTestSupport.hpp"

#include "Precompute.hpp"
#include "Sky.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

using namespace umbra::pipeline;  // the scene glue (app/pipeline)

using namespace umbra;
using namespace umbra::render;
using namespace umbra::render::test;

namespace {

constexpr double kDeg = kPi / 180.0;

// Earth at the origin with its atmosphere; the camera altitudeM above the north pole; the
// Sun 1 au away, elevationDeg above the camera's horizontal.
SceneInputs groundScene(double altitudeM, double sunElevationDeg) {
  const double bottomM = atmosphereFixture().tables.bottomRadiusM, topM = atmosphereFixture().tables.topRadiusM;
  SceneInputs in;
  in.sun.positionM = directionFromAngles(sunElevationDeg, 0.0) * kAu;
  in.bodies.push_back({"Earth", {0.0, 0.0, 0.0}, bottomM, {0.1, 0.1, 0.1}});
  in.atmosphere = SceneAtmosphere{"Earth", atmosphere::AtmosphereModel::load("earth"), bottomM, topM};
  in.camera.positionM = {0.0, 0.0, bottomM + altitudeM};
  in.camera.targetM = in.camera.positionM + glm::dvec3(1.0, 0.0, 0.0);
  return in;
}

atmosphere::AtmosphereTables sceneTables(const SceneInputs& in, AtmosphereTableSizes sizes = AtmosphereTableSizes::Small) {
  vtkNew<vtkAtmosphereTablesSource> source;
  source->SetAtmosphere("earth");
  configureAtmosphereTables(source, sizes, atmosphereTableChoice(in));
  source->UseCacheOff();
  source->Update();
  if (!source->GetLastError().empty()) throw std::runtime_error(source->GetLastError());
  return umbra::filters::tablesFromBlocks(source->GetOutput(), atmosphereFixture().model);
}

// The sky from 2 m, viewZenithRad from the zenith towards the Sun's azimuth.
std::vector<double> skyRadiance(const atmosphere::AtmosphereTables& t, double sunZenithRad, double viewZenithRad) {
  const double mu = std::cos(viewZenithRad), muS = std::cos(sunZenithRad);
  const double nu = mu * muS + std::sin(viewZenithRad) * std::sin(sunZenithRad);
  return atmosphere::skyRadiance(t, atmosphereFixture().model, t.bottomRadiusM + 2.0, mu, muS, nu);
}
std::vector<double> zenith(const atmosphere::AtmosphereTables& t, double sunZenithRad) { return skyRadiance(t, sunZenithRad, 0.0); }

// The twilight tables' value within a factor `within` of the reference, and the day
// tables' at least `worse` times as far off (in log): per channel.
void expectTwilightCloser(const std::vector<double>& day, const std::vector<double>& twilight,
                          const std::vector<double>& reference, double within, double worse, const std::string& what) {
  for (int c = 0; c < 3; ++c) {
    ASSERT_GT(reference[c], 0.0) << what;
    const double twilightError = std::abs(std::log(twilight[c] / reference[c]));
    EXPECT_LT(twilightError, std::log(within)) << what << ", channel " << c;
    EXPECT_GT(std::abs(std::log(day[c] / reference[c])), worse * twilightError) << what << ", channel " << c;
  }
}

} // namespace

// Daylight, the Sun on the horizon, night and a camera above the air: the day's tables.
// In twilight (the Sun's centre 1 deg down to 10 deg past 2 acos(bottom / top), for
// Earth's preset 20.1 deg): twilight tables, their lowest Sun 20 deg below the camera's
// rounded up to 10 deg, at least 120.
TEST(SceneAtmosphereTables, ChoiceFollowsTheSunAtTheCamera) {
  for (double e : {60.0, 0.0, -0.9, -30.3, -45.0, -90.0})
    EXPECT_FALSE(atmosphereTableChoice(groundScene(2.0, e)).twilight) << e;
  const std::vector<std::pair<double, double>> cases = {
      {-1.5, 120.0}, {-9.9, 120.0}, {-10.5, 130.0}, {-16.0, 130.0}, {-21.9, 140.0}, {-29.9, 140.0}};
  for (const auto& [elevationDeg, lowestDeg] : cases) {
    const AtmosphereTableChoice c = atmosphereTableChoice(groundScene(2.0, elevationDeg));
    EXPECT_TRUE(c.twilight) << elevationDeg;
    EXPECT_NEAR(c.lowestSunZenithRad / kDeg, lowestDeg, 1e-9) << elevationDeg;
  }
  // At the top of the atmosphere and above it: the day's tables, whatever the Sun.
  const double thickness = atmosphereFixture().tables.topRadiusM - atmosphereFixture().tables.bottomRadiusM;
  EXPECT_TRUE(atmosphereTableChoice(groundScene(thickness - 1e3, -20.0)).twilight);
  EXPECT_FALSE(atmosphereTableChoice(groundScene(thickness, -20.0)).twilight);
  EXPECT_FALSE(atmosphereTableChoice(groundScene(1.5e8, -90.0)).twilight);
  SceneInputs airless = groundScene(2.0, -20.0);
  airless.atmosphere.reset();
  EXPECT_FALSE(atmosphereTableChoice(airless).twilight);
}

// The zenith from 2 m, 10 and 16 deg after sunset, on the day's small tables and on the
// twilight ones the scene asks for, against the sky command's (128 mu_s cells, 24 x 48
// directions, 4 orders). The day's: x26-43 too bright at 10 deg (8 mu_s cells), black at
// 16 deg (their lowest Sun is 12 deg down); the twilight ones within x3 at both (x1.2-2.5;
// the default sizes' within 7 %: docs/accuracy-vs-speed/atmosphere-tables.md, "Twilight in the render pass").
TEST(SceneAtmosphereTables, TwilightTablesCarryTheZenithAfterSunset) {
  const atmosphere::Atmosphere& model = atmosphereFixture().model;
  for (double depressionDeg : {10.0, 16.0}) {
    const double z = (90.0 + depressionDeg) * kDeg;
    const SceneInputs in = groundScene(2.0, -depressionDeg);
    ASSERT_TRUE(atmosphereTableChoice(in).twilight);
    const auto day = zenith(atmosphereFixture().tables, z);
    const auto twilight = zenith(sceneTables(in), z);
    const auto reference = zenith(atmosphere::precompute(model, atmosphere::skyPrecomputeOptions(model, 4, z)), z);
    for (int c = 0; c < 3; ++c) {
      std::printf("  Sun %.0f deg down, channel %d: day %.3g, twilight %.3g, sky command %.3g\n", depressionDeg, c,
                  day[c], twilight[c], reference[c]);
      if (depressionDeg > 12.0) {
        EXPECT_EQ(day[c], 0.0) << "channel " << c;
      }
    }
    expectTwilightCloser(day, twilight, reference, 3.0, 3.0, std::to_string(depressionDeg) + " deg down");
  }
}

// The zenith, the twilight arch (87 deg from the zenith towards the Sun) and the ground's
// indirect irradiance at the default sizes (twilight: 16,128,128,8; about 10 s each on 2
// cores, so not in the suite: --gtest_also_run_disabled_tests), 4 to 16 deg after sunset,
// the default (continental) sky. Measured: the twilight tables within 10 % of the sky
// command's to 7 deg, 21 % at 10, 12-43 % low at 13-16 (the arch the most); the day's
// ground irradiance within 5 % to 7 deg and 18 % at 10 (geometric across the irradiance
// table's cells below the horizon; a straight line gave +35..60 %), black from 12.
TEST(SceneAtmosphereTables, DISABLED_DefaultSizesAgainstTheSkyCommand) {
  const atmosphere::Atmosphere& model = atmosphereFixture().model;
  const atmosphere::AtmosphereTables day = sceneTables(groundScene(2.0, 30.0), AtmosphereTableSizes::Default);
  for (double depressionDeg : {4.0, 7.0, 10.0, 13.0, 16.0}) {
    const double z = (90.0 + depressionDeg) * kDeg;
    const atmosphere::AtmosphereTables twilight =
        sceneTables(groundScene(2.0, -depressionDeg), AtmosphereTableSizes::Default);
    atmosphere::PrecomputeOptions fine = atmosphere::skyPrecomputeOptions(model, 4, z);
    fine.irradianceWidth = 1024;
    const atmosphere::AtmosphereTables reference = atmosphere::precompute(model, fine);
    const double b = twilight.bottomRadiusM;
    const auto e = atmosphere::indirectIrradiance(reference, b, std::cos(z));
    const auto ed = atmosphere::indirectIrradiance(day, b, std::cos(z));
    const auto et = atmosphere::indirectIrradiance(twilight, b, std::cos(z));
    for (int c = 0; c < 3; ++c) {
      std::printf("  Sun %2.0f deg down, ground irradiance, channel %d: 1024 cells %.3g; twilight tables %+.0f %%, "
                  "day tables %+.0f %%\n", depressionDeg, c, e[c], 100.0 * (et[c] / e[c] - 1.0), 100.0 * (ed[c] / e[c] - 1.0));
      EXPECT_LT(std::abs(et[c] / e[c] - 1.0), depressionDeg <= 10.0 ? 0.15 : 0.35) << depressionDeg << " deg, channel " << c;
      if (depressionDeg <= 7.0) { EXPECT_LT(std::abs(ed[c] / e[c] - 1.0), 0.1) << depressionDeg << " deg, channel " << c; }
      if (depressionDeg == 10.0) { EXPECT_LT(std::abs(ed[c] / e[c] - 1.0), 0.25) << depressionDeg << " deg, channel " << c; }
    }
    for (double viewDeg : {0.0, 87.0}) {  // the zenith, the twilight arch
      const auto d = skyRadiance(day, z, viewDeg * kDeg), t = skyRadiance(twilight, z, viewDeg * kDeg), r = skyRadiance(reference, z, viewDeg * kDeg);
      for (int c = 0; c < 3; ++c) {
        std::printf("  Sun %2.0f deg down, view %2.0f deg, channel %d: sky command %.3g; twilight tables %+.0f %%, "
                    "day tables %+.0f %%\n", depressionDeg, viewDeg, c, r[c], 100.0 * (t[c] / r[c] - 1.0),
                    100.0 * (d[c] / r[c] - 1.0));
        EXPECT_LT(std::abs(t[c] / r[c] - 1.0), depressionDeg <= 10.0 ? 0.25 : 0.5) << depressionDeg << " deg, channel " << c;
      }
    }
  }
}

// The ground's indirect irradiance after sunset (what lights the ground and the terrain):
// the irradiance table spans mu_s in [-1, 1], so its cells are coarse just below the
// horizon, where it falls by orders of magnitude (the lookup is geometric across the cells
// below the horizon; 16 cells still miss the fall). Small sizes, day (16 cells) and
// twilight (64), against the sky command's tables with 512 cells. Measured: the day's
// x2.0-2.7 at 4 deg down, x9-12 at 9, black at 14 (below its lowest Sun); the twilight ones
// within x1.5 (the default sizes' in DISABLED_DefaultSizesAgainstTheSkyCommand).
TEST(SceneAtmosphereTables, TwilightTablesCarryTheGroundIrradiance) {
  const atmosphere::Atmosphere& model = atmosphereFixture().model;
  const double b = atmosphereFixture().tables.bottomRadiusM;
  for (double depressionDeg : {4.0, 9.0, 14.0}) {
    const double z = (90.0 + depressionDeg) * kDeg;
    atmosphere::PrecomputeOptions fine = atmosphere::skyPrecomputeOptions(model, 4, z);
    fine.irradianceWidth = 512;
    const auto reference = atmosphere::indirectIrradiance(atmosphere::precompute(model, fine), b, std::cos(z));
    const auto day = atmosphere::indirectIrradiance(atmosphereFixture().tables, b, std::cos(z));
    const auto twilight = atmosphere::indirectIrradiance(sceneTables(groundScene(2.0, -depressionDeg)), b, std::cos(z));
    for (int c = 0; c < 3; ++c)
      std::printf("  Sun %2.0f deg down, channel %d: E_ind day %.3g, twilight %.3g, reference %.3g\n", depressionDeg, c,
                  day[c], twilight[c], reference[c]);
    expectTwilightCloser(day, twilight, reference, 3.0, 2.0, std::to_string(depressionDeg) + " deg down");
  }
}

// Deep twilight, 13 and 16 deg after sunset, the default sky from 2 m: the scene's
// twilight tables (default sizes) and the sky command's against converged tables (R 32,
// MU 128, MU_S 256, NU 32, 48 x 96 density directions, 100 samples a ray, irradiance 1024
// cells; each of these doubled alone moves the zenith, the arch and the ground's light by
// at most 5 %). The twilight tables are within x1.5 and nearer than the sky command's,
// which its 8 radii make too bright there. About 4 min on 2 cores, so not in the suite
// (--gtest_also_run_disabled_tests). UMBRA_TWILIGHT_REFERENCE="R MU_S NU DIRECTIONS
// SAMPLES" gives the reference other sizes (docs/accuracy-vs-speed/atmosphere-tables.md, "Deep twilight").
TEST(SceneAtmosphereTables, DISABLED_DeepTwilightAgainstConvergedTables) {
  const atmosphere::Atmosphere& model = atmosphereFixture().model;
  int sizes[5] = {32, 256, 32, 48, 100};
  if (const char* env = std::getenv("UMBRA_TWILIGHT_REFERENCE")) {
    ASSERT_EQ(std::sscanf(env, "%d %d %d %d %d", &sizes[0], &sizes[1], &sizes[2], &sizes[3], &sizes[4]), 5) << env;
  }
  for (double depressionDeg : {13.0, 16.0}) {
    const double z = (90.0 + depressionDeg) * kDeg;
    const atmosphere::AtmosphereTables twilight =
        sceneTables(groundScene(2.0, -depressionDeg), AtmosphereTableSizes::Default);
    const atmosphere::AtmosphereTables sky = atmosphere::precompute(model, atmosphere::skyPrecomputeOptions(model, 4, z));
    atmosphere::PrecomputeOptions o = atmosphere::skyPrecomputeOptions(model, 4, z);
    o.scatteringR = sizes[0];
    o.scatteringMu = 128;
    o.scatteringMuS = sizes[1];
    o.scatteringNu = sizes[2];
    o.sphereSamples = sizes[3];
    o.singleScatteringSamples = o.multipleScatteringSamples = sizes[4];
    o.irradianceWidth = 1024;
    const atmosphere::AtmosphereTables converged = atmosphere::precompute(model, o);
    auto compare = [&](const char* what, const std::vector<double>& r, const std::vector<double>& t,
                       const std::vector<double>& s) {
      for (int c = 0; c < 3; ++c) {
        std::printf("  Sun %2.0f deg down, %s, channel %d: converged %.3g; twilight tables %+.0f %%, sky command %+.0f %%\n",
                    depressionDeg, what, c, r[c], 100.0 * (t[c] / r[c] - 1.0), 100.0 * (s[c] / r[c] - 1.0));
        ASSERT_GT(r[c], 0.0);
        EXPECT_LT(std::abs(std::log(t[c] / r[c])), std::log(1.5)) << depressionDeg << " deg, " << what << ", channel " << c;
        EXPECT_LT(std::abs(std::log(t[c] / r[c])), std::abs(std::log(s[c] / r[c])))
            << depressionDeg << " deg, " << what << ", channel " << c;
      }
    };
    const double b = twilight.bottomRadiusM;
    compare("ground irradiance", atmosphere::indirectIrradiance(converged, b, std::cos(z)),
            atmosphere::indirectIrradiance(twilight, b, std::cos(z)), atmosphere::indirectIrradiance(sky, b, std::cos(z)));
    compare("zenith", skyRadiance(converged, z, 0.0), skyRadiance(twilight, z, 0.0), skyRadiance(sky, z, 0.0));
    compare("arch (87 deg)", skyRadiance(converged, z, 87.0 * kDeg), skyRadiance(twilight, z, 87.0 * kDeg),
            skyRadiance(sky, z, 87.0 * kDeg));
  }
}
