#pragma once
// vtkUmbraRenderPass: renders its delegate into a floating-point (RGBA32F) framebuffer
// and tone-maps that HDR frame onto the current framebuffer.
//
// The HDR frame holds linear radiance in W m^-2 sr^-1 (what EclipseShading writes). The
// display transform (glsl/ToneMap.glsl) is
//     display = sRGB( curve( radiance * 2^ExposureEV ) )
// with curve = clamp to [0, 1] (Linear) or x / (1 + x) per channel (Reinhard, default),
// and sRGB the exact IEC 61966-2-1 encoding. The last HDR frame stays readable with
// ReadHdrPixels (EXR output, tests).
//
// With stars (SetStars, StarRendering.h), they are added to the delegate's frame where it
// holds nothing, before the atmosphere; without an atmosphere the Sun's disc with them (the
// atmosphere's composite draws it otherwise).
//
// With an atmosphere (SetAtmosphere), the frame is composed with it
// (AtmosphereRendering::Draw) into a second float buffer between the delegate and the tone
// map; that composed frame is the HDR frame.
//
// With GlareStrength > 0 (Glare.h), the HDR frame then gets an energy-preserving glare
// (halos of 0.03, 0.15 and 0.75 deg around bright pixels); the glared frame is the HDR
// frame that is tone-mapped and read back.
//
// Usage: renderer->SetPass(pass). The default delegate is a vtkRenderStepsPass (which is
// itself a vtkCameraPass around the usual lights/opaque/translucent/volume/overlay
// sequence); SetDelegatePass replaces it.
//
// Limitations: the renderer's viewport should start at the window's lower-left corner
// (as for vtkToneMappingPass, VTK's camera pass positions the delegate's viewport at the
// renderer's origin).
#include <vtkImageProcessingPass.h>
#include <vtkSmartPointer.h>
#include <vtkWeakPointer.h>

#include <memory>
#include <vector>

class vtkOpenGLFramebufferObject;
class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
namespace umbra::render {
class AtmosphereRendering;
class GlareRendering;
class StarRendering;
}

class vtkUmbraRenderPass : public vtkImageProcessingPass {
 public:
  static vtkUmbraRenderPass* New();
  vtkTypeMacro(vtkUmbraRenderPass, vtkImageProcessingPass)
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Render(const vtkRenderState* s) override;
  void ReleaseGraphicsResources(vtkWindow* w) override;

  enum ToneMappingType { Linear = 0, Reinhard = 1 };

  /// Exposure in stops: the HDR value is multiplied by 2^ExposureEV before the curve.
  vtkSetClampMacro(ExposureEV, double, -120.0, 120.0);
  vtkGetMacro(ExposureEV, double);

  /// Tone curve, Linear (clamp) or Reinhard (default).
  vtkSetClampMacro(ToneMapping, int, Linear, Reinhard);
  vtkGetMacro(ToneMapping, int);

  /// Night vision on the display (not on the HDR frame): each pixel as the eye sees it at
  /// its own luminance (sky/NightVision.hpp: CIE 191 mesopic adaptation, scotopic grey).
  /// Off by default.
  vtkSetMacro(NightVision, bool);
  vtkGetMacro(NightVision, bool);

  /// Glare strength in [0, 10]: 0 (default) none, 1 moves 7 % of the light into halos
  /// (Glare.h); the frame's total radiance is kept.
  vtkSetClampMacro(GlareStrength, double, 0.0, 10.0);
  vtkGetMacro(GlareStrength, double);

  /// The float colour buffer of the last frame, RGBA, 4 floats per pixel, row 0 = bottom
  /// row (as in GL). False (and empty) when nothing has been rendered since the last
  /// ReleaseGraphicsResources, or the window is gone.
  bool ReadHdrPixels(std::vector<float>& rgba, int& width, int& height);

  /// The atmosphere drawn over the frame (not owned; nullptr: none).
  void SetAtmosphere(umbra::render::AtmosphereRendering* atmosphere) { this->Atmosphere = atmosphere; }

  /// The stars drawn behind everything (not owned; nullptr: none).
  void SetStars(umbra::render::StarRendering* stars) { this->Stars = stars; }

  /// GPU time per stage of a frame (GL_TIMESTAMP queries between the stages), for the
  /// benches: the paper's Table 1 times the receivers alone, Table 2 the atmosphere.
  struct StageTimes {
    double receiversMs = 0.0;   ///< the delegate: bodies, their eclipse shading, terrain
    double starsMs = 0.0;       ///< the star splats (0: none)
    double atmosphereMs = 0.0;  ///< the atmosphere composite or limb ring (0: none)
    double glareMs = 0.0;       ///< 0 without glare
    double toneMapMs = 0.0;     ///< the tone map onto the window's framebuffer
  };
  /// Off by default: with it on, each Render records timestamps between its stages.
  void SetStageTiming(bool on) { this->StageTiming = on; }
  /// The last frame's stage times: waits for the GPU to reach the end of that frame. False
  /// when stage timing was off for it, or nothing was rendered since.
  bool GetLastStageTimes(StageTimes& times);

 protected:
  vtkUmbraRenderPass();
  ~vtkUmbraRenderPass() override;

  double ExposureEV = 0.0;
  int ToneMapping = Reinhard;
  bool NightVision = false;

  vtkSmartPointer<vtkOpenGLFramebufferObject> FrameBufferObject;
  vtkSmartPointer<vtkTextureObject> ColorTexture;
  vtkSmartPointer<vtkTextureObject> DepthTexture;
  std::unique_ptr<vtkOpenGLQuadHelper> QuadHelper;
  umbra::render::AtmosphereRendering* Atmosphere = nullptr;
  umbra::render::StarRendering* Stars = nullptr;
  vtkSmartPointer<vtkOpenGLFramebufferObject> ComposedFrameBuffer;  // the atmosphere's output
  vtkSmartPointer<vtkTextureObject> ComposedTexture;
  bool HdrComposed = false;
  double GlareStrength = 0.0;
  std::unique_ptr<umbra::render::GlareRendering> Glare;
  bool HdrGlared = false;

  static constexpr int kStageMarks = 6;  // before the delegate and after each stage
  bool StageTiming = false;
  std::vector<unsigned int> StageQueries;  // GL query names: before and after each stage
  bool StageTimesPending = false;

  vtkWeakPointer<vtkOpenGLRenderWindow> LastWindow;
  int HdrWidth = 0;
  int HdrHeight = 0;
  bool HdrValid = false;

 private:
  bool PrepareBuffers(vtkOpenGLRenderWindow* renWin, int width, int height);
  void MarkStage(int stage);
  // The stages of Render, each false (after an error message) when it fails: the delegate
  // and the stars into the float framebuffer; the atmosphere over it into the composed
  // buffer (`hdr` becomes that); the glare (`hdr` becomes its output); the tone map of
  // `hdr` onto the current framebuffer at (x, y).
  bool DrawScene(const vtkRenderState* s, vtkOpenGLRenderWindow* renWin, int w, int h);
  bool ComposeAtmosphere(vtkRenderer* r, vtkOpenGLRenderWindow* renWin, int w, int h, vtkTextureObject*& hdr);
  bool ApplyGlare(vtkRenderer* r, vtkOpenGLRenderWindow* renWin, int w, int h, vtkTextureObject*& hdr);
  bool ToneMap(vtkOpenGLRenderWindow* renWin, vtkTextureObject* hdr, int x, int y, int w, int h);
  vtkUmbraRenderPass(const vtkUmbraRenderPass&) = delete;
  void operator=(const vtkUmbraRenderPass&) = delete;
};
