#include "EglRenderWindow.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkGenericRenderWindowInteractor.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkVersionMacros.h>
#include <vtk_glew.h>

#include <dlfcn.h>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

// ---- GLEW under EGL -------------------------------------------------------------------
// Debian's VTK calls GLEW's glewInit(), built for GLX: after loading the GL functions it
// asks GLX for the current display (through glXGetProcAddressARB("glXGetCurrentDisplay"))
// and fails when there is none, as under EGL. While EGL windows are in use, the three GLX
// entry points it calls are answered here for a stand-in display; every other call goes
// on to libGLX. Executables export them (-Wl,--export-dynamic-symbol: umbra_render's link
// options, app/render/CMakeLists.txt).
namespace {
struct StandInDisplay;
bool gEglWindows = false;
StandInDisplay* standInDisplay() {
  static char storage[64];
  return reinterpret_cast<StandInDisplay*>(storage);
}
extern "C" StandInDisplay* umbraStandInCurrentDisplay() { return standInDisplay(); }
template <class F>
F nextSymbol(const char* name) {
  return reinterpret_cast<F>(dlsym(RTLD_NEXT, name));
}
}  // namespace

extern "C" {
using UmbraGlxProc = void (*)();
__attribute__((visibility("default"))) UmbraGlxProc glXGetProcAddressARB(const unsigned char* name) {
  if (gEglWindows && std::strcmp(reinterpret_cast<const char*>(name), "glXGetCurrentDisplay") == 0) {
    return reinterpret_cast<UmbraGlxProc>(&umbraStandInCurrentDisplay);
  }
  static const auto next = nextSymbol<UmbraGlxProc (*)(const unsigned char*)>("glXGetProcAddressARB");
  return next ? next(name) : nullptr;
}
__attribute__((visibility("default"))) int glXQueryVersion(void* display, int* major, int* minor) {
  if (display == standInDisplay()) {
    *major = 1;
    *minor = 4;
    return 1;
  }
  static const auto next = nextSymbol<int (*)(void*, int*, int*)>("glXQueryVersion");
  return next ? next(display, major, minor) : 0;
}
__attribute__((visibility("default"))) const char* glXGetClientString(void* display, int name) {
  if (display == standInDisplay()) return "";
  static const auto next = nextSymbol<const char* (*)(void*, int)>("glXGetClientString");
  return next ? next(display, name) : nullptr;
}
}

// ---- the EGL display and the window ---------------------------------------------------
namespace {

struct EglSetup {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLConfig config = nullptr;
};
EglSetup gEgl;

std::string hex(EGLint code) {
  char s[16];
  std::snprintf(s, sizeof s, "0x%04x", static_cast<unsigned>(code));
  return s;
}

// The first EGL device that is not Mesa's software one, else the first device, else the
// default display; UMBRA_EGL_DEVICE=N picks device N.
EGLDisplay openDisplay() {
  const auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  const auto queryDeviceString =
      reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  const auto platformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  EGLDeviceEXT devices[16];
  EGLint count = 0;
  if (queryDevices && platformDisplay && queryDevices(16, devices, &count) && count > 0) {
    int pick = 0;
    if (const char* wanted = std::getenv("UMBRA_EGL_DEVICE")) {
      pick = std::min(std::max(std::atoi(wanted), 0), count - 1);
    } else if (queryDeviceString) {
      for (int k = count - 1; k >= 0; --k) {
        const char* ext = queryDeviceString(devices[k], EGL_EXTENSIONS);
        if (!ext || !std::strstr(ext, "EGL_MESA_device_software")) pick = k;
      }
    }
    const EGLDisplay d = platformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[pick], nullptr);
    if (d != EGL_NO_DISPLAY) return d;
  }
  return eglGetDisplay(EGL_DEFAULT_DISPLAY);
}

class EglRenderWindow : public vtkGenericOpenGLRenderWindow {
public:
  static EglRenderWindow* New();
  vtkTypeMacro(EglRenderWindow, vtkGenericOpenGLRenderWindow);

  void MakeCurrent() override {
    if (this->EnsureContext()) eglMakeCurrent(gEgl.display, this->Surface, this->Surface, this->Context);
  }
  bool IsCurrent() override { return this->Context != EGL_NO_CONTEXT && eglGetCurrentContext() == this->Context; }
  void Initialize() override {
    this->MakeCurrent();
    if (this->IsCurrent() && !this->Initialized) this->InitializeFromCurrentContext();
  }
  void Render() override {
    this->Initialize();
    this->Superclass::Render();
  }

protected:
  EglRenderWindow() {
    this->SetReadyForRendering(true);
    this->SetOwnContext(1);
  }
  ~EglRenderWindow() override {
    if (this->Context == EGL_NO_CONTEXT) return;
    this->MakeCurrent();
    this->ReleaseGraphicsResources(this);
    eglMakeCurrent(gEgl.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(gEgl.display, this->Context);
    if (this->Surface != EGL_NO_SURFACE) eglDestroySurface(gEgl.display, this->Surface);
    this->Context = EGL_NO_CONTEXT;
  }

private:
  // A context of its own on a 16x16 pbuffer. VTK renders into framebuffer objects of its
  // own, of the window's size, and reads images back from them; the pbuffer only makes the
  // context current, so the image size is not bound by EGL's largest pbuffer (checked: a
  // 12000x64 render, and PNGs equal to the X window's byte for byte).
  bool EnsureContext() {
    if (this->Context != EGL_NO_CONTEXT) return true;
    if (this->Failed) return false;
    const EGLint pbuffer[] = {EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE};
    this->Surface = eglCreatePbufferSurface(gEgl.display, gEgl.config, pbuffer);
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 2,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    eglBindAPI(EGL_OPENGL_API);
    this->Context = eglCreateContext(gEgl.display, gEgl.config, EGL_NO_CONTEXT, attributes);
    if (this->Surface == EGL_NO_SURFACE || this->Context == EGL_NO_CONTEXT) {
      vtkErrorMacro("EGL: no OpenGL 3.2 core context on a pbuffer (error " << hex(eglGetError()) << ")");
      this->Failed = true;
      return false;
    }
    return true;
  }

  EGLSurface Surface = EGL_NO_SURFACE;
  EGLContext Context = EGL_NO_CONTEXT;
  bool Failed = false;
};
vtkStandardNewMacro(EglRenderWindow);

class EglWindowFactory : public vtkObjectFactory {
public:
  static EglWindowFactory* New() {
    auto* f = new EglWindowFactory;
    f->InitializeObjectBase();
    return f;
  }
  vtkTypeMacro(EglWindowFactory, vtkObjectFactory);
  const char* GetVTKSourceVersion() override { return VTK_SOURCE_VERSION; }
  const char* GetDescription() override { return "umbra: render windows on EGL pbuffers"; }

protected:
  EglWindowFactory() {
    this->RegisterOverride("vtkRenderWindow", "EglRenderWindow", "EGL pbuffer window", 1,
                           [] { return static_cast<vtkObject*>(EglRenderWindow::New()); });
    // Views that make their own interactor (vtkContextView) would get the X one, which
    // opens the display when the window first renders.
    this->RegisterOverride("vtkRenderWindowInteractor", "vtkGenericRenderWindowInteractor",
                           "an interactor without a window system", 1,
                           [] { return static_cast<vtkObject*>(vtkGenericRenderWindowInteractor::New()); });
  }
};

}  // namespace

namespace umbra::render {

bool useEglRenderWindows(std::string& error) {
  if (gEglWindows) return true;
  const EGLDisplay display = openDisplay();
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) {
    error = "EGL: no display could be initialised (error " + hex(eglGetError()) + ")";
    return false;
  }
  const EGLint wanted[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                           EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8,
                           EGL_DEPTH_SIZE, 24, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  if (!eglChooseConfig(display, wanted, &config, 1, &configs) || configs < 1 || !eglBindAPI(EGL_OPENGL_API)) {
    error = "EGL " + std::to_string(major) + "." + std::to_string(minor) + " (" +
            (eglQueryString(display, EGL_VENDOR) ? eglQueryString(display, EGL_VENDOR) : "?") +
            "): no OpenGL pbuffer config with RGBA8 and a 24-bit depth";
    eglTerminate(display);
    return false;
  }
  gEgl = {display, config};
  gEglWindows = true;
  vtkNew<EglWindowFactory> factory;
  vtkObjectFactory::RegisterFactory(factory);
  // The OpenGL2 and UI modules' own overrides (X) are registered first; only ours stay on.
  vtkObjectFactory::SetAllEnableFlags(0, "vtkRenderWindow");
  vtkObjectFactory::SetAllEnableFlags(1, "vtkRenderWindow", "EglRenderWindow");
  vtkObjectFactory::SetAllEnableFlags(0, "vtkRenderWindowInteractor");
  vtkObjectFactory::SetAllEnableFlags(1, "vtkRenderWindowInteractor", "vtkGenericRenderWindowInteractor");
  return true;
}

bool usingEglRenderWindows() { return gEglWindows; }

bool useEglWithoutDisplay() {
  const char* display = std::getenv("DISPLAY");
  if (display && *display) return false;
  std::string error;
  if (useEglRenderWindows(error)) return true;
  throw std::runtime_error("no X display (DISPLAY is unset) and no EGL (" + error + "): run under xvfb-run -a");
}

std::string glRendererString(vtkRenderWindow* window) {
  window->MakeCurrent();
  auto text = [](GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return text(GL_VENDOR) + ", " + text(GL_RENDERER) + ", " + text(GL_VERSION);
}

}  // namespace umbra::render
