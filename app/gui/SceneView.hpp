#pragma once
// The 3D view: a scene's bodies seen from its camera, drawn into a Qt VTK widget's render
// window. The glue between umbra::scene and the render library lives here and nowhere
// else in the GUI, so that the GUI follows the render library with small changes.
#include "scene/Scene.hpp"

#include <memory>

class QVTKOpenGLNativeWidget;
class vtkAtmosphereTablesSource;
class vtkImageData;
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
  /// LuT is too coarse (render::sceneLutRange: Phobos by Mars), the view makes its own over
  /// the receivers' ranges with as many rows.
  void setScene(const scene::Scene& scene, vtkImageData* shadowLut);
  void setExposureEV(double ev);
  /// Glare strength (vtkUmbraRenderPass::SetGlareStrength), 0..10.
  void setGlareStrength(double strength);
  /// Tables (already updated) for the atmosphere the scene asks for; nullptr: none. The
  /// atmosphere is drawn while the scene's atmosphere is the one the tables were made for
  /// (they are applied again on every setScene, as the body moves). Call setScene next.
  void setAtmosphereTables(vtkAtmosphereTablesSource* tables);
  void render();
  vtkRenderer* renderer() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl;
};

} // namespace umbra::gui
