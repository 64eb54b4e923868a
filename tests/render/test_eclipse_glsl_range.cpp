// eclipse/glsl/EclipseShadow.glsl with a range-limited LuT (umbraShadowLutURange,
// umbraShadowLutVRange, umbraShadowLutVLowFraction) against the CPU lookup
// (eclipse::eclipseFactor with the same eclipse::ShadowLut), point by point: Mars' shadow
// over Phobos' distances, run as a full-screen quad into a float framebuffer.
#include "RenderTestSupport.hpp"

#include "EclipseShadowGlsl.hpp"
#include "ShadowLut.hpp"

#include <vtkNew.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderUtilities.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtkRenderWindow.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace umbra;

namespace {

constexpr int kSize = 64;  // points along the arc and along the distance

struct Scene {
  double sunDistanceM = 2.2794e11, sunRadiusM = eclipse::kSunRadiusM, occluderRadiusM = 3389.5e3;
  double minDistanceM = 9376e3 - 11.1e3, maxDistanceM = 9376e3 + 11.1e3, minAngleRad = 0.0, maxAngleRad = 0.0;
  glm::dvec3 point(int i, int j) const {  // occluder at the origin, Sun at (-d, 0, 0)
    const double dist = minDistanceM + (maxDistanceM - minDistanceM) * j / (kSize - 1);
    const double a = minAngleRad + (maxAngleRad - minAngleRad) * i / (kSize - 1);
    return {dist * std::cos(a), dist * std::sin(a), 0.0};
  }
};

// The GLSL factor at every point of the scene's grid.
std::vector<float> gpuFactors(const Scene& s, const eclipse::ShadowLut& lut) {
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(kSize, kSize);
  render::test::useSharedDisplay(window);
  auto* w = vtkOpenGLRenderWindow::SafeDownCast(window);
  w->Initialize();
  w->MakeCurrent();
  vtkNew<vtkTextureObject> table;
  table->SetContext(w);
  table->SetMinificationFilter(vtkTextureObject::Linear);
  table->SetMagnificationFilter(vtkTextureObject::Linear);
  table->SetWrapS(vtkTextureObject::ClampToEdge);
  table->SetWrapT(vtkTextureObject::ClampToEdge);
  table->SetInternalFormat(GL_RGB32F);
  table->SetFormat(GL_RGB);
  table->SetDataType(GL_FLOAT);
  EXPECT_TRUE(table->Create2DFromRaw(lut.width, lut.height, 3, VTK_FLOAT, const_cast<float*>(lut.rgb.data())));
  vtkNew<vtkTextureObject> colour;
  colour->SetContext(w);
  colour->SetInternalFormat(GL_RGBA32F);
  colour->SetFormat(GL_RGBA);
  colour->SetDataType(GL_FLOAT);
  EXPECT_TRUE(colour->Allocate2D(kSize, kSize, 4, VTK_FLOAT));
  vtkNew<vtkOpenGLFramebufferObject> fbo;
  fbo->SetContext(w);
  std::string fs = vtkOpenGLRenderUtilities::GetFullScreenQuadFragmentShaderTemplate();
  vtkShaderProgram::Substitute(fs, "//VTK::FSQ::Decl",
                               std::string(eclipse::kEclipseShadowGlsl) +
                                   "\nuniform vec3 sunPos; uniform float sunRadius, occRadius, dMin, dMax, minAngle, maxAngle;\n"
                                   "//VTK::FSQ::Decl");
  vtkShaderProgram::Substitute(fs, "//VTK::FSQ::Impl",
                               "  vec2 ij = floor(gl_FragCoord.xy);\n"
                               "  float dist = dMin + (dMax - dMin) * ij.y / float(" + std::to_string(kSize - 1) + ");\n"
                               "  float a = minAngle + (maxAngle - minAngle) * ij.x / float(" + std::to_string(kSize - 1) + ");\n"
                               "  vec3 p = dist * vec3(cos(a), sin(a), 0.0);\n"
                               "  gl_FragData[0] = vec4(umbraEclipseFactor(p, sunPos, sunRadius, vec3(0.0), occRadius), texCoord.x);\n"
                               "//VTK::FSQ::Impl");
  vtkOpenGLQuadHelper quad(w, vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(), fs.c_str(), "");
  EXPECT_TRUE(quad.Program && quad.Program->GetCompiled());
  if (!quad.Program || !quad.Program->GetCompiled()) return {};
  vtkShaderProgram* program = quad.Program;
  table->Activate();
  program->SetUniformi("umbraShadowLut", table->GetTextureUnit());
  const float uRange[2] = {float(lut.uMin), float(lut.uMax)}, vRange[2] = {float(lut.vMin), float(lut.vMax)};
  // Left unset for the whole range: the declarations' defaults must read it.
  if (lut.uMin != 0.0 || lut.uMax != 1.0 || lut.vMin != 0.0 || lut.vMax != 1.0 || lut.vLowFraction != 0.0) {
    program->SetUniform2f("umbraShadowLutURange", uRange);
    program->SetUniform2f("umbraShadowLutVRange", vRange);
    program->SetUniformf("umbraShadowLutVLowFraction", float(lut.vLowFraction));
  }
  const float sun[3] = {float(-s.sunDistanceM), 0.0f, 0.0f};
  program->SetUniform3f("sunPos", sun);
  program->SetUniformf("sunRadius", float(s.sunRadiusM));
  program->SetUniformf("occRadius", float(s.occluderRadiusM));
  program->SetUniformf("dMin", float(s.minDistanceM));
  program->SetUniformf("dMax", float(s.maxDistanceM));
  program->SetUniformf("minAngle", float(s.minAngleRad));
  program->SetUniformf("maxAngle", float(s.maxAngleRad));
  vtkOpenGLState* state = w->GetState();
  state->PushFramebufferBindings();
  fbo->Bind();
  fbo->AddColorAttachment(0, colour);
  fbo->ActivateDrawBuffer(0);
  EXPECT_TRUE(fbo->StartNonOrtho(kSize, kSize));
  state->vtkglViewport(0, 0, kSize, kSize);
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglDisable(GL_BLEND);
  state->vtkglDisable(GL_DEPTH_TEST);
  quad.Render();
  std::vector<float> pixels(4 * kSize * kSize);
  fbo->ActivateReadBuffer(0);
  glReadPixels(0, 0, kSize, kSize, GL_RGBA, GL_FLOAT, pixels.data());
  state->PopFramebufferBindings();
  table->Deactivate();
  return pixels;
}

void compare(const eclipse::ShadowLut& lut, const char* what) {
  Scene s;
  // Around the penumbra (an angle 2 phi_sun wide): from 0.97 to 1.01 x its outer angle.
  const double penumbraRad = std::asin(
      eclipse::shadowConeRadii({s.sunRadiusM, s.occluderRadiusM, s.sunDistanceM}, s.maxDistanceM).penumbraRadiusM /
      s.maxDistanceM);
  s.minAngleRad = 0.97 * penumbraRad, s.maxAngleRad = 1.01 * penumbraRad;
  const std::vector<float> gpu = gpuFactors(s, lut);
  ASSERT_EQ(gpu.size(), 4u * kSize * kSize);
  const glm::dvec3 sun(-s.sunDistanceM, 0, 0);
  double maxDiff = 0.0, maxExact = 0.0;
  int worst = 0;
  int penumbra = 0;
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      const glm::dvec3 p = s.point(i, j);
      const double cpu = eclipse::eclipseFactor(p, sun, s.sunRadiusM, {{0, 0, 0}, s.occluderRadiusM}, &lut).r;
      const double exact = eclipse::eclipseFactor(p, sun, s.sunRadiusM, {{0, 0, 0}, s.occluderRadiusM}, nullptr).r;
      const double g = gpu[4 * (static_cast<std::size_t>(j) * kSize + i)];
      if (std::abs(g - cpu) > maxDiff) worst = j * kSize + i;
      maxDiff = std::max(maxDiff, std::abs(g - cpu));
      maxExact = std::max(maxExact, std::abs(g - exact));
      penumbra += cpu > 0.01 && cpu < 0.99;
    }
  std::printf("  %s: %d points (%d in the penumbra), max |GPU - CPU| = %.3g, max |GPU - exact| = %.3g\n", what,
              kSize * kSize, penumbra, maxDiff, maxExact);
  EXPECT_GT(penumbra, kSize);
  if (maxDiff >= 1e-3) {
    const glm::dvec3 p = s.point(worst % kSize, worst / kSize);
    const eclipse::LutCoords c = eclipse::lutCoords(eclipse::shadowAngles(p, sun, s.sunRadiusM, {0, 0, 0}, s.occluderRadiusM));
    std::printf("  worst at (%d, %d): u %.9g v %.9g, GPU %.6g CPU %.6g\n", worst % kSize, worst / kSize, c.u, c.v,
                gpu[4 * worst], eclipse::eclipseFactor(p, sun, s.sunRadiusM, {{0, 0, 0}, s.occluderRadiusM}, &lut).r);
  }
  EXPECT_LT(maxDiff, 1e-3);
}

} // namespace

// A 64^2 LuT over Phobos' ranges (u range, v from the umbra's edge): the GPU reads it as the CPU.
TEST(EclipseGlslRange, RangedLutAgreesWithTheCpuAtPhobos) {
  Scene s;
  const eclipse::LutRange r = eclipse::lutRangeForDistances({s.sunRadiusM, s.occluderRadiusM, s.sunDistanceM},
                                                            s.minDistanceM, 1.01 * s.maxDistanceM, true, 64);
  const eclipse::ShadowLut lut =
      eclipse::buildAirlessShadowLut({64, 64, eclipse::kDefaultLimbDarkening, 1e-10, r.uMin, r.uMax, r.vMin, r.vMax});
  compare(lut, "u range, v range");
  // The split v axis (an atmosphere's layout) on the same ranges.
  const eclipse::LutRange split = eclipse::lutRangeForDistances({s.sunRadiusM, s.occluderRadiusM, s.sunDistanceM},
                                                                s.minDistanceM, 1.01 * s.maxDistanceM, false, 64);
  compare(eclipse::buildAirlessShadowLut({64, 64, eclipse::kDefaultLimbDarkening, 1e-10, split.uMin, split.uMax,
                                          split.vMin, split.vMax, split.vLowFraction}),
          "u range, split v");
}

// Without the uniforms set (as the renderer today) the whole-range LuT reads as before.
TEST(EclipseGlslRange, DefaultUniformsReadTheWholeLut) {
  const eclipse::ShadowLut lut = eclipse::buildAirlessShadowLut({64, 64});
  compare(lut, "whole LuT");
}
