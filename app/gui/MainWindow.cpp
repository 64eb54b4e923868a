#include "MainWindow.hpp"
#include "EclipseList.hpp"

#include "AtmosphereEditor.hpp"
#include "OutputFile.hpp"
#include "ProfilePanel.hpp"
#include "SceneInputs.h"
#include "SceneView.hpp"
#include "AtmosphereShadow.h"
#include "scene/Moon.hpp"
#include "scene/Time.hpp"
#include "vtkAtmosphereTablesSource.h"

#include "Atmosphere.hpp"
#include "Spectrum.hpp"

#include <iostream>

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDockWidget>
#include <QProgressBar>
#include <QPushButton>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFontDatabase>
#include <QHBoxLayout>
#include <QImage>
#include <QKeySequence>
#include <QLabel>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QPixmap>
#include <QSlider>
#include <QSplitter>
#include <QStatusBar>
#include <QVBoxLayout>
#include <QVTKOpenGLNativeWidget.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <vector>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace umbra::gui {
namespace {

constexpr int kSliderHalfRangeMin = 6 * 60;  // +-6 h in 1-minute steps

QString qs(const std::string& s) { return QString::fromStdString(s); }

QString km(double m) { return QString::number(m / 1e3, 'f', 0) + " km"; }

// The model named `model` (kept in `chosen`: read once while the choice stays); null for
// "". Throws naming the atmosphere.
atmosphere::AtmosphereModelPtr chosenAtmosphere(const std::string& model, atmosphere::AtmosphereModelPtr& chosen) {
  try {
    return atmosphere::modelNamed(model, chosen);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("atmosphere: ") + e.what());
  }
}

} // namespace

MainWindow::MainWindow() {
  this->setWindowTitle("umbra-gui");
  this->buildMenu();
  QSplitter* views = this->buildViews();
  this->buildViewControls();
  this->buildAtmosphereControls();
  this->layOut(views);
  this->statusLabel = new QLabel("Open a scene (File > Open scene...)");
  this->statusBar()->addWidget(this->statusLabel, 1);
  this->view->setOnFrame([this] { this->showGpuTimes(); });
  this->resize(1200, 720);
}

void MainWindow::buildMenu() {
  // File menu
  QMenu* file = this->menuBar()->addMenu("&File");
  QAction* open = file->addAction("&Open scene...");
  open->setShortcut(QKeySequence::Open);
  connect(open, &QAction::triggered, this, [this] { this->openSceneDialog(); });
  QAction* shot = file->addAction("&Save screenshot...");
  shot->setShortcut(QKeySequence::Save);
  connect(shot, &QAction::triggered, this, [this] { this->saveScreenshotDialog(); });
  file->addSeparator();
  QAction* loadAtmosphere = file->addAction("&Load atmosphere JSON...");
  connect(loadAtmosphere, &QAction::triggered, this, [this] { this->loadAtmosphereDialog(); });
  QAction* saveAtmosphere = file->addAction("Save atmosphere &as JSON...");
  connect(saveAtmosphere, &QAction::triggered, this, [this] { this->saveAtmosphereDialog(); });
  file->addSeparator();
  QAction* quit = file->addAction("&Quit");
  quit->setShortcut(QKeySequence::Quit);
  connect(quit, &QAction::triggered, this, [this] { this->close(); });
  // Eclipses menu: the list whose rows set the scene's time to a contact.
  QMenu* eclipsesMenu = this->menuBar()->addMenu("&Eclipses");
  QAction* listEclipses = eclipsesMenu->addAction("&List eclipses...");
  connect(listEclipses, &QAction::triggered, this, [this] { this->showEclipseList(); });
  this->eclipses = new EclipseList([this](double ut1Jd) {
    if (!this->current || !this->current->hasTime) {
      this->setStatus("eclipses: the scene has no time to set (no ephemeris bodies)");
      return;
    }
    try {
      scene::UtcTime t;  // UT1, which UTC follows to 0.9 s
      t.jd1 = std::floor(ut1Jd);
      t.jd2 = ut1Jd - t.jd1;
      this->showTime(t);
    } catch (const std::exception& e) {
      this->setStatus(QString("error: ") + e.what());
    }
  });
  this->eclipseDock = new QDockWidget("Eclipses", this);
  this->eclipseDock->setWidget(this->eclipses);
  this->eclipseDock->setObjectName("eclipses");
  this->addDockWidget(Qt::RightDockWidgetArea, this->eclipseDock);
  this->eclipseDock->hide();
}

// The two views side by side.
QSplitter* MainWindow::buildViews() {
  auto* splitter = new QSplitter(Qt::Horizontal);
  this->viewWidget = new QVTKOpenGLNativeWidget;
  this->viewWidget->setMinimumSize(200, 200);
  this->plotWidget = new QVTKOpenGLNativeWidget;
  this->plotWidget->setMinimumSize(200, 200);
  splitter->addWidget(this->viewWidget);
  splitter->addWidget(this->plotWidget);
  splitter->setStretchFactor(0, 1);
  splitter->setStretchFactor(1, 1);
  splitter->setChildrenCollapsible(false);
  this->view = std::make_unique<SceneView>(this->viewWidget);
  this->plot = std::make_unique<ProfilePanel>(this->plotWidget);
  return splitter;
}

void MainWindow::buildViewControls() {
  // Time and exposure
  this->slider = new QSlider(Qt::Horizontal);
  this->slider->setRange(-kSliderHalfRangeMin, kSliderHalfRangeMin);
  this->slider->setSingleStep(1);
  this->slider->setPageStep(30);
  this->slider->setTickInterval(60);
  this->slider->setTickPosition(QSlider::TicksBelow);
  this->slider->setEnabled(false);
  this->slider->setToolTip("Scene time: +-6 h around the scene's time, in 1-minute steps");
  connect(this->slider, &QSlider::valueChanged, this, [this](int v) { this->sliderMoved(v); });
  this->timeLabel = new QLabel("no scene");
  this->timeLabel->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
  this->timeLabel->setMinimumWidth(this->timeLabel->fontMetrics().horizontalAdvance("2015-09-28T01:45:00Z (+0h00m)") + 8);
  this->exposure = new QDoubleSpinBox;
  this->exposure->setRange(-40.0, 40.0);
  this->exposure->setSingleStep(0.5);
  this->exposure->setDecimals(1);
  this->exposure->setSuffix(" EV");
  this->exposure->setToolTip("Exposure of the 3D view in stops");
  connect(this->exposure, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [this](double ev) {
    this->view->setExposureEV(ev);
    this->view->render();
  });

  this->glare = new QDoubleSpinBox;
  this->glare->setRange(0.0, 10.0);
  this->glare->setSingleStep(0.5);
  this->glare->setDecimals(1);
  this->glare->setToolTip("Glare: halos around bright pixels that keep the frame's total light (0: none)");
  connect(this->glare, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [this](double g) { this->setGlare(g); });

  this->starLimit = new QDoubleSpinBox;
  this->starLimit->setRange(-2.0, 9.0);
  this->starLimit->setSingleStep(0.5);
  this->starLimit->setDecimals(1);
  this->starLimit->setValue(6.5);
  this->starLimit->setEnabled(false);
  this->starLimit->setToolTip("The faintest stars drawn, V magnitude (the scene's \"stars\"; the catalogue ends at 9)");
  connect(this->starLimit, qOverload<double>(&QDoubleSpinBox::valueChanged), this,
          [this](double v) { this->setLimitingMagnitude(v); });

  this->nightVisionBox = new QCheckBox("Night vision");
  this->nightVisionBox->setToolTip("Show the view as the eye sees dim light: below about 5 cd/m^2 colour fades to the "
                                   "rods' grey, fully below 0.005 (CIE 191 mesopic adaptation at each pixel)");
  connect(this->nightVisionBox, &QCheckBox::toggled, this, [this](bool on) { this->setNightVision(on); });
}

// The atmosphere's choice, its tables' progress and Cancel, its editor, refraction.
void MainWindow::buildAtmosphereControls() {
  this->atmosphereChoice = new QComboBox;
  this->atmosphereChoice->addItem("none", QString());
  for (const std::string& name : atmosphere::presetNames()) this->atmosphereChoice->addItem(qs(name), qs(name));
  this->atmosphereChoice->setEnabled(false);
  this->atmosphereChoice->setToolTip("The atmosphere drawn on the scene's planet (its tables are computed on change)");
  connect(this->atmosphereChoice, qOverload<int>(&QComboBox::activated), this, [this](int index) {
    try {
      this->setAtmosphere(this->atmosphereChoice->itemData(index).toString().toStdString());
    } catch (const std::exception& e) {
      this->setStatus(QString("error: ") + e.what());
    }
  });
  this->atmosphereProgress = new QProgressBar;
  this->atmosphereProgress->setRange(0, 100);
  this->atmosphereProgress->setMaximumWidth(160);
  this->atmosphereProgress->setVisible(false);
  this->atmosphereCancel = new QPushButton("Cancel");
  this->atmosphereCancel->setVisible(false);
  this->jobs = std::make_unique<TableJobs>([this](int percent) { this->atmosphereProgress->setValue(percent); },
                                           [this](TableJobs::Result& done) { this->tablesMade(done); });
  connect(this->atmosphereCancel, &QPushButton::clicked, this, [this] { this->cancelAtmosphereTables(); });

  // The atmosphere editor, in a dock (hidden until "Edit..."), with its Load/Save buttons.
  this->editor = new AtmosphereEditor;
  this->editor->onChanged([this](const AtmosphereEditor::Json&) { this->atmosphereEdited(); });
  auto* editorPanel = new QWidget;
  auto* editorLayout = new QVBoxLayout(editorPanel);
  auto* editorButtons = new QHBoxLayout;
  auto* loadButton = new QPushButton("Load JSON...");
  connect(loadButton, &QPushButton::clicked, this, [this] { this->loadAtmosphereDialog(); });
  auto* saveButton = new QPushButton("Save as JSON...");
  connect(saveButton, &QPushButton::clicked, this, [this] { this->saveAtmosphereDialog(); });
  editorButtons->addWidget(loadButton);
  editorButtons->addWidget(saveButton);
  editorButtons->addStretch(1);
  editorLayout->addLayout(editorButtons);
  editorLayout->addWidget(this->editor, 1);
  this->editorDock = new QDockWidget("Atmosphere", this);
  this->editorDock->setWidget(editorPanel);
  this->editorDock->setObjectName("atmosphereEditor");
  this->addDockWidget(Qt::RightDockWidgetArea, this->editorDock);
  this->editorDock->hide();
  this->atmosphereEdit = new QPushButton("Edit...");
  this->atmosphereEdit->setToolTip("Show the atmosphere's fields: every component's profile, optics and phase");
  connect(this->atmosphereEdit, &QPushButton::clicked, this, [this] { this->showAtmosphereEditor(); });

  this->refractionBox = new QCheckBox("Refraction");
  this->refractionBox->setToolTip("Bend the rays through the atmosphere: a lifted, flattened Sun at the horizon "
                                  "(the tables are made again with refracted paths)");
  connect(this->refractionBox, &QCheckBox::toggled, this, [this](bool on) { this->setRefraction(on); });
}

void MainWindow::layOut(QSplitter* views) {
  // Two rows: the time slider (as wide as the window), then exposure, glare and the
  // atmosphere's controls.
  auto* timeRow = new QHBoxLayout;
  timeRow->addWidget(new QLabel("Time (UTC)"));
  timeRow->addWidget(this->slider, 1);
  timeRow->addWidget(this->timeLabel);
  auto* controls = new QHBoxLayout;
  controls->addWidget(new QLabel("Exposure"));
  controls->addWidget(this->exposure);
  controls->addWidget(new QLabel("Glare"));
  controls->addWidget(this->glare);
  controls->addWidget(new QLabel("Stars to V"));
  controls->addWidget(this->starLimit);
  controls->addWidget(this->nightVisionBox);
  controls->addSpacing(16);
  controls->addWidget(new QLabel("Atmosphere"));
  controls->addWidget(this->atmosphereChoice);
  controls->addWidget(this->atmosphereEdit);
  controls->addWidget(this->refractionBox);
  controls->addWidget(this->atmosphereProgress);
  controls->addWidget(this->atmosphereCancel);
  this->gpuLabel = new QLabel;
  this->gpuLabel->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);  // never widens the window
  this->gpuLabel->setAlignment(Qt::AlignLeft | Qt::AlignVCenter);  // when narrow, the total stays in sight
  this->gpuLabel->setToolTip("GPU time of the 3D view's last frame (GL timestamp queries), per stage of the render "
                             "pass: the bodies with their eclipse shading, the atmosphere, the glare, the tone map");
  controls->addSpacing(16);
  controls->addWidget(this->gpuLabel, 1);  // the rest of the row

  auto* central = new QWidget;
  auto* layout = new QVBoxLayout(central);
  layout->addWidget(views, 1);
  layout->addLayout(timeRow);
  layout->addLayout(controls);
  this->setCentralWidget(central);
}

void MainWindow::showGpuTimes() {
  const auto t = this->view->lastStageTimes();
  if (!t) return;
  // 3 digits; a stage that drew nothing (two timestamps in a row) shows 0.
  auto ms = [](double v) { return v < 1e-3 ? QString("0") : QString::number(v, 'g', 3); };
  const double total = t->receiversMs + t->starsMs + t->atmosphereMs + t->glareMs + t->toneMapMs;
  this->gpuLabel->setText(QString("GPU %1 ms: bodies %2, atmosphere %3, glare %4")
                              .arg(ms(total), ms(t->receiversMs), ms(t->atmosphereMs), ms(t->glareMs)));
  this->gpuLabel->setToolTip(QString("GPU time of the 3D view's last frame (GL timestamp queries): %1 ms in all; the "
                                     "bodies with their eclipse shading %2 ms, the stars %6 ms, the atmosphere %3 ms, "
                                     "the glare %4 ms, the tone map %5 ms")
                                 .arg(ms(total), ms(t->receiversMs), ms(t->atmosphereMs), ms(t->glareMs),
                                      ms(t->toneMapMs), ms(t->starsMs)));
}

MainWindow::~MainWindow() { this->cancelAtmosphere(); }

void MainWindow::setLimitingMagnitude(double vMag) {
  {
    const QSignalBlocker block(this->starLimit);
    this->starLimit->setValue(vMag);
  }
  if (!this->current || !this->current->stars) return;
  this->current->stars->limitingMagnitude = this->starLimit->value();
  this->refresh();
}

void MainWindow::setNightVision(bool on) {
  {
    const QSignalBlocker block(this->nightVisionBox);
    this->nightVisionBox->setChecked(on);
  }
  this->view->setNightVision(on);
  this->view->render();
}
bool MainWindow::nightVision() const { return this->nightVisionBox->isChecked(); }

double MainWindow::limitingMagnitude() const { return this->starLimit->value(); }
bool MainWindow::limitingMagnitudeEnabled() const { return this->starLimit->isEnabled(); }

void MainWindow::setGlare(double strength) {
  {
    const QSignalBlocker block(this->glare);
    this->glare->setValue(strength);
  }
  this->view->setGlareStrength(strength);
  this->view->render();
}

void MainWindow::useSmallAtmosphereTables(bool small) {
  this->smallTables = small;
  this->view->useSmallAtmosphereShadowTables(small);
}

bool MainWindow::refraction() const { return this->refractionBox->isChecked(); }

void MainWindow::setRefraction(bool on) {
  if (on != this->refractionBox->isChecked()) {
    const QSignalBlocker block(this->refractionBox);
    this->refractionBox->setChecked(on);
  }
  // The tables drawn (or being made) again, with or without refraction.
  vtkAtmosphereTablesSource* making = this->jobs->tablesInProgress();
  const std::string model = making ? std::string(making->GetAtmosphere()) : this->drawnModel;
  const bool drawnWith = this->view->atmosphereTables() && this->view->atmosphereTables()->GetRefractedPaths();
  if (!this->current || model.empty() || (!making && drawnWith == on)) return;
  this->startAtmosphere(model);
}

void MainWindow::setExposure(double ev) { this->exposure->setValue(ev); }

void MainWindow::overrideAtmosphere(const std::string& model) {
  chosenAtmosphere(model, this->chosenModel);
  this->atmosphereOverride = model;
}

bool MainWindow::atmosphereBusy() const { return this->jobs->busy(); }

bool MainWindow::atmosphereTablesBusy() const { return this->jobs->tablesBusy(); }

bool MainWindow::atmosphereShadowBusy() const { return this->jobs->lutsBusy(); }

bool MainWindow::limbLuminanceBusy() const { return this->jobs->limbLuminanceBusy(); }

void MainWindow::setLimbRingThreshold(double px) {
  this->view->setLimbRingThresholdPixels(px);
  this->refresh();  // the limb-luminance LuT in the worker when the scene needs one now
}

double MainWindow::limbRingThreshold() const { return this->view->limbRingThresholdPixels(); }

void MainWindow::cancelAtmosphereTables() { this->jobs->cancel(); }

void MainWindow::cancelAtmosphere() {
  this->jobs->stop();
  this->showJob(std::nullopt);
}

void MainWindow::showJob(const std::optional<std::string>& status) {
  this->atmosphereProgress->setValue(0);
  this->atmosphereProgress->setVisible(status.has_value());
  this->atmosphereCancel->setVisible(status.has_value());
  if (status) this->setStatus(qs(*status));
}

void MainWindow::setAtmosphere(const std::string& model) {
  if (!this->current) throw std::runtime_error("atmosphere: no scene loaded");
  if (this->atmosphereBody.empty()) throw std::runtime_error("atmosphere: the scene has no body to put it on");
  chosenAtmosphere(model, this->chosenModel);
  if (model.empty()) {
    this->editor->setDocument(AtmosphereEditor::Json(), "");
  } else {
    const bool edit = QFileInfo(qs(model)).absolutePath() == QDir(this->editedDir.path()).absolutePath();
    const std::string name = edit                                     ? this->editedFrom
                             : model.find('/') == std::string::npos ? model
                                                                    : QFileInfo(qs(model)).fileName().toStdString();
    this->editor->setDocument(AtmosphereEditor::Json::parse(this->chosenModel->resolvedJson()), name);
  }
  int index = this->atmosphereChoice->findData(qs(model));
  if (index < 0) {
    this->atmosphereChoice->addItem(QFileInfo(qs(model)).fileName(), qs(model));
    index = this->atmosphereChoice->count() - 1;
  }
  this->atmosphereChoice->setCurrentIndex(index);
  this->startAtmosphere(model);
}

void MainWindow::atmosphereEdited() {
  if (!this->current || this->atmosphereBody.empty() || !this->editor->hasDocument()) return;
  // The edited document goes to the tables as a file, as a preset does.
  const std::string path = (this->editedDir.path() + QString("/edit-%1.json").arg(++this->editCount)).toStdString();
  try {
    this->editor->saveJson(path);
  } catch (const std::exception& e) {
    this->setStatus(QString("atmosphere: ") + e.what());
    return;
  }
  this->editedFrom = this->editor->sourceName();
  const QString label = qs(this->editedFrom + " (edited)");
  int index = -1;
  for (int i = 0; i < this->atmosphereChoice->count(); ++i)
    if (this->atmosphereChoice->itemData(i).toString().startsWith(this->editedDir.path() + "/")) index = i;
  if (index < 0) {
    this->atmosphereChoice->addItem(label, qs(path));
    index = this->atmosphereChoice->count() - 1;
  }
  this->atmosphereChoice->setItemText(index, label);
  this->atmosphereChoice->setItemData(index, qs(path));
  this->atmosphereChoice->setCurrentIndex(index);
  this->startAtmosphere(path);
}

void MainWindow::startAtmosphere(const std::string& model) {
  this->cancelAtmosphere();
  if (model.empty()) {
    for (scene::Body& b : this->current->bodies) b.atmosphere = nullptr;
    this->view->setAtmosphereTables(nullptr);
    this->drawnModel.clear();
    this->refresh();
    return;
  }

  // The tables for the scene's sky at its time, configured as `umbra render` configures
  // them (pipeline::configureSceneAtmosphereTables), so that pipeline::showSceneAtmosphereTables
  // (GUI thread) finds them up to date. The view keeps its tables meanwhile.
  scene::Scene withModel = *this->current;
  for (scene::Body& b : withModel.bodies)
    b.atmosphere = b.name == this->atmosphereBody ? chosenAtmosphere(model, this->chosenModel) : nullptr;
  auto source = vtkSmartPointer<vtkAtmosphereTablesSource>::New();
  pipeline::AtmosphereTableChoice choice;
  try {
    const pipeline::SceneInputs in = pipeline::sceneInputs(withModel);
    choice = pipeline::atmosphereTableChoice(in);
    pipeline::configureSceneAtmosphereTables(source, in, this->refraction(),
                                             this->smallTables ? pipeline::AtmosphereTableSizes::Small
                                                               : pipeline::AtmosphereTableSizes::Default);
  } catch (const std::exception& e) {
    if (const auto& missing = this->view->missingAtmosphereTables()) this->jobs->tablesFailed(*missing);  // no retry loop
    this->atmosphereFailed(e.what());
    return;
  }
  this->jobs->startTables(std::move(source), choice);
  this->showJob("computing the " + this->atmosphereChoice->currentText().toStdString() +
                (choice.twilight ? " twilight" : "") + " atmosphere tables...");
}

void MainWindow::startEclipseLuts() {
  if (!this->current) return;
  try {
    if (const std::optional<std::string> status = this->jobs->startEclipseLuts(*this->view)) this->showJob(status);
  } catch (const std::exception& e) {
    this->setStatus(qs(std::string("atmosphere: ") + e.what()));
  }
}

void MainWindow::tablesMade(TableJobs::Result& done) {
  this->showJob(std::nullopt);
  if (done.lutJob()) {
    // The view keeps the table it has for a LuT that was not made.
    if (done.shadow) this->view->setAtmosphereShadow(done.shadow, *done.shadowRequest);
    if (done.limb) this->view->setLimbLuminance(done.limb, *done.limbRequest);
    this->refresh();
    if (!done.problem.empty()) this->setStatus(qs(done.problem));
    return;
  }
  if (!done.tablesError.empty()) {
    this->atmosphereFailed(done.tablesError);
    return;
  }
  const atmosphere::AtmosphereModelPtr model = done.tables->GetAtmosphereModel();
  for (scene::Body& b : this->current->bodies) b.atmosphere = b.name == this->atmosphereBody ? model : nullptr;
  this->view->setAtmosphereTables(done.tables, done.choice);
  this->drawnModel = model->name();
  this->refresh();
}

void MainWindow::atmosphereFailed(const std::string& why) {
  // The view keeps what it drew; the choice goes back to it.
  const int index = this->atmosphereChoice->findData(qs(this->drawnModel));
  this->atmosphereChoice->setCurrentIndex(std::max(index, 0));
  this->refresh();
  this->setStatus(qs("atmosphere: " + why));
}

void MainWindow::showAtmosphereEditor() {
  this->editorDock->show();
  this->editorDock->raise();
}

void MainWindow::showEclipseList() {
  if (this->eclipses->rowCount() == 0) {
    int year = 2024;
    if (this->current && this->current->hasTime)
      year = std::stoi(scene::formatUtc(this->current->time).substr(0, 4));
    try {
      this->eclipses->list(year, year + 3);
    } catch (const std::exception& e) {
      this->setStatus(QString("eclipses: ") + e.what());
    }
  }
  this->eclipseDock->show();
  this->eclipseDock->raise();
}

void MainWindow::saveAtmosphereJson(const std::string& path) const { this->editor->saveJson(path); }

void MainWindow::loadAtmosphereDialog() {
  const QString path = QFileDialog::getOpenFileName(this, "Load atmosphere", QString(), "Atmosphere files (*.json);;All files (*)");
  if (path.isEmpty()) return;
  try {
    this->setAtmosphere(path.toStdString());
    this->showAtmosphereEditor();
  } catch (const std::exception& e) {
    QMessageBox::critical(this, "Cannot load atmosphere", e.what());
  }
}

void MainWindow::saveAtmosphereDialog() {
  QString path = QFileDialog::getSaveFileName(this, "Save atmosphere as JSON", "atmosphere.json", "Atmosphere files (*.json)");
  if (path.isEmpty()) return;
  if (QFileInfo(path).suffix().isEmpty()) path += ".json";
  try {
    this->saveAtmosphereJson(path.toStdString());
    this->statusBar()->showMessage("wrote " + path, 4000);
  } catch (const std::exception& e) {
    QMessageBox::critical(this, "Cannot save atmosphere", e.what());
  }
}

void MainWindow::loadScene(const std::string& path, std::optional<scene::UtcTime> time) {
  scene::Scene s = scene::loadScene(path);
  for (const std::string& note : s.notes) {  // a preset's map not installed, and the like
    std::cerr << "umbra-gui: " << note << "\n";
    this->statusBar()->showMessage(qs(note), 8000);
  }
  const scene::UtcTime fileTime = s.time;  // centres the slider
  if (time) {
    if (!s.hasTime) throw scene::SceneError(path + ": time: the scene has no time to change (no ephemeris bodies)");
    scene::setTime(s, *time);
  }
  this->plot->prepareLut(s.shadowLutSize, scene::receiverShadow(s));  // from the table cache when it is there

  // From here on the new scene is shown; if the view refuses it, the previous one comes back.
  std::optional<scene::Scene> previous = std::move(this->current);
  const scene::UtcTime previousCentre = this->sliderCentre;
  const double previousExposure = this->exposure->value();
  this->current = std::move(s);
  this->sliderCentre = fileTime;
  try {
    this->showCurrent(this->current->exposureEv);
  } catch (const std::exception& e) {
    this->current = std::move(previous);
    this->sliderCentre = previousCentre;
    if (this->current) {
      try {
        this->showCurrent(previousExposure);
      } catch (...) {
        this->current.reset();
      }
    }
    const std::string what = e.what();
    throw std::runtime_error(what.rfind(path, 0) == 0 ? what : path + ": " + what);
  }

  // The atmosphere: the scene's own, on its body; else none, on the observer's or the
  // target body.
  this->cancelAtmosphere();
  this->view->setAtmosphereTables(nullptr);
  this->drawnModel.clear();
  const scene::Scene& c = *this->current;
  std::string model;
  this->atmosphereBody.clear();
  for (const scene::Body& b : c.bodies)
    if (b.atmosphere && this->atmosphereBody.empty()) {
      this->atmosphereBody = b.name, model = b.atmosphere->name();
      this->chosenModel = b.atmosphere;  // read with the scene
    }
  if (this->atmosphereBody.empty() && c.camera.observer) this->atmosphereBody = c.camera.observer->body;
  if (this->atmosphereBody.empty() && !c.camera.targetBody.empty() && c.camera.targetBody != c.sun().name)
    this->atmosphereBody = c.camera.targetBody;
  this->atmosphereChoice->setEnabled(!this->atmosphereBody.empty());
  if (this->atmosphereOverride) model = *this->atmosphereOverride;
  if (this->atmosphereBody.empty()) {
    this->atmosphereChoice->setCurrentIndex(0);
  } else {
    this->setAtmosphere(model);
  }
}

void MainWindow::showCurrent(double exposureEv) {
  this->setWindowTitle(qs(this->current->name) + " - umbra-gui");
  {
    const QSignalBlocker block(this->exposure);
    this->exposure->setValue(exposureEv);
  }
  this->view->setExposureEV(exposureEv);
  {
    const QSignalBlocker block(this->starLimit);
    this->starLimit->setEnabled(this->current->stars.has_value());
    if (this->current->stars) this->starLimit->setValue(this->current->stars->limitingMagnitude);
  }
  this->slider->setEnabled(this->current->hasTime);
  if (this->current->hasTime) {
    this->showTime(this->current->time);
  } else {
    const QSignalBlocker block(this->slider);
    this->slider->setValue(0);
    this->refresh();
  }
}

void MainWindow::showTime(scene::UtcTime time) {
  if (!this->current || !this->current->hasTime) return;
  const double minutes = scene::secondsBetween(this->sliderCentre, time) / 60.0;
  const bool onSlider = std::abs(minutes) <= kSliderHalfRangeMin && std::abs(minutes - std::round(minutes)) < 1e-6;
  if (!onSlider) this->sliderCentre = time;
  scene::setTime(*this->current, time);
  this->jobs->forgetFailures();  // another time: try again
  {
    const QSignalBlocker block(this->slider);
    this->slider->setValue(onSlider ? static_cast<int>(std::lround(minutes)) : 0);
  }
  this->refresh();
}

void MainWindow::sliderMoved(int minutes) {
  if (!this->current || !this->current->hasTime) return;
  try {
    scene::setTime(*this->current, scene::addSeconds(this->sliderCentre, 60.0 * minutes));
    this->jobs->forgetFailures();  // another time: try again
    this->refresh();
  } catch (const std::exception& e) {
    this->setStatus(QString("error: ") + e.what());
  }
}

void MainWindow::refresh() {
  if (!this->current) return;
  const scene::Scene& s = *this->current;
  this->shadow = scene::receiverShadow(s);
  this->view->setScene(s, this->plot->prepareLut(s.shadowLutSize, this->shadow));
  this->plot->setAtmosphereShadowLut(this->view->atmosphereShadowLut(), this->atmosphereBody);
  this->shadowFactor = this->plot->update(this->shadow);
  this->view->render();
  // After sunset (or back in daylight) the sky's tables, then the atmospheric shadow and
  // limb-luminance LuTs the scene needs, in the worker.
  const auto& tables = this->view->missingAtmosphereTables();
  if (!this->drawnModel.empty() && this->jobs->wantsTables(tables)) this->startAtmosphere(this->drawnModel);
  this->startEclipseLuts();

  if (s.hasTime) {
    const int v = this->slider->value();
    const QString sign = v < 0 ? "-" : "+";
    this->timeLabel->setText(qs(scene::formatUtc(s.time)) + QString(" (%1%2h%3m)")
                                                             .arg(sign)
                                                             .arg(std::abs(v) / 60)
                                                             .arg(std::abs(v) % 60, 2, 10, QChar('0')));
  } else {
    this->timeLabel->setText("no time (fixed positions)");
  }

  QString text = qs(s.name) + " | " + (s.hasTime ? qs(scene::formatUtc(s.time)) : QString("no time"));
  if (const std::optional<double> sun = scene::sunElevationDeg(s))
    text += " | " + qs(scene::describeSunElevation(*sun));
  if (const std::optional<double> visible = scene::sunVisibleFractionAtCamera(s))
    text += " | " + qs(scene::describeSunVisible(*visible));
  if (const std::optional<std::string> moon = scene::describeMoonOf(s)) text += " | " + qs(*moon);
  if (this->shadow.valid) {
    text += " | " + qs(this->shadow.receiver) + " " + km(this->shadow.offsetM) + " from " + qs(this->shadow.occluder) +
            "'s shadow axis | shadow factor " + QString::number(this->shadowFactor, 'f', 4);
  } else {
    text += " | " + qs(this->shadow.why) + " | shadow factor 1";
  }
  this->setStatus(text);
}

void MainWindow::setStatus(const QString& text) {
  this->statusLabel->setText(text);
  this->statusLabel->setToolTip(text);  // the whole line when the window is too narrow for it
}

QString MainWindow::statusText() const { return this->statusLabel->text(); }

QString MainWindow::gpuTimeText() const { return this->gpuLabel->text(); }

void MainWindow::renderViews() {
  this->view->render();
  this->plot->render();
}

QRect MainWindow::viewRect() const {
  return QRect(this->viewWidget->mapTo(this, QPoint(0, 0)), this->viewWidget->size());
}

QRect MainWindow::plotRect() const {
  return QRect(this->plotWidget->mapTo(this, QPoint(0, 0)), this->plotWidget->size());
}

QSize MainWindow::saveScreenshot(const std::string& path) {
  output::checkWritable(path, {".png"});
  this->renderViews();
  const QImage image = this->grab().toImage();  // includes the QOpenGLWidgets' content
  if (image.isNull()) throw std::runtime_error(path + ": could not grab the window");
  output::OutputFile out(path);
  if (!image.save(qs(out.tempPath()), "PNG")) throw std::runtime_error(path + ": cannot write PNG");
  out.commit();
  return image.size();
}

void MainWindow::openSceneDialog() {
  const QString path = QFileDialog::getOpenFileName(this, "Open scene", QString(), "Scene files (*.json);;All files (*)");
  if (path.isEmpty()) return;
  try {
    this->loadScene(path.toStdString());
  } catch (const std::exception& e) {
    QMessageBox::critical(this, "Cannot open scene", e.what());
  }
}

void MainWindow::saveScreenshotDialog() {
  QString path = QFileDialog::getSaveFileName(this, "Save screenshot", "umbra-gui.png", "PNG images (*.png)");
  if (path.isEmpty()) return;
  if (QFileInfo(path).suffix().isEmpty()) path += ".png";
  try {
    this->saveScreenshot(path.toStdString());
    this->statusBar()->showMessage("wrote " + path, 4000);
  } catch (const std::exception& e) {
    QMessageBox::critical(this, "Cannot save screenshot", e.what());
  }
}

} // namespace umbra::gui
