// Night vision in the display transform (ToneMap.glsl, umbraNightVision) against its CPU twin
// (sky/NightVision): a coloured Lambert sphere lit at daylight, dusk and starlight levels,
// the PNG's pixel against the CPU's display value of the same HDR pixel.
#include "RenderTestSupport.hpp"
#include "vtkUmbraRenderPass.h"

#include "NightVision.hpp"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

using namespace umbra;
using namespace umbra::render;
using namespace umbra::render::test;

namespace {

double srgbEncode(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; }

}  // namespace

// The sphere's centre pixel, at the Sun's irradiance scaled to give about 1e4 (day), 0.05
// (dusk) and 1e-5 (starlight) cd/m^2, the exposure keeping the display near 0.5 (linear
// curve): the PNG matches the CPU's display value within 2/255 per channel; in daylight the
// colour is as without night vision, in starlight it is grey.
TEST(NightVision, DisplayMatchesTheCpuTwin) {
  constexpr int kSize = 48;
  const SphereBody ball{"Ball", {0.0, 0.0, 0.0}, 1.0e6, {0.6, 0.3, 0.1}};
  ViewCamera cam;
  cam.positionM = {0.0, -5.0e6, 0.0};
  cam.targetM = {0.0, 0.0, 0.0};
  cam.up = {0.0, 0.0, 1.0};
  cam.fovDeg = 30.0;
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("umbra-night-vision-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  for (double scale : {1.0, 5e-6, 1e-9}) {
    BodyView view(kSize, kSize, true);
    useSharedDisplay(view.GetRenderWindow());
    SunLight sun;
    sun.positionM = {0.0, -kAu, 0.0};
    sun.irradianceAt1AuWm2 = 1361.0 * scale;
    view.SetBodies(sun, {ball}, testLutImage());
    view.SetCamera(cam);
    view.SetToneMapping(vtkUmbraRenderPass::Linear);
    const double ev = std::log2(0.3 / (80.0 * scale));
    view.SetExposureEV(ev);
    view.GetRenderPass()->SetNightVision(true);
    view.Render();
    std::vector<float> hdr;
    int w = 0, h = 0;
    view.ReadHdr(hdr, w, h);
    const std::string png = (dir / "nv.png").string();
    view.WritePng(png);
    vtkNew<vtkPNGReader> reader;
    reader->SetFileName(png.c_str());
    reader->Update();
    auto* px = vtkUnsignedCharArray::SafeDownCast(reader->GetOutput()->GetPointData()->GetScalars());
    ASSERT_NE(px, nullptr);
    const int i = kSize / 2, jTop = kSize / 2;  // ReadHdr: row 0 = top; the PNG: row 0 = bottom
    const std::size_t k = (static_cast<std::size_t>(jTop) * kSize + i) * 3;
    const glm::dvec3 radiance(hdr[k], hdr[k + 1], hdr[k + 2]);
    const glm::dvec3 seen = sky::nightVisionColour(radiance) * std::exp2(ev);
    const int comps = px->GetNumberOfComponents();
    const std::size_t p = (static_cast<std::size_t>(kSize - 1 - jTop) * kSize + i) * comps;
    glm::dvec3 shown;
    for (int c = 0; c < 3; ++c) shown[c] = px->GetValue(p + c) / 255.0;
    const double lum = sky::sunlightEfficacyLmPerW() * (0.2126 * radiance.r + 0.7152 * radiance.g + 0.0722 * radiance.b);
    std::printf("  about %.2g cd/m^2: shown %.3f %.3f %.3f, CPU %.3f %.3f %.3f\n", lum, shown.r, shown.g, shown.b,
                srgbEncode(std::clamp(seen.r, 0.0, 1.0)), srgbEncode(std::clamp(seen.g, 0.0, 1.0)),
                srgbEncode(std::clamp(seen.b, 0.0, 1.0)));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(shown[c], srgbEncode(std::clamp(seen[c], 0.0, 1.0)), 2.0 / 255.0) << scale;
    if (scale == 1.0) {
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(seen[c], radiance[c] * std::exp2(ev), 1e-9);
      EXPECT_GT(shown.r - shown.b, 0.2);
    }
    if (scale == 1e-9) {
      EXPECT_NEAR(shown.r, shown.g, 1.0 / 255.0);
      EXPECT_NEAR(shown.g, shown.b, 1.0 / 255.0);
    }
  }
  std::filesystem::remove_all(dir);
}
