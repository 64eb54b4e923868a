#pragma once
// Eclipse shading of sphere receivers drawn as vtkActors: the reflection of the eclipsed
// Sun, as linear radiance (W m^-2 sr^-1) for vtkUmbraRenderPass's HDR buffer.
//
//   Lambert:  radiance = albedo / pi * E_sun * max(0, n . l) * prod_occluders umbraEclipseFactor(...)
//   Hapke:    radiance = A(x) * (E_sun * F(n, l, v) * prod_occluders ... + E_earth * F(n, l_earth, v))
//   E_sun    = irradianceAt1Au * (1 au / distance to the Sun)^2
//
// A(x) is the albedo, times an albedo map at the point's body-fixed longitude and latitude
// when the body has one (libration then follows from its rotation); F the
// Hapke–Lommel–Seeliger reflectance (sky/Photometry.hpp); E_earth the earthshine.
//
// per fragment (app/render/glsl/ReceiverFragment.glsl, with the shadow lookup of
// eclipse/glsl/EclipseShadow.glsl); the shadow itself comes from the LuT (never
// recomputed here). n is the analytic sphere normal at the point where the view ray
// through the fragment meets the true sphere (the mesh is only a proxy).
//
// Coordinates. Positions are in metres in any inertial frame, double precision on the
// CPU. Two conventions keep float precision on the GPU at any distance:
//  * camera-relative actors: the application picks an origin (usually the camera
//    position) and each receiver's actor is placed at (centre - origin), so VTK's float
//    matrices never hold 1e8..1e11 m offsets between camera and body;
//  * body-centred shading: every uniform of a receiver (Sun, occluders) is its position
//    relative to that receiver's centre, computed in double and only then rounded to
//    float. The receiver's mesh is centred on the body with the world's axes.
// So the origin only moves the actors (SetOrigin); it never changes the shading.
//
// The receiver's actor must use a vtkOpenGLPolyDataMapper whose input is a sphere of the
// body's radius centred on (0, 0, 0) with the world's axes (vtkSphereSource), inscribed
// (vertices on the sphere). EclipseShading owns that actor's position/orientation/scale,
// its back-face culling, its "umbraShadowLut" texture and its shader replacements.
#include "MapTexels.h"
#include "Photometry.hpp"
#include "ShadowLut.hpp"  // Occluder

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <memory>
#include <string>
#include <vector>

class vtkActor;
class vtkImageData;
class vtkTexture;

namespace umbra::render {

struct SunLight {
  glm::dvec3 positionM{0.0};
  double radiusM = 6.957e8;
  double irradianceAt1AuWm2 = 1361.0;
  /// The irradiance at `distanceM` from the Sun's centre (the inverse square of it in au).
  double irradianceAtWm2(double distanceM) const {
    const double au = distanceM / 149597870700.0;
    return irradianceAt1AuWm2 / (au * au);
  }
};

struct SphereBody {
  std::string name;  ///< identifies the body; a receiver is never its own occluder
  glm::dvec3 centreM{0.0};
  double radiusM = 0.0;
  /// Linear RGB. Lambert: the Lambertian albedo (radiance = albedo / pi E cos i); Hapke:
  /// the factor A of the reflectance F (radiance = A E F). With an albedo map, its mean
  /// over the disc seen from above the map's centre (sky::nearSideDiscMean).
  glm::dvec3 albedoRgb{0.12};
  sky::Photometry photometry{};  ///< Lambert's law or Hapke's (GLSL twin: sky/glsl/Photometry.glsl)
  /// An equirectangular albedo map's texels (pipeline::mapTexels; sky/AlbedoMap.hpp says how
  /// it lies) in the body-fixed frame below; null for a uniform albedo.
  std::shared_ptr<const MapTexels> albedoMap{};
  /// The map is the surface's reflectance (16-bit linear RGB; albedoRgb multiplies it), not
  /// a grey albedo relative to the geometric albedo.
  bool albedoMapReflectance = false;
  /// An equirectangular normal map's texels (sky/NormalMap.hpp says how it lies), in the
  /// same frame; null for the sphere's normals. reliefStrength scales its slopes (0..4).
  std::shared_ptr<const MapTexels> normalMap{};
  double reliefStrength = 1.0;
  glm::dmat3 bodyFixedToInertial{1.0};
  /// Its shadow is cast by the spheroid of this flattening (0 <= f < 0.5) about its
  /// body-fixed z axis, of the sphere's volume (eclipse::Oblateness); 0: by the sphere.
  /// The body itself is drawn as the sphere.
  double flattening = 0.0;
  /// Earthshine (sky/Earthshine.hpp): the irradiance the Earth at earthCentreM sends to
  /// this body, W m^-2 per channel; zero for none.
  glm::dvec3 earthshineWm2{0.0};
  glm::dvec3 earthCentreM{0.0};
  /// Its velocity in the Sun's rest frame, and how long before the scene's time centreM
  /// has it (eclipse::lightTimeToSurfaceS from the camera): a receiver takes it as an
  /// occluder where the light that reaches the receiver passed it (occluderSeenBy).
  /// Zero: at rest, where it is.
  glm::dvec3 velocityMps{0.0};
  double lightDelayS = 0.0;
};

class EclipseShading {
 public:
  static constexpr int kMaxOccluders = 4;  ///< per receiver, after leaving itself out

  EclipseShading();
  ~EclipseShading();
  EclipseShading(const EclipseShading&) = delete;
  EclipseShading& operator=(const EclipseShading&) = delete;

  /// The eclipse shadow LuT: 2D image W x H x 1 (W, H >= 2), point scalars float RGB
  /// (3 components), texel (i, j) = value at u = (i + .5) / W, v = (j + .5) / H
  /// (see filters/shadow/ShadowLutData.h); a ranged LuT (u, v ranges and vLowFraction in
  /// field data, filters::addLutRange) is read through them. Bound as an RGB32F texture,
  /// linear, clamp-to-edge, no mipmaps, no colour mapping. A copy is kept. Throws
  /// std::invalid_argument.
  void SetShadowLut(vtkImageData* lut);
  bool HasShadowLut() const;
  /// The texture every receiver samples as "umbraShadowLut" (nullptr before SetShadowLut).
  vtkTexture* GetShadowLutTexture() const;

  /// The atmospheric shadow LuT of occluder `occluderName` (vtkEclipseShadowLutSource with
  /// an atmosphere: I / I_sun per channel R, G, B): receivers take that occluder's shadow
  /// from it (per channel) instead of the airless LuT, with the same Eq. 4 lookup. `lut`
  /// may hold only part of the table (an update extent: texels [i0, i1] x [j0, j1]); its
  /// origin and spacing place it in the whole (texel centres (u, v) in the table's u and v
  /// ranges, as the source writes them), and outside that part the edge texels are used.
  /// The ranges (field data, filters::lutRangeOf; [0, 1] when absent) are its own: the
  /// umbraAtmosphereLutMap and MapLow uniforms. One occluder at a
  /// time; an empty name or a null image removes it. A copy is kept. Throws
  /// std::invalid_argument as SetShadowLut does.
  void SetAtmosphereShadowLut(const std::string& occluderName, vtkImageData* lut);
  const std::string& GetAtmosphereOccluder() const;

  /// The Sun (the light). Throws std::invalid_argument on non-finite / non-positive values.
  void SetSun(const SunLight& sun);
  /// Bodies that cast shadows. Each receiver uses all of them except the one with its own
  /// name, at most kMaxOccluders (checked at MakeReceiver / SetOccluders).
  void SetOccluders(const std::vector<SphereBody>& occluders);

  /// Turn `actor` into a receiver of `body`, placed at body.centreM - originM. Throws
  /// std::invalid_argument (bad body, no LuT yet, mapper not an OpenGL poly-data
  /// mapper, too many occluders). Calling it again for the same actor updates the body.
  void MakeReceiver(vtkActor* actor, const SphereBody& body, const glm::dvec3& originM);
  /// Stop shading `actor` (its shader replacements, texture and observer are removed).
  void RemoveReceiver(vtkActor* actor);
  void ClearReceivers();
  int GetNumberOfReceivers() const;

  /// Move every receiver's actor to (centre - originM), e.g. after the camera moved.
  void SetOrigin(const glm::dvec3& originM);
  const glm::dvec3& GetOrigin() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

/// The body as an occluder: its centre, mean radius and figure (the pole its body-fixed z),
/// its velocity and light delay.
eclipse::Occluder occluderOf(const SphereBody& body);
/// `occluder` moved to where it is for `receiver`'s shadow (eclipse::occluderSeenBy): what
/// every receiver's shading, its atmosphere and its clouds take.
SphereBody occluderSeenBy(const SphereBody& occluder, const SphereBody& receiver);

/// Validates a body (finite centre, radius > 0, finite albedo >= 0); throws
/// std::invalid_argument naming the body.
void validateBody(const SphereBody& body);
/// Validates the Sun (finite position, radius > 0, irradiance >= 0); throws std::invalid_argument.
void validateSun(const SunLight& sun);

} // namespace umbra::render
