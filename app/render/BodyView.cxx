#include "BodyView.h"

#include "vtkUmbraRenderPass.h"

#include "ShadowLutData.h"
#include "SolarDisc.hpp"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOutputWindow.h>
#include <vtkPNGWriter.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkSphereSource.h>
#include <vtkWindowToImageFilter.h>
#include <vtk_glew.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

namespace umbra::render {
namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// "0x0505 (GL_OUT_OF_MEMORY)".
std::string glErrorName(unsigned v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04x", v);
  const char* name = v == GL_INVALID_ENUM                    ? "GL_INVALID_ENUM"
                     : v == GL_INVALID_VALUE                 ? "GL_INVALID_VALUE"
                     : v == GL_INVALID_OPERATION             ? "GL_INVALID_OPERATION"
                     : v == GL_OUT_OF_MEMORY                 ? "GL_OUT_OF_MEMORY"
                     : v == GL_INVALID_FRAMEBUFFER_OPERATION ? "GL_INVALID_FRAMEBUFFER_OPERATION"
                                                             : nullptr;
  return name ? std::string(buf) + " (" + name + ")" : std::string(buf);
}

/// Text VTK writes to std::cout while alive (its framebuffer dumps on a failure) goes to
/// VTK's output window instead, with its other messages: stdout holds only umbra's output.
class CoutToOutputWindow {
public:
  CoutToOutputWindow() : previous_(std::cout.rdbuf(captured_.rdbuf())) {}
  ~CoutToOutputWindow() {
    std::cout.rdbuf(previous_);
    if (!captured_.str().empty()) vtkOutputWindow::GetInstance()->DisplayText(captured_.str().c_str());
  }
  CoutToOutputWindow(const CoutToOutputWindow&) = delete;
  CoutToOutputWindow& operator=(const CoutToOutputWindow&) = delete;

private:
  std::ostringstream captured_;
  std::streambuf* previous_;
};

struct BodyProp {
  SphereBody body;
  vtkSmartPointer<vtkSphereSource> source;
  vtkSmartPointer<vtkPolyDataMapper> mapper;
  vtkSmartPointer<vtkActor> actor;
};

} // namespace

struct BodyView::Impl {
  vtkSmartPointer<vtkRenderWindow> window;
  vtkSmartPointer<vtkRenderer> renderer;
  vtkSmartPointer<vtkUmbraRenderPass> pass;
  EclipseShading shading;
  AtmosphereRendering atmosphere;
  StarRendering stars;
  std::vector<BodyProp> bodies;
  ViewCamera camera;
  bool cameraSet = false;
  double nearM = 1.0, farM = 1000.0;
};

BodyView::BodyView(int width, int height, bool offscreen) : impl_(std::make_unique<Impl>()) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384) {
    throw std::invalid_argument("view size " + std::to_string(width) + "x" + std::to_string(height) +
                                " is outside 1..16384");
  }
  Impl& m = *impl_;
  m.pass = vtkSmartPointer<vtkUmbraRenderPass>::New();
  m.renderer = vtkSmartPointer<vtkRenderer>::New();
  m.renderer->SetBackground(0.0, 0.0, 0.0);
  m.renderer->SetBackgroundAlpha(0.0);
  // The receivers light themselves (the Sun); VTK's lights are not used.
  m.renderer->AutomaticLightCreationOff();
  m.renderer->RemoveAllLights();
  m.renderer->SetPass(m.pass);
  m.pass->SetAtmosphere(&m.atmosphere);
  m.pass->SetStars(&m.stars);
  m.window = vtkSmartPointer<vtkRenderWindow>::New();
  m.window->SetOffScreenRendering(offscreen ? 1 : 0);
  m.window->SetMultiSamples(0);
  m.window->SetSize(width, height);
  m.window->AddRenderer(m.renderer);
}

BodyView::~BodyView() {
  Impl& m = *impl_;
  m.shading.ClearReceivers();
  if (m.window) {
    m.renderer->SetPass(nullptr);
    m.pass->ReleaseGraphicsResources(m.window);
    m.window->Finalize();
  }
}

void BodyView::SetBodies(const SunLight& sun, const std::vector<SphereBody>& bodies, vtkImageData* shadowLut) {
  Impl& m = *impl_;
  if (!shadowLut) throw std::invalid_argument("BodyView needs a shadow LuT");
  if (bodies.size() > static_cast<std::size_t>(EclipseShading::kMaxOccluders) + 1) {
    throw std::invalid_argument("BodyView shows at most " + std::to_string(EclipseShading::kMaxOccluders + 1) +
                                " bodies (got " + std::to_string(bodies.size()) + ")");
  }
  std::set<std::string> names;
  for (const SphereBody& b : bodies) {
    validateBody(b);
    if (b.name.empty()) throw std::invalid_argument("every body needs a name");
    if (!names.insert(b.name).second) throw std::invalid_argument("body name '" + b.name + "' is used twice");
  }
  validateSun(sun);
  m.shading.SetShadowLut(shadowLut);  // validates before it changes anything
  m.shading.SetSun(sun);
  m.atmosphere.SetSun(sun);
  std::vector<eclipse::Occluder> occluders;
  for (const SphereBody& b : bodies) occluders.push_back(occluderOf(b));
  m.atmosphere.SetEclipsingBodies(occluders, std::make_shared<const eclipse::ShadowLut>(filters::fromImageData(shadowLut)));
  m.stars.SetSun(sun, eclipse::kDefaultLimbDarkening);

  m.shading.ClearReceivers();
  for (BodyProp& p : m.bodies) m.renderer->RemoveActor(p.actor);
  m.bodies.clear();
  m.shading.SetOccluders(bodies);

  const glm::dvec3 origin = m.cameraSet ? m.camera.positionM : glm::dvec3(0.0);
  for (const SphereBody& b : bodies) {
    BodyProp p;
    p.body = b;
    p.source = vtkSmartPointer<vtkSphereSource>::New();
    p.source->SetCenter(0.0, 0.0, 0.0);
    p.source->SetRadius(b.radiusM);
    p.source->SetThetaResolution(kSphereThetaResolution);
    p.source->SetPhiResolution(kSpherePhiResolution);
    p.source->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
    p.mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
    p.mapper->SetInputConnection(p.source->GetOutputPort());
    p.actor = vtkSmartPointer<vtkActor>::New();
    p.actor->SetMapper(p.mapper);
    m.shading.MakeReceiver(p.actor, b, origin);
    m.renderer->AddActor(p.actor);
    m.bodies.push_back(std::move(p));
  }
  // Bodies and camera move together (SetBodies, then SetCamera for the same time): the
  // camera of the time before may lie inside a body that has moved (an observer on Earth,
  // 1 minute: 1800 km), which SetCamera checks with the new camera.
  if (m.cameraSet) {
    try {
      UpdateClippingRange();
    } catch (const std::invalid_argument&) {
    }
  }
}

void BodyView::SetCamera(const ViewCamera& c) {
  if (!finite(c.positionM) || !finite(c.targetM) || !finite(c.up)) {
    throw std::invalid_argument("camera position, target and up must be finite");
  }
  const glm::dvec3 view = c.targetM - c.positionM;
  if (!(glm::length(view) > 0.0)) throw std::invalid_argument("camera target equals its position");
  const glm::dvec3 dir = glm::normalize(view);
  if (!(glm::length(c.up) > 0.0) || glm::length(glm::cross(dir, glm::normalize(c.up))) < 1e-9) {
    throw std::invalid_argument("camera up vector is zero or parallel to the view direction");
  }
  if (c.parallel) {
    if (!(std::isfinite(c.parallelScaleM) && c.parallelScaleM > 0.0)) {
      throw std::invalid_argument("parallel camera needs parallelScaleM > 0");
    }
  } else if (!(std::isfinite(c.fovDeg) && c.fovDeg > 0.0 && c.fovDeg < 180.0)) {
    throw std::invalid_argument("camera field of view must be in (0, 180) degrees");
  }
  Impl& m = *impl_;
  const ViewCamera previous = m.camera;
  const bool previousSet = m.cameraSet;
  m.camera = c;
  m.cameraSet = true;
  try {
    UpdateClippingRange();  // throws when the camera is inside a body
  } catch (...) {
    m.camera = previous;
    m.cameraSet = previousSet;
    throw;
  }
  vtkCamera* cam = m.renderer->GetActiveCamera();
  cam->SetPosition(0.0, 0.0, 0.0);
  cam->SetFocalPoint(view.x, view.y, view.z);
  cam->SetViewUp(c.up.x, c.up.y, c.up.z);
  cam->OrthogonalizeViewUp();
  cam->SetParallelProjection(c.parallel ? 1 : 0);
  if (c.parallel) cam->SetParallelScale(c.parallelScaleM);
  else cam->SetViewAngle(c.fovDeg);
  cam->SetClippingRange(m.nearM, m.farM);
  m.shading.SetOrigin(c.positionM);
  m.atmosphere.SetOrigin(c.positionM);
  m.stars.SetOrigin(c.positionM);
}

const ViewCamera& BodyView::GetCamera() const { return impl_->camera; }

void BodyView::GetClippingRange(double& nearM, double& farM) const {
  nearM = impl_->nearM;
  farM = impl_->farM;
}

void BodyView::UpdateClippingRange() {
  Impl& m = *impl_;
  const ViewCamera& c = m.camera;
  const glm::dvec3 dir = glm::normalize(c.targetM - c.positionM);
  double nearest = std::numeric_limits<double>::infinity();  // perspective: distance to a surface
  double nearestZ = std::numeric_limits<double>::infinity(); // parallel: view depth of a surface
  double farthest = 0.0;
  bool any = false;
  for (const BodyProp& p : m.bodies) {
    const glm::dvec3 v = p.body.centreM - c.positionM;
    const double r = p.body.radiusM;
    const double dist = glm::length(v);
    if (!c.parallel && dist <= r) throw std::invalid_argument("camera is inside body '" + p.body.name + "'");
    const double z = glm::dot(v, dir);
    if (z + r <= 0.0) continue;  // wholly behind the camera
    any = true;
    nearest = std::min(nearest, dist - r);
    nearestZ = std::min(nearestZ, z - r);
    farthest = std::max(farthest, z + r);
  }
  if (!any) {
    m.nearM = 1.0;
    m.farM = 1000.0;
  } else if (c.parallel) {
    m.farM = farthest * 1.01;
    m.nearM = nearestZ > 0.0 ? nearestZ * 0.99 : m.farM * 1e-9;  // a body across the camera plane is cut
  } else {
    // A visible point at distance >= `nearest` lies within the frustum's half-diagonal
    // angle of the axis, so its view depth is at least nearest * cos(that angle).
    const int* size = m.window->GetSize();
    const double aspect = size[1] > 0 ? double(size[0]) / size[1] : 1.0;
    const double t = std::tan(0.5 * c.fovDeg * 3.14159265358979323846 / 180.0);
    const double cosDiag = 1.0 / std::sqrt(1.0 + t * t * (1.0 + aspect * aspect));
    m.farM = farthest * 1.01;
    m.nearM = std::max(0.5 * nearest * cosDiag, m.farM * 1e-15);
  }
  if (!(m.farM > m.nearM)) m.farM = 2.0 * m.nearM;
  if (m.cameraSet) m.renderer->GetActiveCamera()->SetClippingRange(m.nearM, m.farM);
}

void BodyView::SetExposureEV(double ev) {
  if (!std::isfinite(ev)) throw std::invalid_argument("exposure EV must be finite");
  impl_->pass->SetExposureEV(ev);
}

void BodyView::SetToneMapping(int mode) {
  if (mode != vtkUmbraRenderPass::Linear && mode != vtkUmbraRenderPass::Reinhard) {
    throw std::invalid_argument("unknown tone mapping " + std::to_string(mode));
  }
  impl_->pass->SetToneMapping(mode);
}

void BodyView::Render() {
  Impl& m = *impl_;
  if (!m.cameraSet) throw std::runtime_error("BodyView::Render: SetCamera first");
  m.renderer->GetActiveCamera()->SetClippingRange(m.nearM, m.farM);
  {
    CoutToOutputWindow quiet;
    m.window->Render();
  }
  m.window->MakeCurrent();
  std::string errors;
  bool outOfMemory = false;
  for (int i = 0; i < 16; ++i) {
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) break;
    outOfMemory = outOfMemory || e == GL_OUT_OF_MEMORY;
    errors += (errors.empty() ? "" : ", ") + glErrorName(e);
  }
  if (outOfMemory) {
    const int* size = m.window->GetSize();
    throw std::runtime_error("OpenGL ran out of memory rendering " + std::to_string(size[0]) + " x " +
                             std::to_string(size[1]) + " pixels (" + errors + "): give a smaller image size");
  }
  if (!errors.empty()) throw std::runtime_error("OpenGL error(s) " + errors + " while rendering");
}

vtkRenderWindow* BodyView::GetRenderWindow() { return impl_->window; }
vtkRenderer* BodyView::GetRenderer() { return impl_->renderer; }
vtkUmbraRenderPass* BodyView::GetRenderPass() { return impl_->pass; }
EclipseShading& BodyView::GetShading() { return impl_->shading; }
AtmosphereRendering& BodyView::GetAtmosphere() { return impl_->atmosphere; }
void BodyView::SetStars(const std::vector<StarPoint>& stars) { impl_->stars.SetStars(stars); }

void BodyView::SetMilkyWay(std::shared_ptr<const MapTexels> map, double radianceScale) {
  impl_->stars.SetMilkyWay(std::move(map), radianceScale);
}

void BodyView::WritePng(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (path.empty() || !fs::is_directory(dir, ec)) {
    throw std::runtime_error("cannot write PNG '" + path + "': no such directory");
  }
  const fs::path tmp = dir / ("." + target.filename().string() + ".tmp.png");
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(impl_->window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(tmp.string().c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode() != 0 || !fs::exists(tmp, ec)) {
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot write PNG '" + path + "'");
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    const std::string why = ec.message();  // before the removal sets ec again
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot write PNG '" + path + "': " + why);
  }
}

void BodyView::ReadHdr(std::vector<float>& rgb, int& width, int& height) {
  std::vector<float> rgba;
  int w = 0, h = 0;
  if (!impl_->pass->ReadHdrPixels(rgba, w, h)) throw std::runtime_error("no HDR frame to read (render first)");
  rgb.assign(static_cast<std::size_t>(w) * h * 3, 0.0f);
  std::size_t bad = 0;
  for (int row = 0; row < h; ++row) {
    const float* src = &rgba[static_cast<std::size_t>(h - 1 - row) * w * 4];
    float* dst = &rgb[static_cast<std::size_t>(row) * w * 3];
    for (int i = 0; i < w; ++i) {
      for (int c = 0; c < 3; ++c) {
        const float v = src[4 * i + c];
        if (!std::isfinite(v)) ++bad;
        dst[3 * i + c] = v;
      }
    }
  }
  if (bad) throw std::runtime_error("HDR frame holds " + std::to_string(bad) + " non-finite values");
  width = w;
  height = h;
}

} // namespace umbra::render
