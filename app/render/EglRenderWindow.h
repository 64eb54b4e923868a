// Render windows on EGL pbuffers: offscreen rendering without an X server (a GPU node
// reached only through EGL; `umbra render --egl`, the benches' --egl, UMBRA_TEST_EGL=1 in
// the rendering tests). Debian 12's VTK 9.1 is built for GLX only; this gives it an EGL
// context through vtkGenericOpenGLRenderWindow.
//
// After useEglRenderWindows(), every vtkRenderWindow::New() (BodyView's included) makes an
// EGL window: its own context on a small pbuffer (VTK draws into framebuffer objects of
// its own, of the window's size), on the first EGL device that is not Mesa's software one
// (EGL_EXT_platform_device: the GPU with NVIDIA's driver), else the first device
// (llvmpipe), else the default display.
#pragma once

#include <string>

class vtkRenderWindow;

namespace umbra::render {

/// Makes vtkRenderWindow::New() return EGL windows from now on. Returns false and sets
/// `error` when EGL has no display or no OpenGL config; nothing changes then.
bool useEglRenderWindows(std::string& error);
/// True once useEglRenderWindows() has succeeded.
bool usingEglRenderWindows();
/// Offscreen rendering with no X display: when DISPLAY is unset (or empty), switches to EGL
/// windows and returns true; returns false when DISPLAY is set (X windows, as before).
/// Throws std::runtime_error naming both ways out when there is no display and EGL cannot
/// be used.
bool useEglWithoutDisplay();

/// "vendor, renderer, version" of the window's current GL context (the window rendered
/// once), e.g. to show whether a run went to a GPU or to llvmpipe.
std::string glRendererString(vtkRenderWindow* window);

}  // namespace umbra::render
