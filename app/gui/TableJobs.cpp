#include "TableJobs.hpp"

#include "SceneView.hpp"

#include <QMetaObject>

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkNew.h>

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

namespace umbra::gui {

/// A job's algorithms are only touched by the worker until it has finished (then by the
/// GUI thread), except SetAbortExecute. Nor does the GUI thread take or drop references to
/// them meanwhile: VTK's garbage collector walks an algorithm's references on every
/// UnRegister that leaves it alive, while the worker's pipeline changes them. The job's
/// references are taken before the worker starts and dropped after it has been joined, and
/// what VTK makes on first use (the executives, the outputs) is made before it starts.
/// The worker's progress callbacks set AbortExecute again from `cancelled`: VTK clears it
/// when an execution starts, so a cancel that comes before that is not lost. Each observed
/// algorithm's progress is mapped to its part [from, to] of the job's.
struct TableJobs::Job {
  TableJobs* owner = nullptr;
  Result result;
  struct Stage {
    Job* job;
    double from, to;
    vtkSmartPointer<vtkAlgorithm> algorithm;
    vtkNew<vtkCallbackCommand> onProgress;
  };
  std::vector<std::unique_ptr<Stage>> stages;
  std::thread thread;
  std::atomic<bool> cancelled{false};
  std::atomic<int> shownPercent{0};
  // Set by the worker: whether each LuT was made, else its error.
  bool shadowMade = false, limbMade = false;
  std::string shadowError, limbError;

  void observe(vtkAlgorithm* algorithm, double from, double to) {
    if (!algorithm) return;
    auto stage = std::make_unique<Stage>();
    stage->job = this, stage->from = from, stage->to = to, stage->algorithm = algorithm;
    stage->onProgress->SetClientData(stage.get());
    stage->onProgress->SetCallback([](vtkObject* caller, unsigned long, void* client, void* data) {
      const auto* st = static_cast<const Stage*>(client);
      Job* j = st->job;
      if (j->cancelled) static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
      const double f = std::clamp(*static_cast<double*>(data), 0.0, 1.0);
      // Never back within a job (a VTK pipeline restarts a source's progress at 0 after its
      // input's tables, which were already its first half).
      const int percent =
          std::max(static_cast<int>(100.0 * (st->from + (st->to - st->from) * f)), j->shownPercent.load());
      j->shownPercent = percent;
      TableJobs* owner = j->owner;
      QMetaObject::invokeMethod(owner, [owner, percent] { owner->onProgress(percent); }, Qt::QueuedConnection);
    });
    algorithm->AddObserver(vtkCommand::ProgressEvent, stage->onProgress);
    this->stages.push_back(std::move(stage));
  }
  void cancel() {
    this->cancelled = true;
    for (const auto& st : this->stages) st->algorithm->SetAbortExecute(1);
  }
  void stopObserving() {
    for (const auto& st : this->stages) st->algorithm->RemoveObserver(st->onProgress);
  }
};

TableJobs::TableJobs(std::function<void(int)> progress, std::function<void(Result&)> finished)
    : onProgress(std::move(progress)), onFinished(std::move(finished)) {}

TableJobs::~TableJobs() { this->stop(); }

bool TableJobs::tablesBusy() const { return this->job && this->job->result.tables; }

bool TableJobs::lutsBusy() const { return this->job && this->job->result.lutJob(); }

bool TableJobs::limbLuminanceBusy() const { return this->job && this->job->result.limbRequest; }

vtkAtmosphereTablesSource* TableJobs::tablesInProgress() const {
  return this->job ? this->job->result.tables.Get() : nullptr;
}

bool TableJobs::wantsTables(const std::optional<pipeline::AtmosphereTableChoice>& missing) const {
  return missing && !this->job && missing != this->failedTables;
}

void TableJobs::startTables(vtkSmartPointer<vtkAtmosphereTablesSource>&& source,
                            const pipeline::AtmosphereTableChoice& choice) {
  this->stop();
  auto j = std::make_unique<Job>();
  j->result.tables = std::move(source);  // the GUI thread's only reference from now on
  j->result.choice = choice;
  vtkAtmosphereTablesSource* tables = j->result.tables;
  j->observe(tables, 0.0, 1.0);
  this->run(std::move(j), [tables] { tables->Update(); });
}

std::optional<std::string> TableJobs::startEclipseLuts(const SceneView& view) {
  if (this->job) return std::nullopt;
  auto wanted = [](const auto& missing, const auto& failed) { return missing && !(failed && *failed == *missing); };
  const auto& shadow = view.missingAtmosphereShadow();
  const auto& limb = view.missingLimbLuminance();
  const bool makeShadow = wanted(shadow, this->failedShadow), makeLimb = wanted(limb, this->failedLimb);
  if (!makeShadow && !makeLimb) return std::nullopt;
  auto j = std::make_unique<Job>();
  // Each LuT's part of the progress: the atmosphere's tables with refraction (from their
  // cache) in its first half, the texels in its second; the LuT source reports both (its
  // tables' progress is its first half), the tables are observed too, to be cancelled.
  const double split = makeShadow && makeLimb ? 0.5 : makeShadow ? 1.0 : 0.0;
  std::string occluder;
  try {
    if (makeShadow) {
      occluder = shadow->occluder;
      j->result.shadow = view.newAtmosphereShadowSource();
      j->result.shadowRequest = *shadow;
      j->observe(pipeline::setUpAtmosphereShadow(j->result.shadow, *shadow), 0.0, 0.5 * split);
      j->observe(j->result.shadow, 0.0, split);
    }
    if (makeLimb) {
      occluder = limb->occluder;
      j->result.limb = view.newLimbLuminanceSource();
      j->result.limbRequest = *limb;
      j->observe(pipeline::setUpLimbLuminance(j->result.limb, *limb), split, 0.5 * (split + 1.0));
      j->observe(j->result.limb, split, 1.0);
    }
  } catch (const std::exception& e) {
    if (makeShadow) this->failedShadow = *shadow;
    if (makeLimb) this->failedLimb = *limb;
    throw std::runtime_error(e.what());
  }
  const std::string what = makeShadow && makeLimb ? "the shadow and the limb luminance"
                           : makeShadow           ? "the shadow"
                                                  : "the limb luminance";
  Job* raw = j.get();
  this->run(std::move(j), [raw] {
    try {
      if (raw->result.shadow) pipeline::updateAtmosphereShadow(raw->result.shadow, *raw->result.shadowRequest);
      raw->shadowMade = raw->result.shadow != nullptr;
    } catch (const std::exception& e) {
      raw->shadowError = e.what();
    }
    if (!raw->result.limb || raw->cancelled) return;
    try {
      pipeline::updateLimbLuminance(raw->result.limb, *raw->result.limbRequest);
      raw->limbMade = true;
    } catch (const std::exception& e) {
      raw->limbError = e.what();
    }
  });
  return "computing " + what + " through the atmosphere of " + occluder + "...";
}

void TableJobs::run(std::unique_ptr<Job> j, std::function<void()> work) {
  // The algorithms' executives and outputs, which VTK makes on first use, are made here on
  // the GUI thread: the worker then only runs their pipeline.
  for (const auto& st : j->stages) st->algorithm->UpdateDataObject();
  this->job = std::move(j);
  this->job->owner = this;
  const int g = ++this->generation;
  this->job->thread = std::thread([this, g, work = std::move(work)] {
    work();
    QMetaObject::invokeMethod(this, [this, g] { this->jobEnded(g); }, Qt::QueuedConnection);
  });
}

void TableJobs::jobEnded(int g) {
  if (!this->job || g != this->generation) return;
  this->job->thread.join();
  const std::unique_ptr<Job> done = std::move(this->job);
  done->stopObserving();
  Result& r = done->result;
  if (r.lutJob()) {
    // A cancelled job (also one that ended meanwhile) or a failed LuT is remembered.
    auto outcome = [&](bool asked, bool made, const std::string& name, const std::string& error) {
      if (!asked || (made && !done->cancelled)) return true;
      r.problem += (r.problem.empty() ? "" : "; ") + name + ": " + (done->cancelled ? std::string("cancelled") : error);
      return false;
    };
    if (!outcome(r.shadow != nullptr, done->shadowMade, "atmosphere shadow", done->shadowError)) {
      this->failedShadow = r.shadowRequest;
      r.shadow = nullptr;
    }
    if (!outcome(r.limb != nullptr, done->limbMade, "limb luminance", done->limbError)) {
      this->failedLimb = r.limbRequest;
      r.limb = nullptr;
    }
  } else {
    r.tablesError = r.tables->GetLastError();
    if (!r.tablesError.empty() && done->cancelled) r.tablesError = "cancelled";
    if (r.tablesError.empty()) {
      this->failedTables.reset();
    } else {
      this->failedTables = r.choice;  // not asked for again until the time moves
    }
  }
  this->onFinished(r);
}

void TableJobs::cancel() {
  if (this->job) this->job->cancel();
}

void TableJobs::stop() {
  if (!this->job) return;
  this->job->cancel();
  if (this->job->thread.joinable()) this->job->thread.join();
  this->job->stopObserving();  // its callbacks point into the job
  this->job.reset();
  ++this->generation;  // a queued end of that job is ignored
}

void TableJobs::forgetFailures() {
  this->failedShadow.reset(), this->failedLimb.reset(), this->failedTables.reset();
}

}  // namespace umbra::gui
