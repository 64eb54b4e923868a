#include "AtmosphereTablesBlocks.h"

#include "FieldParameters.h"

#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkPointData.h>

#include <sstream>
#include <stdexcept>

namespace umbra::filters {
namespace {

vtkImageData* findBlock(vtkMultiBlockDataSet* blocks, const std::string& name) {
  for (unsigned i = 0; i < blocks->GetNumberOfBlocks(); ++i) {
    vtkInformation* info = blocks->HasMetaData(i) ? blocks->GetMetaData(i) : nullptr;
    if (info && info->Has(vtkCompositeDataSet::NAME()) && name == info->Get(vtkCompositeDataSet::NAME())) {
      if (auto* image = vtkImageData::SafeDownCast(blocks->GetBlock(i))) return image;
    }
  }
  return nullptr;
}

vtkImageData* block(vtkMultiBlockDataSet* blocks, const std::string& name) {
  if (vtkImageData* image = findBlock(blocks, name)) return image;
  throw std::invalid_argument("atmosphere tables: no block '" + name + "'");
}

/// The block's arrays (one per wavelength, in order) interleaved per texel, in a `Values`
/// (a std::vector of some allocator).
template <class Values>
Values interleaved(vtkImageData* image, const std::string& name, int channels) {
  using Value = typename Values::value_type;
  vtkPointData* pd = image->GetPointData();
  if (pd->GetNumberOfArrays() != channels) {
    throw std::invalid_argument("atmosphere tables: block '" + name + "' has " +
                                std::to_string(pd->GetNumberOfArrays()) + " channels, expected " +
                                std::to_string(channels));
  }
  const vtkIdType n = image->GetNumberOfPoints();
  Values v(static_cast<std::size_t>(n) * channels);
  for (int c = 0; c < channels; ++c) {
    vtkDataArray* a = pd->GetArray(c);
    if (!a || a->GetNumberOfTuples() != n || a->GetNumberOfComponents() != 1) {
      throw std::invalid_argument("atmosphere tables: block '" + name + "' has a malformed array");
    }
    for (vtkIdType i = 0; i < n; ++i) v[static_cast<std::size_t>(i) * channels + c] = static_cast<Value>(a->GetComponent(i, 0));
  }
  return v;
}

/// A table's size and values from its block (2D: depth 1).
template <class Table>
void readTable(vtkImageData* image, const std::string& name, int channels, Table& t, int& depth) {
  int dims[3];
  image->GetDimensions(dims);
  t.width = dims[0];
  t.height = dims[1];
  depth = dims[2];
  t.channels = channels;
  t.values = interleaved<decltype(t.values)>(image, name, channels);
}
void read2D(vtkMultiBlockDataSet* blocks, const std::string& name, int channels, atmosphere::Table2D& t) {
  int depth = 1;
  readTable(block(blocks, name), name, channels, t, depth);
}
void read3D(vtkImageData* image, const std::string& name, int channels, atmosphere::FloatTable3D& t) {
  readTable(image, name, channels, t, t.depth);
}

std::string parameter(vtkImageData* image, const std::string& block, const std::string& key) {
  const auto p = filters::fieldParameters(image);
  const auto it = p.find(key);
  if (it == p.end()) throw std::invalid_argument("atmosphere tables: block '" + block + "' has no parameter '" + key + "'");
  return it->second;
}

} // namespace

atmosphere::AtmosphereTables tablesFromBlocks(vtkMultiBlockDataSet* blocks, const atmosphere::Atmosphere& atm) {
  if (!blocks) throw std::invalid_argument("atmosphere tables: no data");
  atmosphere::AtmosphereTables t;
  const int nc = static_cast<int>(atm.wavelengthsNm.size());
  t.bottomRadiusM = atm.bottomRadiusM;
  t.topRadiusM = atm.topRadiusM;
  t.wavelengthsNm = atm.wavelengthsNm;
  read2D(blocks, "transmittance", nc, t.transmittance);
  read3D(block(blocks, "multiple-scattering"), "multiple-scattering", nc, t.multipleScattering);
  read2D(blocks, "direct-irradiance", nc, t.directIrradiance);
  read2D(blocks, "irradiance", nc, t.irradiance);
  for (const atmosphere::Component& c : atm.components) {
    if (!c.scatters()) continue;
    // The block whose "component" parameter names it.
    vtkImageData* single = nullptr;
    for (unsigned i = 0; i < blocks->GetNumberOfBlocks() && !single; ++i) {
      auto* image = vtkImageData::SafeDownCast(blocks->GetBlock(i));
      if (!image) continue;
      const auto p = filters::fieldParameters(image);
      const auto kind = p.find("kind"), component = p.find("component");
      if (kind != p.end() && kind->second.rfind("atmosphere-single-scattering", 0) == 0 && component != p.end() &&
          component->second == c.name)
        single = image;
    }
    if (!single) throw std::invalid_argument("atmosphere tables: no single-scattering block for component '" + c.name + "'");
    t.scatteringComponents.push_back(c.name);
    t.singleScattering.emplace_back();
    read3D(single, "single-scattering of " + c.name, nc, t.singleScattering.back());
  }
  vtkImageData* ms = block(blocks, "multiple-scattering");
  atmosphere::PrecomputeOptions& o = t.options;
  {
    std::istringstream in(parameter(ms, "multiple-scattering", "scatteringSize"));
    char comma = 0;
    in >> o.scatteringR >> comma >> o.scatteringMu >> comma >> o.scatteringMuS >> comma >> o.scatteringNu;
    if (!in) throw std::invalid_argument("atmosphere tables: bad scatteringSize");
  }
  o.muSMin = std::stod(parameter(ms, "multiple-scattering", "muSMin"));
  o.sunAngularRadiusRad = std::stod(parameter(ms, "multiple-scattering", "sunAngularRadiusRad"));
  o.transmittanceWidth = t.transmittance.width;
  o.transmittanceHeight = t.transmittance.height;
  o.irradianceWidth = t.irradiance.width;
  o.irradianceHeight = t.irradiance.height;
  auto checkScattering = [&](const atmosphere::FloatTable3D& s, const std::string& name) {
    if (s.width != o.scatteringNu * o.scatteringMuS || s.height != o.scatteringMu || s.depth != o.scatteringR)
      throw std::invalid_argument("atmosphere tables: block '" + name + "' does not match scatteringSize");
  };
  checkScattering(t.multipleScattering, "multiple-scattering");
  for (std::size_t q = 0; q < t.singleScattering.size(); ++q)
    checkScattering(t.singleScattering[q], "single-scattering-" + t.scatteringComponents[q]);
  return t;
}


atmosphere::RefractionTable refractionFromBlocks(vtkMultiBlockDataSet* blocks, const atmosphere::Atmosphere& atm) {
  if (!blocks) throw std::invalid_argument("atmosphere tables: no data");
  vtkImageData* image = block(blocks, "refraction");
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* deviation = image->GetPointData()->GetArray("deviation_rad");
  vtkDataArray* contact = image->GetPointData()->GetArray("contact_altitude_m");
  const vtkIdType n = image->GetNumberOfPoints();
  if (!deviation || !contact || deviation->GetNumberOfTuples() != n || contact->GetNumberOfTuples() != n ||
      dims[2] != 1 || dims[0] < 2 || dims[1] < 2)
    throw std::invalid_argument("atmosphere tables: block 'refraction' lacks deviation_rad / contact_altitude_m");
  atmosphere::RefractionTable r;
  r.width = dims[0];
  r.height = dims[1];
  r.bottomRadiusM = atm.bottomRadiusM;
  r.topRadiusM = atm.topRadiusM;
  r.stepM = std::stod(parameter(image, "refraction", "stepM"));
  r.deviationRad.resize(static_cast<std::size_t>(n));
  r.contactAltitudeM.resize(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i) {
    r.deviationRad[static_cast<std::size_t>(i)] = static_cast<float>(deviation->GetComponent(i, 0));
    r.contactAltitudeM[static_cast<std::size_t>(i)] = static_cast<float>(contact->GetComponent(i, 0));
  }
  return r;
}

std::map<std::string, std::string> blockParameters(vtkMultiBlockDataSet* blocks, const std::string& name) {
  vtkImageData* image = blocks ? findBlock(blocks, name) : nullptr;
  return image ? fieldParameters(image) : std::map<std::string, std::string>{};
}

} // namespace umbra::filters
