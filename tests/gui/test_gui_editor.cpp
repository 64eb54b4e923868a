// The atmosphere editor driven in-process (this binary runs under xvfb-run, see
// umbra_add_render_test) on umbra-gui's MainWindow with small tables: an accepted edit
// reaches the tables and changes the sky the way physics says; a rejected one names the
// component and field and leaves the tables; Save/Load JSON round-trips every field; the
// time slider moves the Sun under the same tables.
#include "AtmosphereEditor.hpp"
#include "EclipseList.hpp"
#include "MainWindow.hpp"
#include "ProfilePanel.hpp"
#include "SceneView.hpp"
#include "vtkAtmosphereTablesSource.h"

#include "Atmosphere.hpp"
#include "Describe.hpp"
#include "Spectrum.hpp"
#include "scene/Eclipses.hpp"
#include "scene/Time.hpp"

#include "CliRunner.hpp"
#include "DiscExtent.hpp"

#include <QApplication>
#include <filesystem>
#include <QComboBox>
#include <QProgressBar>
#include <QRegularExpression>
#include <QElapsedTimer>
#include <QImage>
#include <QSurfaceFormat>
#include <QTreeWidget>
#include <QTreeWidgetItemIterator>
#include <QVTKOpenGLNativeWidget.h>
#include <vtkDoubleArray.h>
#include <vtkTable.h>

#include <gtest/gtest.h>

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <fstream>
#include <iostream>
#include <regex>

using umbra::gui::AtmosphereEditor;
using umbra::gui::MainWindow;
using Json = AtmosphereEditor::Json;
namespace atm = umbra::atmosphere;

namespace {

// The sunset scene with Bruneton's thin haze (earth-bruneton): the editor's tests edit its
// "aerosols" component (a Cornette-Shanks phase, one exponential profile).
const std::string kSunset = [] {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("umbra-gui-editor-sunset-" + std::to_string(::getpid()) + ".json")).string();
  std::ifstream in(std::string(UMBRA_SOURCE_DIR) + "/examples/scenes/earth-sunset.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text = std::regex_replace(text, std::regex(R"("atmosphere": "earth")"), R"("atmosphere": "earth-bruneton")");
  std::ofstream(path) << text;
  return path;
}();

/// Runs the event loop until the tables are made and no edit is pending (at most 60 s).
void settle(MainWindow& w) {
  QElapsedTimer clock;
  clock.start();
  while ((w.atmosphereBusy() || w.atmosphereEditor().changePending()) && clock.elapsed() < 60000)
    QApplication::processEvents(QEventLoop::AllEvents, 50);
  QApplication::processEvents();
  ASSERT_FALSE(w.atmosphereBusy()) << "the tables took more than 60 s";
}

struct Window {
  umbra::test::TempDir dir;
  MainWindow w;
  explicit Window(std::optional<umbra::scene::UtcTime> time = std::nullopt) : Window(time, kSunset, time, true) {}
  Window(std::optional<umbra::scene::UtcTime>, const std::string& scene, std::optional<umbra::scene::UtcTime> time,
         bool settleNow) {
    w.useSmallAtmosphereTables(true);
    w.loadScene(scene, time);
    w.show();
    if (settleNow) settle(w);
  }
  QImage shot(const std::string& name) {
    w.saveScreenshot(dir / name);
    return QImage(QString::fromStdString(dir / name));
  }
  /// A sky pixel: a quarter of the view's width in, 10 % below its top (away from the Sun).
  QRgb sky(const QImage& image) const {
    const QRect v = w.viewRect();
    return image.pixel(v.left() + v.width() / 4, v.top() + v.height() / 10);
  }
};

atm::Atmosphere drawn(const MainWindow& w) { return atm::loadAtmosphere(w.drawnAtmosphere(), atm::WavelengthSet::rgb().nm); }

std::string describe(QRgb c) {
  return std::to_string(qRed(c)) + " " + std::to_string(qGreen(c)) + " " + std::to_string(qBlue(c));
}

}  // namespace

TEST(GuiEditor, ThePresetsFieldsAreInTheTreeWithUnits) {
  Window win;
  AtmosphereEditor& e = win.w.atmosphereEditor();
  ASSERT_TRUE(e.hasDocument());
  EXPECT_EQ(e.sourceName(), "earth-bruneton");
  EXPECT_EQ(win.w.drawnAtmosphere(), "earth-bruneton");
  // Every component's profile parameter is an item with the table's unit.
  int scaleHeights = 0;
  for (QTreeWidgetItemIterator it(e.tree()); *it; ++it) {
    const QString path = (*it)->data(0, Qt::UserRole).toString();
    if (path.endsWith(".density.scaleHeightM")) {
      ++scaleHeights;
      EXPECT_EQ((*it)->text(2), "m") << path.toStdString();
      EXPECT_EQ((*it)->text(3), "> 0") << path.toStdString();
    }
  }
  EXPECT_EQ(scaleHeights, 3);  // molecules, aerosols, oxygen (ozone is a tent)

  // As a user edits: a value typed into the tree, a type chosen in its combo box.
  auto item = [&](const QString& path) -> QTreeWidgetItem* {
    for (QTreeWidgetItemIterator it(e.tree()); *it; ++it)
      if ((*it)->data(0, Qt::UserRole).toString() == path) return *it;
    return nullptr;
  };
  QTreeWidgetItem* h = item("components.aerosols.density.scaleHeightM");
  ASSERT_NE(h, nullptr);
  h->setText(1, "3000");
  EXPECT_EQ(e.document()["components"]["aerosols"]["density"]["scaleHeightM"], 3000);
  EXPECT_TRUE(e.changePending());
  QTreeWidgetItem* type = item("components.aerosols.phase.type");
  ASSERT_NE(type, nullptr);
  auto* choice = qobject_cast<QComboBox*>(e.tree()->itemWidget(type, 1));
  ASSERT_NE(choice, nullptr);
  EXPECT_GE(choice->findText("tabulated"), 0);
  emit choice->textActivated("henyey-greenstein");
  QApplication::processEvents();
  EXPECT_EQ(e.document()["components"]["aerosols"]["phase"], Json::parse(R"({"type": "henyey-greenstein", "g": 0.8})"));
  ASSERT_NE(item("components.aerosols.phase.g"), nullptr);  // the tree was rebuilt
  EXPECT_EQ(item("components.aerosols.phase.g")->text(1), "0.8");
  // A number turned into a spectrum table: its wavelengths and values become items.
  ASSERT_EQ(e.setValue("components.aerosols.phase.g", R"({"wavelengthsNm": [440, 680], "values": [0.85, 0.75]})"), "");
  QApplication::processEvents();
  ASSERT_NE(item("components.aerosols.phase.g.values"), nullptr);
  EXPECT_EQ(item("components.aerosols.phase.g.values")->text(1), "[0.85,0.75]");
  settle(win.w);
  const atm::Atmosphere a = drawn(win.w);
  EXPECT_EQ(a.component("aerosols").density.scaleHeightM, 3000.0);
  // g at 680, 550, 440 nm (the view's wavelengths), linear in between: 0.85 - 0.1 * 110 / 240 at 550.
  ASSERT_EQ(a.component("aerosols").phases.size(), 3u);
  EXPECT_DOUBLE_EQ(a.component("aerosols").phases[0].g(), 0.75);
  EXPECT_NEAR(a.component("aerosols").phases[1].g(), 0.85 - 0.1 * 110.0 / 240.0, 1e-12);
  EXPECT_DOUBLE_EQ(a.component("aerosols").phases[2].g(), 0.85);
}

// Twenty times the aerosols (densityScale 1 -> 20: vertical optical depth 0.0053 -> 0.11,
// still thin) scatter more sunlight forward: with the Sun 60 degrees high the sky about 12
// degrees from it, where the aerosols' forward peak (Cornette-Shanks, g = 0.8) dominates,
// gets brighter in every channel (the aerosols are grey).
TEST(GuiEditor, AnEditReachesTheTablesAndTheSky) {
  Window win(umbra::scene::parseUtc("2024-03-20T14:05:00Z"));
  win.w.setExposure(-12.0);
  const QRgb before = win.sky(win.shot("before.png"));
  AtmosphereEditor& e = win.w.atmosphereEditor();
  EXPECT_NE(e.setValue("components.aerosols.densityScales", "20").find("earth-bruneton: components.aerosols.densityScales: no such field"),
            std::string::npos);
  EXPECT_FALSE(e.changePending());
  EXPECT_EQ(e.setValue("components.aerosols.densityScale", "20"), "");  // optional: not in the preset, added
  EXPECT_EQ(e.message(), "");
  EXPECT_TRUE(e.changePending());  // debounced
  settle(win.w);
  EXPECT_NE(win.w.drawnAtmosphere(), "earth-bruneton");
  const atm::Atmosphere a = drawn(win.w);
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(a.component("aerosols").scatteringPerM[i], 20 * 3.996e-6);
    EXPECT_DOUBLE_EQ(a.component("aerosols").absorptionPerM[i], 20 * 4.44e-7);
  }
  EXPECT_EQ(a.component("molecules").density.scaleHeightM, 8000.0);
  const QRgb after = win.sky(win.shot("after.png"));
  std::printf("  sky with the aerosols' densityScale 1: %s, 20: %s\n", describe(before).c_str(),
              describe(after).c_str());
  EXPECT_LT(qRed(before), 200) << "not saturated";
  EXPECT_GT(qRed(after), qRed(before) + 10);
  EXPECT_GT(qGreen(after), qGreen(before) + 10);
  EXPECT_GT(qBlue(after), qBlue(before) + 5);
}

TEST(GuiEditor, ABadValueIsRejectedAndTheTablesStay) {
  Window win;
  AtmosphereEditor& e = win.w.atmosphereEditor();
  const Json doc = e.document();
  const std::string problem = e.setValue("components.molecules.density.scaleHeightM", "-8000");
  EXPECT_NE(problem.find("earth-bruneton: components.molecules.density.scaleHeightM: "), std::string::npos) << problem;
  EXPECT_EQ(std::count(problem.begin(), problem.end(), '\n'), 0) << problem;
  EXPECT_EQ(e.message().toStdString(), problem);
  EXPECT_EQ(e.document(), doc);
  EXPECT_FALSE(e.changePending());
  settle(win.w);
  EXPECT_EQ(win.w.drawnAtmosphere(), "earth-bruneton");
  // The value stays in the tree, in red.
  for (QTreeWidgetItemIterator it(e.tree()); *it; ++it)
    if ((*it)->data(0, Qt::UserRole).toString() == "components.molecules.density.scaleHeightM") {
      EXPECT_EQ((*it)->text(1), "-8000");
      EXPECT_EQ((*it)->foreground(1).color(), QColor(Qt::red));
    }

  const std::string text = e.setValue("components.aerosols.phase.g", "strong");
  EXPECT_NE(text.find("components.aerosols.phase.g: expected a number"), std::string::npos) << text;
  const std::string g = e.setValue("components.aerosols.phase.g", "1.5");
  EXPECT_NE(g.find("components.aerosols.phase.g: expected a number in [-0.999999, 0.999999], got 1.5"), std::string::npos) << g;
  const std::string unknown = e.setType("components.aerosols.phase", "no-such-phase");
  EXPECT_NE(unknown.find("components.aerosols.phase"), std::string::npos) << unknown;
  EXPECT_EQ(e.document(), doc);
  EXPECT_FALSE(e.changePending());
}

// Cancel right after an edit: the view keeps the preset's tables, the choice goes back to it.
TEST(GuiEditor, CancelKeepsTheTablesDrawn) {
  Window win;
  AtmosphereEditor& e = win.w.atmosphereEditor();
  ASSERT_EQ(e.setValue("components.molecules.density.scaleHeightM", "7000"), "");
  e.flush();
  ASSERT_TRUE(win.w.atmosphereBusy());
  win.w.cancelAtmosphereTables();
  settle(win.w);
  EXPECT_EQ(win.w.drawnAtmosphere(), "earth-bruneton");
  EXPECT_NE(win.w.statusText().indexOf("atmosphere: cancelled"), -1) << win.w.statusText().toStdString();
  // The edit is still in the editor; the next one computes its tables.
  EXPECT_EQ(e.document()["components"]["molecules"]["density"]["scaleHeightM"], 7000);
  ASSERT_EQ(e.setValue("components.molecules.density.scaleHeightM", "7500"), "");
  settle(win.w);
  EXPECT_EQ(drawn(win.w).component("molecules").density.scaleHeightM, 7500.0);
}

// A user clicking through the presets: each choice stops the job before it and starts its
// own (the tables from the cache after the first two), while the window goes on drawing;
// the last choice is the one drawn and in the editor, and no stopped job reports.
TEST(GuiEditor, ChoosingAtmospheresInQuickSuccessionDrawsTheLastOne) {
  Window win;
  const std::array<std::string, 2> presets{"earth", "earth-bruneton"};
  for (int i = 0; i < 60; ++i) {
    win.w.setAtmosphere(presets[i % 2]);
    ASSERT_TRUE(win.w.atmosphereTablesBusy()) << i;
    QApplication::processEvents();
  }
  win.w.setAtmosphere("earth");
  settle(win.w);
  EXPECT_EQ(win.w.drawnAtmosphere(), "earth");
  EXPECT_EQ(win.w.atmosphereEditor().sourceName(), "earth");
  EXPECT_EQ(win.w.statusText().indexOf("atmosphere:"), -1) << win.w.statusText().toStdString();
}

// Components: one removed (the ozone: no Chappuis absorption any more), one added with the
// table's defaults; removing the one refraction follows is rejected naming that field.
TEST(GuiEditor, ComponentsAreAddedAndRemoved) {
  Window win;
  AtmosphereEditor& e = win.w.atmosphereEditor();
  const std::string follows = e.removeComponent("molecules");
  EXPECT_NE(follows.find("earth-bruneton: refraction.followsComponent: expected the name of a component"), std::string::npos) << follows;
  EXPECT_NE(e.removeComponent("dust").find("components.dust: no such component"), std::string::npos);
  EXPECT_EQ(e.removeComponent("ozone"), "");
  EXPECT_EQ(e.addComponent("haze"), "");
  EXPECT_NE(e.addComponent("haze").find("exists already"), std::string::npos);
  settle(win.w);
  const atm::Atmosphere a = drawn(win.w);
  EXPECT_EQ(a.find("ozone"), nullptr);
  ASSERT_NE(a.find("haze"), nullptr);
  EXPECT_EQ(a.component("haze").density.scaleHeightM, 8000.0);
  EXPECT_EQ(a.component("haze").scatteringPerM, std::vector<double>(3, 4e-6));
  EXPECT_EQ(a.components.size(), 4u);  // molecules, aerosols, oxygen, haze
}

TEST(GuiEditor, SaveThenLoadGivesTheSameModel) {
  Window win;
  AtmosphereEditor& e = win.w.atmosphereEditor();
  e.setDebounceMs(0);
  ASSERT_EQ(e.setType("components.aerosols.phase", "double-henyey-greenstein"), "");
  ASSERT_EQ(e.setValue("components.aerosols.phase.alpha", "0.7"), "");
  ASSERT_EQ(e.setValue("groundAlbedo", "0.3"), "");
  ASSERT_EQ(e.setValue("components.ozone.optics.crossSectionM2.values[1]", "3e-28"), "");
  ASSERT_EQ(e.setValue("name", "earth-edited"), "");
  const Json edited = e.document();
  const std::string path = win.dir / "mine.json";
  win.w.saveAtmosphereJson(path);
  settle(win.w);

  std::ifstream in(path);
  EXPECT_EQ(Json::parse(in), edited);
  const auto rgb = atm::WavelengthSet::rgb().nm;
  const atm::ParameterMap saved = atm::atmosphereParameters(atm::loadAtmosphere(path, rgb));
  const atm::ParameterMap shown = atm::atmosphereParameters(atm::parseAtmosphere(edited.dump(), "x", rgb));
  EXPECT_EQ(saved, shown);
  EXPECT_EQ(saved.at("groundAlbedo"), "0.3 0.3 0.3");
  EXPECT_NE(saved.at("component.aerosols.phases").find("0.7"), std::string::npos) << saved.at("component.aerosols.phases");
  // The tables drawn are the edited model's.
  EXPECT_EQ(atm::atmosphereParameters(drawn(win.w)), shown);

  // Load: the file becomes the document and the tables' model.
  win.w.setAtmosphere("earth-bruneton");
  settle(win.w);
  EXPECT_NE(e.document(), edited);
  win.w.setAtmosphere(path);
  EXPECT_EQ(e.document(), edited);
  settle(win.w);
  EXPECT_EQ(win.w.drawnAtmosphere(), path);

  // A bad file: one line naming the file and the field; the document and tables stay.
  const std::string bad = win.dir / "bad.json";
  Json broken = edited;
  broken["components"]["aerosols"]["density"]["scaleHeightM"] = -1;
  std::ofstream(bad) << broken.dump();
  try {
    win.w.setAtmosphere(bad);
    ADD_FAILURE() << "a negative scale height was loaded";
  } catch (const std::exception& x) {
    const std::string m = x.what();
    EXPECT_NE(m.find(bad + ": components.aerosols.density.scaleHeightM: "), std::string::npos) << m;
  }
  EXPECT_EQ(e.document(), edited);
  EXPECT_EQ(win.w.drawnAtmosphere(), path);
  // The JSON written is all there is: no temporary left beside it.
  EXPECT_EQ(win.dir.fileCount(), 2);  // mine.json and bad.json
}

// The time slider with an atmosphere: an hour after sunset (the Sun ~15 deg down) the view
// first draws the day's tables, darker, while the worker makes the twilight ones the scene
// asks for (pipeline::atmosphereTableChoice: 4x the mu_s cells, the Sun down to 130 deg);
// the plot panel and the status follow the time. Back at sunset: the day's tables again,
// from the cache.
TEST(GuiEditor, TimeSliderMakesTwilightTablesAndDarkensTheSky) {
  Window win;
  const QRgb before = win.sky(win.shot("sunset.png"));
  const std::string model = win.w.drawnAtmosphere();
  const vtkSmartPointer<vtkAtmosphereTablesSource> day = win.w.sceneView().atmosphereTables();  // held
  ASSERT_NE(day, nullptr);
  win.w.showTime(umbra::scene::parseUtc("2024-03-20T19:05:00Z"));
  EXPECT_TRUE(win.w.atmosphereTablesBusy());
  EXPECT_EQ(win.w.sceneView().atmosphereTables(), day);  // drawn meanwhile
  const QRgb meanwhile = win.sky(win.shot("dusk-day-tables.png"));
  settle(win.w);
  EXPECT_EQ(win.w.drawnAtmosphere(), model);
  vtkAtmosphereTablesSource* twilight = win.w.sceneView().atmosphereTables();
  ASSERT_NE(twilight, day);
  EXPECT_NEAR(std::acos(twilight->GetMuSMin()) * 180.0 / std::acos(-1.0), 130.0, 1e-6);
  EXPECT_EQ(twilight->GetScatteringSize()[2], 4 * day->GetScatteringSize()[2]);
  EXPECT_FALSE(win.w.sceneView().missingAtmosphereTables().has_value());
  const QRgb after = win.sky(win.shot("dusk.png"));
  std::printf("  sky at 18:05 %s, at 19:05 %s (the day's tables: %s)\n", describe(before).c_str(),
              describe(after).c_str(), describe(meanwhile).c_str());
  EXPECT_LT(qBlue(after) + qGreen(after), qBlue(before) + qGreen(before) - 20);
  EXPECT_NE(win.w.statusText().indexOf("2024-03-20T19:05:00Z"), -1) << win.w.statusText().toStdString();
  EXPECT_NE(win.w.statusText().indexOf("Sun 14.4 deg below the horizon"), -1) << win.w.statusText().toStdString();
  EXPECT_GT(win.w.plotRect().width(), 100);

  win.w.showTime(umbra::scene::parseUtc("2024-03-20T18:05:00Z"));
  settle(win.w);
  EXPECT_DOUBLE_EQ(win.w.sceneView().atmosphereTables()->GetMuSMin(), day->GetMuSMin());
  EXPECT_GT(win.w.sceneView().atmosphereTables()->GetLastCacheHits(), 0);
}

// The Eclipses list: the 2015 lunar eclipse's second contact sets the scene's time to the
// catalogue's U2 (scene::eclipseInstantUt, as a scene file's {"eclipse", "at"} does); a
// contact the eclipse lacks is refused.
TEST(GuiEditor, EclipseListSetsTheTimeToAContact) {
  Window win(std::nullopt, std::string(UMBRA_SOURCE_DIR) + "/examples/scenes/lunar-eclipse-2015-09-28.json",
             std::nullopt, false);
  win.w.showEclipseList();
  umbra::gui::EclipseList& list = win.w.eclipseList();
  EXPECT_GE(list.rowCount(), 12);  // 2015-2018: four years of two to five of each kind
  const auto row = list.rowOn("2015-09-28");
  ASSERT_TRUE(row);
  ASSERT_TRUE(list.choose(*row, "U2"));
  const double u2 = umbra::scene::eclipseInstantUt("2015-09-28", "U2");
  umbra::scene::UtcTime expected;
  expected.jd1 = std::floor(u2);
  expected.jd2 = u2 - expected.jd1;
  EXPECT_NE(win.w.statusText().indexOf(QString::fromStdString(umbra::scene::formatUtc(expected))), -1)
      << win.w.statusText().toStdString();
  EXPECT_NE(win.w.statusText().indexOf("2015-09-28T02:11:"), -1) << win.w.statusText().toStdString();
  const auto penumbral = list.rowOn("2016-03-23");  // a penumbral eclipse: no umbra
  ASSERT_TRUE(penumbral);
  EXPECT_FALSE(list.choose(*penumbral, "U2"));
  settle(win.w);
}

// The GPU time of the 3D view's last frame, per render-pass stage (GL
// timestamps): the sunset's atmosphere takes time, the total is the stages' sum (with the
// tone map's), and glare shows up when it is turned on (0 below 1 us: not drawn).
TEST(GuiEditor, GpuTimePerStageIsShown) {
  Window win;
  win.shot("frame.png");
  const QRegularExpression format(
      "^GPU ([0-9.e+-]+) ms: bodies ([0-9.e+-]+), atmosphere ([0-9.e+-]+), glare ([0-9.e+-]+)$");
  auto stages = [&] {
    const QRegularExpressionMatch m = format.match(win.w.gpuTimeText());
    EXPECT_TRUE(m.hasMatch()) << win.w.gpuTimeText().toStdString();
    std::vector<double> v;
    for (int k = 1; k <= 4; ++k) v.push_back(m.captured(k).toDouble());
    return v;
  };
  const std::vector<double> before = stages();
  ASSERT_EQ(before.size(), 4u);
  EXPECT_GT(before[2], 0.0) << "atmosphere";
  EXPECT_EQ(before[3], 0.0) << "no glare";
  // The total holds the tone map too (a few % of the frame on llvmpipe): 3 digits each.
  EXPECT_GE(before[0], 0.99 * (before[1] + before[2] + before[3]));
  EXPECT_LT(before[0], 1.2 * (before[1] + before[2] + before[3]));
  win.w.setGlare(1.0);
  win.shot("glare.png");
  EXPECT_GT(stages()[3], 0.0) << win.w.gpuTimeText().toStdString();
  std::printf("  %s\n", win.w.gpuTimeText().toStdString().c_str());
}

// The "Refraction" check box (umbra-gui --refraction) on the sunset seen through a
// 3-degree field at 18:06 (the Sun just above the horizon; a minute later its disc would
// be cut by it without refraction): the tables are made again in the worker with
// refracted paths and the refraction table, and the Sun's disc is flattened (height /
// width < 0.9; measured 0.865) and lifted, measured as the render pass's test measures
// it (umbra::test::discOf: the bounding box of the pixels above a fraction of the
// brightest; here the screenshot's luma, 80 % of the brightest, above the sky's); without
// refraction it is round (> 0.95; measured 1.0). Off again: the tables from the cache.
TEST(GuiEditor, RefractionCheckBoxFlattensTheSettingSun) {
  umbra::test::TempDir dir;
  std::ifstream in(kSunset);
  std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  json = std::regex_replace(json, std::regex("\"fovDeg\": 30"), "\"fovDeg\": 3");
  const std::string scene = dir / "sunset-3deg.json";
  std::ofstream(scene) << json;
  Window win(std::nullopt, scene, umbra::scene::parseUtc("2024-03-20T18:06:00Z"), /*settleNow=*/true);
  win.w.setExposure(-11.0);
  auto disc = [&](const std::string& name) {
    const QImage image = win.shot(name);
    const QRect v = win.w.viewRect();
    return umbra::test::discOf(
        v.width(), v.height(),
        [&](int i, int j) {
          const QRgb c = image.pixel(v.left() + i, v.top() + j);
          return 0.2126 * qRed(c) + 0.7152 * qGreen(c) + 0.0722 * qBlue(c);
        },
        0.8);
  };
  ASSERT_NE(win.w.sceneView().atmosphereTables(), nullptr);
  EXPECT_FALSE(win.w.sceneView().atmosphereTables()->GetRefractedPaths());
  const umbra::test::DiscExtent o = disc("straight.png");
  win.w.setRefraction(true);
  EXPECT_TRUE(win.w.atmosphereTablesBusy());
  settle(win.w);
  EXPECT_TRUE(win.w.refraction());
  EXPECT_TRUE(win.w.sceneView().atmosphereTables()->GetRefractedPaths());
  EXPECT_EQ(win.w.drawnAtmosphere(), "earth-bruneton");
  const umbra::test::DiscExtent d = disc("bent.png");
  std::printf("  disc %d x %d px with refraction (height / width %.3f), %d x %d px without (%.3f)\n", d.width(),
              d.height(), double(d.height()) / d.width(), o.width(), o.height(), double(o.height()) / o.width());
  ASSERT_GT(o.width(), 50) << "the Sun's disc is about 110 px wide";
  EXPECT_LT(double(d.height()) / d.width(), 0.9);
  EXPECT_GT(double(o.height()) / o.width(), 0.95);
  EXPECT_NEAR(d.width(), o.width(), 3);
  EXPECT_LT(d.bottom, o.bottom);  // lifted

  win.w.setRefraction(true);  // no change: nothing to do
  EXPECT_FALSE(win.w.atmosphereTablesBusy());
  win.w.setRefraction(false);
  settle(win.w);
  EXPECT_FALSE(win.w.sceneView().atmosphereTables()->GetRefractedPaths());
  EXPECT_GT(win.w.sceneView().atmosphereTables()->GetLastCacheHits(), 0);
}

namespace {

const std::string kMoon = std::string(UMBRA_SOURCE_DIR) + "/examples/scenes/lunar-eclipse-2015-09-28-moon.json";

/// Runs the event loop until the atmospheric shadow LuT's job has started (at most 60 s).
bool untilShadowJob(MainWindow& w) {
  QElapsedTimer clock;
  clock.start();
  while (!w.atmosphereShadowBusy() && w.atmosphereBusy() && clock.elapsed() < 60000)
    QApplication::processEvents(QEventLoop::AllEvents, 20);
  return w.atmosphereShadowBusy();
}

/// The summed R, G, B of the 3D view (the Moon on a black sky).
std::array<double, 3> viewSums(Window& win, const std::string& name) {
  const QImage image = win.shot(name);
  const QRect v = win.w.viewRect();
  std::array<double, 3> rgb{0.0, 0.0, 0.0};
  for (int y = v.top(); y <= v.bottom(); ++y)
    for (int x = v.left(); x <= v.right(); ++x) {
      const QRgb c = image.pixel(x, y);
      rgb[0] += qRed(c), rgb[1] += qGreen(c), rgb[2] += qBlue(c);
    }
  return rgb;
}

/// What is written on stderr (file descriptor 2, where VTK's log goes) while it lives.
class StderrCapture {
public:
  explicit StderrCapture(std::string path) : path_(std::move(path)) {
    std::fflush(stderr);
    saved_ = ::dup(2);
    const int fd = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    ::dup2(fd, 2);
    ::close(fd);
  }
  ~StderrCapture() {
    std::fflush(stderr);
    ::dup2(saved_, 2);
    ::close(saved_);
  }
  std::string text() const {
    std::fflush(stderr);
    return umbra::test::readAll(path_);
  }

private:
  std::string path_;
  int saved_ = -1;
};

bool copper(const std::array<double, 3>& rgb) { return rgb[0] > 1.3 * rgb[1] && rgb[1] > rgb[2] && rgb[0] > 1e6; }

}  // namespace

// The Moon in totality: after the atmosphere's tables the worker computes the atmospheric
// shadow LuT (the GUI thread keeps running its event loop meanwhile: the job is seen
// busy), the progress bar moves through intermediate values, and the Moon is copper.
TEST(GuiEditor, AtmosphereShadowLutInTheWorkerWithProgress) {
  Window win(std::nullopt, kMoon, umbra::scene::parseUtc("2015-09-28T02:47:00Z"), /*settleNow=*/false);
  auto* bar = win.w.findChild<QProgressBar*>();
  ASSERT_NE(bar, nullptr);
  std::vector<int> values;
  QObject::connect(bar, &QProgressBar::valueChanged, [&](int v) {
    if (win.w.atmosphereShadowBusy()) values.push_back(v);
  });
  ASSERT_TRUE(untilShadowJob(win.w)) << "no atmospheric shadow LuT job after the tables";
  EXPECT_FALSE(win.w.sceneView().atmosphereShadowCurrent());
  QElapsedTimer clock;
  clock.start();
  settle(win.w);
  const qint64 computedMs = clock.elapsed();
  EXPECT_TRUE(win.w.sceneView().atmosphereShadowCurrent());
  EXPECT_FALSE(win.w.sceneView().atmosphereShadowFromCache());
  EXPECT_FALSE(bar->isVisible());
  const auto between = std::count_if(values.begin(), values.end(), [](int v) { return v > 0 && v < 100; });
  std::printf("  progress values during the shadow job: %zu, %ld of them in (0, 100)\n", values.size(), long(between));
  EXPECT_GE(between, 3);
  const auto rgb = viewSums(win, "copper.png");
  std::printf("  Moon's summed RGB %.0f %.0f %.0f\n", rgb[0], rgb[1], rgb[2]);
  EXPECT_TRUE(copper(rgb));

  // Again in a new window: the table from the cache (by its parameters' hash).
  Window again(std::nullopt, kMoon, umbra::scene::parseUtc("2015-09-28T02:47:00Z"), /*settleNow=*/false);
  ASSERT_TRUE(untilShadowJob(again.w));
  clock.restart();
  settle(again.w);
  std::printf("  the shadow LuT job (64x32, limb views of 32 rows): computed %lld ms, from the cache %lld ms\n",
              static_cast<long long>(computedMs), static_cast<long long>(clock.elapsed()));
  EXPECT_TRUE(again.w.sceneView().atmosphereShadowCurrent());
  EXPECT_TRUE(again.w.sceneView().atmosphereShadowFromCache());
}

// Cancel: with no table before, the Moon stays airless-dark in the umbra, and the table
// is not asked for again until the time moves (a cancelled or failed table is retried
// then). With one, the view keeps shading with it (copper) after a cancelled
// recomputation (here for another atmosphere of the same body). The tables of the scene
// are the same through the eclipse (pipeline::sunDistanceOnGrid, ranged u on a grid): a
// time step needs none, and slider steps while a table is made wait for it. A cancel is
// not an error: nothing on stderr (VTK printed the source's error and the executive's
// failure, 12 lines).
TEST(GuiEditor, CancelTheAtmosphereShadowLutKeepsThePreviousShading) {
  Window win(std::nullopt, kMoon, umbra::scene::parseUtc("2015-09-28T02:50:00Z"), /*settleNow=*/false);
  const StderrCapture err(win.dir / "stderr.txt");
  ASSERT_TRUE(untilShadowJob(win.w));
  win.w.cancelAtmosphereTables();
  settle(win.w);
  EXPECT_NE(win.w.statusText().indexOf("atmosphere shadow: cancelled"), -1) << win.w.statusText().toStdString();
  EXPECT_EQ(win.w.sceneView().atmosphereShadowLut(), nullptr);
  const auto airless = viewSums(win, "airless.png");
  EXPECT_FALSE(win.w.atmosphereBusy()) << "a cancelled table is not asked for again";

  win.w.showTime(umbra::scene::parseUtc("2015-09-28T02:47:00Z"));  // the time moves: asked for again
  EXPECT_TRUE(win.w.atmosphereShadowBusy());
  settle(win.w);
  const auto before = viewSums(win, "before.png");
  EXPECT_TRUE(copper(before));
  EXPECT_TRUE(win.w.sceneView().atmosphereShadowCurrent());
  win.w.showTime(umbra::scene::parseUtc("2015-09-28T03:17:00Z"));  // the same table half an hour later
  EXPECT_FALSE(win.w.atmosphereBusy());
  EXPECT_TRUE(win.w.sceneView().atmosphereShadowCurrent());

  win.w.setAtmosphere("earth-bruneton");  // its tables, then its shadow LuT: cancelled
  ASSERT_TRUE(untilShadowJob(win.w));
  win.w.cancelAtmosphereTables();
  settle(win.w);
  EXPECT_NE(win.w.statusText().indexOf("atmosphere shadow: cancelled"), -1) << win.w.statusText().toStdString();
  EXPECT_NE(win.w.sceneView().atmosphereShadowLut(), nullptr);
  EXPECT_FALSE(win.w.sceneView().atmosphereShadowCurrent());
  const auto after = viewSums(win, "after.png");
  std::printf("  Moon's summed R: cancelled at 02:50 (airless) %.0f, 02:47 %.0f, cancelled for 'earth-bruneton' (02:47's table) %.0f\n",
              airless[0], before[0], after[0]);
  EXPECT_LT(airless[0], 0.1 * before[0]);
  EXPECT_TRUE(copper(after));
  EXPECT_FALSE(win.w.atmosphereBusy());
  // Slider steps: the first asks for the cancelled table again, the next ones (the same
  // table) wait for it; then it is current at the latest time.
  win.w.showTime(umbra::scene::parseUtc("2015-09-28T03:18:00Z"));
  EXPECT_TRUE(win.w.atmosphereShadowBusy());
  win.w.showTime(umbra::scene::parseUtc("2015-09-28T03:19:00Z"));
  win.w.showTime(umbra::scene::parseUtc("2015-09-28T03:20:00Z"));
  settle(win.w);
  EXPECT_TRUE(win.w.sceneView().atmosphereShadowCurrent());
  EXPECT_NE(win.w.statusText().indexOf("03:20:00Z"), -1) << win.w.statusText().toStdString();
  EXPECT_EQ(err.text(), "");
}

// The plot panel through Earth's atmosphere (the Moon in totality, small tables): the
// profile comes from the atmospheric shadow LuT the view shades with, red-dominant at the
// umbra's centre, and it matches `umbra profile shadow --atmosphere` (the same tables,
// limb views and rows: --draft-tables --orders 2 --limb-size 32 --scattering-cells 4
// --size 32; both LuTs ranged, over the Moon's distances in the view, over the
// cross-section's in the CLI: 0.5 % apart) inside the umbra within kTolerance per channel.
// (With --size 64, 64 rows to the view's 32, they differ by up to 45 % in blue at 4000 km.)
TEST(GuiEditor, ProfileThroughTheAtmosphereMatchesTheCli) {
  constexpr double kTolerance = 0.02;
  Window win(std::nullopt, kMoon, umbra::scene::parseUtc("2015-09-28T02:47:00Z"), /*settleNow=*/true);
  ASSERT_TRUE(win.w.sceneView().atmosphereShadowCurrent());
  vtkTable* t = win.w.profilePanel().profile();
  auto column = [&](const char* name) { return vtkDoubleArray::SafeDownCast(t->GetColumnByName(name)); };
  ASSERT_NE(column("offset_km"), nullptr);
  // Linear interpolation over the offsets (as the panel's marker does).
  auto at = [](const std::vector<double>& x, const std::vector<double>& y, double km) {
    const auto k = std::upper_bound(x.begin(), x.end(), km) - x.begin();
    if (k == 0) return y.front();
    if (k == static_cast<long>(x.size())) return y.back();
    const double f = (km - x[k - 1]) / (x[k] - x[k - 1]);
    return (1.0 - f) * y[k - 1] + f * y[k];
  };
  std::array<std::vector<double>, 4> gui;  // offset, r, g, b
  const char* names[] = {"offset_km", "r", "g", "b"};
  for (int c = 0; c < 4; ++c)
    for (vtkIdType i = 0; i < t->GetNumberOfRows(); ++i) gui[c].push_back(column(names[c])->GetValue(i));
  EXPECT_GT(gui[1][0], 2.0 * gui[2][0]);
  EXPECT_GT(gui[2][0], 2.0 * gui[3][0]);
  EXPECT_GT(gui[1][0], 1e-5) << "red light reaches the umbra's centre";

  const std::string csv = win.dir / "cli.csv";
  const umbra::test::RunResult r = umbra::test::run(
      UMBRA_EXE, {"profile", "shadow", "--scene", kMoon, "--time", "2015-09-28T02:47:00Z", "--atmosphere",
                  "earth-2015-calbuco", "--draft-tables", "--orders", "2", "--limb-size", "32", "--scattering-cells",
                  "4", "--size", "32", "--csv", csv},
      {"UMBRA_CACHE_DIR=" + std::string(std::getenv("UMBRA_CACHE_DIR"))});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const umbra::test::Csv cli = umbra::test::readCsv(csv);
  std::array<std::vector<double>, 4> ref;
  for (const auto& row : cli.rows)
    for (int c = 0; c < 4; ++c) ref[c].push_back(row[c]);
  double worst = 0.0;
  for (double km : {0.0, 1000.0, 2000.0, 3000.0, 4000.0}) {
    std::printf("  %4.0f km: GUI", km);
    for (int c = 1; c < 4; ++c) std::printf(" %.3e", at(gui[0], gui[c], km));
    std::printf(", CLI");
    for (int c = 1; c < 4; ++c) {
      const double a = at(gui[0], gui[c], km), b = at(ref[0], ref[c], km);
      std::printf(" %.3e", b);
      worst = std::max(worst, std::abs(a - b) / b);
      EXPECT_NEAR(a, b, kTolerance * b) << "channel " << c << " at " << km << " km";
    }
    std::printf("\n");
  }
  std::printf("  largest relative difference %.3f\n", worst);
}

namespace {

const std::string kPole =
    std::string(UMBRA_SOURCE_DIR) + "/examples/scenes/earth-from-lunar-north-pole-2015-09-28.json";

/// The ring: the pixels of `a` or `b` (same size) with a channel above `floor`, and the mean
/// R, G, B of each image over them.
struct Ring {
  int pixels = 0;
  std::array<double, 3> a{}, b{};
};

Ring ringOf(const QImage& a, const QImage& b, int floor) {
  Ring r;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const QRgb p = a.pixel(x, y), q = b.pixel(x, y);
      if (std::max({qRed(p), qGreen(p), qBlue(p), qRed(q), qGreen(q), qBlue(q)}) <= floor) continue;
      ++r.pixels;
      r.a[0] += qRed(p), r.a[1] += qGreen(p), r.a[2] += qBlue(p);
      r.b[0] += qRed(q), r.b[1] += qGreen(q), r.b[2] += qBlue(q);
    }
  for (int c = 0; c < 3; ++c) r.a[c] /= std::max(r.pixels, 1), r.b[c] /= std::max(r.pixels, 1);
  return r;
}

}  // namespace

// Earth from the lunar north pole in totality (the example scene at its time, 2015-09-28
// 02:30, eclipse paper Figure 11 bottom row; small tables, refraction, a 443x280 view):
// the worker makes the limb-luminance LuT in the job of the atmospheric shadow LuT (again
// for another atmosphere; from the table cache for one seen before), and the ring, 1.7 px
// wide, is drawn from it as `umbra render` draws it: the view's pixels and the CLI's PNG
// of the same scene, time, size and exposure (the same table cache) were measured equal
// (0 pixels differ: one code path, pipeline::applySceneLimbLuminance's request and update),
// so the ring's mean R, G, B (over the pixels above 8 in either) must agree within
// kTolerance, which leaves room for a driver's rounding; the ray-marched ring (threshold
// 0) is far from it (mean R 93 vs 218), so the comparison tells the two paths apart.
TEST(GuiEditor, LimbRingFromTheLutAsTheCliDrawsIt) {
  constexpr double kTolerance = 0.02;
  umbra::test::TempDir dir;
  MainWindow w;
  w.useSmallAtmosphereTables(true);
  w.setRefraction(true);
  w.resize(640, 400);
  w.loadScene(kPole);
  w.show();
  ASSERT_TRUE(untilShadowJob(w));
  EXPECT_TRUE(w.limbLuminanceBusy());
  EXPECT_FALSE(w.sceneView().limbLuminanceCurrent());
  QElapsedTimer clock;
  clock.start();
  settle(w);
  std::printf("  the shadow and limb-luminance LuT job: %lld ms\n", static_cast<long long>(clock.elapsed()));
  ASSERT_TRUE(w.sceneView().limbLuminanceCurrent());
  EXPECT_TRUE(w.sceneView().atmosphereShadowCurrent());  // the lunar ground in the umbra
  const std::string png = dir / "gui.png";
  w.saveScreenshot(png);
  const double ringPx = w.sceneView().lastRingWidthPixels();
  EXPECT_TRUE(w.sceneView().lastDrawUsedLimbLuminance()) << "ring " << ringPx << " px";
  EXPECT_LT(ringPx, w.limbRingThreshold());
  const QRect v = w.viewRect();
  auto read = [&](const std::string& path, const QRect& part) {
    const QImage image(QString::fromStdString(path));
    return (part.isNull() ? image : image.copy(part)).convertToFormat(QImage::Format_RGB32);
  };
  const QImage gui = read(png, v);

  const std::string cliPng = dir / "cli.png";
  const std::string size = std::to_string(v.width()) + "x" + std::to_string(v.height());
  const umbra::test::RunResult r =
      umbra::test::run(UMBRA_EXE, {"render", kPole, "--size", size, "--atmosphere-tables", "small", "--refraction",
                                   "--output", cliPng},
                       {"UMBRA_CACHE_DIR=" + std::string(std::getenv("UMBRA_CACHE_DIR"))});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const QImage cli = read(cliPng, QRect());
  ASSERT_EQ(cli.size(), gui.size());
  const Ring ring = ringOf(gui, cli, 8);
  int differ = 0, worst = 0;
  for (int y = 0; y < gui.height(); ++y)
    for (int x = 0; x < gui.width(); ++x) {
      const QRgb p = gui.pixel(x, y), q = cli.pixel(x, y);
      const int d =
          std::max({std::abs(qRed(p) - qRed(q)), std::abs(qGreen(p) - qGreen(q)), std::abs(qBlue(p) - qBlue(q))});
      differ += d > 0;
      worst = std::max(worst, d);
    }
  std::printf("  view %s, ring %.2f px wide: %d pixels, mean R G B GUI %.1f %.1f %.1f, CLI %.1f %.1f %.1f; "
              "%d pixels differ, by at most %d\n",
              size.c_str(), ringPx, ring.pixels, ring.a[0], ring.a[1], ring.a[2], ring.b[0], ring.b[1], ring.b[2],
              differ, worst);
  EXPECT_GT(ring.pixels, 500);  // around Earth's 110 px radius
  EXPECT_GT(ring.a[0], 1.3 * ring.a[1]);  // red
  EXPECT_GT(ring.a[1], ring.a[2]);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(ring.a[c], ring.b[c], kTolerance * ring.b[c]) << "channel " << c;

  // Threshold 0: ray marched (the view keeps the table: back at 5 px it draws from it again).
  w.setLimbRingThreshold(0.0);
  EXPECT_FALSE(w.atmosphereBusy());
  const std::string marchedPng = dir / "marched.png";
  w.saveScreenshot(marchedPng);
  EXPECT_FALSE(w.sceneView().lastDrawUsedLimbLuminance());
  const Ring marched = ringOf(gui, read(marchedPng, v), 8);
  std::printf("  ray marched: mean R G B %.1f %.1f %.1f over %d pixels (the LuT's %.1f %.1f %.1f)\n", marched.b[0],
              marched.b[1], marched.b[2], marched.pixels, marched.a[0], marched.a[1], marched.a[2]);
  EXPECT_GT(std::abs(marched.b[0] / marched.a[0] - 1.0), 5.0 * kTolerance);
  w.setLimbRingThreshold(5.0);
  EXPECT_FALSE(w.atmosphereBusy());
  w.renderViews();
  EXPECT_TRUE(w.sceneView().lastDrawUsedLimbLuminance());

  // Another atmosphere (Bruneton's thin haze, without earth's troposphere or Calbuco's sulphate): its tables, then its LuTs
  // in the worker; less extinction along the limb, a brighter ring (measured R 243 vs 170,
  // G 157 vs 96).
  w.setAtmosphere("earth-bruneton");
  ASSERT_TRUE(untilShadowJob(w));
  EXPECT_TRUE(w.limbLuminanceBusy());
  settle(w);
  EXPECT_TRUE(w.sceneView().limbLuminanceCurrent());
  const std::string clearPng = dir / "clear.png";
  w.saveScreenshot(clearPng);
  EXPECT_TRUE(w.sceneView().lastDrawUsedLimbLuminance());
  const Ring clear = ringOf(gui, read(clearPng, v), 8);
  std::printf("  earth-bruneton: mean R G B %.1f %.1f %.1f over %d pixels\n", clear.b[0], clear.b[1],
              clear.b[2], clear.pixels);
  EXPECT_GT(clear.b[0], ring.a[0]);
  EXPECT_GT(clear.b[1], 1.1 * ring.a[1]);
  EXPECT_FALSE(w.sceneView().limbLuminanceFromCache());

  // Back to Calbuco's: both LuTs from the table cache, the same ring.
  w.setAtmosphere("earth-2015-calbuco");
  settle(w);
  ASSERT_TRUE(w.sceneView().limbLuminanceCurrent());
  EXPECT_TRUE(w.sceneView().limbLuminanceFromCache());
  EXPECT_TRUE(w.sceneView().atmosphereShadowFromCache());
  const std::string againPng = dir / "again.png";
  w.saveScreenshot(againPng);
  const Ring again = ringOf(gui, read(againPng, v), 8);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(again.b[c], ring.a[c]) << "channel " << c;
}

int main(int argc, char** argv) {
  umbra::test::TempDir cache;  // a private table cache
  setenv("UMBRA_CACHE_DIR", cache.path.c_str(), 1);
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

// The "Stars to V" box: enabled with the scene's limit (6.5) for a scene with stars (Orion
// on a moonless night), and the view's stars follow it: above the horizon fewer pixels
// stand out of the dark sky to V 2 than to V 6.5. The "Night vision" box turns that
// starlit view grey. A scene without stars (no time) leaves the limit disabled.
TEST(GuiEditor, StarsToVFollowsTheLimitingMagnitude) {
  if (!std::filesystem::exists("/usr/share/kstars/stars.dat")) GTEST_SKIP() << "kstars-data is not installed";
  Window win(std::nullopt, std::string(UMBRA_SOURCE_DIR) + "/examples/scenes/orion-night-sky.json", std::nullopt, true);
  EXPECT_TRUE(win.w.limitingMagnitudeEnabled());
  EXPECT_EQ(win.w.limitingMagnitude(), 6.5);
  auto brightPixels = [&](const QImage& image) {
    const QRect v = win.w.viewRect();
    int n = 0;
    for (int y = v.top(); y < v.bottom(); ++y)
      for (int x = v.left(); x < v.right(); ++x) n += qGreen(image.pixel(x, y)) > 40 ? 1 : 0;
    return n;
  };
  const int many = brightPixels(win.shot("stars-6.5.png"));
  win.w.setLimitingMagnitude(2.0);
  EXPECT_EQ(win.w.limitingMagnitude(), 2.0);
  const int few = brightPixels(win.shot("stars-2.png"));
  std::printf("  pixels above 40 of 255: %d to V 6.5, %d to V 2\n", many, few);
  EXPECT_GT(many, few);
  EXPECT_GT(few, 0);
  // Night vision: the starlit view turns grey (the stars and the glow far below 0.005 cd/m^2).
  auto colourfulness = [&](const QImage& image) {
    const QRect v = win.w.viewRect();
    long spread = 0;
    for (int y = v.top(); y < v.bottom(); y += 2)
      for (int x = v.left(); x < v.right(); x += 2) {
        const QRgb c = image.pixel(x, y);
        spread += std::max({qRed(c), qGreen(c), qBlue(c)}) - std::min({qRed(c), qGreen(c), qBlue(c)});
      }
    return spread;
  };
  win.w.setLimitingMagnitude(6.5);
  const long colour = colourfulness(win.shot("colour.png"));
  win.w.setNightVision(true);
  EXPECT_TRUE(win.w.nightVision());
  const long grey = colourfulness(win.shot("night-vision.png"));
  std::printf("  colour spread over the view: %ld, with night vision %ld\n", colour, grey);
  EXPECT_LT(grey, colour / 4 + 1);
  win.w.setNightVision(false);
  win.w.loadScene(std::string(UMBRA_SOURCE_DIR) + "/examples/scenes/phobos-in-mars-shadow.json");
  EXPECT_FALSE(win.w.limitingMagnitudeEnabled());
}
