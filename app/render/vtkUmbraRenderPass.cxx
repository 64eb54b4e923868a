#include "vtkUmbraRenderPass.h"

#include "AtmosphereRendering.h"
#include "Glare.h"
#include "RenderGlsl.hpp"
#include "StarRendering.h"
#include "NightVision.hpp"
#include "StarLight.hpp"

#include <vtkObjectFactory.h>
#include <vtkOpenGLError.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderUtilities.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
#include <vtkCamera.h>
#include <vtkRenderState.h>
#include <vtkRenderStepsPass.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <cmath>

vtkStandardNewMacro(vtkUmbraRenderPass);

vtkUmbraRenderPass::vtkUmbraRenderPass() {
  vtkNew<vtkRenderStepsPass> steps;
  this->SetDelegatePass(steps);
}

vtkUmbraRenderPass::~vtkUmbraRenderPass() = default;

void vtkUmbraRenderPass::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ExposureEV: " << this->ExposureEV << "\n";
  os << indent << "NightVision: " << (this->NightVision ? "on" : "off") << "\n";
  os << indent << "GlareStrength: " << this->GlareStrength << "\n";
  os << indent << "ToneMapping: " << (this->ToneMapping == Linear ? "Linear" : "Reinhard") << "\n";
  os << indent << "HDR frame: " << this->HdrWidth << "x" << this->HdrHeight
     << (this->HdrValid ? "" : " (none)") << "\n";
}

namespace {
// An RGBA32F colour buffer of w x h (re)allocated as needed; Nearest: the quads read each
// texel at its own pixel centre, unfiltered.
bool prepareColour(vtkSmartPointer<vtkTextureObject>& t, vtkOpenGLRenderWindow* renWin, int w, int h) {
  return umbra::render::prepareFloatTexture(t, renWin, w, h);
}
} // namespace

bool vtkUmbraRenderPass::PrepareBuffers(vtkOpenGLRenderWindow* renWin, int w, int h) {
  if (this->ColorTexture && this->ColorTexture->GetContext() != renWin) {
    this->ReleaseGraphicsResources(renWin);
  }
  if (!prepareColour(this->ColorTexture, renWin, w, h)) return false;
  if (this->Atmosphere && this->Atmosphere->HasAtmosphere()) {
    if (!prepareColour(this->ComposedTexture, renWin, w, h)) return false;
    if (!this->ComposedFrameBuffer) {
      this->ComposedFrameBuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
      this->ComposedFrameBuffer->SetContext(renWin);
    }
  }
  if (!this->DepthTexture) {
    this->DepthTexture = vtkSmartPointer<vtkTextureObject>::New();
    this->DepthTexture->SetContext(renWin);
    this->DepthTexture->SetWrapS(vtkTextureObject::ClampToEdge);
    this->DepthTexture->SetWrapT(vtkTextureObject::ClampToEdge);
    if (!this->DepthTexture->AllocateDepth(w, h, vtkTextureObject::Float32)) return false;
  } else if (this->DepthTexture->GetWidth() != static_cast<unsigned>(w) ||
             this->DepthTexture->GetHeight() != static_cast<unsigned>(h)) {
    this->DepthTexture->Resize(w, h);
  }
  if (!this->FrameBufferObject) {
    this->FrameBufferObject = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
    this->FrameBufferObject->SetContext(renWin);
  }
  return true;
}

void vtkUmbraRenderPass::Render(const vtkRenderState* s) {
  vtkOpenGLClearErrorMacro();
  this->NumberOfRenderedProps = 0;
  this->HdrValid = false;

  vtkRenderer* r = s->GetRenderer();
  auto* renWin = vtkOpenGLRenderWindow::SafeDownCast(r->GetRenderWindow());
  if (!renWin) {
    vtkErrorMacro("vtkUmbraRenderPass needs an OpenGL render window.");
    return;
  }
  if (!this->DelegatePass) {
    vtkWarningMacro("no delegate in vtkUmbraRenderPass.");
    return;
  }
  vtkOpenGLState* ostate = renWin->GetState();
  vtkOpenGLState::ScopedglEnableDisable bsaver(ostate, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable dsaver(ostate, GL_DEPTH_TEST);

  int x = 0, y = 0, w = 0, h = 0;
  r->GetTiledSizeAndOrigin(&w, &h, &x, &y);
  if (w < 1 || h < 1) return;
  if (!this->PrepareBuffers(renWin, w, h)) {
    vtkErrorMacro("cannot allocate the " << w << "x" << h << " float framebuffer.");
    return;
  }

  this->StageTimesPending = false;
  // Timestamps need GL 3.3 or ARB_timer_query (VTK asks for 3.2): without, no stage times.
  if (this->StageTiming && this->StageQueries.empty() && glQueryCounter && glGetQueryObjectui64v) {
    this->StageQueries.assign(kStageMarks, 0);
    glGenQueries(kStageMarks, this->StageQueries.data());
  }
  this->MarkStage(0);

  vtkTextureObject* hdr = this->ColorTexture;
  if (!this->DrawScene(s, renWin, w, h)) return;
  if (!this->ComposeAtmosphere(r, renWin, w, h, hdr)) return;
  this->MarkStage(3);
  if (!this->ApplyGlare(r, renWin, w, h, hdr)) return;
  this->MarkStage(4);
  if (!this->ToneMap(renWin, hdr, x, y, w, h)) return;
  this->MarkStage(5);
  this->StageTimesPending = this->StageTiming;

  this->LastWindow = renWin;
  this->HdrWidth = w;
  this->HdrHeight = h;
  this->HdrValid = true;
  vtkOpenGLCheckErrorMacro("failed after vtkUmbraRenderPass::Render");
}

bool vtkUmbraRenderPass::DrawScene(const vtkRenderState* s, vtkOpenGLRenderWindow* renWin, int w, int h) {
  vtkOpenGLState* ostate = renWin->GetState();
  vtkRenderer* r = s->GetRenderer();
  // 1. The delegate into the float framebuffer.
  ostate->PushFramebufferBindings();
  this->FrameBufferObject->Bind();
  this->FrameBufferObject->AddColorAttachment(0, this->ColorTexture);
  this->FrameBufferObject->ActivateDrawBuffer(0);
  this->FrameBufferObject->AddDepthAttachment(this->DepthTexture);
  if (!this->FrameBufferObject->StartNonOrtho(w, h)) {
    ostate->PopFramebufferBindings();
    vtkErrorMacro("the float framebuffer is incomplete.");
    return false;
  }
  ostate->vtkglViewport(0, 0, w, h);
  ostate->vtkglScissor(0, 0, w, h);
  ostate->vtkglEnable(GL_DEPTH_TEST);

  vtkRenderState s2(r);
  s2.SetPropArrayAndCount(s->GetPropArray(), s->GetPropArrayCount());
  s2.SetFrameBuffer(this->FrameBufferObject);
  this->DelegatePass->Render(&s2);
  this->NumberOfRenderedProps += this->DelegatePass->GetNumberOfRenderedProps();
  this->MarkStage(1);

  // 1a. The stars behind it.
  // The Sun with them where no atmosphere is composed (the composite draws it through the air).
  const bool sunHere = !(this->Atmosphere && this->Atmosphere->HasAtmosphere());
  if (this->Stars && !this->Stars->Draw(renWin, r, w, h, sunHere)) {
    ostate->PopFramebufferBindings();
    vtkErrorMacro("cannot draw the stars.");
    return false;
  }
  ostate->PopFramebufferBindings();
  this->MarkStage(2);
  return true;
}

bool vtkUmbraRenderPass::ComposeAtmosphere(vtkRenderer* r, vtkOpenGLRenderWindow* renWin, int w, int h,
                                           vtkTextureObject*& hdr) {
  vtkOpenGLState* ostate = renWin->GetState();
  // 1b. The atmosphere over it, into the composed buffer.
  this->HdrComposed = false;
  if (this->Atmosphere && this->Atmosphere->HasAtmosphere()) {
    ostate->PushFramebufferBindings();
    this->ComposedFrameBuffer->Bind();
    this->ComposedFrameBuffer->AddColorAttachment(0, this->ComposedTexture);
    this->ComposedFrameBuffer->ActivateDrawBuffer(0);
    if (!this->ComposedFrameBuffer->Start(w, h)) {
      ostate->PopFramebufferBindings();
      vtkErrorMacro("the composed float framebuffer is incomplete.");
      return false;
    }
    ostate->vtkglViewport(0, 0, w, h);
    ostate->vtkglScissor(0, 0, w, h);
    ostate->vtkglDisable(GL_BLEND);
    ostate->vtkglDisable(GL_DEPTH_TEST);
    bool drawn = false;
    try {
      drawn = this->Atmosphere->Draw(renWin, r, this->ColorTexture, this->DepthTexture, w, h);
    } catch (const std::exception& e) {
      vtkErrorMacro("atmosphere: " << e.what());
    }
    ostate->PopFramebufferBindings();
    if (!drawn) {
      vtkErrorMacro("cannot draw the atmosphere.");
      return false;
    }
    hdr = this->ComposedTexture;
    this->HdrComposed = true;
  }
  return true;
}

bool vtkUmbraRenderPass::ApplyGlare(vtkRenderer* r, vtkOpenGLRenderWindow* renWin, int w, int h, vtkTextureObject*& hdr) {
  // 1c. Glare.
  this->HdrGlared = false;
  if (this->GlareStrength > 0.0) {
    if (!this->Glare) this->Glare = std::make_unique<umbra::render::GlareRendering>();
    const double fovDeg = r->GetActiveCamera()->GetViewAngle();
    const auto kernels = umbra::render::glareKernels(this->GlareStrength, h / fovDeg);
    if (!this->Glare->Apply(renWin, hdr, w, h, kernels)) {
      vtkErrorMacro("cannot apply the glare.");
      return false;
    }
    hdr = this->Glare->Output();
    this->HdrGlared = true;
  }
  return true;
}

bool vtkUmbraRenderPass::ToneMap(vtkOpenGLRenderWindow* renWin, vtkTextureObject* hdr, int x, int y, int w, int h) {
  vtkOpenGLState* ostate = renWin->GetState();
  // 2. Tone-map onto the current framebuffer.
  if (!this->QuadHelper) {
    std::string fs = vtkOpenGLRenderUtilities::GetFullScreenQuadFragmentShaderTemplate();
    vtkShaderProgram::Substitute(fs, "//VTK::FSQ::Decl",
                                 std::string(umbra::render::glsl::kToneMap) + "\n//VTK::FSQ::Decl");
    vtkShaderProgram::Substitute(fs, "//VTK::FSQ::Impl",
                                 "  vec4 hdr = texture(umbraHdr, texCoord);\n"
                                 "  gl_FragData[0] = vec4(umbraDisplayColour(hdr.rgb), 1.0);\n"
                                 "//VTK::FSQ::Impl");
    this->QuadHelper = std::make_unique<vtkOpenGLQuadHelper>(
        renWin, vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(), fs.c_str(), "");
  } else {
    renWin->GetShaderCache()->ReadyShaderProgram(this->QuadHelper->Program);
  }
  if (!this->QuadHelper->Program || !this->QuadHelper->Program->GetCompiled()) {
    vtkErrorMacro("cannot build the tone-mapping shader program.");
    return false;
  }

  hdr->Activate();
  vtkShaderProgram* program = this->QuadHelper->Program;
  program->SetUniformi("umbraHdr", hdr->GetTextureUnit());
  program->SetUniformf("umbraExposureScale", static_cast<float>(std::exp2(this->ExposureEV)));
  program->SetUniformi("umbraToneMapping", this->ToneMapping);
  program->SetUniformi("umbraNightVision", this->NightVision ? 1 : 0);
  if (this->NightVision) {
    static const glm::dvec3 sun = umbra::sky::sunLinearSrgb();
    const float sunF[3] = {static_cast<float>(sun.x), static_cast<float>(sun.y), static_cast<float>(sun.z)};
    program->SetUniform3f("umbraSunLinearSrgb", sunF);
    static const double efficacy = umbra::sky::sunlightEfficacyLmPerW(), scotopic = umbra::sky::sunlightScotopicRatio();
    program->SetUniformf("umbraSunlightEfficacy", static_cast<float>(efficacy));
    program->SetUniformf("umbraSunlightScotopic", static_cast<float>(scotopic));
  }

  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglDisable(GL_DEPTH_TEST);
  ostate->vtkglViewport(x, y, w, h);
  ostate->vtkglScissor(x, y, w, h);
  this->QuadHelper->Render();
  hdr->Deactivate();
  return true;
}

bool vtkUmbraRenderPass::ReadHdrPixels(std::vector<float>& rgba, int& width, int& height) {
  rgba.clear();
  width = height = 0;
  vtkOpenGLRenderWindow* renWin = this->LastWindow;
  if (!this->HdrValid || !renWin || !this->FrameBufferObject) return false;
  renWin->MakeCurrent();
  vtkOpenGLState* ostate = renWin->GetState();
  rgba.resize(static_cast<std::size_t>(this->HdrWidth) * this->HdrHeight * 4);
  ostate->PushReadFramebufferBinding();
  vtkOpenGLFramebufferObject* fbo = this->HdrComposed ? this->ComposedFrameBuffer.Get() : this->FrameBufferObject.Get();
  if (this->HdrGlared) fbo = this->Glare->OutputFramebuffer();
  fbo->Bind(GL_READ_FRAMEBUFFER);
  fbo->ActivateReadBuffer(0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, this->HdrWidth, this->HdrHeight, GL_RGBA, GL_FLOAT, rgba.data());
  ostate->PopReadFramebufferBinding();
  if (glGetError() != GL_NO_ERROR) {
    rgba.clear();
    return false;
  }
  width = this->HdrWidth;
  height = this->HdrHeight;
  return true;
}

void vtkUmbraRenderPass::MarkStage(int stage) {
  if (this->StageTiming && !this->StageQueries.empty()) glQueryCounter(this->StageQueries[stage], GL_TIMESTAMP);
}

bool vtkUmbraRenderPass::GetLastStageTimes(StageTimes& times) {
  vtkOpenGLRenderWindow* renWin = this->LastWindow;
  if (!this->StageTimesPending || !renWin || this->StageQueries.size() != kStageMarks) return false;
  renWin->MakeCurrent();
  GLuint64 ns[kStageMarks] = {};
  for (int k = 0; k < kStageMarks; ++k) glGetQueryObjectui64v(this->StageQueries[k], GL_QUERY_RESULT, &ns[k]);
  auto ms = [&](int k) { return ns[k + 1] >= ns[k] ? (ns[k + 1] - ns[k]) * 1e-6 : 0.0; };
  times = {ms(0), ms(1), ms(2), ms(3), ms(4)};
  return true;
}

void vtkUmbraRenderPass::ReleaseGraphicsResources(vtkWindow* w) {
  this->Superclass::ReleaseGraphicsResources(w);
  if (!this->StageQueries.empty()) {
    if (auto* renWin = vtkOpenGLRenderWindow::SafeDownCast(w)) {
      renWin->MakeCurrent();
      glDeleteQueries(static_cast<GLsizei>(this->StageQueries.size()), this->StageQueries.data());
    }
    this->StageQueries.clear();
    this->StageTimesPending = false;
  }
  if (this->QuadHelper) {
    this->QuadHelper->ReleaseGraphicsResources(w);
    this->QuadHelper.reset();
  }
  if (this->FrameBufferObject) {
    this->FrameBufferObject->ReleaseGraphicsResources(w);
    this->FrameBufferObject = nullptr;
  }
  if (this->ColorTexture) {
    this->ColorTexture->ReleaseGraphicsResources(w);
    this->ColorTexture = nullptr;
  }
  if (this->DepthTexture) {
    this->DepthTexture->ReleaseGraphicsResources(w);
    this->DepthTexture = nullptr;
  }
  if (this->ComposedFrameBuffer) {
    this->ComposedFrameBuffer->ReleaseGraphicsResources(w);
    this->ComposedFrameBuffer = nullptr;
  }
  if (this->ComposedTexture) {
    this->ComposedTexture->ReleaseGraphicsResources(w);
    this->ComposedTexture = nullptr;
  }
  if (this->Glare) this->Glare->ReleaseGraphicsResources(w);
  if (this->Stars) this->Stars->ReleaseGraphicsResources(vtkOpenGLRenderWindow::SafeDownCast(w));
  if (this->Atmosphere) this->Atmosphere->ReleaseGraphicsResources(vtkOpenGLRenderWindow::SafeDownCast(w));
  this->HdrValid = false;
  this->LastWindow = nullptr;
}
