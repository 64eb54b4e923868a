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
  SunLight sun;
  bool hasSun = false;
  double limbDarkening = 0.6;
  glm::dvec3 origin{0.0};
  std::unique_ptr<vtkOpenGLQuadHelper> sunQuad;
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

void StarRendering::SetSun(const SunLight& sun, double limbDarkening) {
  if (!(limbDarkening >= 0.0 && limbDarkening <= 1.0))
    throw std::invalid_argument("the Sun's limb darkening must be within [0, 1]");
  impl_->sun = sun;
  impl_->limbDarkening = limbDarkening;
  impl_->hasSun = true;
}

void StarRendering::SetOrigin(const glm::dvec3& originM) { impl_->origin = originM; }

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

/// A full-screen quad at depth 1 (gl_Position.z = w: drawn where the frame holds nothing)
/// whose fragments run `function` of StarSplat.glsl after `declarations`, bound; null when it
/// does not compile. Its corners come from both of the helper's attributes (texCoordIn =
/// (ndCoordIn + 1) / 2), so that neither is compiled away.
vtkShaderProgram* readyBackgroundQuad(vtkOpenGLRenderWindow* window, std::unique_ptr<vtkOpenGLQuadHelper>& quad,
                                      const std::string& declarations, const char* function) {
  if (!quad) {
    const char* vs = "//VTK::System::Dec\nin vec4 ndCoordIn;\nin vec2 texCoordIn;\n"
                     "void main() { gl_Position = vec4(0.5 * (ndCoordIn.xy + 2.0 * texCoordIn - 1.0), 1.0, 1.0); }\n";
    const std::string fs = "//VTK::System::Dec\n//VTK::Output::Dec\n" + declarations + "\n" + glsl::kStarSplat +
                           "\nvoid main() { gl_FragData[0] = " + function + "(); }\n";
    quad = std::make_unique<vtkOpenGLQuadHelper>(window, vs, fs.c_str(), "");
  } else {
    window->GetShaderCache()->ReadyShaderProgram(quad->Program);
  }
  vtkShaderProgram* p = quad->Program;
  return p && p->GetCompiled() ? p : nullptr;
}

}  // namespace

bool StarRendering::Draw(vtkOpenGLRenderWindow* window, vtkRenderer* renderer, int width, int height, bool withSun) {
  Impl& m = *impl_;
  vtkCamera* cam = renderer->GetActiveCamera();
  const bool sun = withSun && m.hasSun;
  if ((m.values.empty() && !m.milkyWay && !sun) || cam->GetParallelProjection()) return true;
  if (m.context != window) {
    ReleaseGraphicsResources(m.context);
    m.context = window;
    m.stale = true;
  }
  // The perspective ray basis, as the atmosphere's composite takes it.
  const CameraBasis basis = cameraBasis(cam, width, height);
  if (m.milkyWay && !DrawMilkyWay(window, basis, width, height)) return false;
  if (sun && !DrawSun(window, renderer, basis, width, height)) return false;
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
  vtkShaderProgram* p = readyBackgroundQuad(window, m.milkyWayQuad,
                                            std::string("#define UMBRA_MILKY_WAY\n") + sky::kMilkyWayGlsl, "umbraMilkyWay");
  if (!p) return false;
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

bool StarRendering::DrawSun(vtkOpenGLRenderWindow* window, vtkRenderer* renderer, const CameraBasis& basis, int width,
                            int height) {
  Impl& m = *impl_;
  glm::dvec3 position;
  renderer->GetActiveCamera()->GetPosition(&position.x);
  const glm::dvec3 toSun = m.sun.positionM - (m.origin + position);
  const double distanceM = glm::length(toSun);
  if (!(distanceM > m.sun.radiusM)) return true;  // inside the Sun: nothing to see
  const glm::dvec3 d = toSun / distanceM;
  const double f = glm::dot(d, basis.forward);
  if (f <= 0.0) return true;  // behind the camera
  // Where its centre falls (window coordinates) and how many pixels its radius spans there.
  const glm::dvec3 x = basis.rayX(), y = basis.rayY();
  const double ndcX = glm::dot(d, x) / glm::dot(x, x) / f, ndcY = glm::dot(d, y) / glm::dot(y, y) / f;
  const double alpha = std::asin(std::min(1.0, m.sun.radiusM / distanceM));
  // dir = F + ndc.x X + ndc.y Y: a pixel spans 2 |Y| / H of the image plane at distance
  // |F| from the eye, foreshortened by f^2 = cos^2 of its angle off the axis.
  const double pixelAngle = 2.0 * glm::length(y) / height * f * f / glm::length(basis.forward);
  const double radiusPixels = alpha / pixelAngle;
  const double reachPixels = kSunCoronaReachSolarRadii * radiusPixels + 2.0;  // the corona's
  if (std::abs(ndcX) > 1.0 + 2.0 * reachPixels / width || std::abs(ndcY) > 1.0 + 2.0 * reachPixels / height)
    return true;  // off the image
  vtkShaderProgram* p = readyBackgroundQuad(window, m.sunQuad, std::string("#define UMBRA_SUN_DISC\n") + glsl::kSunDisc,
                                            "umbraSunDisc");
  if (!p) return false;
  setRayBasis(p, basis, width, height);
  setVec3(p, "umbraSunFromCamera", d);
  p->SetUniformf("umbraSunAngularRadius", static_cast<float>(alpha));
  p->SetUniformf("umbraSolarIrradiance", static_cast<float>(m.sun.irradianceAtWm2(distanceM)));
  p->SetUniformf("umbraLimbDarkening", static_cast<float>(m.limbDarkening));
  const float pixel[2] = {static_cast<float>((0.5 * ndcX + 0.5) * width), static_cast<float>((0.5 * ndcY + 0.5) * height)};
  p->SetUniform2f("umbraSunPixel", pixel);
  p->SetUniformf("umbraSunRadiusPixels", static_cast<float>(radiusPixels));
  p->SetUniformf("umbraSunCoronaRadii", static_cast<float>(kSunCoronaReachSolarRadii));
  const AddWhereEmpty add(window->GetState());
  m.sunQuad->Render();
  return true;
}

void StarRendering::ReleaseGraphicsResources(vtkOpenGLRenderWindow* window) {
  Impl& m = *impl_;
  m.sunQuad = nullptr;
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
