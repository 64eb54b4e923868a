// Render windows on EGL pbuffers, for timing the render pass on a machine without an X
// server (a GPU node reached only through EGL). Debian 12's VTK 9.1 is built for GLX
// only; this gives it an EGL context through vtkGenericOpenGLRenderWindow.
//
// After useEglRenderWindows(), every vtkRenderWindow::New() (BodyView's included) makes an
// EGL window: its own context on a pbuffer of the window's size, on the first EGL device
// (EGL_EXT_platform_device: the GPU with NVIDIA's driver, llvmpipe with Mesa's) or else
// the default display.
#pragma once

#include <string>

class vtkRenderWindow;

namespace umbra::bench {

/// Makes vtkRenderWindow::New() return EGL windows from now on. Returns false and sets
/// `error` when EGL has no display or no OpenGL config; nothing changes then.
bool useEglRenderWindows(std::string& error);

/// "vendor, renderer, version" of the window's current GL context (the window rendered
/// once), e.g. to show whether a run went to a GPU or to llvmpipe.
std::string glRendererString(vtkRenderWindow* window);

}  // namespace umbra::bench
