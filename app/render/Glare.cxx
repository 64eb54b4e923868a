#include "Glare.h"

#include "RenderGlsl.hpp"

#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderUtilities.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace umbra::render {

std::vector<GlareKernel> glareKernels(double strength, double pixelsPerDegree) {
  if (!(strength >= 0.0 && strength <= 10.0)) throw std::invalid_argument("glare strength must be in [0, 10]");
  if (!(pixelsPerDegree > 0.0 && std::isfinite(pixelsPerDegree)))
    throw std::invalid_argument("glare: pixels per degree must be positive");
  std::vector<GlareKernel> kernels;
  if (strength == 0.0) return kernels;
  constexpr double kSigmaDeg[3] = {0.03, 0.15, 0.75};
  constexpr double kFraction[3] = {0.04, 0.02, 0.01};
  for (int k = 0; k < 3; ++k) {
    GlareKernel g;
    g.energyFraction = kFraction[k] * strength;
    g.sigmaPx = std::min(kSigmaDeg[k] * pixelsPerDegree, kMaxGlareRadiusPx / 3.0);
    const int r = std::min(kMaxGlareRadiusPx, static_cast<int>(std::ceil(3.0 * g.sigmaPx)));
    double sum = 0.0;
    std::vector<double> w(static_cast<std::size_t>(2 * r + 1));
    for (int j = -r; j <= r; ++j) {
      // the Gaussian's mass over the pixel [j - 1/2, j + 1/2]: exact for any sigma
      const double a = (j - 0.5) / (std::sqrt(2.0) * g.sigmaPx), b = (j + 0.5) / (std::sqrt(2.0) * g.sigmaPx);
      w[static_cast<std::size_t>(j + r)] = 0.5 * (std::erf(b) - std::erf(a));
      sum += w[static_cast<std::size_t>(j + r)];
    }
    for (double v : w) g.weights.push_back(static_cast<float>(v / sum));
    kernels.push_back(std::move(g));
  }
  return kernels;
}

bool prepareFloatTexture(vtkSmartPointer<vtkTextureObject>& t, vtkOpenGLRenderWindow* renWin, int w, int h) {
  if (!t) {
    t = vtkSmartPointer<vtkTextureObject>::New();
    t->SetContext(renWin);
    t->SetMinificationFilter(vtkTextureObject::Nearest);
    t->SetMagnificationFilter(vtkTextureObject::Nearest);
    t->SetWrapS(vtkTextureObject::ClampToEdge);
    t->SetWrapT(vtkTextureObject::ClampToEdge);
    t->SetInternalFormat(GL_RGBA32F);
    t->SetFormat(GL_RGBA);
    t->SetDataType(GL_FLOAT);
    return t->Allocate2D(w, h, 4, VTK_FLOAT);
  }
  if (t->GetWidth() != static_cast<unsigned>(w) || t->GetHeight() != static_cast<unsigned>(h)) t->Resize(w, h);
  return true;
}

GlareRendering::GlareRendering() = default;
GlareRendering::~GlareRendering() { delete this->Quad; }
vtkTextureObject* GlareRendering::Output() const { return this->OutputTexture; }
vtkOpenGLFramebufferObject* GlareRendering::OutputFramebuffer() const { return this->OutputBuffer; }

bool GlareRendering::Pass(vtkOpenGLRenderWindow* renWin, vtkTextureObject* source, vtkOpenGLFramebufferObject* target,
                          vtkTextureObject* targetTexture, int w, int h, bool alongRows,
                          const std::vector<float>& weights, float scale, bool add) {
  vtkOpenGLState* ostate = renWin->GetState();
  ostate->PushFramebufferBindings();
  target->Bind();
  target->AddColorAttachment(0, targetTexture);
  target->ActivateDrawBuffer(0);
  if (!target->Start(w, h)) {
    ostate->PopFramebufferBindings();
    return false;
  }
  ostate->vtkglViewport(0, 0, w, h);
  ostate->vtkglScissor(0, 0, w, h);
  ostate->vtkglDisable(GL_DEPTH_TEST);
  if (add) {
    ostate->vtkglEnable(GL_BLEND);
    ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);  // colour added, alpha kept
  } else {
    ostate->vtkglDisable(GL_BLEND);
  }
  renWin->GetShaderCache()->ReadyShaderProgram(this->Quad->Program);
  vtkShaderProgram* program = this->Quad->Program;
  const int r = static_cast<int>(weights.size() / 2);
  std::vector<float> prefix(weights.size() + 1, 0.0f);
  for (std::size_t i = 0; i < weights.size(); ++i) prefix[i + 1] = prefix[i] + weights[i];
  const int step[2] = {alongRows ? 1 : 0, alongRows ? 0 : 1};
  source->Activate();
  program->SetUniformi("umbraGlareSource", source->GetTextureUnit());
  program->SetUniform2i("umbraGlareStep", step);
  program->SetUniformi("umbraGlareRadius", r);
  program->SetUniformi("umbraGlareLength", alongRows ? w : h);
  program->SetUniform1fv("umbraGlareWeight", static_cast<int>(weights.size()), weights.data());
  program->SetUniform1fv("umbraGlarePrefix", static_cast<int>(prefix.size()), prefix.data());
  program->SetUniformf("umbraGlareScale", scale);
  this->Quad->Render();
  source->Deactivate();
  ostate->vtkglDisable(GL_BLEND);
  ostate->PopFramebufferBindings();
  return true;
}

bool GlareRendering::Apply(vtkOpenGLRenderWindow* renWin, vtkTextureObject* source, int w, int h,
                           const std::vector<GlareKernel>& kernels) {
  if (!prepareFloatTexture(this->TempTexture, renWin, w, h) || !prepareFloatTexture(this->OutputTexture, renWin, w, h))
    return false;
  for (auto* fbo : {&this->TempBuffer, &this->OutputBuffer}) {
    if (!*fbo) {
      *fbo = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
      (*fbo)->SetContext(renWin);
    }
  }
  if (!this->Quad) {
    std::string fs = vtkOpenGLRenderUtilities::GetFullScreenQuadFragmentShaderTemplate();
    vtkShaderProgram::Substitute(fs, "//VTK::FSQ::Decl", std::string(glsl::kGlare) + "\n//VTK::FSQ::Decl");
    vtkShaderProgram::Substitute(fs, "//VTK::FSQ::Impl",
                                 "  ivec2 p = ivec2(floor(texCoord * vec2(textureSize(umbraGlareSource, 0))));\n"
                                 "  gl_FragData[0] = vec4(umbraGlare(p), 1.0);\n//VTK::FSQ::Impl");
    this->Quad = new vtkOpenGLQuadHelper(renWin, vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(),
                                         fs.c_str(), "");
  }
  if (!this->Quad->Program || !this->Quad->Program->GetCompiled()) return false;
  double kept = 1.0;
  for (const GlareKernel& k : kernels) kept -= k.energyFraction;
  if (!this->Pass(renWin, source, this->OutputBuffer, this->OutputTexture, w, h, true, {1.0f}, static_cast<float>(kept),
                  false))
    return false;
  for (const GlareKernel& k : kernels) {
    if (!this->Pass(renWin, source, this->TempBuffer, this->TempTexture, w, h, true, k.weights, 1.0f, false) ||
        !this->Pass(renWin, this->TempTexture, this->OutputBuffer, this->OutputTexture, w, h, false, k.weights,
                    static_cast<float>(k.energyFraction), true))
      return false;
  }
  return true;
}

void GlareRendering::ReleaseGraphicsResources(vtkWindow* w) {
  if (this->Quad) {
    this->Quad->ReleaseGraphicsResources(w);
    delete this->Quad;
    this->Quad = nullptr;
  }
  for (auto* t : {&this->TempTexture, &this->OutputTexture}) {
    if (*t) (*t)->ReleaseGraphicsResources(w);
    *t = nullptr;
  }
  for (auto* f : {&this->TempBuffer, &this->OutputBuffer}) {
    if (*f) (*f)->ReleaseGraphicsResources(w);
    *f = nullptr;
  }
}

} // namespace umbra::render
