// umbra-gui under Xvfb (this binary runs under xvfb-run; see umbra_add_render_test):
// --screenshot writes the window as a PNG and prints the window size, where the 3D view
// and the plot panel lie, and the status line. The PNG and the status are checked.
#include "CliRunner.hpp"

#include <array>
#include <QColor>
#include <QImage>
#include <QRect>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

using umbra::test::RunResult;
using umbra::test::TempDir;

namespace {

const std::string kExample = std::string(UMBRA_SOURCE_DIR) + "/examples/scenes/lunar-eclipse-2015-09-28.json";

struct Shot {
  RunResult run;
  QImage image;
  int width = 0, height = 0;  // as printed
  QRect view, plot;
  std::string status;
  double shadowFactor = -1.0;
};

QRect rectAfter(const std::string& out, const std::string& key) {
  std::smatch m;
  const std::regex re(key + ": (\\d+) (\\d+) (\\d+) (\\d+)");
  if (!std::regex_search(out, m, re)) return {};
  return QRect(std::stoi(m[1]), std::stoi(m[2]), std::stoi(m[3]), std::stoi(m[4]));
}

Shot screenshotOf(const std::string& scene, const TempDir& dir, const std::string& name,
                 std::vector<std::string> extra = {}) {
  Shot s;
  const std::string png = dir / name;
  std::vector<std::string> args{scene, "--screenshot", png, "--quit-after-screenshot"};
  args.insert(args.end(), extra.begin(), extra.end());
  // A private table cache: the test neither reads nor fills the user's.
  s.run = umbra::test::run(UMBRA_GUI_EXE, args, {"UMBRA_CACHE_DIR=" + (dir / "cache")});
  std::smatch m;
  if (std::regex_search(s.run.out, m, std::regex("window: (\\d+)x(\\d+)"))) {
    s.width = std::stoi(m[1]);
    s.height = std::stoi(m[2]);
  }
  s.view = rectAfter(s.run.out, "view3d");
  s.plot = rectAfter(s.run.out, "plot");
  if (std::regex_search(s.run.out, m, std::regex("status: ([^\n]*)"))) s.status = m[1];
  if (std::regex_search(s.status, m, std::regex("shadow factor ([0-9.]+)"))) s.shadowFactor = std::stod(m[1]);
  s.image.load(QString::fromStdString(png));
  return s;
}

Shot screenshot(const TempDir& dir, const std::string& name, std::vector<std::string> extra = {}) {
  return screenshotOf(kExample, dir, name, std::move(extra));
}

double luma(QRgb c) { return 0.2126 * qRed(c) + 0.7152 * qGreen(c) + 0.0722 * qBlue(c); }

/// Pixels of `r` within `tol` (per channel) of the colour.
int countNear(const QImage& img, const QRect& r, int red, int green, int blue, int tol) {
  int n = 0;
  for (int y = r.top(); y <= r.bottom(); ++y)
    for (int x = r.left(); x <= r.right(); ++x) {
      const QRgb c = img.pixel(x, y);
      if (std::abs(qRed(c) - red) <= tol && std::abs(qGreen(c) - green) <= tol && std::abs(qBlue(c) - blue) <= tol) ++n;
    }
  return n;
}

/// Fraction of the 3D view's pixels clearly brighter than the black sky.
double litFraction(const Shot& s) {
  long lit = 0;
  for (int y = s.view.top(); y <= s.view.bottom(); ++y)
    for (int x = s.view.left(); x <= s.view.right(); ++x) lit += luma(s.image.pixel(x, y)) > 40.0;
  return double(lit) / (double(s.view.width()) * s.view.height());
}

void expectWindowLooksRight(const Shot& s) {
  ASSERT_EQ(s.run.exitCode, 0) << s.run.err;
  ASSERT_FALSE(s.image.isNull()) << "no readable PNG; stdout: " << s.run.out;
  // The image is the window: its size as the program reports it (the default 1200x720).
  EXPECT_EQ(s.image.width(), s.width);
  EXPECT_EQ(s.image.height(), s.height);
  EXPECT_EQ(s.width, 1200);
  EXPECT_EQ(s.height, 720);
  ASSERT_TRUE(s.view.isValid() && s.plot.isValid()) << s.run.out;
  const QRect all(0, 0, s.image.width(), s.image.height());
  EXPECT_TRUE(all.contains(s.view) && all.contains(s.plot));
  EXPECT_FALSE(s.view.intersects(s.plot));
  EXPECT_GT(s.view.width(), 300);
  EXPECT_GT(s.plot.width(), 300);

  // 3D view: a black sky with the Moon in it, which fills ~80 % of the view's height.
  std::vector<double> l;
  for (int y = s.view.top(); y <= s.view.bottom(); ++y)
    for (int x = s.view.left(); x <= s.view.right(); ++x) l.push_back(luma(s.image.pixel(x, y)));
  std::sort(l.begin(), l.end());
  const double dark = l[l.size() / 20], bright = l[l.size() * 19 / 20];
  EXPECT_LT(dark, 20.0) << "the sky should be black";
  EXPECT_GT(bright, dark + 60.0) << "the Moon should be clearly brighter than the sky";
  const auto moonPixels = std::count_if(l.begin(), l.end(), [&](double v) { return v > dark + 40.0; });
  EXPECT_GT(moonPixels, static_cast<long>(l.size() / 10)) << "the Moon should cover a good part of the view";

  // Plot panel: a white chart with the profile lines (addProfileLines' colours) and the
  // Moon's marker (orange: dashed centre line, point, and the pale extent band).
  const QRect chart = s.plot.adjusted(2, 2, -2, -2);
  EXPECT_GT(countNear(s.image, chart, 255, 255, 255, 4), chart.width() * chart.height() / 3) << "white background";
  EXPECT_GT(countNear(s.image, chart, 30, 30, 30, 25), 300) << "the luminance line (30,30,30)";
  EXPECT_GT(countNear(s.image, chart, 220, 50, 47, 30), 10) << "the red line's colour (legend)";
  EXPECT_GT(countNear(s.image, chart, 230, 140, 0, 30), 200) << "the Moon's centre marker (230,140,0)";
  // The band: orange at alpha 60/255 over white.
  EXPECT_GT(countNear(s.image, chart, 249, 233, 200, 8), 2000) << "the Moon's extent band";
}

} // namespace

TEST(GuiScreenshot, EclipseSceneDuringThePartialPhase) {
  TempDir dir;
  const Shot s = screenshot(dir, "partial.png");
  expectWindowLooksRight(s);
  EXPECT_NE(s.status.find("Total lunar eclipse of 2015-09-28"), std::string::npos) << s.status;
  EXPECT_NE(s.status.find("2015-09-28T01:45:00Z"), std::string::npos) << s.status;
  EXPECT_NE(s.status.find("from Earth's shadow axis"), std::string::npos) << s.status;
  // The Moon's numbers from the observer (umbra moon --time 2015-09-28T01:45:00Z
  // --observer 1.33,-29.02,0): at the zenith, 34.1', phase 0.7 deg, V -12.9 outside the shadow.
  EXPECT_NE(s.status.find("Moon: alt 90.0 deg"), std::string::npos) << s.status;
  EXPECT_NE(s.status.find("34.1', phase 0.7 deg (100 % lit), V -12.9"), std::string::npos) << s.status;
  // The Moon's centre lies inside the umbra at 01:45.
  ASSERT_GE(s.shadowFactor, 0.0) << s.status;
  EXPECT_LT(s.shadowFactor, 0.05) << s.status;
  // Nothing but the PNG (and the private cache) is left in the directory.
  EXPECT_TRUE(std::filesystem::exists(dir / "partial.png"));
  EXPECT_EQ(dir.fileCount(), 2);
}

TEST(GuiScreenshot, TimeMovesTheMoonOutOfTheShadow) {
  TempDir dir;
  const Shot s = screenshot(dir, "after.png", {"--time", "2015-09-28T05:30:00Z"});
  expectWindowLooksRight(s);
  EXPECT_NE(s.status.find("2015-09-28T05:30:00Z"), std::string::npos) << s.status;
  // After the last penumbral contact (05:22 UTC) the Moon's centre is in full sunlight.
  ASSERT_GE(s.shadowFactor, 0.0) << s.status;
  EXPECT_GE(s.shadowFactor, 0.999) << s.status;
  // Its offset from the axis is beyond the penumbra (~8000 km) plus its radius (1737 km).
  std::smatch m;
  ASSERT_TRUE(std::regex_search(s.status, m, std::regex("Moon ([0-9]+) km from")));
  EXPECT_GT(std::stod(m[1]), 9800.0);

  // The 3D view follows: at 01:45 the umbra covers more than half of the Moon's disc, at
  // 05:30 the whole disc (~50 % of the view) is lit.
  const Shot partial = screenshot(dir, "partial.png");
  ASSERT_EQ(partial.run.exitCode, 0) << partial.run.err;
  const double before = litFraction(partial), after = litFraction(s);
  std::cout << "lit part of the 3D view: 01:45 " << before << ", 05:30 " << after << "\n";
  EXPECT_GT(after, 0.35) << "05:30: the full Moon";
  EXPECT_LT(before, 0.7 * after) << "01:45: part of the Moon in the umbra (lit " << before << " vs " << after << ")";
}

// A solar eclipse seen from 400 km over it (2024-04-08): the status line says how much of
// the Sun reaches the camera (scene::sunVisibleFractionAtCamera: the camera in the
// penumbra, 7.0 %), and the time slider moves it: three hours later the line has none.
TEST(GuiScreenshot, SolarEclipseStatusShowsTheSunsVisibleFraction) {
  TempDir dir;
  const std::string scene = std::string(UMBRA_SOURCE_DIR) + "/examples/scenes/solar-eclipse-2024-04-08-from-400km.json";
  const Shot s = screenshotOf(scene, dir, "eclipse.png", {"--atmosphere", "none"});
  ASSERT_EQ(s.run.exitCode, 0) << s.run.err;
  EXPECT_NE(s.status.find("Sun 7.0 % visible"), std::string::npos) << s.status;
  const Shot later = screenshotOf(scene, dir, "later.png", {"--atmosphere", "none", "--time", "2024-04-08T21:17:16Z"});
  ASSERT_EQ(later.run.exitCode, 0) << later.run.err;
  EXPECT_EQ(later.status.find("% visible"), std::string::npos) << later.status;
}

TEST(GuiScreenshot, BadSceneIsOneLineAndExitOne) {
  TempDir dir;
  const std::string bad = dir / "bad.json";
  std::ofstream(bad) << R"({"bodies": [{"preset": "Sun"}, {"preset": "Pluto"}], "camera": {"target": "Sun", "position": [1, 0, 0]}})";
  const RunResult r = umbra::test::run(UMBRA_GUI_EXE, {bad, "--screenshot", dir / "x.png", "--quit-after-screenshot"});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("bad.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Pluto"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));

  const RunResult t = umbra::test::run(UMBRA_GUI_EXE, {kExample, "--time", "yesterday", "--screenshot", dir / "x.png"});
  EXPECT_EQ(t.exitCode, 1);
  EXPECT_NE(t.err.find("--time"), std::string::npos) << t.err;

  const RunResult limb =
      umbra::test::run(UMBRA_GUI_EXE, {kExample, "--limb-ring-threshold", "-1", "--screenshot", dir / "x.png"});
  EXPECT_EQ(limb.exitCode, 1);
  EXPECT_EQ(std::count(limb.err.begin(), limb.err.end(), '\n'), 1) << limb.err;
  EXPECT_NE(limb.err.find("--limb-ring-threshold: expected a number"), std::string::npos) << limb.err;

  const RunResult ext = umbra::test::run(UMBRA_GUI_EXE, {kExample, "--screenshot", dir / "x.jpg"});
  EXPECT_EQ(ext.exitCode, 1);
  EXPECT_NE(ext.err.find("x.jpg"), std::string::npos) << ext.err;
  EXPECT_EQ(dir.fileCount(), 1);  // bad.json only
}

// The atmosphere, computed in the worker thread before the batch screenshot: the sunset
// scene's sky is lit with it and black without it (--atmosphere none); the Martian sunset
// has its blue glow around the Sun (the view's centre). An unknown preset is one line.
TEST(GuiScreenshot, AtmosphereOnOffAndPreset) {
  TempDir dir;
  const std::string sunset = std::string(UMBRA_SOURCE_DIR) + "/examples/scenes/earth-sunset.json";
  const Shot on = screenshotOf(sunset, dir, "on.png", {"--atmosphere-tables", "small"});
  const Shot off = screenshotOf(sunset, dir, "off.png", {"--atmosphere", "none"});
  ASSERT_EQ(on.run.exitCode, 0) << on.run.err;
  ASSERT_EQ(off.run.exitCode, 0) << off.run.err;
  // 10 % below the top of the view, away from the Sun: the sky.
  const QPoint sky(on.view.left() + on.view.width() / 4, on.view.top() + on.view.height() / 10);
  std::printf("  sky with the atmosphere %d %d %d, without %d %d %d\n", qRed(on.image.pixel(sky)),
              qGreen(on.image.pixel(sky)), qBlue(on.image.pixel(sky)), qRed(off.image.pixel(sky)),
              qGreen(off.image.pixel(sky)), qBlue(off.image.pixel(sky)));
  EXPECT_GT(luma(on.image.pixel(sky)), 25.0);
  EXPECT_LT(luma(off.image.pixel(sky)), 3.0);

  const Shot mars = screenshotOf(std::string(UMBRA_SOURCE_DIR) + "/examples/scenes/mars-sunset.json", dir, "mars.png",
                                 {"--atmosphere-tables", "small"});
  ASSERT_EQ(mars.run.exitCode, 0) << mars.run.err;
  const QRgb glow = mars.image.pixel(mars.view.center() - QPoint(0, mars.view.height() / 20));
  std::printf("  Mars glow %d %d %d\n", qRed(glow), qGreen(glow), qBlue(glow));
  // 186 198 209 with Lorenz-Mie dust (atmosphere/presets/mars.json; tone-mapped close to
  // white, B/R 1.80 in radiance: tests/cli/test_render_cli.cpp)
  EXPECT_GT(qBlue(glow), qRed(glow) + 3);

  const RunResult bad = umbra::test::run(UMBRA_GUI_EXE, {sunset, "--atmosphere", "venus", "--screenshot", dir / "x.png"},
                                         {"UMBRA_CACHE_DIR=" + (dir / "cache")});
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_NE(bad.err.find("--atmosphere: atmosphere: "), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("venus"), std::string::npos) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

// The Moon in totality through Earth's atmosphere (small tables): shaded with the
// atmospheric shadow LuT it is copper (summed R > G > B over the Moon's pixels), as
// `umbra render` draws it; without the atmosphere (airless umbra) it is dark.
TEST(GuiScreenshot, MoonInTotalityIsCopperWithTheAtmosphere) {
  TempDir dir;
  const std::string moon = std::string(UMBRA_SOURCE_DIR) + "/examples/scenes/lunar-eclipse-2015-09-28-moon.json";
  const Shot on = screenshotOf(moon, dir, "on.png", {"--time", "2015-09-28T02:47:00Z", "--atmosphere-tables", "small"});
  const Shot off = screenshotOf(moon, dir, "off.png", {"--time", "2015-09-28T02:47:00Z", "--atmosphere", "none"});
  ASSERT_EQ(on.run.exitCode, 0) << on.run.err;
  ASSERT_EQ(off.run.exitCode, 0) << off.run.err;
  auto sums = [](const Shot& s) {
    std::array<double, 3> rgb{0.0, 0.0, 0.0};
    for (int y = s.view.top(); y <= s.view.bottom(); ++y)
      for (int x = s.view.left(); x <= s.view.right(); ++x) {
        const QRgb c = s.image.pixel(x, y);
        rgb[0] += qRed(c), rgb[1] += qGreen(c), rgb[2] += qBlue(c);
      }
    return rgb;
  };
  const auto a = sums(on), b = sums(off);
  std::printf("  Moon's summed RGB with the atmosphere %.0f %.0f %.0f, without %.0f %.0f %.0f\n", a[0], a[1], a[2],
              b[0], b[1], b[2]);
  EXPECT_GT(a[0], 1.3 * a[1]);
  EXPECT_GT(a[1], a[2]);
  EXPECT_GT(a[0], 3.0 * b[0]);
}

// --atmosphere-set goes through the editor: a bad value is one line naming the field, exit 1.
TEST(GuiScreenshot, AtmosphereSetBadValueIsOneLine) {
  TempDir dir;
  const std::string sunset = std::string(UMBRA_SOURCE_DIR) + "/examples/scenes/earth-sunset.json";
  const RunResult r = umbra::test::run(
      UMBRA_GUI_EXE,
      {sunset, "--atmosphere-tables", "small", "--atmosphere-set", "components.troposphere.density.scaleHeightM=-5",
       "--screenshot", dir / "x.png"},
      {"UMBRA_CACHE_DIR=" + (dir / "cache")});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("--atmosphere-set: earth: components.troposphere.density.scaleHeightM: expected"), std::string::npos)
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

TEST(GuiScreenshot, Help) {
  const RunResult r = umbra::test::run(UMBRA_GUI_EXE, {"--help"});
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("--screenshot"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--quit-after-screenshot"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--time"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--atmosphere"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--atmosphere-set"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--limb-ring-threshold"), std::string::npos) << r.out;
}
