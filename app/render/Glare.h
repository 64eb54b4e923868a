#pragma once
// Glare of the HDR frame: a bright source (the Sun, a thin lit limb) spreads
// a little of its light into halos around it, as in an eye or a camera lens, without
// changing the frame's total energy:
//     out = (1 - sum_k f_k) in + sum_k f_k (G_k * in)
// with G_k Gaussians of standard deviation sigma_k (angular, so the halo has the same size
// on the sky at any resolution), each normalised over the frame per source pixel (light
// that would fall outside the frame stays in it), so sum(out) = sum(in) per channel
// exactly, up to float rounding. Three Gaussians at 0.03, 0.15 and 0.75 deg with energy
// fractions 4 %, 2 % and 1 % times the strength (1: a mild camera-like glare) stand in for
// the core, the corona and the wide veil of an Airy/eye point spread function; a kernel
// wider than 64 px in radius (3 sigma) is clipped to sigma = 64/3 px.
//
// GlareRendering runs it on the GPU (glsl/Glare.glsl): per kernel a horizontal and a
// vertical pass, the second one added into the output.
#include <vtkSmartPointer.h>

#include <vector>

class vtkOpenGLFramebufferObject;
class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

namespace umbra::render {

struct GlareKernel {
  double energyFraction = 0.0;  ///< f_k
  double sigmaPx = 0.0;         ///< after clipping
  std::vector<float> weights;   ///< w(j), j = -R..R, sum 1 (R = (size - 1) / 2)
};

inline constexpr int kMaxGlareRadiusPx = 64;

/// An RGBA32F texture of w x h, (re)allocated as needed; Nearest filtering, clamped.
bool prepareFloatTexture(vtkSmartPointer<vtkTextureObject>& t, vtkOpenGLRenderWindow* renWin, int w, int h);

/// The kernels for a strength in [0, 10] (0: none) at pixelsPerDegree. Throws
/// std::invalid_argument for a strength outside [0, 10] or a non-positive scale.
std::vector<GlareKernel> glareKernels(double strength, double pixelsPerDegree);

class GlareRendering {
 public:
  GlareRendering();
  ~GlareRendering();
  /// Applies the kernels to source (w x h, RGBA32F) into Output(). False on a GL failure.
  bool Apply(vtkOpenGLRenderWindow* renWin, vtkTextureObject* source, int w, int h,
             const std::vector<GlareKernel>& kernels);
  vtkTextureObject* Output() const;
  vtkOpenGLFramebufferObject* OutputFramebuffer() const;
  void ReleaseGraphicsResources(vtkWindow* w);

 private:
  bool Pass(vtkOpenGLRenderWindow* renWin, vtkTextureObject* source, vtkOpenGLFramebufferObject* target,
            vtkTextureObject* targetTexture, int w, int h, bool alongRows, const std::vector<float>& weights,
            float scale, bool add);
  vtkSmartPointer<vtkTextureObject> TempTexture, OutputTexture;
  vtkSmartPointer<vtkOpenGLFramebufferObject> TempBuffer, OutputBuffer;
  vtkOpenGLQuadHelper* Quad = nullptr;
};

} // namespace umbra::render
