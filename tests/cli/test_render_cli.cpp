// `umbra render` on the example scene (needs an X display: runs under xvfb-run).
// The frame must be finite and not black, and the Moon darker on its umbral side.
#include "CliRunner.hpp"
#include "CraterField.hpp"
#include "GeoTiffSupport.hpp"
#include "RenderCliSupport.hpp"

#include "scene/Scene.hpp"
#include "umbra/tables/Exr.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <vector>

using namespace umbra;
using namespace umbra::test;

namespace {
const std::string kScene = UMBRA_SOURCE_DIR "/examples/scenes/lunar-eclipse-2015-09-28.json";

// The mean over a PNG's pixels of max(R, G, B) - min(R, G, B), 0..255: how coloured it is.
double meanChroma(const std::filesystem::path& png) {
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(png.c_str());
  reader->Update();
  vtkDataArray* px = reader->GetOutput()->GetPointData()->GetScalars();
  double sum = 0.0;
  for (vtkIdType i = 0; i < px->GetNumberOfTuples(); ++i) {
    const double r = px->GetComponent(i, 0), g = px->GetComponent(i, 1), b = px->GetComponent(i, 2);
    sum += std::max({r, g, b}) - std::min({r, g, b});
  }
  return sum / px->GetNumberOfTuples();
}
}

TEST(RenderCli, ExampleSceneShowsTheMoonDarkerOnItsUmbralSide) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE, {"render", kScene, "--output", dir / "moon.exr"},
                          {"UMBRA_CACHE_DIR=" + dir / "cache"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const tables::Table img = tables::readExr(dir / "moon.exr", {"R", "G", "B"});
  const scene::Scene s = scene::loadScene(kScene);
  ASSERT_EQ(img.width, s.width);
  ASSERT_EQ(img.height, s.height);
  for (float v : img.data) ASSERT_TRUE(std::isfinite(v));

  // Where the shadow axis passes at the Moon's distance, projected into the image: the
  // umbral side of the Moon is the one facing it.
  const scene::Body& earth = *s.find("Earth");
  const scene::Body& moon = *s.find("Moon");
  const glm::dvec3 antiSun = glm::normalize(earth.positionM - s.sun().positionM);
  const glm::dvec3 axisPoint = earth.positionM + antiSun * glm::length(moon.positionM - earth.positionM);
  const glm::dvec3 view = glm::normalize(s.camera.targetM - s.camera.positionM);
  const glm::dvec3 up = glm::normalize(s.camera.up - view * glm::dot(s.camera.up, view));
  const glm::dvec3 right = glm::cross(view, up);
  const glm::dvec2 towardsAxis(glm::dot(axisPoint - moon.positionM, right), glm::dot(axisPoint - moon.positionM, up));

  // The Moon's disc in pixels (camera aimed at its centre).
  const double distance = glm::length(moon.positionM - s.camera.positionM);
  const double radiusPx = std::tan(std::asin(moon.radiusM / distance)) /
                          std::tan(0.5 * s.camera.fovDeg * M_PI / 180.0) * 0.5 * s.height;
  double sums[2] = {0, 0};
  int counts[2] = {0, 0};
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const glm::dvec2 p(x + 0.5 - 0.5 * img.width, 0.5 * img.height - (y + 0.5));  // row 0 = top
      if (glm::length(p) > 0.9 * radiusPx) continue;
      const int side = glm::dot(p, towardsAxis) > 0.0 ? 0 : 1;  // 0: umbral side
      sums[side] += img.at(x, y, 1);
      ++counts[side];
    }
  }
  ASSERT_GT(counts[0], 1000);
  ASSERT_GT(counts[1], 1000);
  const double umbral = sums[0] / counts[0], other = sums[1] / counts[1];
  EXPECT_GT(other, 0.1);            // lit (W m^-2 sr^-1); not an all-black frame
  EXPECT_LT(umbral, 0.5 * other);   // the umbral side is much darker
}

TEST(RenderCli, PngIsWrittenAndNotBlank) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE, {"render", kScene, "--size", "320x240", "--output", dir / "moon.png"},
                          {"UMBRA_CACHE_DIR=" + dir / "cache"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("wrote"), std::string::npos);
  EXPECT_GT(std::filesystem::file_size(dir.path / "moon.png"), 1000u);
  EXPECT_EQ(dir.fileCount(), 2);  // the PNG and the cache folder, no temporary
}

TEST(RenderCli, ProfilePlotAsPng) {
  TempDir dir;
  const RunResult r = run(UMBRA_EXE, {"profile", "shadow", "--occluder", "Earth", "--no-atmosphere", "--distance",
                                      "384400km", "--samples", "200", "--csv", dir / "p.csv", "--plot", dir / "p.png"},
                          {"UMBRA_CACHE_DIR=" + dir / "cache"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_GT(std::filesystem::file_size(dir.path / "p.png"), 2000u);
}

// An animation: --from/--to/--step writes one frame per step, each the same image as a
// single render at its time; the Moon darkens as it enters the umbra (partial phase from
// 01:07 UTC, total from 02:11). Bad animation options name the option and write nothing.
TEST(RenderCli, AnimationWritesOneFramePerStep) {
  TempDir dir;
  const std::vector<std::string> env{"UMBRA_CACHE_DIR=" + dir / "cache"};
  std::filesystem::create_directory(dir.path / "frames");
  const RunResult r = run(UMBRA_EXE, {"render", kScene, "--size", "48x36", "--from", "2015-09-28T01:00:00Z", "--to",
                                      "2015-09-28T02:30:00Z", "--step", "45min", "--output",
                                      dir / "frames/frame-%02d.exr"},
                          env);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir.path / "frames")) names.push_back(e.path().filename());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"frame-00.exr", "frame-01.exr", "frame-02.exr"}));
  double moon[3];
  for (int k = 0; k < 3; ++k) {
    const tables::Table t = tables::readExr(dir / ("frames/frame-0" + std::to_string(k) + ".exr"), {"R", "G", "B"});
    moon[k] = 0.0;
    for (float v : t.data) moon[k] += v;
  }
  EXPECT_LT(moon[1], 0.8 * moon[0]);
  EXPECT_LT(moon[2], 0.1 * moon[0]);
  ASSERT_EQ(run(UMBRA_EXE, {"render", kScene, "--size", "48x36", "--time", "2015-09-28T01:45:00Z", "--output",
                            dir / "single.exr"},
                env).exitCode,
            0);
  EXPECT_EQ(tables::readExr(dir / "single.exr", {"R", "G", "B"}).data,
            tables::readExr(dir / "frames/frame-01.exr", {"R", "G", "B"}).data);

  struct Bad {
    std::vector<std::string> args;
    std::string message;
  };
  const std::string from = "2015-09-28T01:00:00Z", to = "2015-09-28T02:00:00Z";
  for (const Bad& b : {Bad{{"--from", from, "--to", to, "--step", "1h", "--output", dir / "bad.png"},
                           "--output: an animation needs one frame number"},
                       Bad{{"--from", from, "--to", to, "--output", dir / "bad-%d.png"}, "--from, --to and --step go together"},
                       Bad{{"--from", to, "--to", from, "--step", "1h", "--output", dir / "bad-%d.png"}, "is before --from"},
                       Bad{{"--from", from, "--to", to, "--step", "-1h", "--output", dir / "bad-%d.png"}, "--step: must be positive"},
                       Bad{{"--from", from, "--to", to, "--step", "1 fortnight", "--output", dir / "bad-%d.png"}, "--step: invalid duration"},
                       Bad{{"--time", from, "--from", from, "--to", to, "--step", "1h", "--output", dir / "bad-%d.png"},
                           "--time: not with --from"}}) {
    std::vector<std::string> args{"render", kScene};
    args.insert(args.end(), b.args.begin(), b.args.end());
    const RunResult bad = run(UMBRA_EXE, args, env);
    EXPECT_NE(bad.exitCode, 0) << b.message;
    EXPECT_NE(bad.err.find(b.message), std::string::npos) << bad.err;
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  }
  for (const auto& e : std::filesystem::directory_iterator(dir.path))
    EXPECT_EQ(e.path().filename().string().rfind("bad", 0), std::string::npos) << e.path();
}

// ---- scenes with an atmosphere (small tables: --atmosphere-tables small) ----------------


// Progress of the tables a render makes on demand (cold cache: the atmosphere's, the
// atmospheric shadow LuT, the limb-luminance LuT of the ring seen from the Moon): a live
// percentage per table on a terminal (run under a pseudo-terminal by util-linux `script`)
// that never goes back, each line cleared when its table is done so that "wrote ..."
// starts a clean line; and nothing of it when stderr is not a terminal.
TEST(RenderCli, ProgressOnATerminalOnly) {
  if (!std::filesystem::exists("/usr/bin/script")) GTEST_SKIP() << "no /usr/bin/script (util-linux)";
  TempDir dir;
  const std::string scene = UMBRA_SOURCE_DIR "/examples/scenes/earth-from-lunar-north-pole-2015-09-28.json";
  const std::vector<std::string> args{"render", scene, "--size", "64x36", "--atmosphere-tables", "small", "--refraction"};
  std::string command = quote(UMBRA_EXE);
  for (const std::string& a : args) command += " " + quote(a);
  command += " --cache-dir " + quote(dir / "tty-cache") + " -o " + quote(dir / "tty.png");
  const RunResult tty = run("/usr/bin/script", {"-qec", command, "/dev/null"});
  ASSERT_EQ(tty.exitCode, 0) << tty.out << tty.err;
  for (const std::string what : {"atmosphere tables", "atmospheric shadow LuT", "limb-luminance LuT"}) {
    // Every "\r\033[K<what>: N%" in order: from below 50 % up to above 50 %, never back
    // (the LuTs' own tables are the first half of theirs).
    const std::string prefix = "\r\033[K" + what + ": ";
    std::vector<int> percents;
    for (std::size_t at = tty.out.find(prefix); at != std::string::npos; at = tty.out.find(prefix, at + 1))
      percents.push_back(std::atoi(tty.out.c_str() + at + prefix.size()));
    ASSERT_GE(percents.size(), 3u) << what << " in " << tty.out;
    EXPECT_LT(percents.front(), 50) << what;
    EXPECT_GT(percents.back(), 50) << what;
    EXPECT_TRUE(std::is_sorted(percents.begin(), percents.end())) << what << ": " << ::testing::PrintToString(percents);
  }
  const std::size_t wrote = tty.out.find("wrote ");
  ASSERT_NE(wrote, std::string::npos) << tty.out;
  EXPECT_GE(wrote, 4u);
  EXPECT_EQ(tty.out.substr(wrote - 4, 4), "\r\033[K");  // the last progress line cleared first
  EXPECT_EQ(tty.out.find('%', wrote), std::string::npos);

  std::vector<std::string> plain = args;
  plain.insert(plain.end(), {"--cache-dir", dir / "cache", "-o", dir / "plain.png"});
  const RunResult r = run(UMBRA_EXE, plain);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err.find('%'), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("wrote "), std::string::npos);
}

// The sunset example: the Sun (the camera's target, at the centre) is reddened, the sky
// above it is lit and bluer high up than beside the Sun, the ground below is darker.
TEST(RenderCli, SunsetExampleHasARedSunUnderABluerSky) {
  TempDir dir;
  const tables::Table img = renderExr(dir, UMBRA_SOURCE_DIR "/examples/scenes/earth-sunset.json", "160x90");
  const int w = img.width, h = img.height;
  const glm::dvec3 sun = pixel(img, w / 2, h / 2), top = pixel(img, w / 4, 0), beside = pixel(img, w / 4, h / 2);
  const glm::dvec3 ground = pixel(img, w / 2, h - 1);
  EXPECT_GT(sun.r, 2.0 * sun.b);
  EXPECT_GT(sun.r, 100.0 * beside.r);
  EXPECT_GT(top.b, 0.0);
  EXPECT_GT(top.b / top.r, 1.5 * beside.b / beside.r);
  EXPECT_LT(ground.g, beside.g);
}

// The Martian sunset example: the Sun (at the centre) sits in a blue glow, the sky 25 deg
// from it is grey-red (redder still 90 deg away, where the CPU test looks) (Curiosity's and Spirit's sunset images; tests/atmosphere/test_sky.cpp
// has the same on the CPU).
TEST(RenderCli, MarsSunsetExampleHasABlueGlowInAReddishSky) {
  TempDir dir;
  const tables::Table img = renderExr(dir, UMBRA_SOURCE_DIR "/examples/scenes/mars-sunset.json", "160x90");
  const int w = img.width, h = img.height;
  const glm::dvec3 glow = pixel(img, w / 2, h / 2 - 6);  // 2.7 deg above the Sun (40 deg / 90 px)
  const glm::dvec3 away = pixel(img, 2, 2);              // 25 deg from it
  std::printf("  Mars sunset: glow rgb %.3g %.3g %.3g, away %.3g %.3g %.3g\n", glow.r, glow.g, glow.b, away.r, away.g,
              away.b);
  // B/R 1.80 with Lorenz-Mie dust (atmosphere/presets/mars.json): at 2.7 deg Mie's phase
  // has p(440)/p(680) = 2.3 for the size distribution.
  EXPECT_GT(glow.b, 1.1 * glow.r);
  EXPECT_GT(glow.b / glow.r, 1.5 * away.b / away.r);  // measured: 1.80 against 0.75
  EXPECT_GT(glow.g, 2.0 * away.g);  // the glow is bright
}

// The Earth's shadow example, looking east with the Sun 2 deg down: just over the horizon the
// sky is in the planet's shadow (darker, lit only by the twilight's second-order light),
// above it the Belt of Venus, lit by the reddened Sun (brighter and redder), and higher up
// the bluer sky. Rows of the central column, elevation from the camera (perspective).
TEST(RenderCli, EarthShadowExampleHasADarkBandUnderThePinkBelt) {
  TempDir dir;
  const tables::Table img = renderExr(dir, UMBRA_SOURCE_DIR "/examples/scenes/earth-shadow-east.json", "64x90");
  const int w = img.width, h = img.height;
  const double halfHeight = std::tan(15.0 * M_PI / 180.0);  // fovDeg 30, centred 12 deg up
  auto elevationDeg = [&](int y) {
    const double t = (1.0 - 2.0 * (y + 0.5) / h) * halfHeight;  // image-plane height, the camera pitched 12 deg
    return std::atan2(std::sin(12.0 * M_PI / 180.0) + t * std::cos(12.0 * M_PI / 180.0),
                      std::cos(12.0 * M_PI / 180.0) - t * std::sin(12.0 * M_PI / 180.0)) * 180.0 / M_PI;
  };
  // The shadow band (0-1.5 deg up), the belt (3-12 deg: its brightest red and its reddest
  // R/B), the sky at the top (27 deg).
  double bandR = 0.0, beltR = 0.0, beltRedness = 0.0, bandRedness = 0.0;
  int bandRows = 0;
  for (int y = 0; y < h; ++y) {
    const glm::dvec3 c = pixel(img, w / 2, y);
    const double e = elevationDeg(y);
    if (e >= 0.0 && e <= 1.5) bandR += c.r, bandRedness = std::max(bandRedness, c.r / c.b), ++bandRows;
    if (e >= 3.0 && e <= 12.0) beltR = std::max(beltR, c.r), beltRedness = std::max(beltRedness, c.r / c.b);
  }
  ASSERT_GT(bandRows, 0);
  bandR /= bandRows;
  const glm::dvec3 top = pixel(img, w / 2, 0);
  std::printf("  shadow band R %.3g (R/B <= %.2f), belt R <= %.3g (R/B <= %.2f), top R/B %.2f\n", bandR, bandRedness,
              beltR, beltRedness, top.r / top.b);
  // Measured (small tables): band R 0.73, R/B 0.84; belt 3.41, R/B 2.51; top R/B 0.87.
  EXPECT_LT(bandR, 0.5 * beltR);
  EXPECT_GT(beltRedness, 1.5 * bandRedness);
  EXPECT_GT(beltRedness, 1.5 * top.r / top.b);
}

// EXR output keeps the HDR frame: FLOAT channels hold the reddened Sun's radiance (some
// 270 W m^-2 sr^-1 per channel at 96x54), the same whatever the exposure; --glare moves
// light into halos (at 1.8 px per degree mostly the 0.75 deg one) and keeps the frame's
// total radiance.
TEST(RenderCli, ExrKeepsHdrValuesAndGlareKeepsTheEnergy) {
  TempDir dir;
  const std::string scene = UMBRA_SOURCE_DIR "/examples/scenes/earth-sunset.json";
  auto render = [&](const std::string& name, std::vector<std::string> extra) {
    std::vector<std::string> args{"render", scene, "--size", "96x54", "--atmosphere-tables", "small", "--output",
                                  dir / name};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult r = run(UMBRA_EXE, args, {"UMBRA_CACHE_DIR=" + dir / "cache"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return tables::readExr(dir / name, {"R", "G", "B"});
  };
  const tables::Table dark = render("dark.exr", {"--exposure", "-12"});
  const tables::Table bright = render("bright.exr", {"--exposure", "3"});
  const tables::Table glare = render("glare.exr", {"--glare", "3"});
  EXPECT_EQ(dark.data, bright.data);
  const float peak = *std::max_element(dark.data.begin(), dark.data.end());
  EXPECT_GT(peak, 100.0f);
  double sum[2] = {0, 0};
  for (std::size_t i = 0; i < dark.data.size(); ++i) sum[0] += dark.data[i], sum[1] += glare.data[i];
  EXPECT_NEAR(sum[1] / sum[0], 1.0, 1e-4);
  EXPECT_LT(*std::max_element(glare.data.begin(), glare.data.end()), 0.99f * peak);

  const RunResult bad = run(UMBRA_EXE, {"render", scene, "--glare", "11", "--output", dir / "x.exr"});
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.err.find("--glare"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path / "x.exr"));
}

// Earth from 150 000 km: the disc is lit, space around it dark (no more than the Milky
// Way's brightest light, 2.2e-6 W m^-2 sr^-1: docs/stars.md).
TEST(RenderCli, EarthFrom150000kmExampleShowsALitDisc) {
  TempDir dir;
  const tables::Table img = renderExr(dir, UMBRA_SOURCE_DIR "/examples/scenes/earth-from-150000km.json", "160x120");
  const glm::dvec3 centre = pixel(img, img.width / 2, img.height / 2), corner = pixel(img, 0, 0);
  EXPECT_GT(centre.b, 1.0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_GE(corner[c], 0.0);
    EXPECT_LT(corner[c], 3e-6);
  }
}

// The Moon's shadow on Earth from 150 000 km over the greatest eclipse of 2024-04-08: the
// umbra black at the image's centre, and the penumbra the view without the Moon times one
// grey factor, the Sun's visible fraction, which dims the ground's direct light, its sky
// light and the light its air scatters alike (with the direct light alone dimmed, the
// umbra kept 26-37 % of the light, bluish).
TEST(RenderCli, SolarEclipseFromSpaceHasABlackUmbraAndAGreyPenumbra) {
  TempDir dir, withoutMoon, cache;
  const std::string scene = UMBRA_SOURCE_DIR "/examples/scenes/solar-eclipse-2024-04-08-from-space.json";
  std::string text = readAll(scene);
  const std::string moon = ",\n    {\"preset\": \"Moon\"}";
  ASSERT_NE(text.find(moon), std::string::npos);
  text.replace(text.find(moon), moon.size(), "");
  const std::string clearScene = withoutMoon / "clear.json";
  std::ofstream(clearScene) << text;
  const tables::Table eclipsed = renderExr(dir, scene, "64x64", {}, &cache);
  const tables::Table clear = renderExr(withoutMoon, clearScene, "64x64", {}, &cache);
  const glm::dvec3 centre = pixel(eclipsed, 32, 32), centreClear = pixel(clear, 32, 32);
  for (int c = 0; c < 3; ++c) EXPECT_LT(centre[c], 1e-3 * centreClear[c]) << c;
  int penumbra = 0;
  double worst = 0.0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const glm::dvec3 e = pixel(eclipsed, x, y), c = pixel(clear, x, y);
      const glm::dvec3 ratio = e / c;
      if (!(ratio.g > 0.1 && ratio.g < 0.9)) continue;
      ++penumbra;
      worst = std::max({worst, std::abs(ratio.r - ratio.g), std::abs(ratio.b - ratio.g)});
    }
  std::printf("centre %.3g of the view without the Moon; %d penumbra pixels, R, G, B ratios within %.2g\n",
              centre.g / centreClear.g, penumbra, worst);
  EXPECT_GT(penumbra, 1000);
  EXPECT_LT(worst, 0.01);
}

TEST(RenderCli, UnknownAtmosphereNamesTheFileAndField) {
  TempDir dir;
  const std::string scene = dir / "bad.json";
  std::ofstream(scene) << R"({"bodies": [{"preset": "Sun"}, {"preset": "Earth", "position": [1.5e11, 0, 0],
                             "atmosphere": "venus"}],
                             "camera": {"position": [1.5e11, 0, 1e8], "target": "Earth"}})";
  const RunResult r = run(UMBRA_EXE, {"render", scene, "--output", dir / "x.png"}, {"UMBRA_CACHE_DIR=" + dir / "cache"});
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find(scene + ": bodies[1].atmosphere: unknown atmosphere preset 'venus'"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path / "x.png"));
}

// A scene's terrain read from a DEM (GeoTIFF, lunar south polar stereographic) renders
// exactly as the synthetic crater field the DEM was written from, and unlike another
// field: the scene's "dem" path (relative to the scene file) reaches the renderer.
TEST(RenderCli, SceneTerrainFromADemRendersAsTheFieldItHolds) {
  TempDir dir;
  terrain::CraterFieldOptions o;
  o.seed = 7;
  o.size = 96;
  writeGeoTiff(dir / "dem.tif", terrain::makeCraterField(o), 0.0);
  auto writeScene = [&](const std::string& name, const std::string& terrain) {
    std::ofstream(dir / name) << R"({"time": "2024-03-01T00:00:00Z",
      "bodies": [{"preset": "Sun"}, {"preset": "Earth"},
                 {"preset": "Moon", "terrain": )" << terrain << R"(}],
      "camera": {"observer": {"body": "Moon", "latDeg": -90.0, "lonDeg": 0.0, "altM": 400},
                 "target": "Sun", "up": "zenith", "fovDeg": 60},
      "exposure": -5.0})";
    return dir / name;
  };
  const std::string place = R"("spacing": "30m", "latDeg": -90.0, "lonDeg": 0.0)";
  const std::string fromDem = writeScene("dem.json", R"({"dem": "dem.tif", )" + place + "}");
  const std::string seed7 = writeScene("seed7.json", R"({"seed": 7, "size": 96, )" + place + "}");
  const std::string seed8 = writeScene("seed8.json", R"({"seed": 8, "size": 96, )" + place + "}");
  TempDir a, b, c;
  const tables::Table dem = renderExr(a, fromDem, "64x36", {}, &dir);
  const tables::Table same = renderExr(b, seed7, "64x36", {}, &dir);
  const tables::Table other = renderExr(c, seed8, "64x36", {}, &dir);
  EXPECT_EQ(dem.data, same.data);
  // Another crater field changes a visible part of the frame (the terrain is in view).
  std::size_t differing = 0;
  for (std::size_t i = 0; i < dem.data.size(); ++i)
    if (std::abs(dem.data[i] - other.data[i]) > 0.05f * std::max(std::abs(dem.data[i]), 1e-6f)) ++differing;
  EXPECT_GT(differing, dem.data.size() / 20) << differing << " of " << dem.data.size() << " values differ";
}

TEST(RenderCli, EglWithoutADisplayGivesTheImageOfX) {
  // The sunset with its sky (the atmosphere composite) and the Sun's disc, small tables:
  // on X, with --egl, and with no DISPLAY at all (EGL then, with a note).
  TempDir dir;
  const std::string scene = UMBRA_SOURCE_DIR "/examples/scenes/earth-sunset.json";
  const tables::Table x = renderExr(dir, scene, "64x36", {}, &dir);
  const float brightest = *std::max_element(x.data.begin(), x.data.end());
  ASSERT_GT(brightest, 0.0f);
  auto renderWithoutDisplay = [&](const std::string& name, const std::vector<std::string>& extra,
                                  const std::vector<std::string>& env) {
    std::vector<std::string> args = {"-u", "DISPLAY", UMBRA_EXE, "render", scene, "--size", "64x36",
                                     "--atmosphere-tables", "small", "--output", dir / name};
    args.insert(args.end(), extra.begin(), extra.end());
    std::vector<std::string> environment = {"UMBRA_CACHE_DIR=" + dir / "cache"};
    environment.insert(environment.end(), env.begin(), env.end());
    return run("/usr/bin/env", args, environment);
  };
  for (const bool asked : {true, false}) {
    const std::string name = asked ? "egl.exr" : "no-display.exr";
    const RunResult r = renderWithoutDisplay(name, asked ? std::vector<std::string>{"--egl"} : std::vector<std::string>{}, {});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("no X display: rendering through EGL") != std::string::npos, !asked) << r.err;
    EXPECT_NE(r.err.find("umbra: EGL: "), std::string::npos) << r.err;  // which GL renders: GPU or llvmpipe
    const tables::Table egl = tables::readExr(dir / name, {"R", "G", "B"});
    ASSERT_EQ(egl.data.size(), x.data.size());
    double worst = 0.0;
    for (std::size_t k = 0; k < x.data.size(); ++k)
      worst = std::max(worst, std::abs(double(egl.data[k]) - double(x.data[k])) / brightest);
    EXPECT_LT(worst, 1e-6) << name;
  }

  // No display and no EGL (glvnd pointed at a vendor file that is not there): one line
  // naming both, no file.
  const RunResult neither = renderWithoutDisplay("none.png", {}, {"__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json"});
  EXPECT_NE(neither.exitCode, 0);
  EXPECT_NE(neither.err.find("no X display"), std::string::npos) << neither.err;
  EXPECT_NE(neither.err.find("xvfb-run"), std::string::npos) << neither.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "none.png"));
}

// A PNG plot with no X display goes through EGL; with neither, the error names the file
// and the SVG way out, and no PNG is left.
TEST(RenderCli, ProfilePlotAsPngWithoutADisplay) {
  TempDir dir;
  const std::vector<std::string> args = {"-u", "DISPLAY", UMBRA_EXE, "profile", "shadow", "--occluder", "Earth",
                                         "--no-atmosphere", "--distance", "384400km", "--samples", "200", "--csv",
                                         dir / "p.csv", "--plot", dir / "p.png"};
  const RunResult r = run("/usr/bin/env", args, {"UMBRA_CACHE_DIR=" + dir / "cache"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_GT(std::filesystem::file_size(dir.path / "p.png"), 2000u);
  std::filesystem::remove(dir / "p.png");
  const RunResult neither = run("/usr/bin/env", args,
                                {"UMBRA_CACHE_DIR=" + dir / "cache", "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json"});
  EXPECT_NE(neither.exitCode, 0);
  EXPECT_NE(neither.err.find("p.png"), std::string::npos) << neither.err;
  EXPECT_NE(neither.err.find(".svg"), std::string::npos) << neither.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "p.png"));
}

// The crescent of 2026-10-13 from Madrid as it sets (0.25 deg up at 18:40 UTC), through the
// Earth's air in twilight (the Sun 12 deg down): the Moon's disc seen through the horizon's
// air mass, finite everywhere and lit; and the same Moon without the Clementine map
// installed: a uniform albedo and one note on stderr, not an error.
TEST(RenderCli, MoonAtTheHorizonAndWithoutItsMap) {
  TempDir dir;
  const std::string scene = dir / "moonset.json";
  std::ofstream(scene) << R"({"time": "2026-10-13T18:40:00Z",
    "bodies": [{"preset": "Sun"}, {"preset": "Earth", "atmosphere": "earth"}, {"preset": "Moon"}],
    "camera": {"observer": {"body": "Earth", "latDeg": 40.42, "lonDeg": -3.70, "altM": 2},
               "target": "Moon", "up": "zenith", "fovDeg": 1.0}, "exposure": 2})";
  const tables::Table img = renderExr(dir, scene, "48x48");
  double brightest = 0.0, skyAbove = 0.0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) brightest = std::max(brightest, pixel(img, x, y).r);
  for (int x = 0; x < img.width; ++x) skyAbove += pixel(img, x, 0).r / img.width;
  EXPECT_GT(brightest, 10.0 * skyAbove) << "the crescent through the air, over the twilight sky above it";
  const RunResult r = run(UMBRA_EXE, {"render", scene, "--size", "32x32", "--atmosphere-tables", "small", "--output",
                                      dir / "nomap.png"},
                          {"UMBRA_CACHE_DIR=" + dir / "cache", "UMBRA_MARBLE_DATA_DIR=" + dir / "nowhere"});
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("umbra: Moon: uniform albedo (the clementine map is not installed: Debian package "
                       "marble-qt-data)"), std::string::npos) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "nomap.png"));
}

// --limiting-magnitude: the line says how many stars were drawn to which V; fewer to V 1
// than to V 3 (kstars-data's catalogue); refused for a scene without stars.
TEST(RenderCli, LimitingMagnitudeCountsTheStars) {
  if (!std::filesystem::exists("/usr/share/kstars/stars.dat")) GTEST_SKIP() << "kstars-data is not installed";
  TempDir dir;
  auto starsTo = [&](const std::string& v) {
    const RunResult r = run(UMBRA_EXE, {"render", kScene, "--size", "32x24", "--limiting-magnitude", v, "--output",
                                        dir / "stars.png"},
                            {"UMBRA_CACHE_DIR=" + dir / "cache"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    const std::smatch m = [&] {
      std::smatch match;
      std::regex_search(r.out, match, std::regex(", (\\d+) stars to V " + v + "\\)"));
      return match;
    }();
    EXPECT_FALSE(m.empty()) << r.out;
    return m.empty() ? -1 : std::stoi(m[1].str());
  };
  const int bright = starsTo("1"), more = starsTo("3");
  EXPECT_GT(bright, 0);
  EXPECT_GT(more, bright);
  const RunResult r = run(UMBRA_EXE, {"render", std::string(UMBRA_SOURCE_DIR) + "/examples/scenes/phobos-in-mars-shadow.json", "--size",
                                      "32x24", "--limiting-magnitude", "3", "--output", dir / "none.png"},
                          {"UMBRA_CACHE_DIR=" + dir / "cache"});
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("--limiting-magnitude: the scene draws no stars"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path / "none.png"));
}

// A PNG of a night scene shows as the eye sees it (night vision and its glare), with a note
// saying so; --no-night-vision gives the camera's colours without the note; an EXR keeps the
// radiance (no glare). The moonlit sky (about 1e-3 cd m^-2) is blue for the camera and grey
// for the eye.
TEST(RenderCli, NightScenesShowAsTheEyeSeesThem) {
  TempDir dir;
  const std::string scene = UMBRA_SOURCE_DIR "/examples/scenes/moonlit-night-2026-10-26.json";
  auto render = [&](const std::string& out, std::vector<std::string> extra) {
    std::vector<std::string> args = {"render", scene, "--size", "48x27", "--atmosphere-tables", "small", "--output",
                                     dir / out};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult r = run(UMBRA_EXE, args, {"UMBRA_CACHE_DIR=" + dir / "cache"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return r;
  };
  const RunResult eye = render("eye.png", {});
  EXPECT_NE(eye.err.find("umbra: night vision on, glare 1 (Sun "), std::string::npos) << eye.err;
  EXPECT_NE(eye.err.find("deg below the horizon): the eye's view; --no-night-vision for the camera's colours"),
            std::string::npos) << eye.err;
  const RunResult camera = render("camera.png", {"--no-night-vision"});
  EXPECT_EQ(camera.err.find("night vision"), std::string::npos) << camera.err;
  const RunResult exr = render("radiance.exr", {});
  EXPECT_EQ(exr.err.find("night vision"), std::string::npos) << exr.err;
  EXPECT_EQ(tables::readExr(dir / "radiance.exr").parameters.at("glare"), "0.000000");
  const double grey = meanChroma(dir / "eye.png"), blue = meanChroma(dir / "camera.png");
  std::printf("  mean chroma (0..255): the eye's %.2f, the camera's %.2f\n", grey, blue);
  EXPECT_GT(blue, 10.0);
  EXPECT_LT(grey, 0.25 * blue);  // the default sky's haze: 2.96 against 13.76
  EXPECT_NE(run(UMBRA_EXE, {"render", scene, "--night-vision", "--no-night-vision", "--output", dir / "x.png"})
                .exitCode,
            0);
}
