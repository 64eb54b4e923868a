#include "SceneView.hpp"

#include <QVTKOpenGLNativeWidget.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkNew.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <string>
#include <vector>

#if UMBRA_GUI_HAS_RENDER
#include "BodyView.h"
#else
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkLight.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkSphereSource.h>

#include <map>
#endif

namespace umbra::gui {
namespace {

/// The render library's view of the scene's bodies. A body whose sphere (mean radius)
/// holds the camera - an observer standing below the mean radius, e.g. near a pole - is
/// shrunk to just below the camera, so that it still shadows the others.
struct RenderBody {
  std::string name;
  glm::dvec3 centreM;
  double radiusM;
  glm::dvec3 albedoRgb;  ///< the geometric albedo, tinted by the display colour
};

std::vector<RenderBody> renderBodies(const scene::Scene& s) {
  std::vector<RenderBody> out;
  for (const scene::Body& b : s.bodies) {
    if (b.isSun()) continue;
    const double mean = (b.color.r + b.color.g + b.color.b) / 3.0;
    const glm::dvec3 tint = mean > 0.0 ? b.color / mean : glm::dvec3(1.0);
    const double cameraDistance = glm::length(s.camera.positionM - b.positionM);
    const double radius = std::min(b.radiusM, cameraDistance * (1.0 - 1e-4));
    out.push_back({b.name, b.positionM, radius, b.albedo * tint});
  }
  return out;
}

} // namespace

#if UMBRA_GUI_HAS_RENDER

// The render library's BodyView (vtkUmbraRenderPass + EclipseShading) builds the renderer;
// the renderer is moved into the widget's render window and drawn there. BodyView's own
// window (offscreen, never rendered) only keeps the aspect ratio of the view for its
// clipping range.
struct SceneView::Impl {
  QVTKOpenGLNativeWidget* widget = nullptr;
  std::unique_ptr<render::BodyView> bodies;
  vtkSmartPointer<vtkRenderer> renderer;
};

SceneView::SceneView(QVTKOpenGLNativeWidget* widget) : impl(std::make_unique<Impl>()) {
  impl->widget = widget;
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  widget->setRenderWindow(window);
  // The view is the scene's camera (a physical observer): no mouse camera moves.
  widget->interactor()->SetInteractorStyle(nullptr);
  impl->bodies = std::make_unique<render::BodyView>(std::max(1, widget->width()), std::max(1, widget->height()), true);
  impl->renderer = impl->bodies->GetRenderer();
  impl->bodies->GetRenderWindow()->RemoveRenderer(impl->renderer);
  window->AddRenderer(impl->renderer);
}

SceneView::~SceneView() {
  // Release the renderer's OpenGL resources while the widget's context still exists.
  if (vtkRenderWindow* window = impl->widget->renderWindow()) window->RemoveRenderer(impl->renderer);
}

vtkRenderer* SceneView::renderer() const { return impl->renderer; }

void SceneView::setScene(const scene::Scene& s, vtkImageData* shadowLut) {
  const scene::Body& sun = s.sun();
  std::vector<render::SphereBody> bodies;
  for (const RenderBody& b : renderBodies(s)) bodies.push_back({b.name, b.centreM, b.radiusM, b.albedoRgb});
  render::SunLight light;
  light.positionM = sun.positionM;
  light.radiusM = sun.radiusM;
  impl->bodies->GetRenderWindow()->SetSize(std::max(1, impl->widget->width()), std::max(1, impl->widget->height()));
  impl->bodies->SetBodies(light, bodies, shadowLut);
  render::ViewCamera camera;
  camera.positionM = s.camera.positionM;
  camera.targetM = s.camera.targetM;
  camera.up = s.camera.up;
  camera.fovDeg = s.camera.fovDeg;
  impl->bodies->SetCamera(camera);
}

void SceneView::setExposureEV(double ev) { impl->bodies->SetExposureEV(ev); }

#else  // no render library yet: Lambertian spheres lit by the Sun, without the eclipse

struct SceneView::Impl {
  QVTKOpenGLNativeWidget* widget = nullptr;
  vtkSmartPointer<vtkRenderer> renderer;
  vtkSmartPointer<vtkLight> sunLight;
  std::map<std::string, vtkSmartPointer<vtkActor>> actors;
};

SceneView::SceneView(QVTKOpenGLNativeWidget* widget) : impl(std::make_unique<Impl>()) {
  impl->widget = widget;
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  widget->setRenderWindow(window);
  widget->interactor()->SetInteractorStyle(nullptr);  // the view is the scene's camera
  impl->renderer = vtkSmartPointer<vtkRenderer>::New();
  impl->renderer->AutomaticLightCreationOff();
  impl->sunLight = vtkSmartPointer<vtkLight>::New();
  impl->sunLight->SetLightTypeToSceneLight();
  impl->sunLight->PositionalOff();
  impl->renderer->AddLight(impl->sunLight);
  window->AddRenderer(impl->renderer);
}

SceneView::~SceneView() = default;

vtkRenderer* SceneView::renderer() const { return impl->renderer; }

void SceneView::setScene(const scene::Scene& s, vtkImageData*) {
  const glm::dvec3 origin = s.camera.positionM;  // camera-relative: no 1e11 m in float matrices
  for (auto& entry : impl->actors) impl->renderer->RemoveActor(entry.second);
  impl->actors.clear();
  for (const RenderBody& b : renderBodies(s)) {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetThetaResolution(128);
    sphere->SetPhiResolution(64);
    sphere->SetRadius(b.radiusM);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(sphere->GetOutputPort());
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    const glm::dvec3 p = b.centreM - origin;
    actor->SetPosition(p.x, p.y, p.z);
    const glm::dvec3 c = glm::min(glm::dvec3(1.0), 4.0 * b.albedoRgb);
    actor->GetProperty()->SetColor(c.r, c.g, c.b);
    // From (or just above) a body's surface its sphere would only hide the sky.
    actor->SetVisibility(glm::length(p) > 1.001 * b.radiusM);
    impl->renderer->AddActor(actor);
    impl->actors[b.name] = actor;
  }
  const glm::dvec3 sun = s.sun().positionM - origin;
  impl->sunLight->SetPosition(sun.x, sun.y, sun.z);
  impl->sunLight->SetFocalPoint(0.0, 0.0, 0.0);
  vtkCamera* camera = impl->renderer->GetActiveCamera();
  const glm::dvec3 target = s.camera.targetM - origin;
  camera->SetPosition(0.0, 0.0, 0.0);
  camera->SetFocalPoint(target.x, target.y, target.z);
  camera->SetViewUp(s.camera.up.x, s.camera.up.y, s.camera.up.z);
  camera->SetViewAngle(s.camera.fovDeg);
  impl->renderer->ResetCameraClippingRange();
}

void SceneView::setExposureEV(double) {}

#endif

void SceneView::render() { impl->widget->renderWindow()->Render(); }

} // namespace umbra::gui
