#include "AtmosphereRendering.h"

#include "CameraBasis.h"

#include "AtmosphereGlsl.hpp"
#include "CloudsGlsl.hpp"
#include "FieldParameters.h"
#include "MapTexels.h"
#include "RenderGlsl.hpp"
#include "ShadowLutData.h"
#include "ShadowMapping.hpp"
#include "Spectrum.hpp"
#include "StarRendering.h"  // kSunCoronaReachSolarRadii

#include <vtkCamera.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderUtilities.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
#include <vtkPointData.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkSmartPointer.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace umbra::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// A float texture, linear, clamped to the edges. Three-channel data go up as RGBA32F
/// (padded): Mesa's llvmpipe samples four-channel float textures much faster than RGB32F.
vtkSmartPointer<vtkTextureObject> floatTexture(vtkOpenGLRenderWindow* window, int w, int h, int d,
                                               const std::vector<float>& values, int components = 3,
                                               bool repeatS = false) {
  auto t = vtkSmartPointer<vtkTextureObject>::New();
  t->SetContext(window);
  t->SetMinificationFilter(vtkTextureObject::Linear);
  t->SetMagnificationFilter(vtkTextureObject::Linear);
  t->SetWrapS(repeatS ? vtkTextureObject::Repeat : vtkTextureObject::ClampToEdge);
  t->SetWrapT(vtkTextureObject::ClampToEdge);
  t->SetWrapR(vtkTextureObject::ClampToEdge);
  std::vector<float> data = values;
  if (components == 3) {
    data.assign(values.size() / 3 * 4, 0.0f);
    for (std::size_t i = 0; i < values.size() / 3; ++i)
      for (int c = 0; c < 3; ++c) data[4 * i + c] = values[3 * i + c];
    components = 4;
  }
  t->SetInternalFormat(components == 2 ? GL_RG32F : GL_RGBA32F);
  t->SetFormat(components == 2 ? GL_RG : GL_RGBA);
  t->SetDataType(GL_FLOAT);
  const bool ok = d <= 1 ? t->Create2DFromRaw(w, h, components, VTK_FLOAT, data.data())
                         : t->Create3DFromRaw(w, h, d, components, VTK_FLOAT, data.data());
  if (!ok) throw std::runtime_error("cannot create a " + std::to_string(w) + "x" + std::to_string(h) + " float texture");
  return t;
}

// A rectangle of pixels [x0, x1) x [y0, y1).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool whole(int w, int h) const { return x0 <= 0 && y0 <= 0 && x1 >= w && y1 >= h; }
};

// The pixels whose view rays can meet a sphere (centre relative to the camera, radius):
// the bounding box, one pixel wider each side, of the projected corners of the cube around
// it (the sphere's projection lies in their convex hull). The whole frame when a corner is
// not in front of a perspective camera. halfWidth, halfHeight: the frame's half extent at
// unit distance (perspective) or in metres (parallel).
PixelRect sphereOnScreen(const glm::dvec3& centre, double radius, const glm::dvec3& fwd, const glm::dvec3& right,
                         const glm::dvec3& up, bool parallel, double halfWidth, double halfHeight, int w, int h) {
  const PixelRect whole{0, 0, w, h};
  double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 c = centre + radius * ((corner & 1 ? 1.0 : -1.0) * right + (corner & 2 ? 1.0 : -1.0) * up +
                                            (corner & 4 ? 1.0 : -1.0) * fwd);
    const double z = parallel ? 1.0 : glm::dot(c, fwd);
    if (!(z > 0.0)) return whole;
    const double ndc[2] = {glm::dot(c, right) / (z * halfWidth), glm::dot(c, up) / (z * halfHeight)};
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], ndc[k]);
      hi[k] = std::max(hi[k], ndc[k]);
    }
  }
  if (!(std::isfinite(lo[0]) && std::isfinite(lo[1]) && std::isfinite(hi[0]) && std::isfinite(hi[1]))) return whole;
  auto pixel = [](double ndc, int n, double round) {
    return static_cast<int>(std::clamp(round + 0.5 * (ndc + 1.0) * n, -1.0, n + 1.0));
  };
  PixelRect r{pixel(lo[0], w, 0.0) - 1, pixel(lo[1], h, 0.0) - 1, pixel(hi[0], w, 1.0) + 1, pixel(hi[1], h, 1.0) + 1};
  r.x0 = std::max(r.x0, 0);
  r.y0 = std::max(r.y0, 0);
  r.x1 = std::min(r.x1, w);
  r.y1 = std::min(r.y1, h);
  return r;
}

std::vector<float> asFloat(const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); }

} // namespace

glm::dmat3 atmosphereToDisplayMatrix(const std::vector<double>& wavelengthsNm) {
  const atmosphere::WavelengthSet set = atmosphere::WavelengthSet::rgb();
  if (wavelengthsNm != set.nm) throw std::invalid_argument("the atmosphere renders with 3 wavelengths (680, 550, 440 nm)");
  glm::dmat3 x(0.0);  // column i: the linear sRGB of a unit spectral radiance at sample i, times E_sun there
  for (int i = 0; i < 3; ++i) {
    std::vector<double> unit(3, 0.0);
    unit[i] = atmosphere::solarIrradianceWm2PerNm(set.nm[i]);
    x[i] = atmosphere::spectralRadianceToLinearSrgb(set, unit);
  }
  const glm::dvec3 sun = x * glm::dvec3(1.0);
  glm::dmat3 m(0.0);
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row) m[col][row] = x[col][row] / sun[row];
  return m;
}

void phaseLobes(const atmosphere::PhaseFunction& p, PhaseLobe& first, PhaseLobe& second) {
  using Kind = atmosphere::PhaseFunction::Kind;
  second = {};
  // A single lobe A (1 + B c^2) / (1 + g^2 - 2 g c)^(3/2): A and B from p(0) and p(1).
  auto lobe = [](const atmosphere::PhaseFunction& f, double g) {
    PhaseLobe l;
    l.g = g;
    l.a = f(0.0) * std::pow(1.0 + g * g, 1.5);
    const double oneMinusG = 1.0 - g;
    l.b = f(1.0) * oneMinusG * oneMinusG * std::abs(oneMinusG) / l.a - 1.0;
    return l;
  };
  switch (p.kind()) {
    case Kind::Isotropic:
    case Kind::Rayleigh:
    case Kind::Penndorf: first = lobe(p, 0.0); return;
    case Kind::HenyeyGreenstein:
    case Kind::CornetteShanks: first = lobe(p, p.g()); return;
    case Kind::DoubleHenyeyGreenstein: {
      first = lobe(atmosphere::PhaseFunction::henyeyGreenstein(p.g()), p.g());
      second = lobe(atmosphere::PhaseFunction::henyeyGreenstein(p.g2()), p.g2());
      first.a *= p.alpha();
      second.a *= 1.0 - p.alpha();
      return;
    }
    case Kind::Tabulated: return;  // drawn from the phase table (phaseTableRow)
  }
  throw std::invalid_argument("the renderer has no GLSL form of the phase function " + p.describe());
}

bool phaseTableRow(const atmosphere::Component& c, std::vector<float>& row) {
  bool tabulated = false;
  for (int l = 0; l < 3; ++l) tabulated = tabulated || c.phase(l).kind() == atmosphere::PhaseFunction::Kind::Tabulated;
  row.assign(3 * static_cast<std::size_t>(kPhaseTableSamples), 0.0f);
  if (!tabulated) return false;
  for (int i = 0; i < kPhaseTableSamples; ++i) {
    const double mu = std::cos(kPi * i / (kPhaseTableSamples - 1));
    for (int l = 0; l < 3; ++l) row[3 * i + l] = static_cast<float>(c.phase(l)(mu));
  }
  return true;
}

namespace {
struct FrameView;  // the camera and the body of a frame (below)
} // namespace

struct AtmosphereRendering::Impl {
  bool has = false;
  atmosphere::Atmosphere model;
  atmosphere::AtmosphereTables tables;
  glm::dvec3 centre{0.0}, albedo{0.1};
  std::vector<float> phase;  // 24 vec3
  std::vector<float> phaseTable;  // kMaxComponents rows of kPhaseTableSamples RGB
  int phaseTabulated[kMaxComponents] = {};
  SunLight sun;
  glm::dvec3 origin{0.0};
  glm::dmat3 colour{1.0};
  double limbDarkening = 0.6;
  glm::dvec3 moonPositionM{0.0}, moonIrradianceWm2{0.0};
  double nightGlowWm2Sr = 0.0, glowLayerAltitudeM = 90.0e3;
  std::vector<CloudLayerView> clouds;
  glm::dvec3 cloudSunFactor{1.0};
  // The ground's reflectance map (SetGroundAlbedoMap): texels, frame, texture (a 1x1 white
  // one without a map keeps the sampler valid).
  std::shared_ptr<const MapTexels> groundMap;
  glm::dmat3 groundToBodyFixed{1.0};
  vtkSmartPointer<vtkTextureObject> groundTexture;
  bool texturesStale = true;

  vtkSmartPointer<vtkTextureObject> transmittance, scattering, irradiance, refraction, phaseTexture;
  std::vector<float> refractionValues;  // deviation, contact altitude per texel; empty: off
  int refractionSize[2] = {0, 0};
  std::unique_ptr<vtkOpenGLQuadHelper> quad;
  vtkOpenGLRenderWindow* context = nullptr;
  // The limb-luminance LuT (SetLimbLuminance): values, size, texture, its program.
  std::vector<float> limbValues;
  int limbSize[3] = {0, 0, 0};
  eclipse::LutRange limbRange;  // its u and v ranges (field data; [0, 1] when absent)
  vtkSmartPointer<vtkTextureObject> limb;
  std::unique_ptr<vtkOpenGLQuadHelper> limbQuad;
  // The composite's programs: with the Moon's light (1), with clouds (2), both (3).
  std::unique_ptr<vtkOpenGLQuadHelper> variantQuads[3];
  std::unique_ptr<vtkOpenGLQuadHelper> backgroundQuad;  // umbraAtmosphereBackground
  double limbThresholdPx = 5.0;
  // The eclipsed sky (SetEclipsingBodies): the bodies, the LuT, the knobs; the grid (per unit
  // irradiance, table channels) for `eclipsedKey` (camera, Sun and bodies relative to the
  // centre), its frame, its texture (a 1x1 black one when unused keeps the sampler valid).
  std::vector<eclipse::Occluder> eclipsingBodies;
  // This frame's: those of eclipsingBodies that are not the atmosphere's own body, each
  // where it is for the shadow in this atmosphere (eclipse::occluderSeenBy: the body's
  // ground the receiver, drawn a light time from the camera).
  std::vector<eclipse::Occluder> seenBodies;
  std::shared_ptr<const eclipse::ShadowLut> eclipsingLut;
  atmosphere::EclipsedSkyOptions eclipsedOptions;
  std::vector<float> eclipsedValues;
  std::vector<double> eclipsedKey;
  glm::dvec3 eclipsedE1{1.0, 0.0, 0.0}, eclipsedE2{0.0, 1.0, 0.0};
  glm::dvec3 eclipsedIrradiance{0.0};  // the grid's sky on level ground, per unit irradiance
  vtkSmartPointer<vtkTextureObject> eclipsedTexture;
  bool eclipsedTextureStale = true, lastUsedEclipsedSky = false;
  double cameraSunVisible = 1.0;  // the Sun's visible fraction at the camera (this frame)
  double lastEclipsedSkySeconds = 0.0;
  double terrainMeanElevationM = 0.0;
  int lastLimbSubsamples = 1;
  double lastRingWidthPx = 0.0;
  bool lastUsedLimb = false;

  /// The composite's uniforms for a frame (the tables, the camera, the Sun, the Moon's
  /// light, the ground, the ring from the LuT when lastUsedLimb); the clouds' apart.
  void setUniforms(vtkShaderProgram* p, const FrameView& f, vtkTextureObject* frameColour,
                   vtkTextureObject* frameDepth) const;
  void setCloudUniforms(vtkShaderProgram* p) const;
  /// Activates (or deactivates) the frame's textures and the tables'.
  void activate(vtkTextureObject* colour, vtkTextureObject* depth, bool on);

  void upload(vtkOpenGLRenderWindow* window) {
    const atmosphere::AtmosphereTables& t = tables;
    transmittance = floatTexture(window, t.transmittance.width, t.transmittance.height, 1, asFloat(t.transmittance.values));
    irradiance = floatTexture(window, t.irradiance.width, t.irradiance.height, 1, asFloat(t.irradiance.values));
    // Slab 0: multiple scattering, then one slab per component (z-major: consecutive).
    std::vector<float> stacked(t.multipleScattering.values.begin(), t.multipleScattering.values.end());
    for (const atmosphere::FloatTable3D& s : t.singleScattering) stacked.insert(stacked.end(), s.values.begin(), s.values.end());
    const atmosphere::FloatTable3D& m = t.multipleScattering;
    scattering = floatTexture(window, m.width, m.height, m.depth * static_cast<int>(1 + t.singleScattering.size()), stacked);
    // Without refraction a 2x2 table of zeros keeps the sampler valid.
    const std::vector<float> none(8, 0.0f);
    const bool on = !refractionValues.empty();
    refraction = floatTexture(window, on ? refractionSize[0] : 2, on ? refractionSize[1] : 2, 1,
                              on ? refractionValues : none, 2);
    limb = limbValues.empty() ? nullptr
                              : floatTexture(window, limbSize[0], limbSize[1], limbSize[2], limbValues);
    phaseTexture = floatTexture(window, kPhaseTableSamples, kMaxComponents, 1, phaseTable);
    groundTexture = groundMap ? mapTextureObjectOf(window, *groundMap)
                              : floatTexture(window, 1, 1, 1, std::vector<float>{1.0f, 1.0f, 1.0f}, 3);
    if (!groundTexture) throw std::runtime_error("cannot create the ground's albedo map texture");
    texturesStale = false;
    uploadEclipsedSky(window);
  }
  void uploadEclipsedSky(vtkOpenGLRenderWindow* window) {
    const bool on = !eclipsedValues.empty();
    eclipsedTexture = floatTexture(window, on ? kEclipsedSkyWidth : 1, on ? kEclipsedSkyHeight : 1, 1,
                                   on ? eclipsedValues : std::vector<float>{0.0f, 0.0f, 0.0f}, 3, true);
    eclipsedTextureStale = false;
  }
  /// The Sun's visible fraction at world point p past the eclipsing bodies.
  double sunVisibleAt(const glm::dvec3& p) const {
    double v = 1.0;
    for (const eclipse::Occluder& b : seenBodies)
      v *= eclipse::eclipseFactor(p, sun.positionM, sun.radiusM, b, eclipsingLut.get()).g;
    return v;
  }
  /// seenBodies for a camera at cameraWorld.
  void updateSeenBodies(const glm::dvec3& cameraWorld) {
    seenBodies.clear();
    const double delayS = eclipse::lightTimeToSurfaceS(cameraWorld, centre, tables.bottomRadiusM);
    for (const eclipse::Occluder& b : eclipsingBodies)
      if (glm::length(b.centreM - centre) > 1.0e3)
        seenBodies.push_back(eclipse::occluderSeenBy(b, centre, tables.bottomRadiusM, delayS));
  }
  /// The eclipsed sky's grid for a camera at cameraWorld (inside the atmosphere): computed
  /// again only when the camera, the Sun or a body has moved.
  void updateEclipsedSky(const glm::dvec3& cameraWorld);
};

AtmosphereRendering::AtmosphereRendering() : impl_(std::make_unique<Impl>()) {}
AtmosphereRendering::~AtmosphereRendering() = default;

void AtmosphereRendering::SetAtmosphere(const atmosphere::Atmosphere& model, atmosphere::AtmosphereTables tables,
                                        const glm::dvec3& centreM, const glm::dvec3& groundAlbedoRgb) {
  if (!finite(centreM)) throw std::invalid_argument("atmosphere centre must be finite");
  if (!finite(groundAlbedoRgb) || glm::min(groundAlbedoRgb.x, glm::min(groundAlbedoRgb.y, groundAlbedoRgb.z)) < 0.0)
    throw std::invalid_argument("ground albedo must be finite and >= 0");
  if (tables.wavelengthsNm != model.wavelengthsNm) throw std::invalid_argument("atmosphere tables and model differ in wavelengths");
  if (tables.singleScattering.size() > static_cast<std::size_t>(kMaxComponents))
    throw std::invalid_argument("the renderer draws at most " + std::to_string(kMaxComponents) + " scattering components");
  Impl& m = *impl_;
  std::vector<float> phase(24 * 3, 0.0f), phaseTable, row;
  for (std::size_t q = 0; q < static_cast<std::size_t>(kMaxComponents); ++q) {
    const bool used = q < tables.scatteringComponents.size();
    m.phaseTabulated[q] = used && phaseTableRow(model.component(tables.scatteringComponents[q]), row) ? 1 : 0;
    if (!m.phaseTabulated[q]) row.assign(3 * static_cast<std::size_t>(kPhaseTableSamples), 0.0f);
    phaseTable.insert(phaseTable.end(), row.begin(), row.end());
  }
  for (std::size_t q = 0; q < tables.scatteringComponents.size(); ++q) {
    const atmosphere::Component& c = model.component(tables.scatteringComponents[q]);
    for (int l = 0; l < 3; ++l) {
      PhaseLobe a, b;
      phaseLobes(c.phase(l), a, b);
      const PhaseLobe lobes[2] = {a, b};
      for (int k = 0; k < 2; ++k) {
        const std::size_t base = (6 * q + 3 * k) * 3 + l;
        phase[base] = static_cast<float>(lobes[k].a);
        phase[base + 3] = static_cast<float>(lobes[k].b);
        phase[base + 6] = static_cast<float>(lobes[k].g);
      }
    }
  }
  m.colour = atmosphereToDisplayMatrix(tables.wavelengthsNm);
  m.phase = std::move(phase);
  m.phaseTable = std::move(phaseTable);
  m.model = model;
  m.tables = std::move(tables);
  m.centre = centreM;
  m.albedo = groundAlbedoRgb;
  m.has = true;
  m.texturesStale = true;
  m.eclipsedKey.clear();  // another atmosphere: its eclipsed sky again
}

bool AtmosphereRendering::HasAtmosphere() const { return impl_->has; }
void AtmosphereRendering::ClearAtmosphere() { impl_->has = false; }
const atmosphere::Atmosphere& AtmosphereRendering::GetModel() const { return impl_->model; }
const atmosphere::AtmosphereTables& AtmosphereRendering::GetTables() const { return impl_->tables; }
const glm::dvec3& AtmosphereRendering::GetCentre() const { return impl_->centre; }
void AtmosphereRendering::SetCentre(const glm::dvec3& centreM) {
  if (!finite(centreM)) throw std::invalid_argument("atmosphere centre must be finite");
  impl_->centre = centreM;
}
void AtmosphereRendering::SetSun(const SunLight& sun) {
  validateSun(sun);
  impl_->sun = sun;
}
void AtmosphereRendering::SetRefraction(vtkImageData* table) {
  Impl& m = *impl_;
  m.texturesStale = true;
  if (!table) {
    m.refractionValues.clear();
    return;
  }
  int dims[3];
  table->GetDimensions(dims);
  vtkDataArray* dev = table->GetPointData()->GetArray("deviation_rad");
  vtkDataArray* contact = table->GetPointData()->GetArray("contact_altitude_m");
  const vtkIdType n = table->GetNumberOfPoints();
  if (!dev || !contact || dims[2] != 1 || dims[0] < 2 || dims[1] < 2 || dev->GetNumberOfTuples() != n ||
      contact->GetNumberOfTuples() != n)
    throw std::invalid_argument("refraction table: expected a 2D image with arrays deviation_rad and contact_altitude_m");
  m.refractionValues.resize(2 * static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i) {
    m.refractionValues[2 * i] = static_cast<float>(dev->GetComponent(i, 0));
    m.refractionValues[2 * i + 1] = static_cast<float>(contact->GetComponent(i, 0));
  }
  m.refractionSize[0] = dims[0];
  m.refractionSize[1] = dims[1];
}

void AtmosphereRendering::SetLimbLuminance(vtkImageData* lut) {
  Impl& m = *impl_;
  m.texturesStale = true;
  if (!lut) {
    m.limbValues.clear();
    return;
  }
  int dims[3];
  lut->GetDimensions(dims);
  vtkDataArray* values = lut->GetPointData()->GetScalars();
  const vtkIdType n = lut->GetNumberOfPoints();
  if (!values || values->GetNumberOfComponents() != 3 || values->GetNumberOfTuples() != n || dims[0] < 2 ||
      dims[1] < 2 || dims[2] < 2)
    throw std::invalid_argument("limb-luminance LuT: expected a 3D image (at least 2x2x2) of RGB point scalars");
  std::vector<float> v(3 * static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      v[3 * i + c] = static_cast<float>(values->GetComponent(i, c));
      if (!std::isfinite(v[3 * i + c])) throw std::invalid_argument("limb-luminance LuT has a non-finite value");
    }
  try {
    m.limbRange = filters::lutRangeOf(filters::fieldParameters(lut), "limb-luminance LuT");
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(e.what());
  }
  m.limbValues = std::move(v);
  for (int k = 0; k < 3; ++k) m.limbSize[k] = dims[k];
}
bool AtmosphereRendering::HasLimbLuminance() const { return !impl_->limbValues.empty(); }
void AtmosphereRendering::SetLimbRingThresholdPixels(double px) {
  if (!(std::isfinite(px) && px >= 0.0)) throw std::invalid_argument("limb ring threshold must be finite and >= 0 px");
  impl_->limbThresholdPx = px;
}
double AtmosphereRendering::GetLimbRingThresholdPixels() const { return impl_->limbThresholdPx; }
double AtmosphereRendering::GetLastRingWidthPixels() const { return impl_->lastRingWidthPx; }
bool AtmosphereRendering::GetLastDrawUsedLimbLuminance() const { return impl_->lastUsedLimb; }

bool AtmosphereRendering::HasRefraction() const { return !impl_->refractionValues.empty(); }

void AtmosphereRendering::SetOrigin(const glm::dvec3& originM) { impl_->origin = originM; }
void AtmosphereRendering::SetColourMatrix(const glm::dmat3& m) { impl_->colour = m; }
void AtmosphereRendering::SetEclipsingBodies(const std::vector<eclipse::Occluder>& bodies,
                                             std::shared_ptr<const eclipse::ShadowLut> lut) {
  for (const eclipse::Occluder& b : bodies)
    if (!finite(b.centreM) || !(b.radiusM > 0.0) || !std::isfinite(b.radiusM))
      throw std::invalid_argument("an eclipsing body needs a finite centre and a positive radius");
  if (!bodies.empty() && (!lut || lut->rgb.empty()))
    throw std::invalid_argument("the eclipsing bodies need a shadow LuT with texels");
  impl_->eclipsingBodies = bodies;
  impl_->eclipsingLut = bodies.empty() ? nullptr : std::move(lut);
  impl_->eclipsedKey.clear();
}

void AtmosphereRendering::SetEclipsedSkyOptions(const atmosphere::EclipsedSkyOptions& options) {
  if (const std::string problem = options.validate(); !problem.empty())
    throw std::invalid_argument("eclipsed sky: " + problem);
  if (options == impl_->eclipsedOptions) return;
  impl_->eclipsedOptions = options;
  impl_->eclipsedKey.clear();
}

bool AtmosphereRendering::GetLastDrawUsedEclipsedSky() const { return impl_->lastUsedEclipsedSky; }
double AtmosphereRendering::GetLastEclipsedSkySeconds() const { return impl_->lastEclipsedSkySeconds; }

namespace {
/// The eclipsed sky grid's elevation at t in [-1, 1]: (pi / 2) sign(t) t^2.
double gridElevation(double t) { return 0.5 * kPi * (t < 0.0 ? -t * t : t * t); }
}  // namespace

std::vector<glm::dvec3> AtmosphereRendering::eclipsedSkyDirections(const glm::dvec3& up, const glm::dvec3& e1) {
  const glm::dvec3 e2 = glm::cross(up, e1);
  std::vector<glm::dvec3> directions;
  directions.reserve(static_cast<std::size_t>(kEclipsedSkyWidth) * kEclipsedSkyHeight);
  for (int j = 0; j < kEclipsedSkyHeight; ++j) {
    const double e = gridElevation(-1.0 + 2.0 * (j + 0.5) / kEclipsedSkyHeight);
    for (int i = 0; i < kEclipsedSkyWidth; ++i) {
      const double a = -kPi + 2.0 * kPi * (i + 0.5) / kEclipsedSkyWidth;
      directions.push_back(glm::normalize(std::cos(e) * (std::cos(a) * e1 + std::sin(a) * e2) + std::sin(e) * up));
    }
  }
  return directions;
}

void AtmosphereRendering::Impl::updateEclipsedSky(const glm::dvec3& cameraWorld) {
  const glm::dvec3 camera = cameraWorld - centre, toSun = sun.positionM - centre;
  std::vector<double> key{camera.x, camera.y, camera.z, toSun.x, toSun.y, toSun.z};
  for (const eclipse::Occluder& b : seenBodies)
    for (double c : {b.centreM.x - centre.x, b.centreM.y - centre.y, b.centreM.z - centre.z, b.radiusM}) key.push_back(c);
  bool same = key.size() == eclipsedKey.size();
  for (std::size_t i = 0; same && i < key.size(); ++i) same = std::abs(key[i] - eclipsedKey[i]) <= 1.0;  // 1 m
  lastEclipsedSkySeconds = 0.0;
  if (same && !eclipsedValues.empty()) return;
  const glm::dvec3 up = glm::normalize(camera), sunDirection = glm::normalize(toSun);
  glm::dvec3 e1 = sunDirection - glm::dot(sunDirection, up) * up;
  if (glm::length(e1) < 1e-6) e1 = glm::cross(up, std::abs(up.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0));
  e1 = glm::normalize(e1);
  const std::vector<glm::dvec3> directions = eclipsedSkyDirections(up, e1);
  const glm::dvec3 c = centre;
  const atmosphere::SunVisibility visibility = [this, c](const glm::dvec3& p) { return sunVisibleAt(p + c); };
  const atmosphere::EclipsedSky sky =
      atmosphere::eclipsedSkyRadiance(tables, model, camera, directions, sunDirection, visibility, eclipsedOptions);
  eclipsedValues.assign(directions.size() * 3, 0.0f);
  for (std::size_t k = 0; k < directions.size(); ++k)
    for (std::size_t w = 0; w < 3; ++w) eclipsedValues[3 * k + w] = static_cast<float>(sky.radiance[k][w]);
  // Its irradiance on level ground: sum of L sin e cos e de da over the rows above the
  // horizon, each row's (sin^2 e_hi - sin^2 e_lo) / 2 times its azimuth step.
  eclipsedIrradiance = glm::dvec3(0.0);
  for (int j = kEclipsedSkyHeight / 2; j < kEclipsedSkyHeight; ++j) {
    const double lo = std::sin(gridElevation(std::max(0.0, -1.0 + 2.0 * j / kEclipsedSkyHeight)));
    const double hi = std::sin(gridElevation(-1.0 + 2.0 * (j + 1.0) / kEclipsedSkyHeight));
    const double weight = 0.5 * (hi * hi - lo * lo) * 2.0 * kPi / kEclipsedSkyWidth;
    for (int i = 0; i < kEclipsedSkyWidth; ++i)
      for (int w = 0; w < 3; ++w)
        eclipsedIrradiance[w] += weight * sky.radiance[static_cast<std::size_t>(j) * kEclipsedSkyWidth + i][static_cast<std::size_t>(w)];
  }
  eclipsedE1 = e1;
  eclipsedE2 = glm::cross(up, e1);
  eclipsedKey = key;
  eclipsedTextureStale = true;
  lastEclipsedSkySeconds = sky.seconds;
}

void AtmosphereRendering::SetLimbDarkening(double u) { impl_->limbDarkening = u; }

void AtmosphereRendering::SetMoonLight(const glm::dvec3& moonPositionM, const glm::dvec3& irradianceWm2) {
  for (int c = 0; c < 3; ++c) {
    if (!std::isfinite(moonPositionM[c])) throw std::invalid_argument("moon light: the Moon's position is not finite");
    if (!(irradianceWm2[c] >= 0.0 && std::isfinite(irradianceWm2[c])))
      throw std::invalid_argument("moon light: irradiance must be finite and >= 0");
  }
  impl_->moonPositionM = moonPositionM;
  impl_->moonIrradianceWm2 = irradianceWm2;
}

void AtmosphereRendering::SetNightGlow(double zenithRadianceWm2Sr, double layerAltitudeM) {
  if (!(zenithRadianceWm2Sr >= 0.0 && std::isfinite(zenithRadianceWm2Sr)) ||
      !(layerAltitudeM > 0.0 && std::isfinite(layerAltitudeM)))
    throw std::invalid_argument("night glow: radiance must be finite and >= 0, the layer's altitude > 0");
  impl_->nightGlowWm2Sr = zenithRadianceWm2Sr;
  impl_->glowLayerAltitudeM = layerAltitudeM;
}
void AtmosphereRendering::SetGroundAlbedoMap(std::shared_ptr<const MapTexels> map, const glm::dmat3& bodyFixedToWorld) {
  Impl& m = *impl_;
  if (!std::isfinite(glm::determinant(bodyFixedToWorld)) || std::abs(glm::determinant(bodyFixedToWorld) - 1.0) > 1e-6)
    throw std::invalid_argument("the ground's body-fixed frame must be a rotation");
  if (map && !map->texels) throw std::invalid_argument("the ground's map has no texels");
  m.groundToBodyFixed = glm::transpose(bodyFixedToWorld);
  if (map == m.groundMap) return;
  m.groundMap = std::move(map);
  m.texturesStale = true;
}

void AtmosphereRendering::SetClouds(const std::vector<CloudLayerView>& layers, const glm::dvec3& sunFactor) {
  if (layers.size() > static_cast<std::size_t>(kMaxCloudLayers))
    throw std::invalid_argument("clouds: at most " + std::to_string(kMaxCloudLayers) + " layers are drawn");
  for (const CloudLayerView& v : layers) {
    const sky::CloudLayer& l = v.layer;
    const bool ok = std::isfinite(l.altitudeM) && l.altitudeM >= 0.0 && std::isfinite(l.opticalDepth) &&
                    l.opticalDepth >= 0.0 && l.coverage >= 0.0 && l.coverage <= 1.0 && std::isfinite(l.featureSizeM) &&
                    l.featureSizeM > 0.0 && finite(v.worldToNoise[0]) && finite(v.worldToNoise[1]) &&
                    finite(v.worldToNoise[2]);
    if (!ok)
      throw std::invalid_argument("clouds: a layer needs a finite altitude >= 0, optical depth >= 0, coverage in [0, 1], "
                                  "feature size > 0 and a finite frame");
  }
  if (!finite(sunFactor) || glm::min(sunFactor.x, glm::min(sunFactor.y, sunFactor.z)) < 0.0)
    throw std::invalid_argument("clouds: the Sun's factor must be finite and >= 0");
  Impl& m = *impl_;
  m.clouds = layers;
  m.cloudSunFactor = sunFactor;
}
int AtmosphereRendering::GetNumberOfCloudLayers() const { return static_cast<int>(impl_->clouds.size()); }

void AtmosphereRendering::SetTerrainMeanElevation(double meanElevationM) {
  if (!(std::isfinite(meanElevationM) && meanElevationM >= 0.0))
    throw std::invalid_argument("terrain mean elevation must be finite and >= 0 m");
  impl_->terrainMeanElevationM = meanElevationM;
}
int AtmosphereRendering::GetLastLimbSubsamples() const { return impl_->lastLimbSubsamples; }

namespace {

/// The camera and the body of a frame as the composite sees them (double): the camera's
/// basis and world position, the body's centre and the Sun from it, the angular radii of
/// the ground and of the top of the atmosphere, the camera's (u, v) of Eq. 4 for the
/// ground as occluder.
struct FrameView {
  CameraBasis basis;
  bool parallel = false;
  double pixelAngle = 0.0;
  glm::dvec3 cameraWorld{0.0}, toCentre{0.0}, toSun{0.0};
  double camRadius = 0.0, dSun = 0.0, nearFar[2] = {0.0, 0.0};
  double phiOcc = 0.0, phiAtmo = 0.0;
  eclipse::LutCoords limbUv;
};

FrameView frameView(vtkCamera* cam, int width, int height, const glm::dvec3& origin, const glm::dvec3& centre,
                    const SunLight& sun, const atmosphere::AtmosphereTables& t) {
  FrameView f;
  f.basis = cameraBasis(cam, width, height);
  f.parallel = cam->GetParallelProjection() != 0;
  f.pixelAngle = 2.0 * std::tan(0.5 * cam->GetViewAngle() * kPi / 180.0) / height;
  glm::dvec3 pos;
  cam->GetPosition(&pos.x);
  f.cameraWorld = origin + pos;
  f.toCentre = centre - f.cameraWorld;
  f.camRadius = glm::length(f.toCentre);
  cam->GetClippingRange(f.nearFar);
  f.toSun = sun.positionM - centre;
  f.dSun = glm::length(f.toSun);
  f.phiOcc = std::asin(std::min(1.0, t.bottomRadiusM / f.camRadius));
  f.phiAtmo = std::asin(std::min(1.0, t.topRadiusM / f.camRadius));
  // The LuT holds the ring as seen from the shadow (v < 1: umbra, penumbra, antumbra).
  f.limbUv = eclipse::lutCoords(eclipse::shadowAngles(f.cameraWorld, sun.positionM, sun.radiusM, centre, t.bottomRadiusM));
  return f;
}

/// A full-screen program running `function` (texCoord) of AtmosphereComposite.glsl (with
/// LimbRing.glsl for the ring; the Moon's light and the clouds compiled in or not), bound;
/// null when it does not compile.
vtkShaderProgram* readyQuad(vtkOpenGLRenderWindow* window, std::unique_ptr<vtkOpenGLQuadHelper>& quad,
                            const char* function, bool limbCode, bool moonCode = false, bool cloudCode = false) {
  if (!quad) {
    std::string fs = vtkOpenGLRenderUtilities::GetFullScreenQuadFragmentShaderTemplate();
    std::string decl = std::string(moonCode ? "#define UMBRA_MOON_LIGHT\n" : "") +
                       (cloudCode ? std::string("#define UMBRA_CLOUDS\n") + sky::kCloudsGlsl + "\n" : std::string()) +
                       atmosphere::kAtmosphereGlsl + "\n" + glsl::kSunDisc + "\n" + glsl::kAtmosphereComposite + "\n";
    if (limbCode) decl += std::string(glsl::kLimbRing) + "\n";
    vtkShaderProgram::Substitute(fs, "//VTK::FSQ::Decl", decl + "//VTK::FSQ::Decl");
    vtkShaderProgram::Substitute(fs, "//VTK::FSQ::Impl",
                                 // Light outside the display's gamut (a deep red ring's blue through the
                                 // colour matrix) has a negative channel: 0, as the sky command writes it.
                                 std::string("  gl_FragData[0] = vec4(max(") + function +
                                     "(texCoord), vec3(0.0)), 1.0);\n//VTK::FSQ::Impl");
    quad = std::make_unique<vtkOpenGLQuadHelper>(window, vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(),
                                                 fs.c_str(), "");
  } else {
    window->GetShaderCache()->ReadyShaderProgram(quad->Program);
  }
  vtkShaderProgram* p = quad->Program;
  return p && p->GetCompiled() ? p : nullptr;
}

} // namespace

void AtmosphereRendering::Impl::setUniforms(vtkShaderProgram* p, const FrameView& f, vtkTextureObject* frameColour,
                                            vtkTextureObject* frameDepth) const {
  const atmosphere::AtmosphereTables& t = tables;
  setVec3(p, "umbraPlanetFromCamera", f.toCentre);
  setVec3(p, "umbraCameraUp", f.camRadius > 0.0 ? -f.toCentre / f.camRadius : glm::dvec3(0.0, 0.0, 1.0));
  p->SetUniformf("umbraCameraRadius", static_cast<float>(f.camRadius));
  setVec3(p, "umbraRayForward", f.basis.forward);
  p->SetUniformi("umbraParallel", f.parallel ? 1 : 0);
  const glm::dvec3 x = f.basis.rayX(), y = f.basis.rayY();
  setVec3(p, "umbraRayOriginX", f.parallel ? x : glm::dvec3(0.0));
  setVec3(p, "umbraRayOriginY", f.parallel ? y : glm::dvec3(0.0));
  setVec3(p, "umbraRayX", f.parallel ? glm::dvec3(0.0) : x);
  setVec3(p, "umbraRayY", f.parallel ? glm::dvec3(0.0) : y);
  p->SetUniformf("umbraNear", static_cast<float>(f.nearFar[0]));
  p->SetUniformf("umbraFar", static_cast<float>(f.nearFar[1]));

  setVec3(p, "umbraSunDirection", f.toSun / f.dSun);
  p->SetUniformf("umbraSunAngularRadius", static_cast<float>(std::asin(std::min(1.0, sun.radiusM / f.dSun))));
  p->SetUniformf("umbraSolarIrradiance", static_cast<float>(sun.irradianceAtWm2(f.dSun)));
  p->SetUniformf("umbraLimbDarkening", static_cast<float>(limbDarkening));
  const glm::dvec3 toMoon = moonPositionM - centre;
  setVec3(p, "umbraMoonDirection", glm::length(toMoon) > 0.0 ? glm::normalize(toMoon) : glm::dvec3(0.0, 0.0, 1.0));
  setVec3(p, "umbraMoonIrradiance", moonIrradianceWm2);
  p->SetUniformf("umbraNightGlow", static_cast<float>(nightGlowWm2Sr));
  p->SetUniformf("umbraGlowLayerRatio",
                 static_cast<float>(std::min(f.camRadius / (t.bottomRadiusM + glowLayerAltitudeM), 0.9999)));
  float mat[9];
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row) mat[3 * col + row] = static_cast<float>(colour[col][row]);
  p->SetUniformMatrix3x3("umbraAtmToDisplay", mat);
  setVec3(p, "umbraGroundAlbedo", albedo);
  p->SetUniformi("umbraGroundMapOn", groundMap ? 1 : 0);
  p->SetUniformi("umbraGroundAlbedoMap", groundTexture->GetTextureUnit());
  float toBody[9];
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row) toBody[3 * col + row] = static_cast<float>(groundToBodyFixed[col][row]);
  p->SetUniformMatrix3x3("umbraGroundToBodyFixed", toBody);
  p->SetUniformf("umbraGroundMapTexelM",
                 static_cast<float>(2.0 * kPi * t.bottomRadiusM / (groundMap ? groundMap->width : 1)));

  // The tables.
  p->SetUniformf("umbraAtmBottom", static_cast<float>(t.bottomRadiusM));
  p->SetUniformf("umbraAtmTop", static_cast<float>(t.topRadiusM));
  p->SetUniformf("umbraAtmMuSMin", static_cast<float>(t.options.muSMin));
  p->SetUniformf("umbraAtmSunAngularRadius", static_cast<float>(t.options.sunAngularRadiusRad));
  const int size[4] = {t.options.scatteringR, t.options.scatteringMu, t.options.scatteringMuS, t.options.scatteringNu};
  p->SetUniform1iv("umbraAtmScatteringSize", 4, size);
  p->SetUniformi("umbraAtmComponents", static_cast<int>(t.singleScattering.size()));
  p->SetUniformi("umbraRefraction", refractionValues.empty() ? 0 : 1);
  p->SetUniformf("umbraTerrainMeanElevation", static_cast<float>(terrainMeanElevationM));
  p->SetUniformf("umbraPixelAngle", static_cast<float>(f.pixelAngle));
  p->SetUniformi("umbraLimbSubsamples", lastLimbSubsamples);
  p->SetUniform3fv("umbraAtmPhase", 24, reinterpret_cast<const float(*)[3]>(phase.data()));
  p->SetUniform1iv("umbraAtmPhaseTabulated", kMaxComponents, phaseTabulated);
  p->SetUniformi("umbraAtmPhaseTable", phaseTexture->GetTextureUnit());
  p->SetUniformi("umbraRefractionTable", refraction->GetTextureUnit());
  p->SetUniformi("umbraFrameColour", frameColour->GetTextureUnit());
  p->SetUniformi("umbraFrameDepth", frameDepth->GetTextureUnit());
  p->SetUniformi("umbraAtmTransmittanceTable", transmittance->GetTextureUnit());
  p->SetUniformi("umbraAtmScatteringTable", scattering->GetTextureUnit());
  p->SetUniformi("umbraAtmIrradianceTable", irradiance->GetTextureUnit());
  p->SetUniformf("umbraSunCoronaRadii", static_cast<float>(kSunCoronaReachSolarRadii));
  p->SetUniformf("umbraCameraSunVisible", static_cast<float>(cameraSunVisible));
  p->SetUniformi("umbraEclipsedSkyOn", lastUsedEclipsedSky ? 1 : 0);
  p->SetUniformi("umbraEclipsedSky", eclipsedTexture->GetTextureUnit());
  setVec3(p, "umbraEclipsedSkyE1", eclipsedE1);
  setVec3(p, "umbraEclipsedSkyE2", eclipsedE2);
  setVec3(p, "umbraEclipsedSkyIrradiance", eclipsedIrradiance);
  if (lastUsedLimb) {
    // The camera's (u, v) of Eq. 4 for this occluder (its ground), in double.
    // ... as the texture coordinate through the LuT's ranges (in double: a ranged LuT may
    // span a u range of 1e-5).
    const float uv[2] = {static_cast<float>(limbRange.textureU(f.limbUv.u)),
                         static_cast<float>(limbRange.textureV(f.limbUv.v))};
    p->SetUniform2f("umbraLimbUv", uv);
    p->SetUniformf("umbraLimbOccluder", static_cast<float>(f.phiOcc));
    p->SetUniformf("umbraLimbAtmosphere", static_cast<float>(f.phiAtmo));
    p->SetUniformf("umbraLimbDistance",
                   static_cast<float>(std::sqrt(std::max(f.camRadius * f.camRadius - t.topRadiusM * t.topRadiusM, 0.0))));
    setVec3(p, "umbraSunFromCamera", glm::normalize(sun.positionM - f.cameraWorld));
    p->SetUniformi("umbraLimbLuminance", limb->GetTextureUnit());
  }
}

// The cloud layers (sorted by nothing: the shader orders the crossings of each ray).
void AtmosphereRendering::Impl::setCloudUniforms(vtkShaderProgram* p) const {
  const atmosphere::AtmosphereTables& t = tables;
  const int n = static_cast<int>(clouds.size());
  float radius[kMaxCloudLayers] = {}, tau[kMaxCloudLayers] = {}, cover[kMaxCloudLayers] = {}, scale[kMaxCloudLayers] = {};
  int seed[kMaxCloudLayers] = {};
  for (int k = 0; k < n; ++k) {
    const sky::CloudLayer& l = clouds[k].layer;
    const double rc = std::clamp(t.bottomRadiusM + l.altitudeM, t.bottomRadiusM + 1.0, t.topRadiusM - 1.0);
    radius[k] = static_cast<float>(rc);
    tau[k] = static_cast<float>(l.opticalDepth);
    cover[k] = static_cast<float>(l.coverage);
    scale[k] = static_cast<float>(rc / std::max(l.featureSizeM, sky::kMinCloudFeatureSizeM));
    seed[k] = static_cast<int>(l.seed);  // its bits: the shader's uint() keeps them
    float frame[9];
    for (int col = 0; col < 3; ++col)
      for (int row = 0; row < 3; ++row) frame[3 * col + row] = static_cast<float>(clouds[k].worldToNoise[col][row]);
    p->SetUniformMatrix3x3(("umbraCloudFrame[" + std::to_string(k) + "]").c_str(), frame);
  }
  p->SetUniformi("umbraCloudCount", n);
  p->SetUniform1fv("umbraCloudRadius", kMaxCloudLayers, radius);
  p->SetUniform1fv("umbraCloudTau", kMaxCloudLayers, tau);
  p->SetUniform1fv("umbraCloudCoverage", kMaxCloudLayers, cover);
  p->SetUniform1fv("umbraCloudScale", kMaxCloudLayers, scale);
  p->SetUniform1iv("umbraCloudSeed", kMaxCloudLayers, seed);
  setVec3(p, "umbraCloudSunFactor", cloudSunFactor);
}

void AtmosphereRendering::Impl::activate(vtkTextureObject* colour, vtkTextureObject* depth, bool on) {
  for (vtkTextureObject* texture : {colour, depth, transmittance.Get(), scattering.Get(), irradiance.Get(), refraction.Get(),
                                    phaseTexture.Get(), groundTexture.Get(), eclipsedTexture.Get(),
                                    lastUsedLimb ? limb.Get() : nullptr})
    if (texture) on ? texture->Activate() : texture->Deactivate();
}

bool AtmosphereRendering::Draw(vtkOpenGLRenderWindow* window, vtkRenderer* renderer, vtkTextureObject* colour,
                               vtkTextureObject* depth, int width, int height) {
  Impl& m = *impl_;
  if (!m.has) return true;
  if (m.context != window) {
    ReleaseGraphicsResources(m.context);
    m.context = window;
    m.texturesStale = true;
  }
  if (m.texturesStale) m.upload(window);
  const atmosphere::AtmosphereTables& t = m.tables;
  const FrameView f = frameView(renderer->GetActiveCamera(), width, height, m.origin, m.centre, m.sun, t);

  // The ring's width on screen: the limb-luminance LuT draws it when thin (5.4).
  m.lastRingWidthPx = f.parallel ? 0.0 : (f.phiAtmo - f.phiOcc) / f.pixelAngle;
  m.lastUsedLimb = m.limb && !f.parallel && f.camRadius > t.topRadiusM && f.limbUv.v < 1.0 &&
                   eclipse::occluderInFront(f.cameraWorld, m.sun.positionM, m.centre) &&
                   m.lastRingWidthPx < m.limbThresholdPx;
  // The pixel's extent at the limb (camera outside the atmosphere) in sub-rays.
  const double limbExtentM =
      f.pixelAngle * std::sqrt(std::max(f.camRadius * f.camRadius - t.bottomRadiusM * t.bottomRadiusM, 0.0));
  m.lastLimbSubsamples = f.parallel || f.camRadius <= t.topRadiusM || m.refractionValues.empty()
                             ? 1
                             : static_cast<int>(std::clamp(std::ceil(limbExtentM / kLimbSubsampleSpacingM), 1.0,
                                                           double(kMaxLimbSubsamples)));

  // The eclipsed sky: a camera inside the atmosphere, part of the Sun hidden from it.
  m.lastUsedEclipsedSky = false;
  m.lastEclipsedSkySeconds = 0.0;
  m.updateSeenBodies(f.cameraWorld);
  m.cameraSunVisible = m.sunVisibleAt(f.cameraWorld);
  if (!m.eclipsingBodies.empty() && !f.parallel && f.camRadius < t.topRadiusM && m.cameraSunVisible < kEclipsedSkyBelow) {
    m.updateEclipsedSky(f.cameraWorld);
    m.lastUsedEclipsedSky = true;
  }
  if (m.eclipsedTextureStale) m.uploadEclipsedSky(window);

  m.activate(colour, depth, true);
  // Every ray outside the atmosphere's rectangle on screen misses it and sees the
  // background: a cheap program draws that, the composite only the rectangle (a SIMD
  // rasteriser such as Mesa's llvmpipe pays the whole composite at every pixel it draws).
  const PixelRect rect = sphereOnScreen(f.toCentre, t.topRadiusM, f.basis.forward, f.basis.right, f.basis.up, f.parallel,
                                        f.basis.halfWidth, f.basis.halfHeight, width, height);
  bool ok = true;
  if (!rect.whole(width, height)) {
    vtkShaderProgram* b = readyQuad(window, m.backgroundQuad, "umbraAtmosphereBackground", false);
    if (b) {
      m.setUniforms(b, f, colour, depth);
      m.backgroundQuad->Render();
    }
    ok = b != nullptr;
  }
  // The Moon's light and the clouds are programs of their own: a SIMD rasteriser pays for
  // every branch.
  const bool moonLight = glm::length(m.moonIrradianceWm2) > 0.0 && glm::length(m.moonPositionM - m.centre) > 0.0;
  const bool clouds = !m.clouds.empty();
  const int variant = (moonLight ? 1 : 0) + (clouds ? 2 : 0);
  std::unique_ptr<vtkOpenGLQuadHelper>& composite =
      m.lastUsedLimb ? m.limbQuad : variant == 0 ? m.quad : m.variantQuads[variant - 1];
  vtkShaderProgram* p = m.lastUsedLimb ? readyQuad(window, m.limbQuad, "umbraLimbRing", true)
                                       : readyQuad(window, composite, "umbraAtmosphereComposite", false, moonLight, clouds);
  ok = ok && p;
  if (ok && !rect.empty()) {
    m.setUniforms(p, f, colour, depth);
    if (clouds && !m.lastUsedLimb) m.setCloudUniforms(p);
    vtkOpenGLState* state = window->GetState();
    vtkOpenGLState::ScopedglEnableDisable scissorSaver(state, GL_SCISSOR_TEST);
    vtkOpenGLState::ScopedglScissor scissorBoxSaver(state);
    state->vtkglEnable(GL_SCISSOR_TEST);
    state->vtkglScissor(rect.x0, rect.y0, rect.x1 - rect.x0, rect.y1 - rect.y0);
    composite->Render();
  }
  m.activate(colour, depth, false);
  return ok;
}

void AtmosphereRendering::ReleaseGraphicsResources(vtkOpenGLRenderWindow* window) {
  Impl& m = *impl_;
  for (auto* q : {&m.quad, &m.limbQuad, &m.variantQuads[0], &m.variantQuads[1], &m.variantQuads[2], &m.backgroundQuad}) {
    if (*q) {
      (*q)->ReleaseGraphicsResources(window);
      q->reset();
    }
  }
  for (auto* t : {&m.transmittance, &m.scattering, &m.irradiance, &m.refraction, &m.phaseTexture, &m.limb, &m.groundTexture,
                  &m.eclipsedTexture}) {
    if (*t && window) (*t)->ReleaseGraphicsResources(window);
    *t = nullptr;
  }
  m.texturesStale = true;
}

} // namespace umbra::render
