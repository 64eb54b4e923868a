// eclipse/glsl/EclipseShadow.glsl with a range-limited LuT (umbraShadowLutMap,
// umbraShadowLutMapLow from eclipse::LutRange::textureMap) against the CPU lookup
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

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
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

// An offscreen kSize x kSize window with its context current.
vtkSmartPointer<vtkRenderWindow> quadWindow() {
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetOffScreenRendering(1);
  window->SetSize(kSize, kSize);
  render::test::useSharedDisplay(window);
  auto* w = vtkOpenGLRenderWindow::SafeDownCast(window);
  w->Initialize();
  w->MakeCurrent();
  return window;
}

// Runs `impl` (GLSL writing gl_FragData[0]; gl_FragCoord gives the pixel) over a kSize^2
// full-screen quad into a float framebuffer, after eclipse/glsl/EclipseShadow.glsl and
// `decl`; `setUp` sets the uniforms. Returns RGBA per pixel, row by row (empty on failure).
std::vector<float> quadPixels(vtkRenderWindow* window, const std::string& decl, const std::string& impl,
                              const std::function<void(vtkShaderProgram&)>& setUp) {
  auto* w = vtkOpenGLRenderWindow::SafeDownCast(window);
  vtkNew<vtkTextureObject> colour;
  colour->SetContext(w);
  colour->SetInternalFormat(GL_RGBA32F);
  colour->SetFormat(GL_RGBA);
  colour->SetDataType(GL_FLOAT);
  EXPECT_TRUE(colour->Allocate2D(kSize, kSize, 4, VTK_FLOAT));
  vtkNew<vtkOpenGLFramebufferObject> fbo;
  fbo->SetContext(w);
  std::string fs = vtkOpenGLRenderUtilities::GetFullScreenQuadFragmentShaderTemplate();
  vtkShaderProgram::Substitute(fs, "//VTK::FSQ::Decl", std::string(eclipse::kEclipseShadowGlsl) + "\n" + decl +
                                                           "\n//VTK::FSQ::Decl");
  vtkShaderProgram::Substitute(fs, "//VTK::FSQ::Impl", impl + "\n//VTK::FSQ::Impl");
  vtkOpenGLQuadHelper quad(w, vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(), fs.c_str(), "");
  EXPECT_TRUE(quad.Program && quad.Program->GetCompiled());
  if (!quad.Program || !quad.Program->GetCompiled()) return {};
  setUp(*quad.Program);
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
  return pixels;
}

// The GLSL factor at every point of the scene's grid.
std::vector<float> gpuFactors(const Scene& s, const eclipse::ShadowLut& lut) {
  auto window = quadWindow();
  vtkNew<vtkTextureObject> table;
  table->SetContext(vtkOpenGLRenderWindow::SafeDownCast(window));
  table->SetMinificationFilter(vtkTextureObject::Linear);
  table->SetMagnificationFilter(vtkTextureObject::Linear);
  table->SetWrapS(vtkTextureObject::ClampToEdge);
  table->SetWrapT(vtkTextureObject::ClampToEdge);
  table->SetInternalFormat(GL_RGB32F);
  table->SetFormat(GL_RGB);
  table->SetDataType(GL_FLOAT);
  EXPECT_TRUE(table->Create2DFromRaw(lut.width, lut.height, 3, VTK_FLOAT, const_cast<float*>(lut.rgb.data())));
  table->Activate();
  const std::vector<float> pixels = quadPixels(
      window, "uniform vec3 sunPos; uniform float sunRadius, occRadius, dMin, dMax, minAngle, maxAngle;",
      "  vec2 ij = floor(gl_FragCoord.xy);\n"
      "  float dist = dMin + (dMax - dMin) * ij.y / float(" + std::to_string(kSize - 1) + ");\n"
      "  float a = minAngle + (maxAngle - minAngle) * ij.x / float(" + std::to_string(kSize - 1) + ");\n"
      "  vec3 p = dist * vec3(cos(a), sin(a), 0.0);\n"
      "  gl_FragData[0] = vec4(umbraEclipseFactor(p, sunPos, sunRadius, vec3(0.0), occRadius), texCoord.x);",
      [&](vtkShaderProgram& program) {
        program.SetUniformi("umbraShadowLut", table->GetTextureUnit());
        // Left unset for the whole range: the declarations' defaults must read it.
        if (lut.uMin != 0.0 || lut.uMax != 1.0 || lut.vMin != 0.0 || lut.vMax != 1.0 || lut.vLowFraction != 0.0) {
          const auto m = eclipse::LutRange{lut.uMin, lut.uMax, lut.vMin, lut.vMax, lut.vLowFraction}.textureMap();
          const float map[4] = {float(m.uOrigin), float(m.uScale), float(m.vOrigin), float(m.vScale)};
          const float low[3] = {float(m.vSplit), float(m.vLowOrigin), float(m.vLowScale)};
          program.SetUniform4f("umbraShadowLutMap", map);
          program.SetUniform3f("umbraShadowLutMapLow", low);
        }
        const float sun[3] = {float(-s.sunDistanceM), 0.0f, 0.0f};
        program.SetUniform3f("sunPos", sun);
        program.SetUniformf("sunRadius", float(s.sunRadiusM));
        program.SetUniformf("occRadius", float(s.occluderRadiusM));
        program.SetUniformf("dMin", float(s.minDistanceM));
        program.SetUniformf("dMax", float(s.maxDistanceM));
        program.SetUniformf("minAngle", float(s.minAngleRad));
        program.SetUniformf("maxAngle", float(s.maxAngleRad));
      });
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

namespace {

// A receiver (centre at the origin, as the renderer hands positions over) with the Sun and
// one occluder around it.
struct ReceiverGeometry {
  const char* name;
  double receiverRadiusM;
  glm::dvec3 sunM;
  double sunRadiusM;
  glm::dvec3 occluderM;
  double occluderRadiusM;
  bool expands;  ///< eclipse::receiverShadowExpands: Phobos is too close to Mars (0.37 rad)
};

// The point of the receiver's sphere that pixel (i, j) stands for (the shader's formula).
glm::dvec3 receiverPoint(const ReceiverGeometry& g, int i, int j) {
  const double th = 3.14159265358979 * (j + 0.5) / kSize, ph = 6.28318530717959 * (i + 0.5) / kSize;
  return g.receiverRadiusM * glm::dvec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
}

void setVec4(vtkShaderProgram& program, const char* name, const eclipse::AngularRadiusExpansion& x) {
  const float v[4] = {float(x.distanceM), float(x.phi0Rad), float(x.c1Rad), float(x.c2Rad)};
  program.SetUniform4f(name, v);
}

// The receiver's uniforms and the GLSL that puts p on it at the pixel (receiverPoint's
// formula), with toSun and invSun from there.
const char* const kReceiverUniforms =
    "uniform vec3 sunPos, occPos; uniform float receiverRadius, sunRadius, occRadius; uniform vec4 sunX, occX;\n";
std::string receiverPointGlsl() {
  return "  vec2 ij = floor(gl_FragCoord.xy);\n"
         "  float th = 3.14159265 * (ij.y + 0.5) / float(" + std::to_string(kSize) + ");\n"
         "  float ph = 6.28318531 * (ij.x + 0.5) / float(" + std::to_string(kSize) + ");\n"
         "  vec3 p = receiverRadius * vec3(sin(th) * cos(ph), sin(th) * sin(ph), cos(th));\n"
         "  vec3 toSun = sunPos - p;\n"
         "  float invSun = 1.0 / length(toSun);\n";
}
void setReceiverUniforms(vtkShaderProgram& program, const ReceiverGeometry& g, double occRadiusM,
                         const eclipse::AngularRadiusExpansion& sunX, const eclipse::AngularRadiusExpansion& occX) {
  const float sun[3] = {float(g.sunM.x), float(g.sunM.y), float(g.sunM.z)};
  const float occ[3] = {float(g.occluderM.x), float(g.occluderM.y), float(g.occluderM.z)};
  program.SetUniform3f("sunPos", sun);
  program.SetUniform3f("occPos", occ);
  program.SetUniformf("receiverRadius", float(g.receiverRadiusM));
  program.SetUniformf("sunRadius", float(g.sunRadiusM));
  program.SetUniformf("occRadius", float(occRadiusM));
  setVec4(program, "sunX", sunX);
  setVec4(program, "occX", occX);
}

} // namespace

// The receiver's (u, v) (umbraReceiverShadowUv: both angular radii expanded about the
// receiver's centre, eclipse::AngularRadiusExpansion, and the series angle, where
// eclipse::receiverShadowExpands) against Eq. 3-4 in double, over the whole receiver, at
// the extremes: Phobos by Mars (exact: too close), the Moon behind Earth, a Moon at the
// tip of Earth's umbra, and a receiver 0.1 au from the Sun. Where the point is in the
// shadow (v < 1) it must be no less accurate than Eq. 3-4 computed exactly in float
// (umbraShadowUv, the GLSL of eclipseFactor, as the receiver had it before).
TEST(EclipseGlslRange, ReceiverShadowUvAgreesWithEquations3And4AtTheExtremes) {
  constexpr double au = 1.495978707e11, sunR = eclipse::kSunRadiusM;
  const std::vector<ReceiverGeometry> geometries = {
      {"Phobos by Mars", 11.1e3, {-9376e3 - 1.523679 * au, 3389e3, 0.0}, sunR, {-9376e3, 3389e3, 0.0}, 3389.5e3, false},
      {"Moon behind Earth", 1737.4e3, {-384400e3 - au, 5000e3, 0.0}, sunR, {-384400e3, 5000e3, 0.0}, 6371e3, true},
      {"Moon at Earth's umbra tip", 1737.4e3, {-1.38e9 - au, 0.0, 0.0}, sunR, {-1.38e9, 0.0, 0.0}, 6371e3, true},
      {"receiver 0.1 au from the Sun", 2439.7e3, {-384400e3 - 0.1 * au, 0.0, 0.0}, sunR, {-384400e3, 0.0, 0.0},
       1737.4e3, true}};
  for (const ReceiverGeometry& g : geometries) {
    const auto sunX = eclipse::angularRadiusExpansion(g.sunRadiusM, glm::length(g.sunM), g.receiverRadiusM);
    const auto occX = eclipse::angularRadiusExpansion(g.occluderRadiusM, glm::length(g.occluderM), g.receiverRadiusM);
    const bool expands = eclipse::receiverShadowExpands(sunX, occX);
    EXPECT_EQ(expands, g.expands) << g.name;
    auto window = quadWindow();
    const std::vector<float> px = quadPixels(
        window, std::string(kReceiverUniforms) + "uniform int exact;",
        receiverPointGlsl() +
        "  vec2 near = umbraReceiverShadowUv(toSun * invSun, invSun, sunX, sunRadius, occPos - p, occX, occRadius,\n"
        "                                    exact != 0, vec4(0.0, 0.0, 1.0, 0.0), false);\n"
        "  gl_FragData[0] = vec4(near, umbraShadowUv(p, sunPos, sunRadius, occPos, occRadius));",
        [&](vtkShaderProgram& program) {
          setReceiverUniforms(program, g, g.occluderRadiusM, sunX, occX);
          program.SetUniformi("exact", expands ? 0 : 1);
        });
    ASSERT_EQ(px.size(), 4u * kSize * kSize) << g.name;
    double nearU = 0.0, nearV = 0.0, exactU = 0.0, exactV = 0.0;
    int shadowed = 0;
    for (int j = 0; j < kSize; ++j)
      for (int i = 0; i < kSize; ++i) {
        const glm::dvec3 p = receiverPoint(g, i, j);
        const eclipse::LutCoords c =
            eclipse::lutCoords(eclipse::shadowAngles(p, g.sunM, g.sunRadiusM, g.occluderM, g.occluderRadiusM));
        const float* q = &px[4 * (static_cast<std::size_t>(j) * kSize + i)];
        if (c.v >= 1.0) {
          if (c.v > 1.0 + 1e-5) { EXPECT_GE(q[1], 1.0f) << g.name << " at (" << i << ", " << j << ")"; }
          continue;
        }
        ++shadowed;
        nearU = std::max(nearU, std::abs(q[0] - c.u));
        nearV = std::max(nearV, std::abs(q[1] - c.v));
        exactU = std::max(exactU, std::abs(q[2] - c.u));
        exactV = std::max(exactV, std::abs(q[3] - c.v));
      }
    std::printf("  %s: %d of %d points in the shadow; max |u - Eq. 4|: expanded %.3g, exact in float %.3g; "
                "max |v - Eq. 4|: %.3g, %.3g\n",
                g.name, shadowed, kSize * kSize, nearU, exactU, nearV, exactV);
    EXPECT_GT(shadowed, kSize) << g.name;
    EXPECT_LE(nearU, 1.5 * exactU + 1e-7) << g.name;
    EXPECT_LE(nearV, 1.5 * exactV + 1e-7) << g.name;
  }
}

// The oblate occluder in the receiver's shader (umbraReceiverShadowUv with a figure,
// expanded and exact) against eclipse::shadowAngles with the same figure in double: the
// Moon in the Earth's penumbra, the Earth's pole tilted 23.4 deg towards the Sun and 20
// deg across. The outline moves (u, v) by about 1e-3 from the sphere's; float keeps them
// within 2e-6.
TEST(EclipseGlslRange, OblateOccluderAgreesWithTheCpu) {
  constexpr double au = 1.495978707e11, sunR = eclipse::kSunRadiusM, meanR = 6371.0084e3, moonR = 1737.4e3;
  const eclipse::Oblateness figure{glm::normalize(glm::dvec3(-0.3978, 0.34, 0.9175)), 1.0 / 298.257};
  const ReceiverGeometry g{"Moon in the Earth's penumbra", moonR, {-384400e3 - au, 0.0, 6000e3}, sunR,
                           {-384400e3, 0.0, 6000e3}, meanR, true};
  const double a = eclipse::equatorialRadiusM(meanR, figure);
  const auto sunX = eclipse::angularRadiusExpansion(g.sunRadiusM, glm::length(g.sunM), g.receiverRadiusM);
  const auto occX = eclipse::angularRadiusExpansion(a, glm::length(g.occluderM), g.receiverRadiusM);
  ASSERT_TRUE(eclipse::receiverShadowExpands(sunX, occX));
  for (const int exact : {0, 1}) {
    auto window = quadWindow();
    const std::vector<float> px = quadPixels(
        window, std::string(kReceiverUniforms) + "uniform vec4 figure; uniform int exact;",
        receiverPointGlsl() +
        "  vec2 uv = exact != 0 ? umbraReceiverShadowUv(toSun * invSun, invSun, sunX, sunRadius, occPos - p, occX,\n"
        "                                               occRadius, true, figure, true)\n"
        "                       : umbraReceiverShadowUv(toSun * invSun, invSun, sunX, sunRadius, occPos - p, occX,\n"
        "                                               occRadius, false, figure, true);\n"
        "  gl_FragData[0] = vec4(uv, umbraOutlineRadiusFactor(normalize(occPos - p), toSun, figure), 0.0);",
        [&](vtkShaderProgram& program) {
          setReceiverUniforms(program, g, a, sunX, occX);
          const float fig[4] = {float(figure.pole.x), float(figure.pole.y), float(figure.pole.z),
                                float(figure.flattening * (2.0 - figure.flattening))};
          program.SetUniform4f("figure", fig);
          program.SetUniformi("exact", exact);
        });
    ASSERT_EQ(px.size(), 4u * kSize * kSize);
    double maxU = 0.0, maxV = 0.0, maxFactor = 0.0, maxMoved = 0.0;
    int shadowed = 0;
    for (int j = 0; j < kSize; ++j)
      for (int i = 0; i < kSize; ++i) {
        const glm::dvec3 p = receiverPoint(g, i, j);
        const eclipse::LutCoords c =
            eclipse::lutCoords(eclipse::shadowAngles(p, g.sunM, g.sunRadiusM, g.occluderM, meanR, figure));
        const eclipse::LutCoords sphere =
            eclipse::lutCoords(eclipse::shadowAngles(p, g.sunM, g.sunRadiusM, g.occluderM, meanR));
        const float* q = &px[4 * (static_cast<std::size_t>(j) * kSize + i)];
        maxFactor = std::max(maxFactor, std::abs(q[2] - eclipse::outlineRadiusFactor(glm::normalize(g.occluderM - p),
                                                                                       g.sunM - p, figure)));
        if (c.v >= 1.0) continue;
        ++shadowed;
        maxU = std::max(maxU, std::abs(q[0] - c.u));
        maxV = std::max(maxV, std::abs(q[1] - c.v));
        maxMoved = std::max(maxMoved, std::max(std::abs(sphere.u - c.u), std::abs(sphere.v - c.v)));
      }
    std::printf("  %s: %d points in the shadow; max |u - CPU| %.3g, |v - CPU| %.3g, |factor - CPU| %.3g; "
                "the outline moves (u, v) by up to %.3g\n",
                exact ? "exact" : "expanded", shadowed, maxU, maxV, maxFactor, maxMoved);
    EXPECT_GT(shadowed, kSize);
    EXPECT_GT(maxMoved, 5e-4);
    EXPECT_LT(maxU, 2e-6);
    EXPECT_LT(maxV, 2e-6);
    EXPECT_LT(maxFactor, 1e-6);
  }
}
