#include "TerrainRendering.h"

#include "RenderGlsl.hpp"
#include "TerrainShadowGlsl.hpp"
#include "TerrainShadowGpu.h"

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkOpenGLPolyDataMapper.h>
#include <vtkOpenGLVertexBufferObject.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkShaderProgram.h>
#include <vtkShaderProperty.h>
#include <vtkTexture.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace umbra::render {
namespace {

constexpr int kLevels = 6;  // N' of the DP search, as terrain::ShadowOptions

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// VTK declares the samplers of a property's textures itself: drop the file's own.
std::string shadowGlslWithoutSamplers() {
  std::string src = terrain::kTerrainShadowGlsl;
  for (const char* decl : {"uniform sampler2D umbraHeights;", "uniform sampler2D umbraMipAtlas;"}) {
    const auto at = src.find(decl);
    if (at == std::string::npos)
      throw std::logic_error(std::string("terrain/glsl/TerrainShadow.glsl no longer declares '") + decl + "'");
    src.replace(at, std::string(decl).size(), "// (sampler declared by VTK)");
  }
  if (src.find("//VTK::") != std::string::npos) throw std::logic_error("TerrainShadow.glsl contains a //VTK:: tag");
  return src;
}

vtkSmartPointer<vtkTexture> floatTexture(int width, int height, const std::vector<float>& data) {
  vtkNew<vtkImageData> image;
  image->SetDimensions(width, height, 1);
  // Three components: VTK 9.1 passes float RGB through unchanged (as the eclipse LuT)
  // but maps single-component scalars to 8-bit colours.
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfComponents(3);
  values->SetNumberOfTuples(static_cast<vtkIdType>(data.size()));
  float* out = values->GetPointer(0);
  for (std::size_t k = 0; k < data.size(); ++k) out[3 * k] = out[3 * k + 1] = out[3 * k + 2] = data[k];
  image->GetPointData()->SetScalars(values);
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->SetColorModeToDirectScalars();
  texture->InterpolateOff();
  texture->MipmapOff();
  texture->SetWrap(vtkTexture::ClampToEdge);
  texture->UseSRGBColorSpaceOff();
  texture->SetInputData(image);
  return texture;
}

} // namespace

struct TerrainRendering::Impl {
  TerrainPatch patch;
  std::unique_ptr<terrain::MaximumMipmap> mip;
  TerrainShadowTextures textures;
  vtkSmartPointer<vtkActor> actor;
  vtkSmartPointer<vtkOpenGLPolyDataMapper> mapper;
  SunLight sun;
  glm::dvec3 origin{0.0};
  Output output = Output::Radiance;
  unsigned long observerTag = 0;
  std::shared_ptr<const terrain::ShadowTable> table;

  glm::dvec3 tangentPointM() const {
    return patch.bodyCentreM + patch.tangentToWorld * glm::dvec3(0.0, 0.0, patch.field.bodyRadiusM);
  }
  void place() const {
    if (!actor) return;
    const glm::dvec3 p = tangentPointM() - origin;
    vtkNew<vtkMatrix4x4> m;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) m->SetElement(r, c, patch.tangentToWorld[c][r]);
      m->SetElement(r, 3, p[r]);
    }
    actor->SetUserMatrix(m);
  }
  /// The shadow search and the fragment stage, with or without the table.
  void setFragmentDeclarations() const {
    vtkShaderProperty* sp = actor->GetShaderProperty();
    sp->ClearFragmentShaderReplacement("//VTK::Edges::Dec", true);
    sp->AddFragmentShaderReplacement("//VTK::Edges::Dec", true,
                                     std::string("#define UMBRA_TERRAIN_TABLE ") + (table ? "1" : "0") + "\n" +
                                         shadowGlslWithoutSamplers() + "\n" + glsl::kTerrainFragment +
                                         "\n//VTK::Edges::Dec",
                                     false);
  }
  terrain::SunDisc sunDisc() const {
    const glm::dvec3 toSun = sun.positionM - tangentPointM();
    terrain::SunDisc disc;
    disc.direction = glm::normalize(glm::transpose(patch.tangentToWorld) * toSun);
    disc.angularRadiusRad = std::asin(std::min(1.0, sun.radiusM / glm::length(toSun)));
    return disc;
  }
  double irradiance() const { return sun.irradianceAtWm2(glm::length(sun.positionM - tangentPointM())); }
  void setUniforms(vtkShaderProgram& program) const {
    const terrain::SunDisc exact = sunDisc();
    const terrain::ShadowOptions near = table ? table->nearSearch() : terrain::ShadowOptions{};
    setTerrainShadowUniforms(program, textures, patch.field, *mip, table ? table->sun : exact, kLevels,
                             table ? near.toTexels : 1e30);
    const glm::dvec3 l = glm::normalize(exact.direction);
    const float light[3] = {float(l.x), float(l.y), float(l.z)};
    program.SetUniform3f("umbraTerrainLight", light);
    const float albedo[3] = {float(patch.albedoRgb.r), float(patch.albedoRgb.g), float(patch.albedoRgb.b)};
    program.SetUniform3f("umbraTerrainAlbedo", albedo);
    program.SetUniformf("umbraTerrainIrradiance", float(irradiance()));
    program.SetUniformi("umbraTerrainOutput", output == Output::GridAndFraction ? 1 : 0);
    const glm::dvec3 eye = glm::transpose(patch.tangentToWorld) * (origin - tangentPointM());
    const float eyePatch[3] = {float(eye.x), float(eye.y), float(eye.z)};
    program.SetUniform3f("umbraTerrainEye", eyePatch);
  }
};

namespace {
class TerrainUniformsCommand : public vtkCommand {
public:
  static TerrainUniformsCommand* New() { return new TerrainUniformsCommand; }
  void Execute(vtkObject*, unsigned long, void* callData) override {
    auto* program = static_cast<vtkShaderProgram*>(callData);
    if (program && owner && owner->mip) owner->setUniforms(*program);
  }
  const TerrainRendering::Impl* owner = nullptr;
};

// The pre-displaced mesh: (R + h) along the unit vector through each mesh sample, in
// patch coordinates (tangent frame - (0, 0, R)) formed from small differences.
vtkSmartPointer<vtkPolyData> displacedMesh(const terrain::HeightField& f, int step) {
  std::vector<int> is, js;
  for (int i = 0; i < f.width - 1; i += step) is.push_back(i);
  is.push_back(f.width - 1);
  for (int j = 0; j < f.height - 1; j += step) js.push_back(j);
  js.push_back(f.height - 1);
  const double R = f.bodyRadiusM;
  // Lowered so that the mesh stays below the bilinear surface (the paper starts its rays
  // from a mesh on one side of the surface too): a camera above the ground is then always
  // above the mesh, and every view ray that meets the ground meets the mesh first. Within
  // a cell of one sample the surface rises at most |h00 - h10 - h01 + h11| / 4 above the
  // triangles; over a coarser cell, at most its highest sample above its lowest corner.
  const std::size_t nx = is.size(), ny = js.size();
  std::vector<double> lower(nx * ny, 0.0);
  const double cellM = step * f.spacingM * std::sqrt(2.0);
  const double sagittaM = cellM * cellM / (8.0 * R);
  for (std::size_t b = 0; b + 1 < ny; ++b)
    for (std::size_t a = 0; a + 1 < nx; ++a) {
      const double c00 = f.receiverHeight(is[a], js[b]), c10 = f.receiverHeight(is[a + 1], js[b]);
      const double c01 = f.receiverHeight(is[a], js[b + 1]), c11 = f.receiverHeight(is[a + 1], js[b + 1]);
      double rise = 0.25 * std::abs(c00 - c10 - c01 + c11);
      if (is[a + 1] - is[a] > 1 || js[b + 1] - js[b] > 1) {
        double hi = -1e300;
        for (int j = js[b]; j <= js[b + 1]; ++j)
          for (int i = is[a]; i <= is[a + 1]; ++i)
            if (f.valid(i, j)) hi = std::max(hi, f.at(i, j));
        rise = std::max(0.0, hi - std::min({c00, c10, c01, c11}));
      }
      rise += sagittaM + 0.01;
      for (std::size_t v : {b * nx + a, b * nx + a + 1, (b + 1) * nx + a, (b + 1) * nx + a + 1})
        lower[v] = std::max(lower[v], rise);
    }
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(nx * ny));
  vtkIdType id = 0;
  for (int j : js)
    for (int i : is) {
      const double h = f.receiverHeight(i, j) - lower[static_cast<std::size_t>(id)];
      const glm::dvec2 p = f.planeM(i, j);
      const double p2 = glm::dot(p, p), n = std::sqrt(p2 + R * R);
      points->SetPoint(id++, (R + h) / n * p.x, (R + h) / n * p.y, (h * R - R * p2 / (n + R)) / n);
    }
  vtkNew<vtkCellArray> cells;
  for (vtkIdType b = 0; b + 1 < static_cast<vtkIdType>(ny); ++b)
    for (vtkIdType a = 0; a + 1 < static_cast<vtkIdType>(nx); ++a) {
      const vtkIdType p00 = b * static_cast<vtkIdType>(nx) + a, p10 = p00 + 1, p01 = p00 + static_cast<vtkIdType>(nx), p11 = p01 + 1;
      const vtkIdType t1[3] = {p00, p10, p11}, t2[3] = {p00, p11, p01};
      cells->InsertNextCell(3, t1);
      cells->InsertNextCell(3, t2);
    }
  vtkNew<vtkPolyData> mesh;
  mesh->SetPoints(points);
  mesh->SetPolys(cells);
  return mesh;
}
} // namespace

TerrainRendering::TerrainRendering() : impl_(std::make_unique<Impl>()) {}

TerrainRendering::~TerrainRendering() {
  if (impl_->mapper && impl_->observerTag) impl_->mapper->RemoveObserver(impl_->observerTag);
}

namespace {
void validatePlacement(const glm::dvec3& bodyCentreM, const glm::dmat3& tangentToWorld) {
  for (int c = 0; c < 3; ++c)
    if (!finite(tangentToWorld[c]) || std::abs(glm::length(tangentToWorld[c]) - 1.0) > 1e-6)
      throw std::invalid_argument("terrain: the tangent-to-world rotation must have unit columns");
  if (!finite(bodyCentreM)) throw std::invalid_argument("terrain: the body centre is not finite");
}
} // namespace

void TerrainRendering::SetTerrain(const TerrainPatch& patch) {
  patch.field.validate();
  validatePlacement(patch.bodyCentreM, patch.tangentToWorld);
  if (!finite(patch.albedoRgb) || patch.albedoRgb.r < 0 || patch.albedoRgb.g < 0 || patch.albedoRgb.b < 0)
    throw std::invalid_argument("terrain: the albedo must be finite and >= 0");
  if (patch.meshStep < 0) throw std::invalid_argument("terrain: the mesh step must be >= 0");
  Impl& m = *impl_;
  m.patch = patch;
  if (m.patch.meshStep == 0)
    m.patch.meshStep = std::max(1, (std::max(patch.field.width, patch.field.height) - 1 + 1023) / 1024);
  m.mip = std::make_unique<terrain::MaximumMipmap>(m.patch.field);
  m.textures = terrainShadowTextures(m.patch.field, *m.mip);

  if (!m.actor) {
    m.actor = vtkSmartPointer<vtkActor>::New();
    m.mapper = vtkSmartPointer<vtkOpenGLPolyDataMapper>::New();
    m.actor->SetMapper(m.mapper);
    // vertexMC must be the plain patch coordinate in the shader.
    m.mapper->SetVBOShiftScaleMethod(vtkOpenGLVertexBufferObject::DISABLE_SHIFT_SCALE);
    m.mapper->ScalarVisibilityOff();
    // The fragment stage writes its depth, so every fragment is shaded before the depth
    // test. From above the mesh (where the camera always is: the mesh lies below the
    // surface) a ray enters the mesh through a front face first; the back faces, where it
    // comes out again further on, are always hidden: not drawn.
    m.actor->GetProperty()->BackfaceCullingOn();
    vtkShaderProperty* sp = m.actor->GetShaderProperty();
    sp->AddVertexShaderReplacement("//VTK::Camera::Dec", true, glsl::kReceiverVertex, false);
    sp->AddVertexShaderReplacement("//VTK::CustomEnd::Impl", true,
                                   "  umbraReceiverVertex(vertexMC);\n//VTK::CustomEnd::Impl", false);
    m.setFragmentDeclarations();
    sp->AddFragmentShaderReplacement("//VTK::TCoord::Impl", true, "  umbraTerrainShade();\n//VTK::TCoord::Impl", false);
    vtkNew<TerrainUniformsCommand> cmd;
    cmd->owner = impl_.get();
    m.observerTag = m.mapper->AddObserver(vtkCommand::UpdateShaderEvent, cmd);
  }
  if (m.table) {  // made for another height field
    m.table.reset();
    m.actor->GetProperty()->RemoveTexture("umbraFarOffsets");
    m.setFragmentDeclarations();
  }
  m.mapper->SetInputData(displacedMesh(m.patch.field, m.patch.meshStep));
  vtkProperty* prop = m.actor->GetProperty();
  prop->SetTexture("umbraHeights", floatTexture(m.patch.field.width, m.patch.field.height, m.textures.heights));
  prop->SetTexture("umbraMipAtlas", floatTexture(m.textures.atlasWidth, m.textures.atlasHeight, m.textures.atlas));
  m.place();
  m.actor->Modified();
}

void TerrainRendering::SetPlacement(const glm::dvec3& bodyCentreM, const glm::dmat3& tangentToWorld) {
  if (!impl_->mip) throw std::logic_error("TerrainRendering: no terrain set");
  validatePlacement(bodyCentreM, tangentToWorld);
  impl_->patch.bodyCentreM = bodyCentreM;
  impl_->patch.tangentToWorld = tangentToWorld;
  impl_->place();
}

void TerrainRendering::SetSun(const SunLight& sun) {
  validateSun(sun);
  impl_->sun = sun;
}

void TerrainRendering::SetOrigin(const glm::dvec3& originM) {
  if (!finite(originM)) throw std::invalid_argument("terrain: the origin is not finite");
  impl_->origin = originM;
  impl_->place();
}

void TerrainRendering::SetOutput(Output output) {
  impl_->output = output;
  if (impl_->actor) impl_->actor->Modified();
}

void TerrainRendering::SetShadowTable(std::shared_ptr<const terrain::ShadowTable> table) {
  Impl& m = *impl_;
  if (!m.mip) throw std::logic_error("TerrainRendering: no terrain set");
  if (table && (table->width != m.patch.field.width || table->height != m.patch.field.height ||
                table->offsets.size() != static_cast<std::size_t>(table->width) * table->height))
    throw std::invalid_argument("terrain: the shadow table is not of this patch's size");
  const bool modeChanges = bool(table) != bool(m.table);
  m.table = std::move(table);
  vtkProperty* prop = m.actor->GetProperty();
  if (m.table)
    prop->SetTexture("umbraFarOffsets", floatTexture(m.table->width, m.table->height, m.table->offsets));
  else
    prop->RemoveTexture("umbraFarOffsets");
  if (modeChanges) m.setFragmentDeclarations();
  m.actor->Modified();
}

const terrain::ShadowTable* TerrainRendering::GetShadowTable() const { return impl_->table.get(); }

vtkActor* TerrainRendering::GetActor() const { return impl_->actor; }
const TerrainPatch& TerrainRendering::GetPatch() const { return impl_->patch; }
const terrain::MaximumMipmap& TerrainRendering::GetMipmap() const {
  if (!impl_->mip) throw std::logic_error("TerrainRendering: no terrain set");
  return *impl_->mip;
}
terrain::SunDisc TerrainRendering::GetSunDisc() const { return impl_->sunDisc(); }
double TerrainRendering::GetSunIrradiance() const { return impl_->irradiance(); }

} // namespace umbra::render
