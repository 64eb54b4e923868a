// vtkUmbraRenderPass on plain VTK content: float HDR buffer, read-back, display transform
// (exposure, tone curve, sRGB), resource release.
#include "RenderTestSupport.hpp"
#include "vtkUmbraRenderPass.h"

#include "Glare.h"

#include <vtkActor.h>
#include <vtkCamera.h>
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

namespace {
// The glare of Glare.h on the CPU: per kernel, rows then columns, each source pixel's light
// spread with the kernel renormalised over the frame.
std::vector<double> glareOnCpu(const std::vector<float>& rgba, int w, int h,
                               const std::vector<umbra::render::GlareKernel>& kernels) {
  std::vector<double> out(rgba.size(), 0.0);
  double kept = 1.0;
  for (const auto& k : kernels) kept -= k.energyFraction;
  for (std::size_t i = 0; i < rgba.size(); ++i) out[i] = (i % 4 == 3) ? rgba[i] : kept * rgba[i];
  auto spread = [&](const std::vector<double>& in, const std::vector<float>& wts, bool rows) {
    std::vector<double> res(in.size(), 0.0);
    const int r = static_cast<int>(wts.size() / 2), len = rows ? w : h;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const int s = rows ? x : y;
        double inside = 0.0;
        for (int j = -r; j <= r; ++j) inside += (s + j >= 0 && s + j < len) ? wts[j + r] : 0.0;
        for (int j = -r; j <= r; ++j) {
          if (s + j < 0 || s + j >= len) continue;
          const int tx = rows ? x + j : x, ty = rows ? y : y + j;
          for (int c = 0; c < 3; ++c)
            res[4 * (ty * w + tx) + c] += in[4 * (y * w + x) + c] * wts[j + r] / inside;
        }
      }
    return res;
  };
  const std::vector<double> src(rgba.begin(), rgba.end());
  for (const auto& k : kernels) {
    const std::vector<double> g = spread(spread(src, k.weights, true), k.weights, false);
    for (std::size_t i = 0; i < out.size(); ++i)
      if (i % 4 != 3) out[i] += k.energyFraction * g[i];
  }
  return out;
}
} // namespace

TEST(UmbraRenderPass, GlareKernelsAreNormalisedAndAngular) {
  const auto k1 = umbra::render::glareKernels(1.0, 10.0);  // 10 px per degree
  ASSERT_EQ(k1.size(), 3u);
  double fractions = 0.0;
  for (const auto& k : k1) {
    double sum = 0.0, second = 0.0;
    const int r = static_cast<int>(k.weights.size() / 2);
    for (int j = -r; j <= r; ++j) sum += k.weights[j + r], second += j * j * k.weights[j + r];
    EXPECT_NEAR(sum, 1.0, 1e-6);
    if (k.sigmaPx > 1.0) { EXPECT_NEAR(std::sqrt(second), std::sqrt(k.sigmaPx * k.sigmaPx + 1.0 / 12.0), 0.03 * k.sigmaPx); }
    fractions += k.energyFraction;
  }
  EXPECT_NEAR(fractions, 0.07, 1e-12);
  EXPECT_NEAR(k1[2].sigmaPx, 7.5, 1e-12);                                       // 0.75 deg
  EXPECT_NEAR(umbra::render::glareKernels(1.0, 100.0)[2].sigmaPx, 64.0 / 3.0, 1e-12);  // clipped
  EXPECT_TRUE(umbra::render::glareKernels(0.0, 10.0).empty());
  EXPECT_THROW(umbra::render::glareKernels(11.0, 10.0), std::invalid_argument);
}

// The glared HDR frame keeps the total radiance per channel (no light leaves the frame),
// lights pixels around a small bright sphere, and equals the CPU formula pixel by pixel.
TEST(UmbraRenderPass, GlareKeepsTheEnergyAndMatchesTheCpu) {
  Scene s;
  s.actor->GetProperty()->LightingOff();
  s.actor->GetProperty()->SetColor(1.0, 0.5, 0.25);
  s.actor->SetScale(0.08);  // the camera is reset to it: a disc of ~36 px radius
  std::vector<float> plain, glared;
  int w = 0, h = 0;
  s.window->Render();
  ASSERT_TRUE(s.pass->ReadHdrPixels(plain, w, h));
  s.pass->SetGlareStrength(4.0);
  s.window->Render();
  ASSERT_TRUE(s.pass->ReadHdrPixels(glared, w, h));
  ASSERT_EQ(glared.size(), plain.size());

  const double pxPerDeg = h / s.renderer->GetActiveCamera()->GetViewAngle();
  const std::vector<double> cpu = glareOnCpu(plain, w, h, umbra::render::glareKernels(4.0, pxPerDeg));
  double sumPlain[3] = {0, 0, 0}, sumGlared[3] = {0, 0, 0}, maxDiff = 0.0, maxValue = 0.0;
  int litByGlare = 0;
  for (std::size_t i = 0; i < plain.size(); ++i) {
    if (i % 4 == 3) continue;
    ASSERT_TRUE(std::isfinite(glared[i]));
    sumPlain[i % 4] += plain[i];
    sumGlared[i % 4] += glared[i];
    maxDiff = std::max(maxDiff, std::abs(glared[i] - cpu[i]));
    maxValue = std::max(maxValue, static_cast<double>(plain[i]));
    litByGlare += i % 4 == 0 && plain[i] == 0.0f && glared[i] > 1e-4f;
  }
  std::printf("  glare: sums R %.6g -> %.6g, G %.6g -> %.6g; max |GPU - CPU| %.2g; %d dark pixels lit\n", sumPlain[0],
              sumGlared[0], sumPlain[1], sumGlared[1], maxDiff, litByGlare);
  ASSERT_GT(sumPlain[0], 100.0);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sumGlared[c] / sumPlain[c], 1.0, 1e-5) << c;
  EXPECT_LT(maxDiff, 1e-5 * maxValue);
  EXPECT_GT(litByGlare, 500);
}
