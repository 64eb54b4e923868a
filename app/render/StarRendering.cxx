#include "StarRendering.h"

#include "CameraBasis.h"
#include "MilkyWayGlsl.hpp"
#include "RenderGlsl.hpp"

#include <vtkCamera.h>
#include <vtkOpenGLBufferObject.h>
#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
#include <vtkOpenGLVertexArrayObject.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkSmartPointer.h>
#include <vtkTextureObject.h>
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
  std::shared_ptr<const MapTexels> milkyWay;
  double milkyWayScale = 0.0;
  vtkSmartPointer<vtkTextureObject> milkyWayTexture;  // of milkyWay in context
  std::unique_ptr<vtkOpenGLQuadHelper> milkyWayQuad;
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

void StarRendering::SetMilkyWay(std::shared_ptr<const MapTexels> map, double radianceScale) {
  if (!std::isfinite(radianceScale) || radianceScale < 0.0)
    throw std::invalid_argument("the Milky Way's radiance scale is negative or not finite");
  Impl& m = *impl_;
  if (map != m.milkyWay) m.milkyWayTexture = nullptr;
  m.milkyWay = radianceScale > 0.0 ? std::move(map) : nullptr;
  m.milkyWayScale = radianceScale;
}

namespace {

// The additive blend into the frame where it holds nothing (depth 1), for this scope.
struct AddWhereEmpty {
  vtkOpenGLState::ScopedglEnableDisable blend, depthTest;
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc;
  vtkOpenGLState::ScopedglDepthFunc depthFunc;
  vtkOpenGLState::ScopedglDepthMask depthMask;
  explicit AddWhereEmpty(vtkOpenGLState* s)
      : blend(s, GL_BLEND), depthTest(s, GL_DEPTH_TEST), blendFunc(s), depthFunc(s), depthMask(s) {
    s->vtkglEnable(GL_BLEND);
    s->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
    s->vtkglEnable(GL_DEPTH_TEST);
    s->vtkglDepthFunc(GL_LEQUAL);
    s->vtkglDepthMask(GL_FALSE);
  }
};

void setRayBasis(vtkShaderProgram* p, const CameraBasis& basis, int width, int height) {
  setVec3(p, "umbraRayForward", basis.forward);
  setVec3(p, "umbraRayX", basis.rayX());
  setVec3(p, "umbraRayY", basis.rayY());
  const float size[2] = {static_cast<float>(width), static_cast<float>(height)};
  p->SetUniform2f("umbraViewportSize", size);
}

}  // namespace

bool StarRendering::Draw(vtkOpenGLRenderWindow* window, vtkRenderer* renderer, int width, int height) {
  Impl& m = *impl_;
  vtkCamera* cam = renderer->GetActiveCamera();
  if ((m.values.empty() && !m.milkyWay) || cam->GetParallelProjection()) return true;
  if (m.context != window) {
    ReleaseGraphicsResources(m.context);
    m.context = window;
    m.stale = true;
  }
  // The perspective ray basis, as the atmosphere's composite takes it.
  const CameraBasis basis = cameraBasis(cam, width, height);
  if (m.milkyWay && !DrawMilkyWay(window, basis, width, height)) return false;
  if (m.values.empty()) return true;
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

  setRayBasis(m.program, basis, width, height);
  const AddWhereEmpty add(window->GetState());
  glEnable(GL_PROGRAM_POINT_SIZE);
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(GetNumberOfStars()));
  glDisable(GL_PROGRAM_POINT_SIZE);
  m.vao->Release();
  return true;
}

bool StarRendering::DrawMilkyWay(vtkOpenGLRenderWindow* window, const CameraBasis& basis, int width, int height) {
  Impl& m = *impl_;
  if (!m.milkyWayTexture) {
    m.milkyWayTexture = mapTextureObjectOf(window, *m.milkyWay);
    if (!m.milkyWayTexture) return false;
  }
  if (!m.milkyWayQuad) {
    // The quad at depth 1 (gl_Position.z = w): drawn where the frame holds nothing. Its
    // corners from both of the helper's attributes (texCoordIn = (ndCoordIn + 1) / 2), so
    // that neither is compiled away.
    const char* vs = "//VTK::System::Dec\nin vec4 ndCoordIn;\nin vec2 texCoordIn;\n"
                     "void main() { gl_Position = vec4(0.5 * (ndCoordIn.xy + 2.0 * texCoordIn - 1.0), 1.0, 1.0); }\n";
    const std::string fs = std::string("//VTK::System::Dec\n//VTK::Output::Dec\n#define UMBRA_MILKY_WAY\n") +
                           sky::kMilkyWayGlsl + "\n" + glsl::kStarSplat +
                           "\nvoid main() { gl_FragData[0] = umbraMilkyWay(); }\n";
    m.milkyWayQuad = std::make_unique<vtkOpenGLQuadHelper>(window, vs, fs.c_str(), "");
  } else {
    window->GetShaderCache()->ReadyShaderProgram(m.milkyWayQuad->Program);
  }
  vtkShaderProgram* p = m.milkyWayQuad->Program;
  if (!p || !p->GetCompiled()) return false;
  setRayBasis(p, basis, width, height);
  m.milkyWayTexture->Activate();
  p->SetUniformi("umbraMilkyWayMap", m.milkyWayTexture->GetTextureUnit());
  p->SetUniformf("umbraMilkyWayScale", static_cast<float>(m.milkyWayScale));
  p->SetUniformf("umbraMilkyWayRows", static_cast<float>(m.milkyWay->height));
  {
    const AddWhereEmpty add(window->GetState());
    m.milkyWayQuad->Render();
  }
  m.milkyWayTexture->Deactivate();
  return true;
}

void StarRendering::ReleaseGraphicsResources(vtkOpenGLRenderWindow* window) {
  Impl& m = *impl_;
  if (m.milkyWayTexture) m.milkyWayTexture->ReleaseGraphicsResources(window);
  m.milkyWayTexture = nullptr;
  m.milkyWayQuad = nullptr;
  if (m.vao) m.vao->ReleaseGraphicsResources();
  if (m.buffer) m.buffer->ReleaseGraphicsResources();
  if (m.program && window) m.program->ReleaseGraphicsResources(window);
  m.program = nullptr;
  m.vao = nullptr;
  m.buffer = nullptr;
  m.stale = true;
}

}  // namespace umbra::render
