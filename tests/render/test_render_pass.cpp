// vtkUmbraRenderPass on plain VTK content: float HDR buffer, read-back, display transform
// (exposure, tone curve, sRGB), resource release.
#include "RenderTestSupport.hpp"
#include "vtkUmbraRenderPass.h"

#include <vtkActor.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkSphereSource.h>
#include <vtkUnsignedCharArray.h>
#include <vtkPointData.h>
#include <vtkWindowToImageFilter.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace {

struct Scene {
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkUmbraRenderPass> pass;
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkPolyDataMapper> mapper;
  vtkNew<vtkActor> actor;
  static constexpr int kSize = 128;

  Scene() {
    sphere->SetThetaResolution(64);
    sphere->SetPhiResolution(32);
    mapper->SetInputConnection(sphere->GetOutputPort());
    actor->SetMapper(mapper);
    renderer->AddActor(actor);
    renderer->SetBackground(0, 0, 0);
    renderer->SetPass(pass);
    umbra::render::test::useSharedDisplay(window);
    window->SetOffScreenRendering(1);
    window->SetMultiSamples(0);
    window->SetSize(kSize, kSize);
    window->AddRenderer(renderer);
  }
  ~Scene() {
    pass->ReleaseGraphicsResources(window);
    window->Finalize();
  }
  // Centre pixel of the HDR frame (RGBA).
  std::vector<float> hdrCentre() {
    std::vector<float> rgba;
    int w = 0, h = 0;
    EXPECT_TRUE(pass->ReadHdrPixels(rgba, w, h));
    EXPECT_EQ(w, kSize);
    EXPECT_EQ(h, kSize);
    if (rgba.empty()) return {0, 0, 0, 0};
    const std::size_t k = 4 * (static_cast<std::size_t>(h / 2) * w + w / 2);
    return {rgba[k], rgba[k + 1], rgba[k + 2], rgba[k + 3]};
  }
  // Centre pixel of the displayed (tone-mapped, 8-bit) frame.
  std::vector<int> displayCentre() {
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window);
    grab->SetInputBufferTypeToRGB();
    grab->ReadFrontBufferOff();
    grab->ShouldRerenderOff();
    grab->Update();
    auto* px = vtkUnsignedCharArray::SafeDownCast(grab->GetOutput()->GetPointData()->GetScalars());
    const vtkIdType k = static_cast<vtkIdType>(kSize / 2) * kSize + kSize / 2;
    return {px->GetValue(3 * k), px->GetValue(3 * k + 1), px->GetValue(3 * k + 2)};
  }
};

double srgbEncode(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; }
double srgbDecode(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

} // namespace

TEST(UmbraRenderPass, FloatBufferKeepsValuesAboveOne) {
  Scene s;
  std::vector<float> rgba;
  int w = 0, h = 0;
  EXPECT_FALSE(s.pass->ReadHdrPixels(rgba, w, h)) << "no frame before the first render";
  s.renderer->AutomaticLightCreationOff();
  vtkNew<vtkLight> light;
  light->SetLightTypeToHeadlight();
  light->SetIntensity(5.0);
  s.renderer->AddLight(light);
  s.actor->GetProperty()->SetColor(1.0, 1.0, 1.0);
  s.actor->GetProperty()->SetAmbient(0.0);
  s.actor->GetProperty()->SetDiffuse(1.0);
  s.actor->GetProperty()->SetSpecular(0.0);
  s.window->Render();
  ASSERT_TRUE(s.pass->ReadHdrPixels(rgba, w, h));
  ASSERT_EQ(rgba.size(), static_cast<std::size_t>(w) * h * 4);
  float maxValue = 0.0f;
  for (float v : rgba) {
    ASSERT_TRUE(std::isfinite(v));
    maxValue = std::max(maxValue, v);
  }
  EXPECT_GT(maxValue, 4.0f) << "an RGBA8 buffer would clamp at 1";
  EXPECT_LT(maxValue, 5.01f);
  // Row 0 is the bottom row: the corners are background, the centre is lit.
  EXPECT_EQ(rgba[0], 0.0f);
  EXPECT_GT(s.hdrCentre()[0], 4.0f);
}

TEST(UmbraRenderPass, DisplayTransformIsExposureCurveSrgb) {
  Scene s;
  s.actor->GetProperty()->LightingOff();
  s.actor->GetProperty()->SetColor(0.3, 0.12, 0.05);
  struct Case {
    int mode;
    double ev;
  };
  std::vector<double> linearDisplay;
  for (const Case c : {Case{vtkUmbraRenderPass::Linear, 0.0}, Case{vtkUmbraRenderPass::Linear, 1.0},
                       Case{vtkUmbraRenderPass::Reinhard, 0.0}, Case{vtkUmbraRenderPass::Reinhard, 2.5}}) {
    s.pass->SetToneMapping(c.mode);
    s.pass->SetExposureEV(c.ev);
    s.window->Render();
    const std::vector<float> hdr = s.hdrCentre();
    const std::vector<int> shown = s.displayCentre();
    ASSERT_GT(hdr[0], 0.0f);
    for (int ch = 0; ch < 3; ++ch) {
      const double x = hdr[ch] * std::exp2(c.ev);
      const double curve = c.mode == vtkUmbraRenderPass::Linear ? std::min(x, 1.0) : x / (1.0 + x);
      const double expected = 255.0 * srgbEncode(curve);
      EXPECT_NEAR(shown[ch], expected, 1.0) << "mode " << c.mode << " EV " << c.ev << " channel " << ch;
    }
    if (c.mode == vtkUmbraRenderPass::Linear) linearDisplay.push_back(srgbDecode(shown[0] / 255.0));
  }
  // +1 EV doubles the (linear) pre-tone-map value.
  ASSERT_EQ(linearDisplay.size(), 2u);
  EXPECT_NEAR(linearDisplay[1] / linearDisplay[0], 2.0, 0.03);
}

TEST(UmbraRenderPass, ReleaseGraphicsResourcesThenRenderAgain) {
  Scene s;
  s.window->Render();
  std::vector<float> rgba;
  int w = 0, h = 0;
  ASSERT_TRUE(s.pass->ReadHdrPixels(rgba, w, h));
  s.pass->ReleaseGraphicsResources(s.window);
  EXPECT_FALSE(s.pass->ReadHdrPixels(rgba, w, h));
  s.window->SetSize(96, 64);  // and a resize
  s.window->Render();
  ASSERT_TRUE(s.pass->ReadHdrPixels(rgba, w, h));
  EXPECT_EQ(w, 96);
  EXPECT_EQ(h, 64);
  s.window->SetSize(Scene::kSize, Scene::kSize);
  s.window->Render();
  ASSERT_TRUE(s.pass->ReadHdrPixels(rgba, w, h));
  EXPECT_EQ(w, Scene::kSize);
}
