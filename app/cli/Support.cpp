#include "Commands.hpp"
#include "OutputFile.hpp"
#include "Ranks.hpp"

#include "scene/Ephemeris.hpp"
#include "scene/Units.hpp"
#include "MieOpticsCache.h"

#include <unistd.h>

#include <vtkCommand.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkObject.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <mutex>

#include <cstdio>
#include <cstring>
#include <ctime>
#include <iostream>

namespace umbra::cli {

void writePng(vtkImageData* image, const std::string& path) {
  output::OutputFile out(path);
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(out.tempPath().c_str());
  writer->Write();
  if (writer->GetErrorCode() != 0) throw CommandError(path + ": cannot write");
  out.commit();
}

scene::UtcTime timeOption(const std::string& text) {
  if (text.empty()) {
    const std::time_t whole = std::time(nullptr);
    char now[32];
    std::strftime(now, sizeof now, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&whole));
    return scene::parseUtc(now);
  }
  try {
    return scene::parseUtc(text);
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("--time: ") + e.what());
  }
}

std::vector<scene::UtcTime> timeSteps(const std::string& from, const std::string& to, const std::string& step) {
  if (from.empty() || to.empty() || step.empty())
    throw CommandError("--from, --to and --step go together (a series in time), got only some of them");
  scene::UtcTime t0, t1;
  double stepS = 0.0;
  try {
    t0 = scene::parseUtc(from);
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("--from: ") + e.what());
  }
  try {
    t1 = scene::parseUtc(to);
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("--to: ") + e.what());
  }
  try {
    stepS = scene::parseDurationS(step);
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("--step: ") + e.what());
  }
  if (!(stepS > 0.0)) throw CommandError("--step: must be positive, got '" + step + "'");
  const double spanS = scene::secondsBetween(t0, t1);
  if (spanS < 0.0) throw CommandError("--to: " + to + " is before --from " + from);
  const double count = std::floor(spanS / stepS + 1e-9) + 1.0;
  constexpr double kMaxSteps = 100000.0;
  if (count > kMaxSteps)
    throw CommandError("--step: " + std::to_string(static_cast<long long>(count)) + " steps, more than " +
                       std::to_string(static_cast<int>(kMaxSteps)));
  std::vector<scene::UtcTime> times;
  for (int k = 0; k < static_cast<int>(count); ++k) times.push_back(scene::addSeconds(t0, k * stepS));
  return times;
}

void noteTimesBeyondEphemeris(const std::vector<scene::UtcTime>& times) {
  if (times.empty()) return;
  for (const scene::UtcTime& t : {times.front(), times.back()})
    if (const std::string note = scene::ephemerisRangeNote(t); !note.empty()) {
      std::cerr << "umbra: " << note << "\n";
      return;
    }
}

void refuseEmptyAndNonFinite(CLI::App& app) {
  const CLI::Validator finite(
      [](std::string& text) -> std::string {
        if (text.find_first_not_of(" \t") == std::string::npos) return "expected a number, got an empty value";
        try {
          std::size_t used = 0;
          const double v = std::stod(text, &used);
          if (!std::isfinite(v)) return "expected a finite number, got '" + text + "'";
        } catch (const std::exception&) {
          return "expected a number, got '" + text + "'";
        }
        return "";
      },
      "");
  const CLI::Validator notEmpty(
      [](std::string& text) -> std::string {
        return text.find_first_not_of(" \t") == std::string::npos ? "expected a value, got an empty one" : "";
      },
      "");
  for (CLI::Option* option : app.get_options()) {
    if (option->get_expected_max() == 0) continue;  // a flag
    const std::string type = option->get_type_name();  // "FLOAT", or "FLOAT:..." with its validators
    bool isNumber = false;
    for (const char* number : {"FLOAT", "INT", "UINT"})
      isNumber = isNumber || (type.rfind(number, 0) == 0 &&
                              (type.size() == std::strlen(number) || type[std::strlen(number)] == ':'));
    option->check(isNumber ? finite : notEmpty);
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) refuseEmptyAndNonFinite(*sub);
}

void CacheOptions::addTo(CLI::App* command) {
  command->add_option("--cache-dir", this->directory,
                      "Table cache directory (default: $UMBRA_CACHE_DIR, else $XDG_CACHE_HOME/umbra, "
                      "else ~/.cache/umbra)");
  command->add_flag("--no-cache", this->disabled, "Neither read nor write the table cache");
  // The Lorenz-Mie optics of the atmosphere go where its tables go (main keeps them in the
  // default cache for the commands without these options).
  command->parse_complete_callback([this] { filters::keepMieOpticsInCache(this->directory, !this->disabled); });
}

ProgressLine::ProgressLine(std::string w, vtkObject* s)
    : what(std::move(w)), terminal(::isatty(STDERR_FILENO) != 0), source(s) {
  if (this->source) this->observer = this->source->AddObserver(vtkCommand::ProgressEvent, this, &ProgressLine::onProgress);
}

ProgressLine::~ProgressLine() {
  if (this->source) this->source->RemoveObserver(this->observer);
  this->clear();
}

void ProgressLine::onProgress(vtkObject*, unsigned long, void* fraction) {
  this->update(*static_cast<double*>(fraction));
}

void ProgressLine::clear() {
  if (this->terminal && this->lastPercent >= 0) std::cerr << "\r\033[K" << std::flush;
  this->lastPercent = -1;
}

void ProgressLine::update(double fraction) {
  const std::lock_guard<std::mutex> lock(this->mutex);  // worker threads report too
  if (!(fraction < 1.0)) {  // done (or not a number): nothing left to show
    this->clear();
    this->done = true;
    return;
  }
  // Late reports of the run just done (threads that counted before the last one) are
  // dropped; a new run starts at 0.
  if (this->done && fraction > 0.0) return;
  this->done = false;
  // Never back while shown (a VTK pipeline restarts a source's progress at 0 after its
  // input's tables were its first half).
  const int percent = std::max(static_cast<int>(std::max(fraction, 0.0) * 100.0), this->lastPercent);
  if (!this->terminal || percent == this->lastPercent) return;
  this->lastPercent = percent;
  std::cerr << "\r\033[K" << this->what << ": " << percent << "%" << std::flush;
}

std::string ranksNote(std::chrono::steady_clock::time_point start) {
  const parallel::Ranks& ranks = parallel::Ranks::world();
  if (ranks.size() == 1) return {};
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  char text[160];
  std::snprintf(text, sizeof text, " on %d ranks in %.2f s (in collectives: rank 0 %.2f s, at most %.2f s)", ranks.size(),
                seconds, ranks.collectiveSeconds(), std::max(ranks.collectiveSeconds(), ranks.mostCollectiveSeconds()));
  return text;
}

} // namespace umbra::cli
