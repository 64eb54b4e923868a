// EGL windows (app/render/EglRenderWindow): the render pass drawn on an EGL
// pbuffer, with no X involved, gives the image the X window gives. Both run on the same
// GL implementation here (Mesa's llvmpipe); on a GPU machine without X, EGL is the way in.
#include "BodyView.h"
#include "EglRenderWindow.h"
#include "RenderTestSupport.hpp"
#include "SceneInputs.h"
#include "scene/Scene.hpp"

#include <gtest/gtest.h>

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkRenderWindow.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace umbra;

namespace {

struct Frame {
  std::vector<float> rgb;
  int width = 0, height = 0;
  std::string windowClass, renderer;
  int windowErrors = 0;  ///< VTK errors of the window (e.g. "GLEW could not be initialized")
};

// The 2015-09-28 eclipse's Moon, partly in Earth's umbra (receiver shading, shadow LuT,
// HDR, tone mapping).
Frame renderMoon(bool useXDisplay) {
  const scene::Scene s = scene::loadScene(UMBRA_SOURCE_DIR "/examples/scenes/lunar-eclipse-2015-09-28.json");
  const pipeline::SceneInputs in = pipeline::sceneInputs(s);
  render::BodyView view(96, 54, true);
  if (useXDisplay) render::test::useSharedDisplay(view.GetRenderWindow());
  Frame f;
  vtkNew<vtkCallbackCommand> countErrors;
  countErrors->SetClientData(&f.windowErrors);
  countErrors->SetCallback([](vtkObject*, unsigned long, void* count, void*) { ++*static_cast<int*>(count); });
  view.GetRenderWindow()->AddObserver(vtkCommand::ErrorEvent, countErrors);
  view.SetBodies(in.sun, in.bodies, render::test::testLutImage());
  view.SetCamera(in.camera);
  view.SetExposureEV(s.exposureEv);
  view.Render();
  view.Render();
  view.ReadHdr(f.rgb, f.width, f.height);
  f.windowClass = view.GetRenderWindow()->GetClassName();
  f.renderer = render::glRendererString(view.GetRenderWindow());
  return f;
}

}  // namespace

TEST(EglWindow, RendersTheImageOfTheXWindow) {
  // EGL first: the process's first context is the one that initialises GLEW, which is
  // what the GLX stand-ins are for.
  std::string error;
  ASSERT_TRUE(render::useEglRenderWindows(error)) << error;
  const Frame egl = renderMoon(false);
  // Back to VTK's own X window.
  vtkObjectFactory::SetAllEnableFlags(1, "vtkRenderWindow");
  vtkObjectFactory::SetAllEnableFlags(0, "vtkRenderWindow", "EglRenderWindow");
  const Frame x = renderMoon(true);
  EXPECT_EQ(egl.windowClass, "EglRenderWindow");
  EXPECT_EQ(egl.windowErrors, 0);
  EXPECT_EQ(x.windowErrors, 0);
  EXPECT_NE(x.windowClass, "EglRenderWindow");
  EXPECT_EQ(egl.renderer.find('?'), std::string::npos) << egl.renderer;
  ASSERT_EQ(egl.width, x.width);
  ASSERT_EQ(egl.height, x.height);
  ASSERT_EQ(egl.rgb.size(), x.rgb.size());
  // The Moon is lit (not a black frame) and partly in the umbra.
  const float brightest = *std::max_element(x.rgb.begin(), x.rgb.end());
  ASSERT_GT(brightest, 0.0f);
  std::size_t lit = 0;
  double worst = 0.0;
  for (std::size_t k = 0; k < x.rgb.size(); ++k) {
    if (x.rgb[k] > 1e-3f * brightest) ++lit;
    worst = std::max(worst, std::abs(double(egl.rgb[k]) - double(x.rgb[k])) / brightest);
  }
  EXPECT_GT(lit, x.rgb.size() / 20);
  EXPECT_LT(worst, 1e-6) << "largest difference, relative to the brightest value";
}
