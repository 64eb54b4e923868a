#include "SceneView.hpp"

#include "AtmosphereRendering.h"
#include "AtmosphereShadow.h"
#include "BodyView.h"
#include "SceneInputs.h"
#include "vtkAtmosphereTablesSource.h"
#include "vtkEclipseShadowLutSource.h"
#include "vtkLimbLuminanceSource.h"
#include "vtkUmbraRenderPass.h"

#include <QVTKOpenGLNativeWidget.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkCommand.h>
#include <vtkCallbackCommand.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

// The render library's BodyView (vtkUmbraRenderPass + EclipseShading) builds the renderer;
// the renderer is moved into the widget's render window and drawn there. BodyView's own
// window (offscreen, never rendered) only keeps the view's aspect ratio for its clipping
// range.

namespace umbra::gui {
namespace {

// An eclipse table of the atmosphere's body computed by the caller: the source, the request
// it was made for, the one the scene shown needs when it differs, and whether the view
// draws with it.
template <class Source, class Request>
struct HeldTable {
  vtkSmartPointer<Source> source;
  std::optional<Request> madeFor, missing;
  bool applied = false, current = false;

  // The scene shown wants `wanted`: the table is current when made for it, else missing;
  // the view draws with it while it is for the same body (apply(its output)), else with
  // none (apply(nullptr)).
  template <class Apply>
  void follow(const std::optional<Request>& wanted, const Apply& apply) {
    this->current = wanted && this->madeFor && *wanted == *this->madeFor;
    this->missing = wanted && !this->current ? wanted : std::nullopt;
    const bool usable = wanted && this->madeFor && this->madeFor->occluder == wanted->occluder;
    if (!usable) {
      if (this->applied) apply(nullptr);
      this->applied = false;
    } else if (!this->applied) {
      apply(this->source->GetOutput());
      this->applied = true;
    }
  }
  void set(Source* s, const Request& request) {
    this->source = s;
    this->madeFor = request;
    this->applied = false;  // applied on the next setScene
  }
  vtkImageData* output() const { return this->applied ? this->source->GetOutput() : nullptr; }
  bool fromCache() const { return this->source && this->source->GetLastUpdateWasCacheHit(); }
};

template <class Source>
std::array<int, 2> sizeOf(const vtkSmartPointer<Source>& source) {
  return {source->GetWidth(), source->GetHeight()};
}

} // namespace

struct SceneView::Impl {
  QVTKOpenGLNativeWidget* widget = nullptr;
  std::unique_ptr<render::BodyView> bodies;
  vtkSmartPointer<vtkRenderer> renderer;
  vtkSmartPointer<vtkAtmosphereTablesSource> tables;
  vtkAtmosphereTablesSource* applied = nullptr;  // the tables the view's atmosphere holds
  pipeline::AtmosphereTableChoice tablesChoice;    // what `tables` were configured for
  std::optional<pipeline::AtmosphereTableChoice> missingTables;
  // Near an occluder (Phobos by Mars) the view's own LuT over the receivers' ranges
  // (pipeline::sceneLutRange), made again when they change; elsewhere the given one.
  vtkSmartPointer<vtkEclipseShadowLutSource> ranged;
  std::optional<eclipse::LutRange> rangedFor;
  int rangedHeight = 0;
  // The atmospheric shadow LuT of the other bodies and the limb-luminance LuT of the ring.
  HeldTable<vtkEclipseShadowLutSource, pipeline::AtmosphereShadowRequest> shadow;
  HeldTable<vtkLimbLuminanceSource, pipeline::LimbLuminanceRequest> limb;
  double ringThresholdPx = 5.0;
  std::function<void()> onFrame;
  vtkNew<vtkCallbackCommand> frameEnded;
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
  impl->bodies->GetRenderPass()->SetStageTiming(true);
  impl->frameEnded->SetClientData(impl.get());
  impl->frameEnded->SetCallback([](vtkObject*, unsigned long, void* data, void*) {
    if (const auto& f = static_cast<Impl*>(data)->onFrame) f();
  });
  window->AddObserver(vtkCommand::EndEvent, impl->frameEnded);
}

SceneView::~SceneView() {
  impl->onFrame = nullptr;
  if (vtkRenderWindow* window = impl->widget->renderWindow()) window->RemoveObserver(impl->frameEnded);
  // Release the renderer's OpenGL resources while the widget's context still exists.
  if (vtkRenderWindow* window = impl->widget->renderWindow()) window->RemoveRenderer(impl->renderer);
}

vtkRenderer* SceneView::renderer() const { return impl->renderer; }

void SceneView::setScene(const scene::Scene& s, vtkImageData* shadowLut) {
  const pipeline::SceneInputs in = pipeline::sceneInputs(s);
  impl->bodies->GetRenderWindow()->SetSize(std::max(1, impl->widget->width()), std::max(1, impl->widget->height()));
  int dims[3] = {0, 0, 0};
  if (shadowLut) shadowLut->GetDimensions(dims);
  const auto range = shadowLut ? pipeline::sceneLutRange(in.sun, in.bodies, in.bodies, /*darkUmbra=*/true, dims[1])
                               : std::nullopt;
  if (range && (!impl->ranged || range != impl->rangedFor || dims[1] != impl->rangedHeight)) {
    auto source = vtkSmartPointer<vtkEclipseShadowLutSource>::New();
    source->SetWidth(pipeline::rangedLutWidth(*range, dims[0]));
    source->SetHeight(dims[1]);
    source->SetLutRange(*range);
    source->Update();
    if (source->GetOutput()->GetNumberOfPoints() == 0) throw std::runtime_error("the ranged shadow LuT could not be computed");
    impl->ranged = source;
    impl->rangedFor = range;
    impl->rangedHeight = dims[1];
  }
  impl->bodies->SetBodies(in.sun, in.bodies, range ? impl->ranged->GetOutput() : shadowLut);
  pipeline::showSceneSky(*impl->bodies, in);
  const bool drawn = impl->tables && in.atmosphere && impl->tables->GetAtmosphere() == in.atmosphere->model->name();
  render::AtmosphereRendering& atmosphere = impl->bodies->GetAtmosphere();
  const auto body = in.atmosphere ? std::find_if(in.bodies.begin(), in.bodies.end(),
                                                 [&](const render::SphereBody& b) { return b.name == in.atmosphere->body; })
                                  : in.bodies.end();
  if (drawn && impl->applied == impl->tables && atmosphere.HasAtmosphere() && body != in.bodies.end()) {
    atmosphere.SetCentre(body->centreM);  // the time moved: the same tables, no upload
  } else if (drawn) {
    pipeline::showSceneAtmosphereTables(*impl->bodies, in, impl->tables);
    impl->applied = impl->tables;
  } else {
    atmosphere.ClearAtmosphere();
    impl->applied = nullptr;
  }
  const pipeline::AtmosphereTableChoice wanted = pipeline::atmosphereTableChoice(in);
  impl->missingTables.reset();
  if (drawn && wanted != impl->tablesChoice) impl->missingTables = wanted;
  // The atmospheric shadow and the limb luminance: the tables the view has for this body
  // while the caller makes the ones the scene needs.
  const auto shadowSize = sizeOf(this->newAtmosphereShadowSource());
  impl->shadow.follow(drawn ? pipeline::sceneAtmosphereShadowRequest(in, shadowSize[0], shadowSize[1]) : std::nullopt,
                      [&](vtkImageData* lut) {
                        const std::string occluder = lut ? impl->shadow.madeFor->occluder : "";
                        impl->bodies->GetShading().SetAtmosphereShadowLut(occluder, lut);
                      });
  const auto limbSize = sizeOf(this->newLimbLuminanceSource());
  atmosphere.SetLimbRingThresholdPixels(impl->ringThresholdPx);
  // The sky of a solar eclipse at interactive rates: the quadrature's quick knobs.
  atmosphere.SetEclipsedSkyOptions(umbra::atmosphere::draftEclipsedSkyOptions());
  impl->limb.follow(drawn ? pipeline::sceneLimbLuminanceRequest(in, limbSize[0], limbSize[1], impl->ringThresholdPx)
                          : std::nullopt,
                    [&](vtkImageData* lut) { atmosphere.SetLimbLuminance(lut); });
  impl->bodies->SetCamera(in.camera);
}

const std::optional<pipeline::AtmosphereShadowRequest>& SceneView::missingAtmosphereShadow() const {
  return impl->shadow.missing;
}

vtkSmartPointer<vtkEclipseShadowLutSource> SceneView::newAtmosphereShadowSource() const {
  auto source = vtkSmartPointer<vtkEclipseShadowLutSource>::New();
  if (this->smallShadowTables) pipeline::useSmallEclipseShadowTables(source);
  return source;
}

void SceneView::setAtmosphereShadow(vtkEclipseShadowLutSource* source, const pipeline::AtmosphereShadowRequest& request) {
  impl->shadow.set(source, request);
}

vtkImageData* SceneView::atmosphereShadowLut() const { return impl->shadow.output(); }

bool SceneView::atmosphereShadowFromCache() const { return impl->shadow.fromCache(); }

bool SceneView::atmosphereShadowCurrent() const { return impl->shadow.applied && impl->shadow.current; }

const std::optional<pipeline::LimbLuminanceRequest>& SceneView::missingLimbLuminance() const {
  return impl->limb.missing;
}

vtkSmartPointer<vtkLimbLuminanceSource> SceneView::newLimbLuminanceSource() const {
  auto source = vtkSmartPointer<vtkLimbLuminanceSource>::New();
  if (this->smallShadowTables) pipeline::useSmallLimbLuminanceTables(source);
  return source;
}

void SceneView::setLimbLuminance(vtkLimbLuminanceSource* source, const pipeline::LimbLuminanceRequest& request) {
  impl->limb.set(source, request);
}

bool SceneView::hasLimbLuminance() const { return impl->limb.applied; }

bool SceneView::limbLuminanceCurrent() const { return impl->limb.applied && impl->limb.current; }

bool SceneView::limbLuminanceFromCache() const { return impl->limb.fromCache(); }

void SceneView::setLimbRingThresholdPixels(double px) {
  if (!(std::isfinite(px) && px >= 0.0)) throw std::invalid_argument("limb ring threshold must be finite and >= 0 px");
  impl->ringThresholdPx = px;
}

double SceneView::limbRingThresholdPixels() const { return impl->ringThresholdPx; }

bool SceneView::lastDrawUsedLimbLuminance() const {
  return impl->bodies->GetAtmosphere().GetLastDrawUsedLimbLuminance();
}

double SceneView::lastRingWidthPixels() const { return impl->bodies->GetAtmosphere().GetLastRingWidthPixels(); }

void SceneView::setGlareStrength(double strength) { impl->bodies->GetRenderPass()->SetGlareStrength(strength); }
void SceneView::setNightVision(bool on) { impl->bodies->GetRenderPass()->SetNightVision(on); }

void SceneView::setAtmosphereTables(vtkAtmosphereTablesSource* tables, const pipeline::AtmosphereTableChoice& choice) {
  impl->tables = tables;
  impl->tablesChoice = choice;
  impl->missingTables.reset();
  impl->applied = nullptr;  // applied again on the next setScene
}

vtkAtmosphereTablesSource* SceneView::atmosphereTables() const { return impl->tables; }

const std::optional<pipeline::AtmosphereTableChoice>& SceneView::missingAtmosphereTables() const {
  return impl->missingTables;
}

void SceneView::setExposureEV(double ev) { impl->bodies->SetExposureEV(ev); }

void SceneView::render() { impl->widget->renderWindow()->Render(); }

std::optional<vtkUmbraRenderPass::StageTimes> SceneView::lastStageTimes() const {
  vtkUmbraRenderPass::StageTimes t;
  if (!impl->bodies->GetRenderPass()->GetLastStageTimes(t)) return std::nullopt;
  return t;
}

void SceneView::setOnFrame(std::function<void()> onFrame) { impl->onFrame = std::move(onFrame); }

} // namespace umbra::gui
