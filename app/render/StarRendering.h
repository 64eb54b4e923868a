#pragma once
// StarRendering: catalogue stars drawn into vtkUmbraRenderPass's HDR frame, behind
// everything, before the atmosphere is composed over it. So the composite does to a star
// what it does to any background: the air's transmittance dims and reddens it, refraction
// moves it, the sky's light is added over it (and outshines it by day: no fade factor),
// and the glare stage spreads it.
//
// Each star is an energy-conserving splat (glsl/StarSplat.glsl): its irradiance E (linear
// sRGB, W m^-2, in the frames' white balance: sky::starFrameIrradianceWm2) goes to the
// 2 x 2 pixels around its image point p with the bilinear weights
// w = (1 - |dx|)(1 - |dy|) (dx, dy from p to the pixel's centre), each as radiance
// E w / Omega_pixel, Omega_pixel the pixel's solid angle. So sum(radiance * Omega) over the
// footprint is E (the weights sum to 1) and the weighted centroid of the pixels is p.
// A pixel of a perspective view with ray basis F, X, Y (dir = F + x X + y Y at NDC x, y,
// as AtmosphereRendering) spans
//     Omega = |(X x Y) . F| (2 / W)(2 / H) / |F + x X + y Y|^3.
// Stars are added only where the frame holds nothing (depth 1): a body in front hides them.
// Perspective views only; a parallel view draws none.
//
// Behind them the Milky Way (SetMilkyWay, sky/MilkyWay.hpp): a full-screen quad at depth 1
// writes the map's radiance in each empty pixel's direction (world axes are ICRS's), from a
// mipmap level whose texel spans about the pixel's footprint.
//
// And the Sun (SetSun), where no atmosphere is composed over the frame (the composite
// draws the Sun through the air itself): the same quad adds its limb-darkened disc
// (glsl/SunDisc.glsl: Eq. 1 of the eclipse paper, mean radiance E / (pi alpha^2), white as
// the frame's convention has it) to every empty pixel, as the pixel's mean over 4 x 4
// subsamples; a disc less than 2 pixels in radius goes in as a star's splat of the whole
// irradiance E. Around the disc, out to kSunCoronaReachSolarRadii, its corona (sky/Corona.hpp:
// Baumbach's K + F profile, 1e-6 of the disc's radiance and less), seen where the Moon or
// another body covers the disc. A body in front hides what is behind it, pixel by pixel.
#include "EclipseShading.h"  // SunLight

#include <glm/vec3.hpp>

#include "MapTexels.h"

#include <memory>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkRenderer;

namespace umbra::render {

struct CameraBasis;

/// How far from the Sun's centre its corona is drawn, in solar radii: 16, where Baumbach's
/// profile is 5e-11 of the disc's mean radiance.
inline constexpr double kSunCoronaReachSolarRadii = 16.0;

/// A star to draw: its apparent direction (unit, world axes) and its irradiance above any
/// atmosphere (linear sRGB, W m^-2, white-balanced to the Sun).
struct StarPoint {
  glm::dvec3 direction{0.0, 0.0, 1.0};
  glm::dvec3 irradianceWm2{0.0};
};

class StarRendering {
 public:
  StarRendering();
  ~StarRendering();
  StarRendering(const StarRendering&) = delete;
  StarRendering& operator=(const StarRendering&) = delete;

  /// Replaces the stars (uploaded at the next Draw). Throws std::invalid_argument for a
  /// non-unit or non-finite direction or a negative or non-finite irradiance.
  void SetStars(const std::vector<StarPoint>& stars);
  std::size_t GetNumberOfStars() const;

  /// The Milky Way behind the stars: a map's texels (pipeline::milkyWayTexels reads them) and the
  /// factor that turns them into frame radiance [W m^-2 sr^-1]; nullptr or a factor of 0
  /// for none. Throws std::invalid_argument for a negative or non-finite factor.
  void SetMilkyWay(std::shared_ptr<const MapTexels> map, double radianceScale);

  /// The Sun (its centre, radius and irradiance at 1 au) and its disc's linear limb
  /// darkening; drawn by Draw when asked (withSun). Throws std::invalid_argument for a
  /// coefficient outside [0, 1].
  void SetSun(const SunLight& sun, double limbDarkening);
  /// World position of the VTK scene's origin (BodyView: the camera's position).
  void SetOrigin(const glm::dvec3& originM);

  /// Adds the Milky Way, the Sun (withSun) and the stars to the bound framebuffer (the HDR
  /// frame, its depth attached) for the renderer's camera; width x height its size. False
  /// when a program cannot be built.
  bool Draw(vtkOpenGLRenderWindow* window, vtkRenderer* renderer, int width, int height, bool withSun = false);
  void ReleaseGraphicsResources(vtkOpenGLRenderWindow* window);

 private:
  bool DrawMilkyWay(vtkOpenGLRenderWindow* window, const CameraBasis& basis, int width, int height);
  bool DrawSun(vtkOpenGLRenderWindow* window, vtkRenderer* renderer, const CameraBasis& basis, int width, int height);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace umbra::render
