#include "RenderTestSupport.hpp"

#include "EglRenderWindow.h"

#include <gtest/gtest.h>
#include <X11/Xlib.h>  // after gtest: its macros (None, ...) clash with gtest's names

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace umbra::render::test {

namespace {
// UMBRA_TEST_EGL=1: every window of the test process on EGL, with no X display (the
// CPU-against-GLSL tests on a GPU machine without an X server: scripts/device-checks.sh).
// Switched in the test environment's SetUp, after VTK's factories have registered.
class EglEnvironment : public ::testing::Environment {
 public:
  void SetUp() override {
    std::string error;
    if (!useEglRenderWindows(error)) {
      std::fprintf(stderr, "UMBRA_TEST_EGL: %s\n", error.c_str());
      std::exit(2);
    }
    std::printf("UMBRA_TEST_EGL: windows on EGL\n");
  }
};
[[maybe_unused]] const bool kEglEnvironmentAdded = [] {
  const char* e = std::getenv("UMBRA_TEST_EGL");
  const bool egl = e && std::strcmp(e, "1") == 0;
  if (egl) ::testing::AddGlobalTestEnvironment(new EglEnvironment);
  return egl;
}();
}  // namespace

void useSharedDisplay(vtkRenderWindow* window) {
  if (usingEglRenderWindows()) return;
  static Display* display = [] {
    for (int attempt = 0; attempt < 20; ++attempt) {
      if (Display* d = XOpenDisplay(nullptr)) return d;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return static_cast<Display*>(nullptr);
  }();
  if (!display) throw std::runtime_error("cannot open the X display (run under xvfb-run)");
  window->SetDisplayId(display);
}

} // namespace umbra::render::test
