#pragma once
// AtmosphereRendering: the atmosphere of one body drawn as a post-process of
// vtkUmbraRenderPass's HDR frame (Algorithm 1 of Costa et al., "Interactive Visualization
// of Atmospheric Effects for Celestial Bodies", section 5): per pixel, the view ray is
// intersected with the atmosphere's shell and compared with the depth buffer; the
// transmittance and the in-scattered radiance come from the precomputed Bruneton tables
// (atmosphere/glsl/Atmosphere.glsl, the GLSL twin of atmosphere/precompute/Parametrisation.hpp's lookups):
//   ray misses the shell, or an object lies before it:  F = frame colour
//   ray ends on the planet's ground:   F = M E_sun [T(x, y) albedo / pi (f E_0 + E_ind)(y) + S(x -> y)]
//   ray ends on an object in the air:  F = T(x, y) frame + M E_sun S(x -> y)
//   ray leaves the atmosphere:         F = T(x, top) (frame + Sun's disc) + M E_sun S(x)
// with S(x -> y) = S(x) - T(x, y) S(y) (aerial perspective) and the tables' per-unit-
// irradiance values turned into the frame's units by M E_sun (below). The planet's ground
// is the analytic sphere (radius bottomRadiusM): it replaces the frame's colour of the
// planet (which EclipseShading lit without air) wherever the frame's depth lies within 1 %
// of the ground hit (from 2 km up, the float camera matrices move grazing ground hits by
// a few tenths of a percent). f is the eclipse factor of other bodies there, read back
// from the frame (its colour over albedo / pi E_sun cos i; where the Sun is within 3
// degrees of the horizon or the frame shows nothing, the Sun's visible fraction at the
// camera past the eclipsing bodies, SetEclipsingBodies, or 1): it dims the direct
// sunlight, the sky light (E_ind) and the air light S.
//
// Colour. The tables hold one channel per wavelength (680, 550, 440 nm: the R, G, B mode of
// vtkAtmosphereTablesSource) per unit solar irradiance. The HDR frame holds linear sRGB
// in W m^-2 sr^-1 for a white Sun of broadband irradiance E_sun (EclipseShading: a
// surface of albedo a has radiance a / pi E_sun cos i). The atmosphere keeps that
// convention: M = diag(1 / s) X W, with W = diag(E_sun,lambda(680, 550, 440 nm)) the
// ASTM G173 solar spectrum (atmosphere/Spectrum.hpp), X the 3x3 map from the three
// spectral samples to linear sRGB (the solar-ratio rule of Spectrum.hpp: CIE 1931 and the
// sRGB primaries) and s = X W (1, 1, 1) the Sun's own linear sRGB. So the bare Sun stays
// white (1, 1, 1), a grey table value k gives k E_sun in every channel, and a sky's colour
// is its CIE colour white-balanced to the Sun. Transmittance (per wavelength) multiplies
// the frame's R, G, B channels directly (680, 550, 440 nm stand for R, G, B).
//
// Coordinates (camera-relative, as BodyView): the world camera is origin + the VTK camera
// position; every uniform is computed in double relative to the camera (or the planet)
// and only then rounded to float: the planet centre relative to the camera, the camera's
// radius and altitude, the ray's basis. The ray-shell intersection uses the impact
// vector (no squares of the camera distance), so a camera 1 au away and one 1 m above the
// ground both keep float precision where it matters.
//
// Depth. Perspective frames hold logarithmic depth (app/render/glsl/ReceiverFragment.glsl:
// distance = 1 mm 2^(depth * 53.15)), parallel ones the window depth between near and far;
// depth 1 is the background.
//
// The Sun's disc (not drawn by the bodies) is drawn behind the atmosphere for rays that
// reach the background: radiance E_sun / (pi alpha^2) times the linear limb darkening of
// the eclipse paper's Eq. 1 (normalised to the disc's mean), attenuated by T.
#include "EclipseShading.h"  // SunLight

#include "Clouds.hpp"

#include "Atmosphere.hpp"
#include "EclipsedSky.hpp"
#include "Precompute.hpp"
#include "ShadowLut.hpp"

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <memory>
#include <string>
#include <vector>

class vtkImageData;
class vtkMultiBlockDataSet;
class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkTextureObject;

namespace umbra::render {

/// The colour matrix M of the header (for 680, 550, 440 nm).
glm::dmat3 atmosphereToDisplayMatrix(const std::vector<double>& wavelengthsNm);

/// One phase lobe per channel: A (1 + B c^2) / (1 + g^2 - 2 g c)^(3/2).
struct PhaseLobe {
  double a = 0.0, b = 0.0, g = 0.0;
};
/// The two lobes of a phase function (the second A = 0 unless double Henyey-Greenstein;
/// both 0 for a tabulated one, which the shader reads from its phase table).
void phaseLobes(const atmosphere::PhaseFunction& phase, PhaseLobe& first, PhaseLobe& second);

/// Samples of the shader's phase table: theta = pi i / (kPhaseTableSamples - 1), every 0.125
/// degrees, so that a Lorenz-Mie table's samples (every 0.5 degrees, linear in cos theta
/// between them) fall on its samples: between them the two differ by < 1e-4.
inline constexpr int kPhaseTableSamples = 1441;
/// A component's row of the phase table, RGB per sample (its phase functions at the first
/// three wavelengths): true when any of them is tabulated (Lorenz-Mie's) and the shader is
/// to read the row; else false and the row zero.
bool phaseTableRow(const atmosphere::Component& component, std::vector<float>& row);

class AtmosphereRendering {
 public:
  static constexpr int kMaxComponents = 4;  ///< scattering components per atmosphere

  AtmosphereRendering();
  ~AtmosphereRendering();
  AtmosphereRendering(const AtmosphereRendering&) = delete;
  AtmosphereRendering& operator=(const AtmosphereRendering&) = delete;

  /// The atmosphere of the body centred at centreM (world, m): its model, its tables
  /// (3 wavelengths) and the ground's linear sRGB albedo. Throws std::invalid_argument.
  void SetAtmosphere(const atmosphere::Atmosphere& model, atmosphere::AtmosphereTables tables,
                     const glm::dvec3& centreM, const glm::dvec3& groundAlbedoRgb);
  bool HasAtmosphere() const;

  void ClearAtmosphere();
  const atmosphere::Atmosphere& GetModel() const;
  const atmosphere::AtmosphereTables& GetTables() const;
  const glm::dvec3& GetCentre() const;
  /// Moves the atmosphere's body (model and tables kept: nothing is uploaded again).
  /// Throws std::invalid_argument for a non-finite centre.
  void SetCentre(const glm::dvec3& centreM);

  void SetSun(const SunLight& sun);
  /// World position of the VTK scene's origin (BodyView: the camera position).
  void SetOrigin(const glm::dvec3& originM);
  /// The matrix from table channels to the frame's colour (default atmosphereToDisplayMatrix).
  void SetColourMatrix(const glm::dmat3& m);
  /// Refraction (eclipse paper, section 4.2; nullptr: off): the "refraction" block of
  /// vtkAtmosphereTablesSource (arrays deviation_rad, contact_altitude_m over the
  /// transmittance parametrisation). Rays that leave the atmosphere are bent by the
  /// deviation before they look up the background and the Sun; rays whose contact altitude
  /// is negative see black; those that descend are attenuated along the refracted path
  /// (eclipse::refractedTransmittanceToTop) and by the terrain at their contact
  /// (SetTerrainMeanElevation); from outside the atmosphere the Sun through the limb is
  /// averaged over sub-rays across the pixel (GetLastLimbSubsamples). Perspective views only. The scattering tables should then come
  /// from refracted paths (vtkAtmosphereTablesSource::RefractedPaths). Throws
  /// std::invalid_argument for a malformed table.
  void SetRefraction(vtkImageData* table);
  bool HasRefraction() const;

  /// The limb-luminance LuT of this atmosphere's body (vtkLimbLuminanceSource, one layer:
  /// W x H x columns, RGB radiance per unit solar irradiance): when the ring of the
  /// atmosphere is thinner than the threshold on screen, the ring is drawn from it
  /// instead of ray marching (eclipse paper, 5.4; app/render/glsl/LimbRing.glsl), at the
  /// camera's (u, v) of Eq. 4 for this occluder (its ground radius, the Sun), when the
  /// camera is in its shadow (v < 1) outside the atmosphere; a ranged LuT (u, v ranges in
  /// field data, filters::lutRangeOf) is read through its ranges. Perspective views only. nullptr: none (always ray marching). Throws std::invalid_argument.
  void SetLimbLuminance(vtkImageData* lut);
  bool HasLimbLuminance() const;
  /// Ring width on screen below which the LuT draws the ring (default 5 px; 0: never).
  void SetLimbRingThresholdPixels(double px);
  double GetLimbRingThresholdPixels() const;
  /// After Draw: the ring's width on screen (phi_atmo - phi_occ over the pixel angle), and
  /// whether the LuT drew it.
  double GetLastRingWidthPixels() const;
  bool GetLastDrawUsedLimbLuminance() const;

  /// The Moon as a second light (the night sky, lit by it): the same tables looked up with
  /// its direction from the planet's centre, times `irradianceWm2` per table channel (the
  /// Sun's light would be E_sun in each), added to the sky, the aerial perspective and the
  /// ground's light. irradianceWm2 zero: none (the default). Throws std::invalid_argument
  /// for non-finite values or a negative irradiance.
  void SetMoonLight(const glm::dvec3& moonPositionM, const glm::dvec3& irradianceWm2);
  /// The night sky's glow above the air (airglow, zodiacal light, unresolved stars): a
  /// layer `layerAltitudeM` above the ground radiating `zenithRadianceWm2Sr` (grey, frame
  /// units) at the zenith and more towards the horizon (van Rhijn), dimmed by the air below
  /// it; seen from inside the atmosphere only. 0: none (the default). Throws
  /// std::invalid_argument for a negative or non-finite value.
  void SetNightGlow(double zenithRadianceWm2Sr, double layerAltitudeM = 90.0e3);

  /// One cloud layer as the renderer draws it: the layer (sky/Clouds.hpp; its altitude above
  /// this atmosphere's ground, drawn within [bottom + 1 m, top - 1 m]; its wind is already in
  /// the frame) and the rotation from the world's axes to its noise's (body-fixed, turned by
  /// the wind).
  struct CloudLayerView {
    sky::CloudLayer layer;
    glm::dmat3 worldToNoise{1.0};
  };
  /// The cloud layers over this atmosphere (at most kMaxCloudLayers; none: a program without
  /// them). `sunFactor`: the eclipse at the camera per channel, which dims the direct
  /// sunlight on the clouds. Throws std::invalid_argument for more layers or a non-finite or
  /// out-of-range value.
  static constexpr int kMaxCloudLayers = 4;
  /// The ground's albedo as a reflectance map's texels (16-bit linear RGB:
  /// pipeline::mapTexels with MapKind::Reflectance, the Earth's colour) in the planet's
  /// body-fixed frame, which `bodyFixedToWorld` turns to world axes; null for SetAtmosphere's
  /// uniform albedo. The map's colour is taken per table channel. SetAtmosphere's albedo
  /// stays the one the planet's receiver is drawn with (uniform): the frame's ground over it
  /// gives the eclipse on the ground. Throws std::invalid_argument for a frame that is not a
  /// rotation or a map without texels (nothing changed).
  void SetGroundAlbedoMap(std::shared_ptr<const MapTexels> map, const glm::dmat3& bodyFixedToWorld = glm::dmat3(1.0));
  void SetClouds(const std::vector<CloudLayerView>& layers, const glm::dvec3& sunFactor = glm::dvec3(1.0));
  int GetNumberOfCloudLayers() const;

  /// The bodies that may hide the Sun from inside this atmosphere (a scene's bodies: the
  /// atmosphere's own, centred within 1 km of its centre, is left out), and the airless
  /// shadow LuT their visible fraction of the Sun is read from (the receivers' LuT). When
  /// the camera is inside the atmosphere and they hide part of the Sun from it (a visible
  /// fraction below kEclipsedSkyBelow), the sky (every ray that leaves the atmosphere) comes
  /// from the eclipsed-sky quadrature (atmosphere/EclipsedSky.hpp: the Sun's visible
  /// fraction at every point of the air, every order of scattering) on a sky-view grid of
  /// kEclipsedSkyWidth azimuths x kEclipsedSkyHeight elevations (dense at the horizon),
  /// computed on the CPU when the camera, the Sun or a body has moved, and looked up per
  /// pixel; the ground and objects in the air keep the tables' light dimmed by the
  /// eclipse at their point. No bodies: the tables' sky always (the default). Throws
  /// std::invalid_argument for a non-finite body or a LuT without texels.
  void SetEclipsingBodies(const std::vector<eclipse::Occluder>& bodies, std::shared_ptr<const eclipse::ShadowLut> lut);
  static constexpr double kEclipsedSkyBelow = 0.999;
  static constexpr int kEclipsedSkyWidth = 256, kEclipsedSkyHeight = 128;
  /// The quadrature's knobs for that grid (default: EclipsedSkyOptions{}; draft knobs for
  /// interactive use). Throws std::invalid_argument for invalid ones.
  void SetEclipsedSkyOptions(const atmosphere::EclipsedSkyOptions& options);
  /// After Draw: whether the eclipsed sky drew the sky, and the seconds its grid took when
  /// it was computed for that frame (0 when the grid was reused or not used).
  bool GetLastDrawUsedEclipsedSky() const;
  double GetLastEclipsedSkySeconds() const;
  /// The sky-view grid's directions around a camera at `up` (unit, from the planet's
  /// centre) with `e1` the azimuths' origin (unit, horizontal): row-major, azimuth
  /// fastest: azimuth -pi + 2 pi (i + 1/2) / W from e1 towards up x e1, elevation
  /// (pi / 2) sign(t) t^2 with t = -1 + 2 (j + 1/2) / H. The composite's lookup inverts it.
  static std::vector<glm::dvec3> eclipsedSkyDirections(const glm::dvec3& up, const glm::dvec3& e1);

  /// Limb darkening of the Sun's disc (eclipse/SolarDisc.hpp's Eq. 1 coefficient).
  void SetLimbDarkening(double u);
  /// Rough land of the body (eclipse::TerrainModel, eclipse paper 5.2; default 0 m: only
  /// rays below the ground are blocked): with refraction, a ray that descends to a contact
  /// altitude below twice this is dimmed as in the limb views (eclipse::defaultTerrain: Earth
  /// 240 m). Throws std::invalid_argument for a negative or non-finite value.
  void SetTerrainMeanElevation(double meanElevationM);

  /// With refraction, from outside the atmosphere, the Sun seen through the limb is averaged
  /// over this many rays across a pixel (towards the planet's centre): the pixel's extent at
  /// the limb over kLimbSubsampleSpacingM, 1 to kMaxLimbSubsamples. After Draw.
  static constexpr double kLimbSubsampleSpacingM = 250.0;
  static constexpr int kMaxLimbSubsamples = 64;
  int GetLastLimbSubsamples() const;

  /// Draws the atmosphere: reads `colour` and `depth` (the delegate's frame), writes the
  /// composed frame into the currently bound draw framebuffer (w x h). False when the
  /// shader cannot be built.
  bool Draw(vtkOpenGLRenderWindow* window, vtkRenderer* renderer, vtkTextureObject* colour,
            vtkTextureObject* depth, int width, int height);
  void ReleaseGraphicsResources(vtkOpenGLRenderWindow* window);

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

} // namespace umbra::render
