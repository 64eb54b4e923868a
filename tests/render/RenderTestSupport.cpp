#include "RenderTestSupport.hpp"

#include "EglRenderWindow.h"

#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <gtest/gtest.h>
#include <X11/Xlib.h>  // after gtest: its macros (None, ...) clash with gtest's names

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include <unistd.h>

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

std::string writeRgbPng(int width, int height, const std::function<glm::dvec3(int, int)>& texel,
                        const std::string& name) {
  vtkNew<vtkImageData> image;
  image->SetDimensions(width, height, 1);
  vtkNew<vtkUnsignedCharArray> px;
  px->SetNumberOfComponents(3);
  px->SetNumberOfTuples(static_cast<vtkIdType>(width) * height);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const glm::dvec3 c = texel(i, j);
      for (int k = 0; k < 3; ++k)
        px->SetTypedComponent(static_cast<vtkIdType>(j) * width + i, k,
                              static_cast<unsigned char>(std::lround(std::clamp(c[k], 0.0, 1.0) * 255.0)));
    }
  image->GetPointData()->SetScalars(px);
  const auto dir = std::filesystem::temp_directory_path() / ("umbra-render-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / name).string();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(image);
  writer->Write();
  return path;
}

} // namespace umbra::render::test
