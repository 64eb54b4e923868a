#include "vtkUmbraRenderPass.h"

#include "RenderGlsl.hpp"

#include <vtkObjectFactory.h>
#include <vtkOpenGLError.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderUtilities.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
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
  os << indent << "ToneMapping: " << (this->ToneMapping == Linear ? "Linear" : "Reinhard") << "\n";
  os << indent << "HDR frame: " << this->HdrWidth << "x" << this->HdrHeight
     << (this->HdrValid ? "" : " (none)") << "\n";
}

bool vtkUmbraRenderPass::PrepareBuffers(vtkOpenGLRenderWindow* renWin, int w, int h) {
  if (this->ColorTexture && this->ColorTexture->GetContext() != renWin) {
    this->ReleaseGraphicsResources(renWin);
  }
  if (!this->ColorTexture) {
    this->ColorTexture = vtkSmartPointer<vtkTextureObject>::New();
    this->ColorTexture->SetContext(renWin);
    // Nearest: the quad reads each texel at its own pixel centre, unfiltered.
    this->ColorTexture->SetMinificationFilter(vtkTextureObject::Nearest);
    this->ColorTexture->SetMagnificationFilter(vtkTextureObject::Nearest);
    this->ColorTexture->SetWrapS(vtkTextureObject::ClampToEdge);
    this->ColorTexture->SetWrapT(vtkTextureObject::ClampToEdge);
    this->ColorTexture->SetInternalFormat(GL_RGBA32F);
    this->ColorTexture->SetFormat(GL_RGBA);
    this->ColorTexture->SetDataType(GL_FLOAT);
    if (!this->ColorTexture->Allocate2D(w, h, 4, VTK_FLOAT)) return false;
  } else if (this->ColorTexture->GetWidth() != static_cast<unsigned>(w) ||
             this->ColorTexture->GetHeight() != static_cast<unsigned>(h)) {
    this->ColorTexture->Resize(w, h);
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

  // 1. The delegate into the float framebuffer.
  ostate->PushFramebufferBindings();
  this->FrameBufferObject->Bind();
  this->FrameBufferObject->AddColorAttachment(0, this->ColorTexture);
  this->FrameBufferObject->ActivateDrawBuffer(0);
  this->FrameBufferObject->AddDepthAttachment(this->DepthTexture);
  if (!this->FrameBufferObject->StartNonOrtho(w, h)) {
    ostate->PopFramebufferBindings();
    vtkErrorMacro("the float framebuffer is incomplete.");
    return;
  }
  ostate->vtkglViewport(0, 0, w, h);
  ostate->vtkglScissor(0, 0, w, h);
  ostate->vtkglEnable(GL_DEPTH_TEST);

  vtkRenderState s2(r);
  s2.SetPropArrayAndCount(s->GetPropArray(), s->GetPropArrayCount());
  s2.SetFrameBuffer(this->FrameBufferObject);
  this->DelegatePass->Render(&s2);
  this->NumberOfRenderedProps += this->DelegatePass->GetNumberOfRenderedProps();
  ostate->PopFramebufferBindings();

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
    return;
  }

  this->ColorTexture->Activate();
  vtkShaderProgram* program = this->QuadHelper->Program;
  program->SetUniformi("umbraHdr", this->ColorTexture->GetTextureUnit());
  program->SetUniformf("umbraExposureScale", static_cast<float>(std::exp2(this->ExposureEV)));
  program->SetUniformi("umbraToneMapping", this->ToneMapping);

  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglDisable(GL_DEPTH_TEST);
  ostate->vtkglViewport(x, y, w, h);
  ostate->vtkglScissor(x, y, w, h);
  this->QuadHelper->Render();
  this->ColorTexture->Deactivate();

  this->LastWindow = renWin;
  this->HdrWidth = w;
  this->HdrHeight = h;
  this->HdrValid = true;
  vtkOpenGLCheckErrorMacro("failed after vtkUmbraRenderPass::Render");
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
  this->FrameBufferObject->Bind(GL_READ_FRAMEBUFFER);
  this->FrameBufferObject->ActivateReadBuffer(0);
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

void vtkUmbraRenderPass::ReleaseGraphicsResources(vtkWindow* w) {
  this->Superclass::ReleaseGraphicsResources(w);
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
  this->HdrValid = false;
  this->LastWindow = nullptr;
}
