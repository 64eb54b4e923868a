// umbra-gui [SCENE.json] [--time ISO] [--atmosphere NAME|FILE|none] [--atmosphere-set FIELD=VALUE ...]
//           [--atmosphere-tables default|small] [--refraction] [--limb-ring-threshold PX] [--exposure EV] [--glare S]
//           [--screenshot FILE.png]
//           [--editor] [--quit-after-screenshot]
//
// The desktop GUI: a scene's bodies in 3D, a time slider that moves them, and the
// cross-section of the shadow the camera's target lies in. With --screenshot it saves
// the window once it is shown (batch mode: errors are one line on stderr and exit 1).
#include "AtmosphereEditor.hpp"
#include "MainWindow.hpp"
#include "MieOpticsCache.h"
#include "OutputFile.hpp"
#include "scene/Time.hpp"

#include <QApplication>
#include <QCommandLineOption>
#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QMessageBox>
#include <QSurfaceFormat>
#include <QTimer>
#include <QVTKOpenGLNativeWidget.h>
#include <QWindow>

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <optional>
#include <string>

namespace {

bool hasDisplay() {
  const char* platform = std::getenv("QT_QPA_PLATFORM");
  if (platform && *platform) return true;  // the user chose one
  const char* x = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x && *x) || (wayland && *wayland);
}

bool asksForHelp(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    for (const char* flag : {"-h", "--help", "-?", "--help-all", "-v", "--version"})
      if (std::strcmp(argv[i], flag) == 0) return true;
  return false;
}

// Qt's harmless note on headless machines (xvfb-run sets no XDG_RUNTIME_DIR) would make
// a batch error two lines; every other message goes to Qt's default handler.
QtMessageHandler defaultHandler = nullptr;
void messageHandler(QtMsgType type, const QMessageLogContext& context, const QString& message) {
  if (type == QtWarningMsg && message.startsWith("QStandardPaths: XDG_RUNTIME_DIR not set")) return;
  if (defaultHandler) defaultHandler(type, context, message);
}

int fail(const std::string& message) {
  std::cerr << "umbra-gui: " << message << "\n";
  return 1;
}

/// umbra-gui's options (besides --help, --version and the scene file).
struct Options {
  const QCommandLineOption timeOption{"time", "Show the scene at this UTC time (ISO 8601, e.g. 2015-09-28T02:47:00Z).",
                                      "ISO"};
  const QCommandLineOption screenshotOption{
      "screenshot", "Once the window is shown, save it as this PNG (batch mode: errors exit 1) and print the status.",
      "FILE.png"};
  const QCommandLineOption quitOption{"quit-after-screenshot", "Exit (0) once the screenshot is written."};
  const QCommandLineOption atmosphereOption{
      "atmosphere", "Draw this atmosphere (a preset, a file, or none) instead of the scene's.", "NAME"};
  const QCommandLineOption setOption{
      "atmosphere-set",
      "Change a field of the atmosphere as the editor does (repeatable), e.g. components.troposphere.densityScale=20.",
      "FIELD=VALUE"};
  const QCommandLineOption editorOption{"editor", "Show the atmosphere editor (every field of the model)."};
  const QCommandLineOption tablesOption{
      "atmosphere-tables", "Atmosphere table sizes: default, or small (quick looks and tests).", "SIZES", "default"};
  const QCommandLineOption refractionOption{
      "refraction", "Bend the rays through the atmosphere (a lifted, flattened Sun at the horizon), as umbra render "
                    "--refraction."};
  const QCommandLineOption limbOption{
      "limb-ring-threshold",
      "Draw an atmosphere's ring from the limb-luminance LuT when it is thinner than this on screen (pixels; "
      "default 5; 0: always ray march), as umbra render --limb-ring-threshold.",
      "PX", "5"};
  const QCommandLineOption exposureOption{"exposure", "Exposure in EV (default: the scene's).", "EV"};
  const QCommandLineOption glareOption{"glare", "Glare strength, 0..10 (default 0).", "S"};

  void addTo(QCommandLineParser& parser) const {
    for (const QCommandLineOption* option : {&atmosphereOption, &setOption, &editorOption, &tablesOption,
                                              &refractionOption, &limbOption, &exposureOption, &glareOption,
                                              &timeOption, &screenshotOption, &quitOption})
      parser.addOption(*option);
  }
};

/// The window set up as the options ask (tables, refraction, the ring's threshold, the
/// atmosphere and its edits, exposure, glare) with the scene loaded. Throws
/// std::runtime_error naming the option.
void setUp(umbra::gui::MainWindow& window, const QCommandLineParser& parser, const Options& o,
           const QStringList& positional) {
  std::optional<umbra::scene::UtcTime> time;
  if (parser.isSet(o.timeOption)) {
    try {
      time = umbra::scene::parseUtc(parser.value(o.timeOption).toStdString());
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string("--time: ") + e.what());
    }
  }
  const QString tables = parser.value(o.tablesOption);
  if (tables != "default" && tables != "small")
    throw std::runtime_error("--atmosphere-tables: expected default or small, got '" + tables.toStdString() + "'");
  window.useSmallAtmosphereTables(tables == "small");
  window.setRefraction(parser.isSet(o.refractionOption));
  auto number = [&](const QCommandLineOption& option, double lo, double hi) {
    bool ok = false;
    const double v = parser.value(option).toDouble(&ok);
    if (!ok || !(v >= lo && v <= hi))
      throw std::runtime_error("--" + option.names().first().toStdString() + ": expected a number in [" +
                               std::to_string(lo) + ", " + std::to_string(hi) + "], got '" +
                               parser.value(option).toStdString() + "'");
    return v;
  };
  window.setLimbRingThreshold(number(o.limbOption, 0.0, 1.0e6));  // (before the scene: its LuT in the first job)
  if (parser.isSet(o.atmosphereOption)) {
    const std::string name = parser.value(o.atmosphereOption).toStdString();
    try {
      window.overrideAtmosphere(name == "none" ? std::string() : name);
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string("--atmosphere: ") + e.what());
    }
  }
  if (!positional.isEmpty()) window.loadScene(positional.first().toStdString(), time);
  else if (time || parser.isSet(o.atmosphereOption) || parser.isSet(o.setOption))
    throw std::runtime_error("--time and --atmosphere need a scene file");
  for (const QString& change : parser.values(o.setOption)) {
    const int eq = change.indexOf('=');
    if (eq <= 0) throw std::runtime_error("--atmosphere-set: expected FIELD=VALUE, got '" + change.toStdString() + "'");
    if (!window.atmosphereEditor().hasDocument()) throw std::runtime_error("--atmosphere-set: the scene shows no atmosphere");
    const std::string problem =
        window.atmosphereEditor().setValue(change.left(eq).toStdString(), change.mid(eq + 1).toStdString());
    if (!problem.empty()) throw std::runtime_error("--atmosphere-set: " + problem);
  }
  window.atmosphereEditor().flush();  // the edited tables now, not after the debounce
  if (parser.isSet(o.exposureOption)) window.setExposure(number(o.exposureOption, -40.0, 40.0));
  if (parser.isSet(o.glareOption)) window.setGlare(number(o.glareOption, 0.0, 10.0));
}

/// Once the window is exposed (mapped by the X server) and its tables made: saves it as
/// `screenshot`, prints its layout and status; exits with 1 on an error, or 0 with `quit`.
void scheduleScreenshot(umbra::gui::MainWindow& window, const std::string& screenshot, bool quit) {
  // Wait until the window is exposed (mapped by the X server), then grab it.
  auto* poll = new QTimer(&window);
  auto* clock = new QElapsedTimer;
  clock->start();
  QObject::connect(poll, &QTimer::timeout, &window, [&window, poll, clock, screenshot, quit] {
    const bool exposed = window.windowHandle() && window.windowHandle()->isExposed();
    if (!exposed && clock->elapsed() < 10000) return;
    if (window.atmosphereBusy() && clock->elapsed() < 120000) return;  // the atmosphere tables
    poll->stop();
    delete clock;
    int code = 0;
    try {
      if (!exposed) throw std::runtime_error("the window was never shown on the display");
      const QSize size = window.saveScreenshot(screenshot);
      const QRect v = window.viewRect(), p = window.plotRect();
      std::cout << "window: " << size.width() << "x" << size.height() << "\n"
                << "view3d: " << v.x() << " " << v.y() << " " << v.width() << " " << v.height() << "\n"
                << "plot: " << p.x() << " " << p.y() << " " << p.width() << " " << p.height() << "\n"
                << "status: " << window.statusText().toStdString() << "\n"
                << "wrote " << screenshot << std::endl;
    } catch (const std::exception& e) {
      std::cerr << "umbra-gui: " << e.what() << std::endl;
      code = 1;
    }
    if (quit || code != 0) QApplication::exit(code);
  });
  poll->start(100);
}

} // namespace

int main(int argc, char** argv) {
  if (!hasDisplay()) {
    if (!asksForHelp(argc, argv))
      return fail("no display: set DISPLAY, or run under xvfb-run -a");
    qputenv("QT_QPA_PLATFORM", "minimal");  // --help and --version need no window
  }
  defaultHandler = qInstallMessageHandler(messageHandler);
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  QApplication::setApplicationName("umbra-gui");
  QApplication::setApplicationVersion("0.1.0");

  QCommandLineParser parser;
  parser.setApplicationDescription(
      "umbra's desktop GUI: a scene's bodies in 3D, a time slider (+-6 h) that moves them, and the "
      "cross-section of the shadow that the camera's target lies in.");
  parser.addHelpOption();
  parser.addVersionOption();
  parser.addPositionalArgument("scene", "Scene file to open (JSON, see docs/scene-format.md).", "[SCENE.json]");
  const Options o;
  o.addTo(parser);
  parser.process(app);
  umbra::filters::keepMieOpticsInCache("");  // the Lorenz-Mie optics beside the tables

  const QStringList positional = parser.positionalArguments();
  const bool batch = parser.isSet(o.screenshotOption);
  const std::string screenshot = parser.value(o.screenshotOption).toStdString();
  if (positional.size() > 1) return fail("expected at most one scene file, got " + std::to_string(positional.size()));
  if (parser.isSet(o.quitOption) && !batch) return fail("--quit-after-screenshot needs --screenshot FILE.png");

  umbra::gui::MainWindow window;
  std::string error;  // interactive mode: shown once the window is up
  try {
    if (batch) umbra::output::checkWritable(screenshot, {".png"});
    setUp(window, parser, o, positional);
  } catch (const std::exception& e) {
    if (batch) return fail(e.what());
    error = e.what();
  }

  if (parser.isSet(o.editorOption)) window.showAtmosphereEditor();
  window.show();
  if (!error.empty())
    QTimer::singleShot(0, &window, [&window, error] { QMessageBox::critical(&window, "umbra-gui", QString::fromStdString(error)); });
  if (batch) scheduleScreenshot(window, screenshot, parser.isSet(o.quitOption));
  return app.exec();
}
