#pragma once
// The GUI's table jobs: the tables a scene view is missing, made in a worker thread, one job
// at a time, so that the window stays live. A job is either the atmosphere's tables (a
// vtkAtmosphereTablesSource configured by the caller: pipeline::configureSceneAtmosphereTables)
// or the eclipse LuTs of its body, one after the other: the atmospheric shadow LuT (the
// other bodies' shading and the profile) and the limb-luminance LuT (the thin ring), as
// the view asks for them (SceneView::missingAtmosphereShadow, missingLimbLuminance).
//
// The job's progress (each observed algorithm mapped to its part of 0..100, never going
// back) and its end reach the caller on the GUI thread. A cancelled or failed request is
// remembered and not started again until forgetFailures (the scene's time moved) or until
// the request changes; the view keeps the tables it has meanwhile.
#include "AtmosphereShadow.h"
#include "SceneInputs.h"
#include "vtkAtmosphereTablesSource.h"
#include "vtkEclipseShadowLutSource.h"
#include "vtkLimbLuminanceSource.h"

#include <QObject>

#include <vtkSmartPointer.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace umbra::gui {

class SceneView;

class TableJobs : public QObject {
public:
  /// What a finished job made. A tables job: `tables` (its configured source) and `choice`,
  /// with `tablesError` ("cancelled" when it was) empty when they were made. A LuT job
  /// (`lutJob()`: no `tables`): `shadow` and `limb` with their requests, each set only when
  /// made and not cancelled, and `problem` naming each that was not ("atmosphere shadow:
  /// cancelled").
  struct Result {
    bool lutJob() const { return !tables; }
    vtkSmartPointer<vtkAtmosphereTablesSource> tables;
    pipeline::AtmosphereTableChoice choice;
    std::string tablesError;
    vtkSmartPointer<vtkEclipseShadowLutSource> shadow;
    std::optional<pipeline::AtmosphereShadowRequest> shadowRequest;
    vtkSmartPointer<vtkLimbLuminanceSource> limb;
    std::optional<pipeline::LimbLuminanceRequest> limbRequest;
    std::string problem;
  };
  /// `progress` gets the percentage while a job runs; `finished` its result (both on the
  /// GUI thread; not for a job that stop() ended).
  TableJobs(std::function<void(int percent)> progress, std::function<void(Result&)> finished);
  ~TableJobs() override;  // stop()

  bool busy() const { return this->job != nullptr; }
  bool tablesBusy() const;
  bool lutsBusy() const;
  bool limbLuminanceBusy() const;
  /// The source of the tables being made, or null.
  vtkAtmosphereTablesSource* tablesInProgress() const;

  /// Whether the view's missing tables should be made now: no job is running and they were
  /// not the last to fail.
  bool wantsTables(const std::optional<pipeline::AtmosphereTableChoice>& missing) const;
  /// Makes the tables of `source` (configured for `choice`; from its cache or computed).
  /// The job takes the caller's reference: no other may be dropped on the GUI thread while
  /// the worker runs (see TableJobs::Job).
  void startTables(vtkSmartPointer<vtkAtmosphereTablesSource>&& source, const pipeline::AtmosphereTableChoice& choice);
  /// Remembers tables that could not even be configured, as a failed job is.
  void tablesFailed(const pipeline::AtmosphereTableChoice& choice) { this->failedTables = choice; }
  /// Starts the eclipse LuTs that `view` is missing and that did not fail last; returns
  /// the status line to show ("computing the shadow through the atmosphere of Earth..."),
  /// or none when there is nothing to do (also while a job runs). Throws
  /// std::runtime_error when a LuT cannot be set up (that request counts as failed).
  std::optional<std::string> startEclipseLuts(const SceneView& view);

  /// Asks the job to stop (its end is reported as cancelled).
  void cancel();
  /// Cancels the job and waits for it; its end is not reported.
  void stop();
  /// Another time: the failed requests may be tried again.
  void forgetFailures();

private:
  struct Job;
  void run(std::unique_ptr<Job> j, std::function<void()> work);
  void jobEnded(int generation);

  std::function<void(int)> onProgress;
  std::function<void(Result&)> onFinished;
  std::unique_ptr<Job> job;
  int generation = 0;
  std::optional<pipeline::AtmosphereShadowRequest> failedShadow;
  std::optional<pipeline::LimbLuminanceRequest> failedLimb;
  std::optional<pipeline::AtmosphereTableChoice> failedTables;
};

}  // namespace umbra::gui
