#pragma once
// BodyView: a render window that shows sphere bodies lit by the (eclipsed) Sun, through
// vtkUmbraRenderPass (HDR, tone-mapped) with EclipseShading. What the CLI and the GUI
// build on.
//
// Camera-relative coordinates: the camera position is the origin. Every body's actor is
// placed at (centre - camera position), computed in double, so that the float matrices
// VTK hands to OpenGL never carry 1e8..1e11 m offsets. SetCamera re-places the actors.
//
// Clipping: near/far are set from the bodies (double precision) in SetCamera and
// SetBodies: near is a fraction of the distance to the nearest body surface, far just
// beyond the farthest. Perspective views write logarithmic depth (ReceiverFragment.glsl),
// so a body 1 m away and one 4e8 m away keep their order whatever near/far are.
//
// Rendering needs an X display (Debian's VTK has no EGL/OSMesa): run under xvfb-run.
#include "AtmosphereRendering.h"
#include "EclipseShading.h"
#include "StarRendering.h"

#include <glm/vec3.hpp>

#include <memory>
#include <string>
#include <vector>

class vtkImageData;
class vtkRenderWindow;
class vtkRenderer;
class vtkUmbraRenderPass;

namespace umbra::render {

struct ViewCamera {
  glm::dvec3 positionM{0.0};
  glm::dvec3 targetM{0.0, 0.0, -1.0};
  glm::dvec3 up{0.0, 0.0, 1.0};
  double fovDeg = 30.0;          ///< vertical field of view (perspective)
  bool parallel = false;
  double parallelScaleM = 0.0;   ///< half the view height in metres (parallel)
};

class BodyView {
 public:
  static constexpr int kSphereThetaResolution = 256;
  static constexpr int kSpherePhiResolution = 128;

  /// Throws std::invalid_argument for a size outside 1..16384.
  BodyView(int width, int height, bool offscreen);
  ~BodyView();
  BodyView(const BodyView&) = delete;
  BodyView& operator=(const BodyView&) = delete;

  /// Every body is a receiver shadowed by all the others (at most
  /// EclipseShading::kMaxOccluders + 1 bodies). Names must be unique. The Sun is the
  /// light and is not drawn. Throws std::invalid_argument.
  void SetBodies(const SunLight& sun, const std::vector<SphereBody>& bodies, vtkImageData* shadowLut);
  /// Origin = camera position; sets near/far from the bodies. Throws std::invalid_argument
  /// (degenerate camera, camera inside a body).
  void SetCamera(const ViewCamera& camera);
  const ViewCamera& GetCamera() const;
  void GetClippingRange(double& nearM, double& farM) const;

  void SetExposureEV(double ev);                 ///< throws for non-finite values
  void SetToneMapping(int mode);                 ///< vtkUmbraRenderPass::Linear / Reinhard

  /// Render one frame; throws std::runtime_error if OpenGL reported an error.
  void Render();

  vtkRenderWindow* GetRenderWindow();
  vtkRenderer* GetRenderer();
  vtkUmbraRenderPass* GetRenderPass();
  EclipseShading& GetShading();
  /// The stars drawn behind everything (StarRendering.h; none by default).
  void SetStars(const std::vector<StarPoint>& stars);
  /// The Milky Way behind the stars (StarRendering::SetMilkyWay; none by default).
  void SetMilkyWay(std::shared_ptr<const MapTexels> map, double radianceScale);
  /// The atmosphere drawn over the bodies (AtmosphereRendering::SetAtmosphere; none by
  /// default). Its Sun and origin follow SetBodies and SetCamera.
  AtmosphereRendering& GetAtmosphere();

  /// The tone-mapped frame as an 8-bit RGB PNG. Written to a temporary file next to
  /// `path`, then renamed. Throws std::runtime_error naming the path on failure.
  void WritePng(const std::string& path);
  /// The last frame's linear radiance (W m^-2 sr^-1), 3 floats per pixel, row 0 = top.
  /// Throws std::runtime_error when there is no frame or it holds non-finite values.
  void ReadHdr(std::vector<float>& rgb, int& width, int& height);

 private:
  void UpdateClippingRange();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace umbra::render
