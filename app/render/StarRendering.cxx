#include "StarRendering.h"

#include "CameraBasis.h"
#include "RenderGlsl.hpp"

#include <vtkCamera.h>
#include <vtkOpenGLBufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
#include <vtkOpenGLVertexArrayObject.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkSmartPointer.h>
#include <vtk_glew.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

namespace umbra::render {
namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

struct StarRendering::Impl {
  std::vector<float> values;  // per star: direction xyz, irradiance rgb
  bool stale = true;
  vtkOpenGLRenderWindow* context = nullptr;
  vtkSmartPointer<vtkOpenGLBufferObject> buffer;
  vtkSmartPointer<vtkOpenGLVertexArrayObject> vao;
  vtkShaderProgram* program = nullptr;  // owned by the window's shader cache
};

StarRendering::StarRendering() : impl_(std::make_unique<Impl>()) {}
StarRendering::~StarRendering() = default;

void StarRendering::SetStars(const std::vector<StarPoint>& stars) {
  std::vector<float> values;
  values.reserve(stars.size() * 6);
  for (std::size_t i = 0; i < stars.size(); ++i) {
    const StarPoint& s = stars[i];
    if (!finite(s.direction) || std::abs(glm::length(s.direction) - 1.0) > 1e-6)
      throw std::invalid_argument("star " + std::to_string(i) + ": its direction is not a finite unit vector");
    if (!finite(s.irradianceWm2) || s.irradianceWm2.x < 0.0 || s.irradianceWm2.y < 0.0 || s.irradianceWm2.z < 0.0)
      throw std::invalid_argument("star " + std::to_string(i) + ": its irradiance is negative or not finite");
    for (int c = 0; c < 3; ++c) values.push_back(static_cast<float>(s.direction[c]));
    for (int c = 0; c < 3; ++c) values.push_back(static_cast<float>(s.irradianceWm2[c]));
  }
  impl_->values = std::move(values);
  impl_->stale = true;
}

std::size_t StarRendering::GetNumberOfStars() const { return impl_->values.size() / 6; }

bool StarRendering::Draw(vtkOpenGLRenderWindow* window, vtkRenderer* renderer, int width, int height) {
  Impl& m = *impl_;
  vtkCamera* cam = renderer->GetActiveCamera();
  if (m.values.empty() || cam->GetParallelProjection()) return true;
  if (m.context != window) {
    ReleaseGraphicsResources(m.context);
    m.context = window;
    m.stale = true;
  }
  if (!m.program) {
    const std::string vs = std::string("//VTK::System::Dec\n#define UMBRA_STAR_VERTEX\n") + glsl::kStarSplat;
    const std::string fs = std::string("//VTK::System::Dec\n//VTK::Output::Dec\n") + glsl::kStarSplat +
                           "\nvoid main() { gl_FragData[0] = umbraStarSplat(); }\n";
    m.program = window->GetShaderCache()->ReadyShaderProgram(vs.c_str(), fs.c_str(), "");
    m.stale = true;
  } else {
    window->GetShaderCache()->ReadyShaderProgram(m.program);
  }
  if (!m.program || !m.program->GetCompiled()) return false;
  if (!m.buffer) m.buffer = vtkSmartPointer<vtkOpenGLBufferObject>::New();
  if (!m.vao) m.vao = vtkSmartPointer<vtkOpenGLVertexArrayObject>::New();
  m.vao->Bind();
  if (m.stale) {
    if (!m.buffer->Upload(m.values, vtkOpenGLBufferObject::ArrayBuffer)) return false;
    m.vao->ReleaseGraphicsResources();
    m.vao->Bind();
    const int stride = 6 * sizeof(float);
    if (!m.vao->AddAttributeArray(m.program, m.buffer, "umbraStarDirection", 0, stride, VTK_FLOAT, 3, false) ||
        !m.vao->AddAttributeArray(m.program, m.buffer, "umbraStarIrradiance", 3 * sizeof(float), stride, VTK_FLOAT, 3,
                                  false))
      return false;
    m.stale = false;
  }

  // The perspective ray basis, as the atmosphere's composite takes it.
  const CameraBasis basis = cameraBasis(cam, width, height);
  setVec3(m.program, "umbraRayForward", basis.forward);
  setVec3(m.program, "umbraRayX", basis.rayX());
  setVec3(m.program, "umbraRayY", basis.rayY());
  const float size[2] = {static_cast<float>(width), static_cast<float>(height)};
  m.program->SetUniform2f("umbraViewportSize", size);

  vtkOpenGLState* ostate = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthTest(ostate, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(ostate);
  vtkOpenGLState::ScopedglDepthMask depthMask(ostate);
  ostate->vtkglEnable(GL_BLEND);
  ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  ostate->vtkglDepthFunc(GL_LEQUAL);
  ostate->vtkglDepthMask(GL_FALSE);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(GetNumberOfStars()));
  glDisable(GL_PROGRAM_POINT_SIZE);
  m.vao->Release();
  return true;
}

void StarRendering::ReleaseGraphicsResources(vtkOpenGLRenderWindow* window) {
  Impl& m = *impl_;
  if (m.vao) m.vao->ReleaseGraphicsResources();
  if (m.buffer) m.buffer->ReleaseGraphicsResources();
  if (m.program && window) m.program->ReleaseGraphicsResources(window);
  m.program = nullptr;
  m.vao = nullptr;
  m.buffer = nullptr;
  m.stale = true;
}

}  // namespace umbra::render
