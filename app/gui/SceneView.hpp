#pragma once
// The 3D view: a scene's bodies seen from its camera, drawn into a Qt VTK widget's render
// window. The glue between umbra::scene and the render library lives here and nowhere
// else in the GUI, so that the GUI follows the render library with small changes.
#include "AtmosphereShadow.h"
#include "SceneInputs.h"
#include "scene/Scene.hpp"
#include "vtkUmbraRenderPass.h"

#include <vtkSmartPointer.h>

#include <array>
#include <functional>
#include <memory>
#include <optional>

class QVTKOpenGLNativeWidget;
class vtkAtmosphereTablesSource;
class vtkEclipseShadowLutSource;
class vtkImageData;
class vtkLimbLuminanceSource;
class vtkRenderer;

namespace umbra::gui {

class SceneView {
public:
  explicit SceneView(QVTKOpenGLNativeWidget* widget);
  ~SceneView();
  SceneView(const SceneView&) = delete;
  SceneView& operator=(const SceneView&) = delete;

  /// Shows the scene (bodies, camera, exposure). Call again after the time changed. The
  /// shadow LuT is the table the render library samples; near an occluder, where a whole
  /// LuT is too coarse (pipeline::sceneLutRange: Phobos by Mars), the view makes its own over
  /// the receivers' ranges with as many rows.
  void setScene(const scene::Scene& scene, vtkImageData* shadowLut);
  void setExposureEV(double ev);
  /// The GPU time of the last frame drawn, per stage of the render pass (GL timestamps:
  /// vtkUmbraRenderPass::SetStageTiming, on for this view); none before the first frame.
  /// `onFrame` is called after every frame (the widget's render window's EndEvent).
  std::optional<vtkUmbraRenderPass::StageTimes> lastStageTimes() const;
  void setOnFrame(std::function<void()> onFrame);
  /// Glare strength (vtkUmbraRenderPass::SetGlareStrength), 0..10.
  void setGlareStrength(double strength);
  /// Night vision on the display (vtkUmbraRenderPass::SetNightVision).
  void setNightVision(bool on);
  /// Tables (already updated) for the atmosphere the scene asks for; nullptr: none. The
  /// atmosphere is drawn while the scene's atmosphere is the one the tables were made for
  /// (they are applied again on every setScene, as the body moves). Call setScene next.
  /// Tables made with refracted paths and the refraction table (SetRefractedPaths): the
  /// view bends its rays (pipeline::showSceneAtmosphereTables). `choice`: the scene choice
  /// they were configured for (pipeline::configureSceneAtmosphereTables).
  void setAtmosphereTables(vtkAtmosphereTablesSource* tables, const pipeline::AtmosphereTableChoice& choice = {});
  vtkAtmosphereTablesSource* atmosphereTables() const;
  /// After setScene: the choice of tables the scene's sky needs when it is not the one of
  /// the tables drawn (pipeline::atmosphereTableChoice: the Sun has set at the camera, or
  /// risen, or gone another 10 deg down, or night has fallen); none otherwise. The view
  /// draws the ones it has meanwhile; the caller makes the others (MainWindow: in a
  /// TableJobs worker) and hands them over with setAtmosphereTables.
  const std::optional<pipeline::AtmosphereTableChoice>& missingAtmosphereTables() const;

  /// The other bodies in the shadow of the body with the atmosphere are shaded with its
  /// atmospheric shadow LuT (pipeline::sceneAtmosphereShadowRequest: their columns only), as
  /// `umbra render` shades them. The view does not compute it: after setScene this is the
  /// request for the scene shown when the view has no table for it (none when it has, or
  /// needs none); the caller computes it (MainWindow: in a TableJobs worker, with
  /// newAtmosphereShadowSource) and hands it over with setAtmosphereShadow. Meanwhile the
  /// view shades with the table it has for that body (another time or model), or airless.
  const std::optional<pipeline::AtmosphereShadowRequest>& missingAtmosphereShadow() const;
  /// A source with the view's table sizes (small: pipeline::useSmallEclipseShadowTables, else
  /// the defaults, as `umbra render --atmosphere-tables`), the default cache.
  vtkSmartPointer<vtkEclipseShadowLutSource> newAtmosphereShadowSource() const;
  void useSmallAtmosphereShadowTables(bool small) { this->smallShadowTables = small; }
  /// The table for `request` (pipeline::updateAtmosphereShadow done). Call setScene next.
  void setAtmosphereShadow(vtkEclipseShadowLutSource* source, const pipeline::AtmosphereShadowRequest& request);
  /// The atmospheric shadow LuT the view shades with (a part of the whole table: its
  /// extent), or null (airless), and whether it is the one the scene shown needs.
  vtkImageData* atmosphereShadowLut() const;
  bool atmosphereShadowCurrent() const;
  /// Whether that table was read from the table cache (vs computed).
  bool atmosphereShadowFromCache() const;

  /// The thin ring of the atmosphere seen from its body's shadow is drawn from the
  /// limb-luminance LuT (pipeline::sceneLimbLuminanceRequest: a camera in the shadow, outside
  /// the atmosphere; the ring thinner than the threshold on screen), as `umbra render`
  /// draws it. As for the shadow: the missing table's request after setScene, a source with
  /// the view's sizes (small: pipeline::useSmallLimbLuminanceTables), the table handed over
  /// when made (pipeline::updateLimbLuminance done; call setScene next). Meanwhile the ring is
  /// drawn from the table the view has for that body, or ray marched.
  const std::optional<pipeline::LimbLuminanceRequest>& missingLimbLuminance() const;
  vtkSmartPointer<vtkLimbLuminanceSource> newLimbLuminanceSource() const;
  void setLimbLuminance(vtkLimbLuminanceSource* source, const pipeline::LimbLuminanceRequest& request);
  /// Whether the view draws with a limb-luminance LuT, and whether it is the one the scene needs.
  bool hasLimbLuminance() const;
  bool limbLuminanceCurrent() const;
  /// Whether that table was read from the table cache (vs computed).
  bool limbLuminanceFromCache() const;
  /// Ring width on screen below which the LuT draws it (default 5 px, as `umbra render
  /// --limb-ring-threshold`; 0: always ray marched, no table asked for). Call setScene next.
  void setLimbRingThresholdPixels(double px);
  double limbRingThresholdPixels() const;
  /// After render: whether the ring was drawn from the LuT, and its width on screen.
  bool lastDrawUsedLimbLuminance() const;
  double lastRingWidthPixels() const;
  void render();
  vtkRenderer* renderer() const;

private:
  struct Impl;

  std::unique_ptr<Impl> impl;
  bool smallShadowTables = false;
};

} // namespace umbra::gui
