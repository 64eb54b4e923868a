#include "vtkEclipseAtmosphereSource.h"

#include "AtmosphereTablesBlocks.h"
#include "Describe.hpp"
#include "vtkAtmosphereTablesSource.h"
#include "EclipseAtmosphere.hpp"
#include "FieldParameters.h"
#include "Precompute.hpp"
#include "Spectrum.hpp"
#include "SpreadTable.h"
#include "umbra/tables/CachedTables.h"

#include <vtkDataObject.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkAlgorithmOutput.h>
#include <vtkCommand.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <mutex>
#include <stdexcept>

namespace {

std::vector<double> wavelengthsOf(int n) {
  using umbra::atmosphere::WavelengthSet;
  return n == 3 ? WavelengthSet::rgb().nm : WavelengthSet::uniform(n).nm;
}

std::string keyOf(const std::map<std::string, std::string>& parameters) {
  std::string key;
  for (const auto& [k, v] : parameters) key += k + "=" + v + "\n";
  return key;
}

/// What the eclipse tables are made of: the atmosphere, the options and the parameters of
/// the prepared model (cache keys); with input tables, their options and parameters.
struct Resolved {
  umbra::atmosphere::Atmosphere atm;
  umbra::eclipse::EclipseAtmosphereOptions options;
  std::map<std::string, std::string> parameters;
};

// `spec` names the atmosphere (or, empty, the input's); `kept` is the model read for that
// name (atmosphere::modelNamed: read once while the name stays).
Resolved resolve(const std::string& spec, umbra::atmosphere::AtmosphereModelPtr& kept, int wavelengths,
                 vtkMultiBlockDataSet* input, const std::string& occluder, double sunOccluderDistanceM,
                 umbra::eclipse::EclipseAtmosphereOptions options) {
  using namespace umbra;
  if (!input) {
    Resolved r{atmosphere::modelNamed(spec, kept)->at(wavelengthsOf(wavelengths)), options, {}};
    r.parameters = eclipse::eclipseAtmosphereParameters(r.atm, occluder, sunOccluderDistanceM, options);
    return r;
  }
  const auto ms = umbra::filters::blockParameters(input, "multiple-scattering");
  if (ms.empty())
    throw std::invalid_argument("atmosphere tables input: no 'multiple-scattering' block (ask vtkAtmosphereTablesSource "
                                "for the Bruneton tables)");
  const std::string name = spec.empty() && ms.count("atmosphere") ? ms.at("atmosphere") : spec;
  Resolved r{atmosphere::modelNamed(name, kept)->at(wavelengthsOf(wavelengths)), options, {}};
  const auto atmosphereKeys = atmosphere::atmosphereParameters(r.atm);
  for (const auto& [k, v] : atmosphereKeys) {
    const auto it = ms.find(k);
    if (it == ms.end() || it->second != v)
      throw std::invalid_argument("atmosphere tables input: made for another atmosphere than '" + name +
                                  "' (parameter '" + k + "' differs)");
  }
  auto get = [&](const std::map<std::string, std::string>& p, const std::string& block, const std::string& k) {
    const auto it = p.find(k);
    if (it == p.end())
      throw std::invalid_argument("atmosphere tables input: block '" + block + "' has no parameter '" + k + "'");
    return it->second;
  };
  const bool refractedPaths = get(ms, "multiple-scattering", "refractedPaths") == "1";
  if (options.refraction != refractedPaths)
    throw std::invalid_argument(std::string("atmosphere tables input: refraction is ") +
                                (options.refraction ? "on" : "off") + " but the tables were made with refracted paths " +
                                (refractedPaths ? "on" : "off") + " (vtkAtmosphereTablesSource::SetRefractedPaths)");
  options.tables.orders = std::stoi(get(ms, "multiple-scattering", "orders"));
  std::string inputKey;
  for (const auto& [k, v] : ms)
    if (k != "kind" && k != "layout" && k != "units" && k != "depth" && !atmosphereKeys.count(k))
      inputKey += k + "=" + v + "; ";
  if (options.refraction) {
    // The refraction table's, when the input has one; else the rows that the limb ray
    // profile reads are traced at the refracted paths' step (prepareEclipseAtmosphere).
    options.refractionStepM = std::stod(get(ms, "multiple-scattering", "refractionStepM"));
    options.tables.refractionStepM = options.refractionStepM;
    const auto rp = umbra::filters::blockParameters(input, "refraction");
    if (!rp.empty()) {
      options.refractionWidth = std::stoi(get(rp, "refraction", "width"));
      options.refractionHeight = std::stoi(get(rp, "refraction", "height"));
      if (std::stod(get(rp, "refraction", "stepM")) != options.refractionStepM)
        throw std::invalid_argument("atmosphere tables input: the refracted paths and the refraction table have different steps");
    }
  }
  r.options = options;
  r.parameters = eclipse::eclipseAtmosphereParameters(r.atm, occluder, sunOccluderDistanceM, options);
  r.parameters["atmosphereTables"] = "input: " + inputKey;  // the input's sizes, orders, samples
  return r;
}

} // namespace

vtkEclipseAtmosphereSource::vtkEclipseAtmosphereSource() { this->SetNumberOfInputPorts(1); }

vtkEclipseAtmosphereSource::~vtkEclipseAtmosphereSource() {
  if (this->TablesSource) this->TablesSource->RemoveObserver(this->TablesProgressObserver);
}

void vtkEclipseAtmosphereSource::TablesProgress(vtkObject*, unsigned long, void* fraction) {
  this->UpdateProgress(0.5 * *static_cast<double*>(fraction));
}

int vtkEclipseAtmosphereSource::FillInputPortInformation(int, vtkInformation* info) {
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkMultiBlockDataSet");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

vtkMultiBlockDataSet* vtkEclipseAtmosphereSource::InputTables() const {
  auto* self = const_cast<vtkEclipseAtmosphereSource*>(this);
  if (self->GetNumberOfInputConnections(0) == 0) return nullptr;
  auto* blocks = vtkMultiBlockDataSet::SafeDownCast(self->GetInputDataObject(0, 0));
  if (!blocks) throw std::invalid_argument("atmosphere tables input: not a vtkMultiBlockDataSet");
  return blocks;
}

void vtkEclipseAtmosphereSource::SetAtmosphereModel(umbra::atmosphere::AtmosphereModelPtr model) {
  if (model == this->Model && model && model->name() == this->Atmosphere) return;
  this->Model = model;
  this->Atmosphere = model ? model->name() : std::string();
  this->Modified();
}

bool vtkEclipseAtmosphereSource::HasAtmosphere() const {
  return !this->Atmosphere.empty() || const_cast<vtkEclipseAtmosphereSource*>(this)->GetNumberOfInputConnections(0) > 0;
}

vtkAlgorithm* vtkEclipseAtmosphereSource::ConnectAtmosphereTables() {
  auto* tables = vtkAtmosphereTablesSource::SafeDownCast(this->TablesSource);
  const bool ours = tables && this->GetNumberOfInputConnections(0) > 0 && this->GetInputAlgorithm(0, 0) == tables;
  if (this->Atmosphere.empty() || (this->GetNumberOfInputConnections(0) > 0 && !ours)) return nullptr;
  if (!ours) {
    if (this->TablesSource) this->TablesSource->RemoveObserver(this->TablesProgressObserver);
    this->TablesSource = vtkSmartPointer<vtkAtmosphereTablesSource>::New();
    tables = vtkAtmosphereTablesSource::SafeDownCast(this->TablesSource);
    this->TablesProgressObserver =
        tables->AddObserver(vtkCommand::ProgressEvent, this, &vtkEclipseAtmosphereSource::TablesProgress);
    this->SetInputConnection(tables->GetOutputPort());
  }
  // (Re)configured on every call: the setters mark it modified only on a change.
  if (this->Model && this->Model->name() == this->Atmosphere) tables->SetAtmosphereModel(this->Model);
  else tables->SetAtmosphere(this->Atmosphere.c_str());
  tables->SetWavelengths(this->Wavelengths);
  tables->SetOrders(this->Orders);
  tables->SetTransmittanceSize(this->TransmittanceSize);
  const umbra::eclipse::EclipseAtmosphereOptions o = this->Options();
  tables->SetScatteringSize(o.tables.scatteringR, o.tables.scatteringMu, o.tables.scatteringMuS, o.tables.scatteringNu);
  tables->SetIrradianceSize(this->IrradianceSize);
  // The Bruneton tables only: of the refraction table the LuTs read two rows, which
  // PrepareAtmosphere traces itself (the whole table would take longer than both LuTs' rays).
  tables->SetTables(vtkAtmosphereTablesSource::Bruneton);
  tables->SetRefractedPaths(this->Refraction);
  tables->SetRefractionStepM(this->RefractionStepM);
  tables->SetCacheDirectory(this->CacheDirectory.c_str());
  tables->SetUseCache(this->UseCache);
  return tables;
}

std::shared_ptr<const umbra::eclipse::EclipseAtmosphere> vtkEclipseAtmosphereSource::GetPreparedAtmosphere() {
  if (this->GetNumberOfInputConnections(0) > 0) this->GetInputAlgorithm(0, 0)->Update();
  return this->PrepareAtmosphere(0.0, 1.0);
}

void vtkEclipseAtmosphereSource::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Occluder: " << this->OccluderName << " (" << this->OccluderRadiusM << " m)\n"
     << indent << "Atmosphere: " << (this->Atmosphere.empty() ? "(none)" : this->Atmosphere) << "\n"
     << indent << "Refraction: " << this->Refraction << "\n"
     << indent << "UseCache: " << this->UseCache << " " << this->CacheDirectory << "\n";
}

umbra::eclipse::EclipseAtmosphereOptions vtkEclipseAtmosphereSource::Options() const {
  umbra::eclipse::EclipseAtmosphereOptions o;
  o.tables.orders = this->Orders;
  o.tables.transmittanceWidth = this->TransmittanceSize[0];
  o.tables.transmittanceHeight = this->TransmittanceSize[1];
  o.tables.scatteringR = this->ScatteringSize[0];
  o.tables.scatteringMu = this->ScatteringSize[1];
  o.tables.scatteringMuS = this->ScatteringSize[2];
  o.tables.scatteringNu = this->ScatteringSize[3] > 0 ? this->ScatteringSize[3]
                                                       : umbra::eclipse::defaultScatteringNu(this->OccluderName, umbra::atmosphere::kDefaultTableSizes.scattering[3]);
  o.tables.irradianceWidth = this->IrradianceSize[0];
  o.tables.irradianceHeight = this->IrradianceSize[1];
  o.refraction = this->Refraction;
  o.refractionWidth = this->RefractionSize[0];
  o.refractionHeight = this->RefractionSize[1];
  o.refractionStepM = this->RefractionStepM;
  o.terrainMeanElevationM = this->TerrainMeanElevationM;
  if (const std::string e = o.tables.validate(); !e.empty()) throw std::invalid_argument("atmosphere tables: " + e);
  return o;
}

std::map<std::string, std::string> vtkEclipseAtmosphereSource::AtmosphereParameters() const {
  return resolve(this->Atmosphere, this->Model, this->Wavelengths, this->InputTables(), this->OccluderName,
                 this->SunOccluderDistanceM, this->Options())
      .parameters;
}

std::shared_ptr<const umbra::eclipse::EclipseAtmosphere> vtkEclipseAtmosphereSource::PrepareAtmosphere(double from,
                                                                                                      double to) {
  using namespace umbra;
  static std::mutex mutex;
  static std::map<std::string, std::weak_ptr<const eclipse::EclipseAtmosphere>> prepared;
  vtkMultiBlockDataSet* input = this->InputTables();
  const Resolved r = resolve(this->Atmosphere, this->Model, this->Wavelengths, input, this->OccluderName,
                             this->SunOccluderDistanceM, this->Options());
  const std::string key = keyOf(r.parameters);
  std::lock_guard<std::mutex> lock(mutex);
  if (auto kept = prepared[key].lock()) return this->Prepared = kept;
  std::shared_ptr<const eclipse::EclipseAtmosphere> made =
      input ? eclipse::prepareEclipseAtmosphere(
                  r.atm, filters::tablesFromBlocks(input, r.atm),
                  r.options.refraction && !filters::blockParameters(input, "refraction").empty()
                      ? filters::refractionFromBlocks(input, r.atm)
                      : atmosphere::RefractionTable{},
                  this->OccluderName, this->SunOccluderDistanceM, r.options)
            : eclipse::prepareEclipseAtmosphere(r.atm, this->OccluderName, this->SunOccluderDistanceM, r.options,
                                                [&](double f, const std::string&) {
                                                  this->UpdateProgress(from + (to - from) * f);
                                                  return !this->GetAbortExecute();
                                                });
  prepared[key] = made;
  return this->Prepared = made;
}

std::vector<float> vtkEclipseAtmosphereSource::CachedOrComputed(const char* kind,
                                                                const std::map<std::string, std::string>& parameters,
                                                                int width, int height, int slices,
                                                                double limbDarkening, const Compute& compute) {
  using namespace umbra;
  this->LastCacheHit = false;
  this->CacheWarning.clear();
  const tables::TableCache cache(this->CacheDirectory.empty() ? tables::TableCache::defaultDirectory()
                                                              : this->CacheDirectory);
  this->CachePath = cache.pathFor(kind, parameters);
  tables::CacheOutcome outcome;
  tables::Table made = filters::spreadOrCached(
      cache, this->UseCache != 0, {kind, parameters, width, height, {"R", "G", "B"}}, width * height / slices, slices,
      this->SpreadOverRanks, [&](int index, int count) {
        if (!this->InputTables()) this->UpdateProgress(0.0);  // (with input: its tables were the first half)
        eclipse::AtmosphericShadowModel model = this->PrepareAtmosphere(0.0, 0.5)->model;
        model.limbDarkening = limbDarkening;
        tables::Table t;
        t.width = width, t.height = height, t.channels = {"R", "G", "B"};
        t.data = compute(model, [this](double f) {
          this->UpdateProgress(0.5 + 0.5 * f);
          return !this->GetAbortExecute();
        }, eclipse::TexelShare{index, count});
        if (t.data.empty()) throw umbra::atmosphere::PrecomputeCancelled();
        return t;
      },
      outcome);
  this->LastCacheHit = outcome.hits > 0;
  this->CacheWarning = outcome.warning;
  return std::move(made.data);
}

int vtkEclipseAtmosphereSource::RequestFailed(const std::exception& e, vtkDataObject* output) {
  if (this->GetAbortExecute() || dynamic_cast<const umbra::atmosphere::PrecomputeCancelled*>(&e)) {
    this->LastAborted = true;
    if (output) output->Initialize();
    return 1;
  }
  this->LastError = e.what();
  vtkErrorMacro(<< e.what());
  return 0;
}

void vtkEclipseAtmosphereSource::SetLutInformation(vtkInformationVector* out, int width, int height, int depth,
                                                   const double uRange[2], const double vRange[2],
                                                   double vLowFraction) {
  vtkInformation* info = out->GetInformationObject(0);
  const int extent[6] = {0, width - 1, 0, height - 1, 0, depth - 1};
  info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  double spacing[3], origin[3];
  LutSpacingOrigin(width, height, uRange, vRange, vLowFraction, spacing, origin);
  info->Set(vtkDataObject::SPACING(), spacing, 3);
  info->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(info, VTK_FLOAT, 3);
}

void vtkEclipseAtmosphereSource::LutSpacingOrigin(int width, int height, const double uRange[2],
                                                  const double vRange[2], double vLowFraction, double spacing[3],
                                                  double origin[3]) {
  const double uMin = uRange ? uRange[0] : 0.0, uMax = uRange ? uRange[1] : 1.0;
  const bool split = vLowFraction > 0.0;
  const double vMin = vRange && !split ? vRange[0] : 0.0, vMax = vRange && !split ? vRange[1] : 1.0;
  const double du = (uMax - uMin) / width, dv = (vMax - vMin) / height;
  spacing[0] = du, spacing[1] = dv, spacing[2] = 1.0;
  origin[0] = uMin + 0.5 * du, origin[1] = vMin + 0.5 * dv, origin[2] = 0.0;
}
