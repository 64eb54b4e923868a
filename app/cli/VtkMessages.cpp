#include "VtkMessages.hpp"

#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>

#include <iostream>
#include <mutex>

namespace umbra::cli {
namespace {

/// One line: newlines and runs of blanks become one space; VTK's "ERROR: In file, line N"
/// header is kept (it says where), the trailing blank lines go.
std::string folded(const char* text) {
  std::string out;
  bool blank = false;
  for (const char* c = text; c && *c; ++c) {
    if (*c == '\n' || *c == '\r' || *c == '\t' || *c == ' ') {
      blank = !out.empty();
      continue;
    }
    if (blank) out += ' ';
    blank = false;
    out += *c;
  }
  return out;
}

class Collector : public vtkOutputWindow {
public:
  static Collector* New();
  vtkTypeMacro(Collector, vtkOutputWindow);

  void DisplayText(const char* text) override { take(text); }
  void DisplayErrorText(const char* text) override { take(text); }
  void DisplayWarningText(const char* text) override { take(text); }
  void DisplayGenericWarningText(const char* text) override { take(text); }
  void DisplayDebugText(const char* text) override { take(text); }

  bool verbose = false;
  std::size_t count = 0;
  std::string first;
  std::mutex mutex;

private:
  void take(const char* text) {
    const std::string line = folded(text);
    if (line.empty()) return;
    std::lock_guard<std::mutex> lock(mutex);
    if (count++ == 0) first = line;
    if (verbose) std::cerr << "umbra: vtk: " << line << '\n';
  }
};
vtkStandardNewMacro(Collector);

Collector* collector() {
  static vtkSmartPointer<Collector> instance = [] {
    auto c = vtkSmartPointer<Collector>::New();
    vtkOutputWindow::SetInstance(c);
    return c;
  }();
  return instance;
}

}  // namespace

void routeVtkMessages(bool verbose) {
  collector()->verbose = verbose;
  // vtkLogger would print errors to stderr a second time.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

std::size_t vtkMessageCount() {
  std::lock_guard<std::mutex> lock(collector()->mutex);
  return collector()->count;
}

std::string firstVtkMessage() {
  std::lock_guard<std::mutex> lock(collector()->mutex);
  return collector()->first;
}

std::string vtkMessagesHint() {
  const std::size_t n = vtkMessageCount();
  if (n == 0 || collector()->verbose) return "";
  return " (VTK gave " + std::to_string(n) + (n == 1 ? " message" : " messages") + "; --verbose shows them)";
}

}  // namespace umbra::cli
