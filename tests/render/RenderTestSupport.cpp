#include "RenderTestSupport.hpp"

#include <X11/Xlib.h>

#include <chrono>
#include <stdexcept>
#include <thread>

namespace umbra::render::test {

void useSharedDisplay(vtkRenderWindow* window) {
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
