#include "SceneView.hpp"

#include "AtmosphereRendering.h"
#include "AtmosphereShadow.h"
#include "BodyView.h"
#include "SceneInputs.h"
#include "vtkAtmosphereTablesSource.h"
#include "vtkEclipseShadowLutSource.h"
#include "vtkUmbraRenderPass.h"

#include <QVTKOpenGLNativeWidget.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <optional>
#include <stdexcept>

// The render library's BodyView (vtkUmbraRenderPass + EclipseShading) builds the renderer;
// the renderer is moved into the widget's render window and drawn there. BodyView's own
// window (offscreen, never rendered) only keeps the view's aspect ratio for its clipping
// range.

namespace umbra::gui {

struct SceneView::Impl {
  QVTKOpenGLNativeWidget* widget = nullptr;
  std::unique_ptr<render::BodyView> bodies;
  vtkSmartPointer<vtkRenderer> renderer;
  vtkSmartPointer<vtkAtmosphereTablesSource> tables;
  vtkAtmosphereTablesSource* applied = nullptr;  // the tables the view's atmosphere holds
  // Near an occluder (Phobos by Mars) the view's own LuT over the receivers' ranges
  // (render::sceneLutRange), made again when they change; elsewhere the given one.
  vtkSmartPointer<vtkEclipseShadowLutSource> ranged;
  std::optional<eclipse::LutRange> rangedFor;
  int rangedHeight = 0;
  // The atmospheric shadow LuT of the other bodies (computed by the caller), the request
  // it was made for, the one the scene shown needs when it differs, and whether the
  // shading has it.
  vtkSmartPointer<vtkEclipseShadowLutSource> atmosphereShadow;
  std::optional<render::AtmosphereShadowRequest> shadowMadeFor, shadowMissing;
  bool shadowApplied = false, shadowCurrent = false;
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
  const render::SceneInputs in = render::sceneInputs(s);
  impl->bodies->GetRenderWindow()->SetSize(std::max(1, impl->widget->width()), std::max(1, impl->widget->height()));
  int dims[3] = {0, 0, 0};
  if (shadowLut) shadowLut->GetDimensions(dims);
  const auto range = shadowLut ? render::sceneLutRange(in.sun, in.bodies, in.bodies, /*darkUmbra=*/true, dims[1])
                               : std::nullopt;
  if (range && (!impl->ranged || range != impl->rangedFor || dims[1] != impl->rangedHeight)) {
    auto source = vtkSmartPointer<vtkEclipseShadowLutSource>::New();
    source->SetWidth(render::rangedLutWidth(*range, dims[0]));
    source->SetHeight(dims[1]);
    source->SetLutRange(*range);
    source->Update();
    if (source->GetOutput()->GetNumberOfPoints() == 0) throw std::runtime_error("the ranged shadow LuT could not be computed");
    impl->ranged = source;
    impl->rangedFor = range;
    impl->rangedHeight = dims[1];
  }
  impl->bodies->SetBodies(in.sun, in.bodies, range ? impl->ranged->GetOutput() : shadowLut);
  const bool drawn = impl->tables && in.atmosphere && impl->tables->GetAtmosphere() == in.atmosphere->model;
  render::AtmosphereRendering& atmosphere = impl->bodies->GetAtmosphere();
  const auto body = in.atmosphere ? std::find_if(in.bodies.begin(), in.bodies.end(),
                                                 [&](const render::SphereBody& b) { return b.name == in.atmosphere->body; })
                                  : in.bodies.end();
  if (drawn && impl->applied == impl->tables && atmosphere.HasAtmosphere() && body != in.bodies.end()) {
    atmosphere.SetCentre(body->centreM);  // the time moved: the same tables, no upload
  } else if (drawn) {
    render::applySceneAtmosphere(*impl->bodies, in, impl->tables, impl->tables->GetRefractedPaths());
    impl->applied = impl->tables;
  } else {
    atmosphere.ClearAtmosphere();
    impl->applied = nullptr;
  }
  // The atmospheric shadow: the table the view has for this body while the caller makes
  // the one the scene needs.
  const std::array<int, 2> size = this->sizeOfShadow();
  const auto wanted = drawn ? render::sceneAtmosphereShadowRequest(in, size[0], size[1]) : std::nullopt;
  impl->shadowCurrent = wanted && impl->shadowMadeFor && *wanted == *impl->shadowMadeFor;
  impl->shadowMissing = wanted && !impl->shadowCurrent ? wanted : std::nullopt;
  const bool usable = wanted && impl->shadowMadeFor && impl->shadowMadeFor->occluder == wanted->occluder;
  if (!usable) {
    if (impl->shadowApplied) impl->bodies->GetShading().SetAtmosphereShadowLut("", nullptr);
    impl->shadowApplied = false;
  } else if (!impl->shadowApplied) {
    impl->bodies->GetShading().SetAtmosphereShadowLut(impl->shadowMadeFor->occluder, impl->atmosphereShadow->GetOutput());
    impl->shadowApplied = true;
  }
  impl->bodies->SetCamera(in.camera);
}

std::array<int, 2> SceneView::sizeOfShadow() const {
  const auto sizes = this->newAtmosphereShadowSource();
  return {sizes->GetWidth(), sizes->GetHeight()};
}

const std::optional<render::AtmosphereShadowRequest>& SceneView::missingAtmosphereShadow() const {
  return impl->shadowMissing;
}

vtkSmartPointer<vtkEclipseShadowLutSource> SceneView::newAtmosphereShadowSource() const {
  auto source = vtkSmartPointer<vtkEclipseShadowLutSource>::New();
  if (this->smallShadowTables) render::useSmallEclipseShadowTables(source);
  return source;
}

void SceneView::setAtmosphereShadow(vtkEclipseShadowLutSource* source, const render::AtmosphereShadowRequest& request) {
  impl->atmosphereShadow = source;
  impl->shadowMadeFor = request;
  impl->shadowApplied = false;  // applied on the next setScene
}

vtkImageData* SceneView::atmosphereShadowLut() const {
  return impl->shadowApplied ? impl->atmosphereShadow->GetOutput() : nullptr;
}

bool SceneView::atmosphereShadowFromCache() const {
  return impl->atmosphereShadow && impl->atmosphereShadow->GetLastUpdateWasCacheHit();
}

bool SceneView::atmosphereShadowCurrent() const { return impl->shadowApplied && impl->shadowCurrent; }

void SceneView::setGlareStrength(double strength) { impl->bodies->GetRenderPass()->SetGlareStrength(strength); }

void SceneView::setAtmosphereTables(vtkAtmosphereTablesSource* tables) {
  impl->tables = tables;
  impl->applied = nullptr;  // applied again on the next setScene
}

vtkAtmosphereTablesSource* SceneView::atmosphereTables() const { return impl->tables; }

void SceneView::setExposureEV(double ev) { impl->bodies->SetExposureEV(ev); }

void SceneView::render() { impl->widget->renderWindow()->Render(); }

} // namespace umbra::gui
