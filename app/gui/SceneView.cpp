#include "SceneView.hpp"

#include <QVTKOpenGLNativeWidget.h>
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkLight.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkSphereSource.h>

#include <glm/geometric.hpp>

#include <map>
#include <string>

// Stand-in until the render library (BodyView) lands: Lambertian spheres lit by the Sun,
// placed relative to the camera (so float matrices never hold heliocentric offsets).

namespace umbra::gui {

struct SceneView::Impl {
  QVTKOpenGLNativeWidget* widget = nullptr;
  vtkSmartPointer<vtkRenderer> renderer;
  vtkSmartPointer<vtkLight> sunLight;
  std::map<std::string, vtkSmartPointer<vtkActor>> actors;
  double exposureEv = 0.0;
};

SceneView::SceneView(QVTKOpenGLNativeWidget* widget) : impl(std::make_unique<Impl>()) {
  impl->widget = widget;
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  widget->setRenderWindow(window);
  impl->renderer = vtkSmartPointer<vtkRenderer>::New();
  impl->renderer->SetBackground(0.0, 0.0, 0.0);
  impl->renderer->AutomaticLightCreationOff();
  impl->sunLight = vtkSmartPointer<vtkLight>::New();
  impl->sunLight->SetLightTypeToSceneLight();
  impl->sunLight->PositionalOff();
  impl->renderer->AddLight(impl->sunLight);
  window->AddRenderer(impl->renderer);
}

SceneView::~SceneView() = default;

vtkRenderer* SceneView::renderer() const { return impl->renderer; }

void SceneView::setScene(const scene::Scene& s, vtkImageData* /*shadowLut*/) {
  const glm::dvec3 origin = s.camera.positionM;
  // Bodies that are gone (another scene) leave the view.
  for (auto it = impl->actors.begin(); it != impl->actors.end();) {
    if (!s.find(it->first)) {
      impl->renderer->RemoveActor(it->second);
      it = impl->actors.erase(it);
    } else {
      ++it;
    }
  }
  for (const scene::Body& body : s.bodies) {
    if (body.isSun()) continue;
    auto& actor = impl->actors[body.name];
    if (!actor) {
      vtkNew<vtkSphereSource> sphere;
      sphere->SetThetaResolution(128);
      sphere->SetPhiResolution(64);
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputConnection(sphere->GetOutputPort());
      actor = vtkSmartPointer<vtkActor>::New();
      actor->SetMapper(mapper);
      actor->GetProperty()->SetAmbient(0.0);
      actor->GetProperty()->SetDiffuse(1.0);
      actor->GetProperty()->SetSpecular(0.0);
      impl->renderer->AddActor(actor);
    }
    const glm::dvec3 p = body.positionM - origin;
    actor->SetPosition(p.x, p.y, p.z);
    actor->SetScale(2.0 * body.radiusM);  // the source's diameter is 1
    actor->GetProperty()->SetColor(body.color.r, body.color.g, body.color.b);
    // From (or just above) a body's surface its sphere would only hide the sky.
    actor->SetVisibility(glm::length(p) > 1.001 * body.radiusM);
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

void SceneView::setExposureEV(double ev) { impl->exposureEv = ev; }

void SceneView::render() { impl->widget->renderWindow()->Render(); }

} // namespace umbra::gui
