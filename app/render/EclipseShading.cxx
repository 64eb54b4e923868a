#include "EclipseShading.h"

#include "MapTexels.h"
#include "EclipseShadowGlsl.hpp"
#include "PhotometryGlsl.hpp"
#include "FieldParameters.h"
#include "Colour.hpp"
#include "ShadowLutData.h"
#include "RenderGlsl.hpp"

#include <vtkActor.h>
#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkImageReader2.h>
#include <vtkImageReader2Factory.h>
#include <vtkOpenGLPolyDataMapper.h>
#include <vtkOpenGLVertexBufferObject.h>
#include <vtkPointData.h>
#include <vtkProperty.h>
#include <vtkShaderProgram.h>
#include <vtkShaderProperty.h>
#include <vtkSmartPointer.h>
#include <vtkTexture.h>
#include <vtkUnsignedCharArray.h>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

namespace umbra::render {
namespace {

constexpr const char* kLutSamplerName = "umbraShadowLut";
constexpr const char* kLutSamplerDecl = "uniform sampler2D umbraShadowLut;";
constexpr const char* kAtmosphereLutSamplerName = "umbraAtmosphereShadowLut";
constexpr const char* kAlbedoMapSamplerName = "umbraAlbedoMap";
constexpr const char* kNormalMapSamplerName = "umbraNormalMap";

vtkSmartPointer<vtkTexture> lutTexture();
vtkSmartPointer<vtkImageData> rgbaTexels(vtkImageData* lut);

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// VTK substitutes its //VTK:: tags anywhere in a shader, comments included.
const char* checkedGlsl(const char* name, const char* src) {
  if (std::string(src).find("//VTK::") != std::string::npos) {
    throw std::logic_error(std::string(name) + " contains a //VTK:: tag; VTK would substitute it");
  }
  return src;
}

// eclipse/glsl/EclipseShadow.glsl declares the LuT sampler; VTK declares the samplers of
// a property's textures itself, so the receiver's shader takes the file without it.
std::string eclipseGlslWithoutSampler() {
  std::string src = checkedGlsl("eclipse/glsl/EclipseShadow.glsl", eclipse::kEclipseShadowGlsl);
  const auto at = src.find(kLutSamplerDecl);
  if (at == std::string::npos) {
    throw std::logic_error("eclipse/glsl/EclipseShadow.glsl no longer declares 'uniform sampler2D umbraShadowLut;'");
  }
  src.replace(at, std::string(kLutSamplerDecl).size(), "// (umbraShadowLut is declared by VTK)");
  return src;
}

// Tags of VTK 9.1's vtkPolyDataVS/FS.glsl templates that the receiver's code goes to.
struct Replacement {
  bool vertex;
  const char* tag;
};
constexpr Replacement kVsDec{true, "//VTK::Camera::Dec"};        // replaced (declares the matrices)
constexpr Replacement kVsImpl{true, "//VTK::CustomEnd::Impl"};   // kept
constexpr Replacement kFsDec{false, "//VTK::Edges::Dec"};        // kept, after TMap::Dec and the output
constexpr Replacement kFsImpl{false, "//VTK::TCoord::Impl"};     // kept, after VTK's lighting

} // namespace

void validateBody(const SphereBody& b) {
  const std::string who = "body '" + b.name + "'";
  if (!finite(b.centreM)) throw std::invalid_argument(who + " has a non-finite centre");
  if (!(std::isfinite(b.radiusM) && b.radiusM > 0.0)) {
    throw std::invalid_argument(who + " needs a finite radius > 0 (got " + std::to_string(b.radiusM) + ")");
  }
  if ((b.albedoMap && !b.albedoMap->texels) || (b.normalMap && !b.normalMap->texels))
    throw std::invalid_argument(who + " has a map without texels");
  if (!finite(b.albedoRgb) || b.albedoRgb.r < 0 || b.albedoRgb.g < 0 || b.albedoRgb.b < 0) {
    throw std::invalid_argument(who + " needs a finite albedo >= 0");
  }
  if (b.photometry.law == sky::Photometry::Law::Hapke) {
    try {
      sky::validate(b.photometry.hapke);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(who + ": " + e.what());
    }
  }
  if (!std::isfinite(glm::determinant(b.bodyFixedToInertial)) ||
        std::abs(glm::determinant(b.bodyFixedToInertial) - 1.0) > 1e-6)
      throw std::invalid_argument(who + " needs a rotation as its body-fixed frame");
  if (!(std::isfinite(b.flattening) && b.flattening >= 0.0 && b.flattening < 0.5))
    throw std::invalid_argument(who + " needs a flattening in [0, 0.5)");
  if (!(std::isfinite(b.reliefStrength) && b.reliefStrength >= 0.0 && b.reliefStrength <= 4.0))
    throw std::invalid_argument(who + " needs a relief strength in [0, 4]");
  if (!finite(b.earthshineWm2) || b.earthshineWm2.r < 0 || b.earthshineWm2.g < 0 || b.earthshineWm2.b < 0 ||
      !finite(b.earthCentreM))
    throw std::invalid_argument(who + " needs a finite earthshine >= 0 from a finite Earth position");
}

eclipse::Occluder occluderOf(const SphereBody& b) {
  return {b.centreM, b.radiusM, {b.bodyFixedToInertial[2], b.flattening}, b.velocityMps, b.lightDelayS};
}

SphereBody occluderSeenBy(const SphereBody& occluder, const SphereBody& receiver) {
  const eclipse::Occluder o =
      eclipse::occluderSeenBy(occluderOf(occluder), receiver.centreM, receiver.radiusM, receiver.lightDelayS);
  SphereBody seen = occluder;
  seen.centreM = o.centreM;
  seen.lightDelayS = o.lightDelayS;
  return seen;
}

struct Receiver {
  vtkSmartPointer<vtkActor> actor;
  vtkSmartPointer<vtkOpenGLPolyDataMapper> mapper;
  SphereBody body;
  vtkSmartPointer<vtkTexture> albedoTexture;  // of body.albedoMap's texels, for this actor's window
  vtkSmartPointer<vtkTexture> normalTexture;  // of body.normalMap's
  unsigned long observerTag = 0;
  std::string fragmentDecl;  // the fragment code its shader was given (fragmentDeclFor)
};

struct EclipseShading::Impl {
  vtkSmartPointer<vtkTexture> lutTexture;
  // The u and v ranges of lutTexture (its field data, filters::lutRangeOf): the
  // umbraShadowLutMap and MapLow uniforms (LutRange::textureMap).
  eclipse::LutRange lutRange;
  SunLight sun;
  std::vector<SphereBody> occluders;
  std::vector<std::unique_ptr<Receiver>> receivers;
  glm::dvec3 origin{0.0};
  // The atmospheric shadow LuT of one occluder (SetAtmosphereShadowLut); without one the
  // receivers still bind a 2x2 table of ones under its name (their shader samples it).
  std::string atmosphereOccluder;
  vtkSmartPointer<vtkTexture> atmosphereTexture;
  vtkSmartPointer<vtkImageData> atmosphereNone;
  // The place of the part held in the whole table: (texture coordinate of its first
  // texel, step, the same in v) in the whole table's texture coordinates, and its size.
  std::array<double, 4> atmospherePart{0.25, 0.5, 0.25, 0.5};
  std::array<int, 2> atmospherePartSize{2, 2};
  // The u and v ranges of the whole atmospheric table (its field data); with the part,
  // the umbraAtmosphereLutMap and MapLow uniforms (atmosphereTextureMap).
  eclipse::LutRange atmosphereRange;

  // The receiver's occluders, each where it is for the receiver's shadow (occluderSeenBy).
  std::vector<SphereBody> occludersOf(const SphereBody& receiver) const {
    std::vector<SphereBody> out;
    for (const SphereBody& o : occluders) {
      const bool self = receiver.name.empty()
                            ? (o.centreM == receiver.centreM && o.radiusM == receiver.radiusM)
                            : o.name == receiver.name;
      if (!self) out.push_back(occluderSeenBy(o, receiver));
    }
    return out;
  }

  void checkOccluderCount(const SphereBody& receiver, std::size_t count) const {
    if (count > static_cast<std::size_t>(kMaxOccluders)) {
      throw std::invalid_argument("receiver '" + receiver.name + "' has " + std::to_string(count) +
                                  " occluders; at most " + std::to_string(kMaxOccluders) + " are supported");
    }
  }

  void place(Receiver& r) const {
    const glm::dvec3 p = r.body.centreM - origin;
    r.actor->SetPosition(p.x, p.y, p.z);
  }

  // The index among occludersOf(receiver) of the occluder shaded with the atmospheric LuT, -1: none.
  int atmosphereIndexOf(const SphereBody& receiver) const {
    if (atmosphereOccluder.empty()) return -1;
    const auto occ = occludersOf(receiver);
    for (std::size_t i = 0; i < occ.size() && i < static_cast<std::size_t>(kMaxOccluders); ++i)
      if (occ[i].name == atmosphereOccluder) return static_cast<int>(i);
    return -1;
  }

  // The radius the receivers' shader takes for an occluder: its equatorial radius when
  // oblate (the shader scales it to the outline's towards the Sun), else its own.
  static double shadowRadiusM(const SphereBody& o) {
    return eclipse::equatorialRadiusM(o.radiusM, occluderOf(o).figure);
  }

  // UMBRA_OBLATE_SHADOW: bit i for an oblate occluder.
  int oblateShadowsOf(const SphereBody& receiver) const {
    int mask = 0, k = 0;
    for (const SphereBody& o : occludersOf(receiver)) {
      if (k == kMaxOccluders) break;
      if (o.flattening > 0.0) mask |= 1 << k;
      ++k;
    }
    return mask;
  }

  // The angular radii (Eq. 3) of the Sun ([kMaxOccluders]) and of the receiver's
  // occluders over the receiver's surface, expanded about its centre
  // (umbraSunAngularRadius, umbraOccluderAngularRadius).
  std::array<eclipse::AngularRadiusExpansion, kMaxOccluders + 1> angularRadiiOver(const SphereBody& receiver) const {
    std::array<eclipse::AngularRadiusExpansion, kMaxOccluders + 1> x{};
    const double h = receiver.radiusM;
    x[kMaxOccluders] = eclipse::angularRadiusExpansion(sun.radiusM, glm::length(sun.positionM - receiver.centreM), h);
    int n = 0;
    for (const SphereBody& o : occludersOf(receiver)) {
      if (n == kMaxOccluders) break;
      x[n++] = eclipse::angularRadiusExpansion(shadowRadiusM(o), glm::length(o.centreM - receiver.centreM), h);
    }
    return x;
  }

  // UMBRA_EXACT_SHADOW: bit i for an occluder whose shadow the receiver's shader must
  // compute exactly (eclipse::receiverShadowExpands false, e.g. a receiver close to it).
  int exactShadowsOf(const SphereBody& receiver) const {
    const auto x = angularRadiiOver(receiver);
    const std::size_t n = std::min(occludersOf(receiver).size(), static_cast<std::size_t>(kMaxOccluders));
    int mask = 0;
    for (std::size_t k = 0; k < n; ++k)
      if (!eclipse::receiverShadowExpands(x[kMaxOccluders], x[k])) mask |= 1 << k;
    return mask;
  }

  // The receiver's fragment code with its occluder count, atmospheric occluder and the
  // shadows it computes exactly as constants (ReceiverFragment.glsl): the shadow loop
  // unrolls to exactly its occluders, one LuT lookup each, nothing for a receiver
  // without any.
  // Its photometry too: UMBRA_PHOTOMETRY, UMBRA_ALBEDO_MAP and UMBRA_EARTHSHINE.
  std::string fragmentDeclFor(const SphereBody& receiver) const {
    const std::size_t n = std::min(occludersOf(receiver).size(), static_cast<std::size_t>(kMaxOccluders));
    const bool hapke = receiver.photometry.law == sky::Photometry::Law::Hapke;
    const bool earthshine = hapke && glm::length(receiver.earthshineWm2) > 0.0;
    return "#define UMBRA_OCCLUDER_COUNT " + std::to_string(n) + "\n#define UMBRA_ATMOSPHERE_OCCLUDER " +
           std::to_string(atmosphereIndexOf(receiver)) + "\n#define UMBRA_EXACT_SHADOW " +
           std::to_string(exactShadowsOf(receiver)) + "\n#define UMBRA_OBLATE_SHADOW " +
           std::to_string(oblateShadowsOf(receiver)) + "\n#define UMBRA_PHOTOMETRY " + (hapke ? "1" : "0") +
           "\n#define UMBRA_ALBEDO_MAP " + (!receiver.albedoMap ? "0" : receiver.albedoMapReflectance ? "2" : "1") +
           "\n#define UMBRA_EARTHSHINE " + (earthshine ? "1" : "0") +
           "\n#define UMBRA_NORMAL_MAP " + (!receiver.normalMap ? "0" : "1") + "\n" +
           eclipseGlslWithoutSampler() + "\n" +
           checkedGlsl("sky/glsl/Photometry.glsl", sky::kPhotometryGlsl) + "\n" +
           checkedGlsl("ReceiverFragment.glsl", glsl::kReceiverFragment) + "\n" + kFsDec.tag;
  }

  // Gives the receiver's shader the code for its present occluders (a rebuild when they changed).
  void updateFragmentDecl(Receiver& r) const {
    std::string decl = fragmentDeclFor(r.body);
    if (decl == r.fragmentDecl) return;
    r.actor->GetShaderProperty()->AddFragmentShaderReplacement(kFsDec.tag, true, decl, false);
    r.fragmentDecl = std::move(decl);
  }

  // Called by the mapper (UpdateShaderEvent) with its program bound, every draw.
  void setUniforms(const Receiver& r, vtkShaderProgram& program) const {
    const SphereBody& b = r.body;
    const glm::dvec3 sunRel = sun.positionM - b.centreM;
    const float sunPos[3] = {float(sunRel.x), float(sunRel.y), float(sunRel.z)};
    // With a map, the albedo over its mean on the disc: the map's texels times this.
    const glm::dvec3 a = b.albedoRgb / (b.albedoMap ? b.albedoMap->discMean : 1.0);
    const float albedo[3] = {float(a.r), float(a.g), float(a.b)};
    program.SetUniformf("umbraBodyRadius", float(b.radiusM));
    program.SetUniform3f("umbraAlbedo", albedo);
    const sky::HapkeParameters& h = b.photometry.hapke;
    const float hapke[3] = {float(h.oppositionWidth), float(h.lambertShare), float(h.forwardScatter)};
    program.SetUniform3f("umbraHapke", hapke);
    float toBody[9];  // column-major, as glUniformMatrix3fv reads it
    const glm::dmat3 inertialToBody = glm::transpose(b.bodyFixedToInertial);
    for (int col = 0; col < 3; ++col)
      for (int row = 0; row < 3; ++row) toBody[3 * col + row] = float(inertialToBody[col][row]);
    program.SetUniformMatrix3x3("umbraInertialToBodyFixed", toBody);
    if (b.albedoMap) program.SetUniformf("umbraAlbedoMapHalfTexel", float(0.5 / b.albedoMap->height));
    if (b.normalMap) {
      program.SetUniformf("umbraNormalMapHalfTexel", float(0.5 / b.normalMap->height));
      program.SetUniformf("umbraReliefStrength", float(b.reliefStrength));
    }
    const glm::dvec3 earthRel = b.earthCentreM - b.centreM;
    const float earthPos[3] = {float(earthRel.x), float(earthRel.y), float(earthRel.z)};
    const float earthshine[3] = {float(b.earthshineWm2.r), float(b.earthshineWm2.g), float(b.earthshineWm2.b)};
    program.SetUniform3f("umbraEarthPos", earthPos);
    program.SetUniform3f("umbraEarthshine", earthshine);
    program.SetUniform3f("umbraSunPos", sunPos);
    program.SetUniformf("umbraSunRadius", float(sun.radiusM));
    program.SetUniformf("umbraSunIrradiance", float(sun.irradianceAt1AuWm2));
    float occ[kMaxOccluders][4] = {}, figure[kMaxOccluders][4] = {};
    int n = 0;
    for (const SphereBody& o : occludersOf(b)) {
      if (n == kMaxOccluders) break;  // checked when set; never silently reached
      const glm::dvec3 rel = o.centreM - b.centreM;
      occ[n][0] = float(rel.x);
      occ[n][1] = float(rel.y);
      occ[n][2] = float(rel.z);
      occ[n][3] = float(shadowRadiusM(o));
      const eclipse::Oblateness f = occluderOf(o).figure;
      figure[n][0] = float(f.pole.x);
      figure[n][1] = float(f.pole.y);
      figure[n][2] = float(f.pole.z);
      figure[n][3] = float(f.flattening * (2.0 - f.flattening));
      ++n;
    }
    program.SetUniform4fv("umbraOccluders", kMaxOccluders, occ);
    program.SetUniform4fv("umbraOccluderFigure", kMaxOccluders, figure);
    const auto radii = angularRadiiOver(b);
    float phi[kMaxOccluders + 1][4];
    for (int k = 0; k <= kMaxOccluders; ++k) {
      const eclipse::AngularRadiusExpansion& x = radii[k];
      phi[k][0] = float(x.distanceM), phi[k][1] = float(x.phi0Rad), phi[k][2] = float(x.c1Rad), phi[k][3] = float(x.c2Rad);
    }
    program.SetUniform4f("umbraSunAngularRadius", phi[kMaxOccluders]);
    program.SetUniform4fv("umbraOccluderAngularRadius", kMaxOccluders, phi);
    setMapUniforms(program, "umbraShadowLut", lutRange.textureMap());
    setMapUniforms(program, "umbraAtmosphereLut", atmosphereTextureMap());
  }

  // The atmospheric table's texture coordinates in the part held: texel k of the part
  // is the whole's at coordinate first + k step, at (k + 0.5) / size in its own texture.
  eclipse::LutRange::TextureMap atmosphereTextureMap() const {
    eclipse::LutRange::TextureMap m = atmosphereRange.textureMap();
    auto fold = [](double& origin, double& scale, double first, double step, int size) {
      origin += (first - 0.5 * step) / scale;
      scale /= step * size;
    };
    const auto& part = atmospherePart;
    fold(m.uOrigin, m.uScale, part[0], part[1], atmospherePartSize[0]);
    fold(m.vOrigin, m.vScale, part[2], part[3], atmospherePartSize[1]);
    fold(m.vLowOrigin, m.vLowScale, part[2], part[3], atmospherePartSize[1]);
    return m;
  }

  static void setMapUniforms(vtkShaderProgram& program, const std::string& prefix,
                             const eclipse::LutRange::TextureMap& m) {
    const float map[4] = {float(m.uOrigin), float(m.uScale), float(m.vOrigin), float(m.vScale)};
    const float low[3] = {float(m.vSplit), float(m.vLowOrigin), float(m.vLowScale)};
    program.SetUniform4f((prefix + "Map").c_str(), map);
    program.SetUniform3f((prefix + "MapLow").c_str(), low);
  }

  void detach(Receiver& r) const {
    if (r.mapper) r.mapper->RemoveObserver(r.observerTag);
    vtkShaderProperty* sp = r.actor->GetShaderProperty();
    for (const Replacement& rep : {kVsDec, kVsImpl}) sp->ClearVertexShaderReplacement(rep.tag, true);
    for (const Replacement& rep : {kFsDec, kFsImpl}) sp->ClearFragmentShaderReplacement(rep.tag, true);
    r.actor->GetProperty()->RemoveTexture(kLutSamplerName);
    r.actor->GetProperty()->RemoveTexture(kAtmosphereLutSamplerName);
    r.actor->GetProperty()->RemoveTexture(kAlbedoMapSamplerName);
    r.actor->GetProperty()->RemoveTexture(kNormalMapSamplerName);
  }
};

namespace {
class ReceiverUniformsCommand : public vtkCommand {
 public:
  static ReceiverUniformsCommand* New() { return new ReceiverUniformsCommand; }
  void Execute(vtkObject*, unsigned long, void* callData) override {
    auto* program = static_cast<vtkShaderProgram*>(callData);
    if (program && owner && receiver) owner->setUniforms(*receiver, *program);
  }
  const EclipseShading::Impl* owner = nullptr;
  const Receiver* receiver = nullptr;
};
} // namespace

EclipseShading::EclipseShading() : impl_(std::make_unique<Impl>()) {
  auto none = vtkSmartPointer<vtkImageData>::New();
  none->SetDimensions(2, 2, 1);
  vtkNew<vtkFloatArray> ones;
  ones->SetNumberOfComponents(3);
  ones->SetNumberOfTuples(4);
  for (int k = 0; k < 12; ++k) ones->SetValue(k, 1.0f);
  none->GetPointData()->SetScalars(ones);
  impl_->atmosphereNone = none;
  impl_->atmosphereTexture = lutTexture();
  impl_->atmosphereTexture->SetInputData(rgbaTexels(none));
}

EclipseShading::~EclipseShading() { ClearReceivers(); }

namespace {
// Checks a shadow LuT image (2D, >= 2x2, float RGB, finite) and returns a copy.
vtkSmartPointer<vtkImageData> checkedLutCopy(vtkImageData* lut) {
  if (!lut) throw std::invalid_argument("shadow LuT image is null");
  int dims[3];
  lut->GetDimensions(dims);
  if (dims[0] < 2 || dims[1] < 2 || dims[2] != 1) {
    throw std::invalid_argument("shadow LuT must be a 2D image of at least 2x2 texels (got " +
                                std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" +
                                std::to_string(dims[2]) + ")");
  }
  vtkDataArray* scalars = lut->GetPointData()->GetScalars();
  if (!scalars || scalars->GetDataType() != VTK_FLOAT || scalars->GetNumberOfComponents() != 3) {
    throw std::invalid_argument("shadow LuT needs float RGB point scalars (3 components)");
  }
  const vtkIdType n = scalars->GetNumberOfTuples();
  if (n != static_cast<vtkIdType>(dims[0]) * dims[1]) {
    throw std::invalid_argument("shadow LuT has " + std::to_string(n) + " texels for " +
                                std::to_string(dims[0]) + "x" + std::to_string(dims[1]));
  }
  for (vtkIdType i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(scalars->GetComponent(i, c))) {
        throw std::invalid_argument("shadow LuT has a non-finite value at texel " + std::to_string(i));
      }
    }
  }
  auto copy = vtkSmartPointer<vtkImageData>::New();
  copy->DeepCopy(lut);
  return copy;
}

// The texels of a checked LuT as RGBA (alpha 1), the form the texture gets: Mesa's
// llvmpipe samples four-channel float textures much faster than RGB32F ones (as
// AtmosphereRendering's tables). (One channel for an airless LuT would not do:
// vtkOpenGLTexture makes one-component float scalars an RGBA8 texture.)
vtkSmartPointer<vtkImageData> rgbaTexels(vtkImageData* lut) {
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->CopyStructure(lut);
  vtkDataArray* rgb = lut->GetPointData()->GetScalars();
  vtkNew<vtkFloatArray> rgba;
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(rgb->GetNumberOfTuples());
  for (vtkIdType i = 0; i < rgb->GetNumberOfTuples(); ++i)
    for (int c = 0; c < 4; ++c) rgba->SetValue(4 * i + c, c < 3 ? static_cast<float>(rgb->GetComponent(i, c)) : 1.0f);
  out->GetPointData()->SetScalars(rgba);
  return out;
}

// A float RGBA LuT texture: values as they are, linear, clamp-to-edge, no mipmaps.
vtkSmartPointer<vtkTexture> lutTexture() {
  auto tex = vtkSmartPointer<vtkTexture>::New();
  tex->SetColorModeToDirectScalars();  // float values as they are: no lookup table
  tex->InterpolateOn();                // GL_LINEAR
  tex->MipmapOff();
  tex->SetWrap(vtkTexture::ClampToEdge);
  tex->UseSRGBColorSpaceOff();
  return tex;
}
} // namespace

void EclipseShading::SetShadowLut(vtkImageData* lut) {
  auto copy = checkedLutCopy(lut);
  try {
    impl_->lutRange = filters::lutRangeOf(filters::fieldParameters(copy), "shadow LuT");
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(e.what());
  }
  copy->SetOrigin(0.0, 0.0, 0.0);
  copy->SetSpacing(1.0, 1.0, 1.0);
  if (!impl_->lutTexture) impl_->lutTexture = lutTexture();
  impl_->lutTexture->SetInputData(rgbaTexels(copy));
  for (auto& r : impl_->receivers) r->actor->GetProperty()->SetTexture(kLutSamplerName, impl_->lutTexture);
}

void EclipseShading::SetAtmosphereShadowLut(const std::string& occluderName, vtkImageData* lut) {
  Impl& m = *impl_;
  if (occluderName.empty() || !lut) {
    m.atmosphereOccluder.clear();
    m.atmosphereTexture->SetInputData(rgbaTexels(m.atmosphereNone));
    m.atmospherePart = {0.25, 0.5, 0.25, 0.5};
    m.atmospherePartSize = {2, 2};
    m.atmosphereRange = {};
    for (auto& r : m.receivers) m.updateFragmentDecl(*r);
    return;
  }
  auto copy = checkedLutCopy(lut);
  eclipse::LutRange range;
  try {
    range = filters::lutRangeOf(filters::fieldParameters(copy), "atmospheric shadow LuT of '" + occluderName + "'");
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(e.what());
  }
  // The place of the part in the whole table: its first texel's (u, v) and the steps,
  // as texture coordinates of the whole. The points are at (u, v) in the ranges (v is
  // already the texture coordinate on a split v axis: filters::toImageData); identity at
  // the default ranges.
  double first[3], spacing[3];
  copy->GetPoint(0, first);
  copy->GetSpacing(spacing);
  if (!(spacing[0] > 0.0 && spacing[1] > 0.0 && std::isfinite(first[0]) && std::isfinite(first[1]))) {
    throw std::invalid_argument("atmospheric shadow LuT of '" + occluderName +
                                "' needs texel coordinates (u, v) with spacing > 0");
  }
  const double uSpan = range.uMax - range.uMin;
  const bool splitV = range.vLowFraction > 0.0;
  const double vMin = splitV ? 0.0 : range.vMin, vSpan = splitV ? 1.0 : range.vMax - range.vMin;
  m.atmospherePart = {(first[0] - range.uMin) / uSpan, spacing[0] / uSpan, (first[1] - vMin) / vSpan,
                      spacing[1] / vSpan};
  m.atmosphereRange = range;
  int ext[6];
  copy->GetExtent(ext);
  m.atmospherePartSize = {ext[1] - ext[0] + 1, ext[3] - ext[2] + 1};
  copy->SetExtent(0, ext[1] - ext[0], 0, ext[3] - ext[2], 0, 0);
  copy->SetOrigin(0.0, 0.0, 0.0);
  copy->SetSpacing(1.0, 1.0, 1.0);
  m.atmosphereOccluder = occluderName;
  m.atmosphereTexture->SetInputData(rgbaTexels(copy));
  for (auto& r : m.receivers) m.updateFragmentDecl(*r);
}

const std::string& EclipseShading::GetAtmosphereOccluder() const { return impl_->atmosphereOccluder; }

bool EclipseShading::HasShadowLut() const { return impl_->lutTexture != nullptr; }

vtkTexture* EclipseShading::GetShadowLutTexture() const { return impl_->lutTexture; }

void validateSun(const SunLight& sun) {
  if (!finite(sun.positionM)) throw std::invalid_argument("Sun position is not finite");
  if (!(std::isfinite(sun.radiusM) && sun.radiusM > 0.0)) throw std::invalid_argument("Sun radius must be > 0");
  if (!(std::isfinite(sun.irradianceAt1AuWm2) && sun.irradianceAt1AuWm2 >= 0.0)) {
    throw std::invalid_argument("Sun irradiance at 1 au must be finite and >= 0");
  }
}

void EclipseShading::SetSun(const SunLight& sun) {
  validateSun(sun);
  impl_->sun = sun;
  for (auto& r : impl_->receivers) impl_->updateFragmentDecl(*r);
}

void EclipseShading::SetOccluders(const std::vector<SphereBody>& occluders) {
  for (const SphereBody& o : occluders) validateBody(o);
  std::vector<SphereBody> previous = std::move(impl_->occluders);
  impl_->occluders = occluders;
  try {
    for (const auto& r : impl_->receivers) impl_->checkOccluderCount(r->body, impl_->occludersOf(r->body).size());
  } catch (...) {
    impl_->occluders = std::move(previous);
    throw;
  }
  for (auto& r : impl_->receivers) impl_->updateFragmentDecl(*r);
}

void EclipseShading::MakeReceiver(vtkActor* actor, const SphereBody& body, const glm::dvec3& originM) {
  if (!actor) throw std::invalid_argument("receiver actor is null");
  validateBody(body);
  if (!finite(originM)) throw std::invalid_argument("origin is not finite");
  if (!impl_->lutTexture) throw std::invalid_argument("set the shadow LuT before making receiver '" + body.name + "'");
  auto* mapper = vtkOpenGLPolyDataMapper::SafeDownCast(actor->GetMapper());
  if (!mapper) {
    throw std::invalid_argument("receiver '" + body.name + "' needs a vtkOpenGLPolyDataMapper");
  }
  impl_->checkOccluderCount(body, impl_->occludersOf(body).size());
  const std::string vsDec = checkedGlsl("ReceiverVertex.glsl", glsl::kReceiverVertex);

  Receiver* receiver = nullptr;
  for (auto& r : impl_->receivers) {
    if (r->actor == actor) receiver = r.get();
    else if (r->mapper == mapper) {
      throw std::invalid_argument("receiver '" + body.name + "' shares its mapper with receiver '" + r->body.name + "'");
    }
  }
  if (receiver && receiver->mapper != mapper) {  // mapper swapped since: start over
    impl_->detach(*receiver);
    receiver->observerTag = 0;
  }
  const bool fresh = !receiver || receiver->observerTag == 0;
  if (!receiver) {
    impl_->receivers.push_back(std::make_unique<Receiver>());
    receiver = impl_->receivers.back().get();
    receiver->actor = actor;
  }
  receiver->mapper = mapper;
  // A texture for each map that is new to this receiver (a fresh one has none).
  if (body.albedoMap != receiver->body.albedoMap)
    receiver->albedoTexture = body.albedoMap ? mapTextureOf(*body.albedoMap) : nullptr;
  if (body.normalMap != receiver->body.normalMap)
    receiver->normalTexture = body.normalMap ? mapTextureOf(*body.normalMap) : nullptr;
  receiver->body = body;

  // The actor only translates: model coordinates stay body-centred with world axes.
  actor->SetOrientation(0.0, 0.0, 0.0);
  actor->SetScale(1.0);
  actor->SetOrigin(0.0, 0.0, 0.0);
  actor->SetUserMatrix(nullptr);
  actor->SetUserTransform(nullptr);
  SetOrigin(originM);  // one origin for all receivers
  // vertexMC must be the plain model coordinate in the shader.
  mapper->SetVBOShiftScaleMethod(vtkOpenGLVertexBufferObject::DISABLE_SHIFT_SCALE);
  mapper->ScalarVisibilityOff();
  vtkProperty* prop = actor->GetProperty();
  prop->BackfaceCullingOn();  // a convex mesh: no self-overlap, depth only orders bodies
  prop->SetTexture(kLutSamplerName, impl_->lutTexture);
  prop->SetTexture(kAtmosphereLutSamplerName, impl_->atmosphereTexture);
  if (receiver->albedoTexture) prop->SetTexture(kAlbedoMapSamplerName, receiver->albedoTexture);
  else prop->RemoveTexture(kAlbedoMapSamplerName);
  if (receiver->normalTexture) prop->SetTexture(kNormalMapSamplerName, receiver->normalTexture);
  else prop->RemoveTexture(kNormalMapSamplerName);

  if (fresh) {
    vtkShaderProperty* sp = actor->GetShaderProperty();
    sp->AddVertexShaderReplacement(kVsDec.tag, true, vsDec, false);
    sp->AddVertexShaderReplacement(kVsImpl.tag, true,
                                   std::string("  umbraReceiverVertex(vertexMC);\n") + kVsImpl.tag, false);
    sp->AddFragmentShaderReplacement(kFsImpl.tag, true, std::string("  umbraReceiverShade();\n") + kFsImpl.tag,
                                     false);
    vtkNew<ReceiverUniformsCommand> cmd;
    cmd->owner = impl_.get();
    cmd->receiver = receiver;
    receiver->observerTag = mapper->AddObserver(vtkCommand::UpdateShaderEvent, cmd);
    receiver->fragmentDecl.clear();
  }
  impl_->updateFragmentDecl(*receiver);
  actor->Modified();
}

void EclipseShading::RemoveReceiver(vtkActor* actor) {
  auto& rs = impl_->receivers;
  auto it = std::find_if(rs.begin(), rs.end(), [&](const auto& r) { return r->actor == actor; });
  if (it == rs.end()) return;
  impl_->detach(**it);
  rs.erase(it);
}

void EclipseShading::ClearReceivers() {
  for (auto& r : impl_->receivers) impl_->detach(*r);
  impl_->receivers.clear();
}

int EclipseShading::GetNumberOfReceivers() const { return static_cast<int>(impl_->receivers.size()); }

void EclipseShading::SetOrigin(const glm::dvec3& originM) {
  if (!finite(originM)) throw std::invalid_argument("origin is not finite");
  impl_->origin = originM;
  for (auto& r : impl_->receivers) impl_->place(*r);
}

const glm::dvec3& EclipseShading::GetOrigin() const { return impl_->origin; }

} // namespace umbra::render
