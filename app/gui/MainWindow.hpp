#pragma once
// umbra-gui's main window: the 3D view of a scene (left), the cross-section of the shadow
// the camera's target lies in (right), a time slider (+-6 h around the scene time, 1-minute
// steps), exposure and glare controls, the atmosphere (none, a preset or a file, drawn on
// the scene's body with an atmosphere, else the observer's or target body) with a progress
// bar and a cancel button while its tables are computed in a worker thread (TableJobs), its
// editor (a dock: every field of the model, AtmosphereEditor.hpp; an accepted edit
// recomputes the tables the same way; Load/Save JSON), and a status bar with the
// receiver's place in the shadow. While new tables are computed the view keeps the ones
// it has; a cancelled or failed computation leaves them. The same worker job, after the
// tables and whenever the atmosphere or the time changes what the view needs, makes the
// atmospheric shadow LuT that shades the other bodies (SceneView) and that the plot
// panel's profile is read from, and, when the camera is in the shadow of the body with the
// atmosphere (Earth from the Moon in totality), the limb-luminance LuT that draws the thin
// ring as `umbra render` does; a "Refraction" check box makes the tables again with
// refracted paths.
#include "AtmosphereShadow.h"
#include "SceneInputs.h"
#include "TableJobs.hpp"
#include "scene/ReceiverShadow.hpp"
#include "scene/Scene.hpp"

#include <QMainWindow>
#include <QRect>
#include <QString>
#include <QTemporaryDir>

#include <functional>
#include <memory>
#include <optional>
#include <string>

class QCheckBox;
class QComboBox;
class QDockWidget;
class QDoubleSpinBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QSlider;
class QSplitter;
class QVTKOpenGLNativeWidget;

namespace umbra::gui {

class AtmosphereEditor;
class EclipseList;
class ProfilePanel;
class SceneView;

class MainWindow : public QMainWindow {
public:
  MainWindow();
  ~MainWindow() override;

  /// Loads a scene file and shows it at `time` (default: the file's time). Throws
  /// std::exception (scene::SceneError naming the file and field, std::runtime_error)
  /// and keeps the scene shown before when it fails.
  void loadScene(const std::string& path, std::optional<scene::UtcTime> time = std::nullopt);
  /// Moves the loaded scene to `time` (the slider follows; it is re-centred on `time`
  /// when that lies outside its range). Throws like loadScene.
  void showTime(scene::UtcTime time);
  /// Draws this atmosphere (a preset name or a file; "" for none) on the atmosphere body:
  /// its tables are computed (or read from the cache) in a worker thread; the view shows
  /// it when they are ready. Throws std::runtime_error when no scene is loaded or the
  /// scene has no body to put an atmosphere on.
  void setAtmosphere(const std::string& model);
  /// The atmosphere later loadScene calls draw instead of the scene's ("" : none).
  /// Throws std::runtime_error for an unknown preset or a bad file.
  void overrideAtmosphere(const std::string& model);
  /// True while atmosphere tables or the eclipse LuTs of its body (the atmospheric shadow
  /// LuT, the limb-luminance LuT) are being computed (in the worker, one job at a time);
  /// the first; the second (either LuT); a job making the limb-luminance LuT.
  bool atmosphereBusy() const;
  bool atmosphereTablesBusy() const;
  bool atmosphereShadowBusy() const;
  bool limbLuminanceBusy() const;
  /// Ring width on screen below which the atmosphere's ring is drawn from the
  /// limb-luminance LuT (default 5 px; 0: always ray marched; `umbra-gui
  /// --limb-ring-threshold`, as `umbra render`'s). Throws std::invalid_argument below 0.
  void setLimbRingThreshold(double px);
  double limbRingThreshold() const;
  /// The Cancel button: stops the tables being computed; the view keeps the ones it has
  /// (a cancelled LuT is not asked for again until the scene needs another one). A cancel
  /// is not an error: nothing is printed.
  void cancelAtmosphereTables();
  /// The model (preset or file) whose tables the view draws ("" : none). An edit's model
  /// is a file in a private temporary folder.
  const std::string& drawnAtmosphere() const { return this->drawnModel; }
  /// The atmosphere editor (its document follows setAtmosphere; its accepted edits
  /// recompute the tables).
  AtmosphereEditor& atmosphereEditor() const { return *this->editor; }
  /// The 3D view (e.g. whether it shades with the atmospheric shadow LuT).
  const SceneView& sceneView() const { return *this->view; }
  /// The plot panel (its profile: the atmospheric shadow's when the view shades with it).
  const ProfilePanel& profilePanel() const { return *this->plot; }
  /// Shows the editor's dock (the "Edit..." button).
  void showAtmosphereEditor();
  /// Shows the "Eclipses" dock (menu Eclipses > List eclipses), listing the eclipses of the
  /// scene's year and the three after it the first time; choosing one moves the time there.
  void showEclipseList();
  EclipseList& eclipseList() const { return *this->eclipses; }
  /// Writes the edited atmosphere as JSON (atomically). Throws std::runtime_error naming the path.
  void saveAtmosphereJson(const std::string& path) const;
  /// Small tables (useSmallAtmosphereTables) for the next setAtmosphere: quick looks, tests.
  /// The atmospheric shadow LuT follows (pipeline::useSmallEclipseShadowTables).
  void useSmallAtmosphereTables(bool small);
  /// Refraction (the "Refraction" check box; `umbra render --refraction`): the atmosphere's
  /// tables are made again in the worker with the refraction table and refracted paths,
  /// and the view bends its rays (a lifted, flattened Sun at the horizon).
  void setRefraction(bool on);
  bool refraction() const;
  /// Exposure of the 3D view in EV (the spin box follows).
  void setExposure(double ev);
  /// Glare strength of the 3D view (0..10).
  void setGlare(double strength);
  /// Night vision on the 3D view (the "Night vision" check box; umbra render --night-vision).
  void setNightVision(bool on);
  bool nightVision() const;
  /// The faintest V of the scene's stars (the "Stars to V" spin box, -2..9; a scene
  /// without "stars" has none to change: the box is disabled and this does nothing).
  void setLimitingMagnitude(double vMag);
  /// The box's value, and whether the scene has stars to change.
  double limitingMagnitude() const;
  bool limitingMagnitudeEnabled() const;

  /// Renders both views now.
  void renderViews();

  /// Writes the window (with the OpenGL views) as a PNG, atomically. Returns the image
  /// size. Throws std::runtime_error naming the path.
  QSize saveScreenshot(const std::string& path);

  /// The status bar's text: scene, time, the receiver's offset from the shadow axis and
  /// the shadow factor at its centre.
  QString statusText() const;
  /// The GPU time of the 3D view's last frame, per stage, right of the controls ("GPU 2.41 ms:
  /// bodies 0.523, atmosphere 1.6, glare 0", 3 digits; the total includes the tone map;
  /// empty before a frame).
  QString gpuTimeText() const;
  /// Where the 3D view and the plot panel lie in the window (window coordinates).
  QRect viewRect() const;
  QRect plotRect() const;

private:
  // The window's parts, built by the constructor.
  void buildMenu();
  QSplitter* buildViews();
  void buildViewControls();  // time, exposure, glare, stars, night vision
  void buildAtmosphereControls();
  void layOut(QSplitter* views);
  void showGpuTimes();  // after each frame of the 3D view
  void openSceneDialog();
  void saveScreenshotDialog();
  void sliderMoved(int minutes);
  void showCurrent(double exposureEv);  // a newly loaded scene: controls, then refresh
  void refresh();  // the current scene: 3D view, profile, labels, status
  void setStatus(const QString& text);
  void cancelAtmosphere();  // stops and joins the job, if any
  void showJob(const std::optional<std::string>& status);  // the progress bar and Cancel with the status; none: hidden
  void startAtmosphere(const std::string& model);  // the tables in the worker
  void startEclipseLuts();  // the view's missing atmospheric shadow / limb-luminance LuTs in the worker
  void tablesMade(TableJobs::Result& done);  // a job's end: the view takes what it made
  void atmosphereFailed(const std::string& why);
  void atmosphereEdited();  // the editor's accepted document -> a file -> startAtmosphere
  void loadAtmosphereDialog();
  void saveAtmosphereDialog();

  QVTKOpenGLNativeWidget* viewWidget = nullptr;
  QVTKOpenGLNativeWidget* plotWidget = nullptr;
  QSlider* slider = nullptr;
  QLabel* timeLabel = nullptr;
  QDoubleSpinBox* exposure = nullptr;
  QLabel* statusLabel = nullptr;
  QLabel* gpuLabel = nullptr;
  QComboBox* atmosphereChoice = nullptr;
  QProgressBar* atmosphereProgress = nullptr;
  QPushButton* atmosphereCancel = nullptr;
  QDoubleSpinBox* glare = nullptr;
  QDoubleSpinBox* starLimit = nullptr;
  QCheckBox* nightVisionBox = nullptr;
  QPushButton* atmosphereEdit = nullptr;
  QCheckBox* refractionBox = nullptr;
  QDockWidget* editorDock = nullptr;
  AtmosphereEditor* editor = nullptr;
  QDockWidget* eclipseDock = nullptr;
  EclipseList* eclipses = nullptr;

  std::unique_ptr<SceneView> view;
  std::unique_ptr<ProfilePanel> plot;

  std::optional<scene::Scene> current;
  scene::UtcTime sliderCentre;  // the time at slider value 0
  scene::ReceiverShadow shadow;
  double shadowFactor = 1.0;

  std::string atmosphereBody;  // the body the atmosphere goes on ("" : none possible)
  std::optional<std::string> atmosphereOverride;
  std::string drawnModel;  // the model of the tables the view has
  atmosphere::AtmosphereModelPtr chosenModel;  // the chosen atmosphere, read once while the choice stays
  QTemporaryDir editedDir;  // the editor's documents, one file per accepted edit
  int editCount = 0;
  std::string editedFrom;  // the name the edits started from (the editor's name for them)
  bool smallTables = false;
  std::unique_ptr<TableJobs> jobs;  // the tables the view is missing, in a worker thread
};

} // namespace umbra::gui
