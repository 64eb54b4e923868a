#include "vtkAtmosphereTablesSource.h"

#include "Atmosphere.hpp"
#include "Describe.hpp"
#include "Precompute.hpp"
#include "Spectrum.hpp"
#include "FieldParameters.h"
#include "Refraction.hpp"
#include "SightLines.hpp"
#include "SpreadTable.h"
#include "Ranks.hpp"
#include "umbra/tables/CachedTables.h"
#include "umbra/tables/PlanarTableFile.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>
#include <optional>
#include <type_traits>

vtkStandardNewMacro(vtkAtmosphereTablesSource);

namespace {

using umbra::atmosphere::formatNumber;
using umbra::atmosphere::ParameterMap;
constexpr const char* kRefractionKind = "atmosphere-refraction";

/// A 2D table over unit ranges with texel centres on the ends (Bruneton's convention).
vtkSmartPointer<vtkImageData> unitRangeImage(int width, int height) {
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(width, height, 1);
  image->SetSpacing(1.0 / (width - 1), 1.0 / (height - 1), 1.0);
  image->SetOrigin(0.0, 0.0, 0.0);
  return image;
}

void addArray(vtkImageData* image, const char* name, const std::vector<float>& values) {
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  image->GetPointData()->AddArray(array);
}

/// "L680nm", "L393p57nm": the channel of a wavelength ('.' is a layer separator in EXR).
std::string channelName(double nm) {
  std::string s = formatNumber(nm);
  std::replace(s.begin(), s.end(), '.', 'p');
  return "L" + s + "nm";
}

/// Kind names allow [A-Za-z0-9_.-]; anything else in a component name becomes '_'.
std::string kindPart(const std::string& name) {
  std::string s = name;
  for (char& c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) c = '_';
  return s;
}

/// One Bruneton table: block name, its cache parameters, depth (1 for 2D), its values.
struct BrunetonTable {
  std::string name;
  ParameterMap parameters;
  int depth = 1;
  std::optional<umbra::tables::Table> table;
};

template <class Values>
umbra::tables::Table toTable(const Values& values, int width, int rows, int channels,
                             const std::vector<std::string>& names) {
  umbra::tables::Table t;
  t.width = width;
  t.height = rows;
  t.channels = names;
  t.data.assign(static_cast<std::size_t>(width) * rows * channels, 0.0f);
  if (!values.empty()) std::transform(values.begin(), values.end(), t.data.begin(), [](auto v) { return static_cast<float>(v); });
  return t;
}

/// The block of a table of width x height texels, no arrays yet: 2D over unit ranges, or 3D
/// in texel indices (rows stacked per slice).
vtkSmartPointer<vtkImageData> imageOf(int width, int height, int depth) {
  if (depth <= 1) return unitRangeImage(width, height);
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(width, height / depth, depth);
  image->SetSpacing(1.0, 1.0, 1.0);
  image->SetOrigin(0.0, 0.0, 0.0);
  return image;
}

/// The block of a table, its channels as arrays.
vtkSmartPointer<vtkImageData> blockOf(const umbra::tables::Table& t, int depth) {
  vtkSmartPointer<vtkImageData> image = imageOf(t.width, t.height, depth);
  const std::size_t n = static_cast<std::size_t>(t.width) * t.height, nc = t.channels.size();
  std::vector<float> values(n);
  for (std::size_t c = 0; c < nc; ++c) {
    for (std::size_t i = 0; i < n; ++i) values[i] = t.data[i * nc + c];
    addArray(image, t.channels[c].c_str(), values);
  }
  if (nc > 0) image->GetPointData()->SetActiveScalars(t.channels[0].c_str());
  return image;
}


/// Everything that changes the Bruneton tables' values (not threads nor wavelengthBatch).
ParameterMap brunetonParameters(const umbra::atmosphere::Atmosphere& atm, const umbra::atmosphere::PrecomputeOptions& po) {
  using namespace umbra;
  ParameterMap base = atmosphere::atmosphereParameters(atm);
  base["transmittanceSize"] = std::to_string(po.transmittanceWidth) + "x" + std::to_string(po.transmittanceHeight);
  base["scatteringSize"] = std::to_string(po.scatteringR) + "," + std::to_string(po.scatteringMu) + "," +
                           std::to_string(po.scatteringMuS) + "," + std::to_string(po.scatteringNu);
  base["irradianceSize"] = std::to_string(po.irradianceWidth) + "x" + std::to_string(po.irradianceHeight);
  base["orders"] = std::to_string(po.orders);
  base["samples"] = std::to_string(po.transmittanceSamples) + " " + std::to_string(po.singleScatteringSamples) + " " +
                    std::to_string(po.multipleScatteringSamples) + " " + std::to_string(po.opticalDepthSubsamples) +
                    " " + std::to_string(po.sphereSamples) + " " + std::to_string(po.irradianceSamples);
  base["densityQuadrature"] = atmosphere::kDensityQuadrature;
  base["muSMin"] = formatNumber(po.muSMin);
  base["sunAngularRadiusRad"] = formatNumber(po.sunAngularRadiusRad);
  base["refractedPaths"] = po.refraction ? "1" : "0";
  if (po.refraction) base["refractionStepM"] = formatNumber(po.refractionStepM);
  base["units"] = "per unit solar irradiance; channels L<nm>nm, one per wavelength ('.' written 'p')";
  return base;
}

/// The Bruneton tables of a run: each with the bit of vtkAtmosphereTablesSource::Tables
/// that asks for it, its cache parameters and its size; their channels (one per wavelength).
struct BrunetonSet {
  umbra::atmosphere::PrecomputeOptions po;
  std::vector<std::string> channels, components;  // components: those that scatter, in order
  std::vector<std::pair<int, BrunetonTable>> all;

  BrunetonSet(const umbra::atmosphere::Atmosphere& atm, const umbra::atmosphere::PrecomputeOptions& options) : po(options) {
    using T = vtkAtmosphereTablesSource;
    const ParameterMap base = brunetonParameters(atm, po);
    for (double nm : atm.wavelengthsNm) this->channels.push_back(channelName(nm));
    const std::string layout3 =
        "x = nu index * MU_S + mu_s index, y = mu index + MU * r index (the MU rows of each R slice stacked; "
        "the lower MU/2 rows of a slice: rays that hit the ground); Bruneton 2017 4D parametrisation";
    auto add = [&](std::string name, int bit, std::string layout, int depth) -> BrunetonTable& {
      BrunetonTable t;
      t.name = std::move(name);
      t.parameters = base;
      t.parameters["layout"] = std::move(layout);
      t.parameters["depth"] = std::to_string(depth);
      t.depth = depth;
      this->all.emplace_back(bit, std::move(t));
      return this->all.back().second;
    };
    add("transmittance", T::Transmittance,
        "x = x_mu, y = x_r (Bruneton 2017 transmittance parametrisation, texel centres on the ends)", 1);
    for (const umbra::atmosphere::Component& c : atm.components)
      if (c.scatters()) {
        this->components.push_back(c.name);
        add("single-scattering-" + kindPart(c.name), T::SingleScattering, layout3, po.scatteringR).parameters["component"] =
            c.name;
      }
    add("multiple-scattering", T::MultipleScattering, layout3, po.scatteringR).parameters["groundSunlight"] =
        umbra::atmosphere::kGroundSunlight;
    const std::string layoutIrradiance =
        "x = x_mu_s, y = x_r (Bruneton 2017 irradiance parametrisation, texel centres on the ends)";
    add("direct-irradiance", T::Irradiance, layoutIrradiance, 1);
    add("irradiance", T::Irradiance, layoutIrradiance, 1).parameters["groundSunlight"] = umbra::atmosphere::kGroundSunlight;
  }

  std::pair<int, int> sizeOf(const BrunetonTable& t) const {
    if (t.name == "transmittance") return {po.transmittanceWidth, po.transmittanceHeight};
    if (t.depth > 1) return {po.scatteringNu * po.scatteringMuS, po.scatteringMu * po.scatteringR};
    return {po.irradianceWidth, po.irradianceHeight};
  }

  /// Table `t` of a precomputation's result, taken out of it (its values there freed: the
  /// result and the tables made of it are not held whole at once).
  umbra::tables::Table takeTable(umbra::atmosphere::AtmosphereTables& result, const BrunetonTable& t) const {
    const auto [w, h] = this->sizeOf(t);
    const int nc = static_cast<int>(this->channels.size());
    // Orders 1: no multiple scattering nor indirect irradiance (empty tables: zeros).
    auto checked = [&](auto& values) {
      if (!values.empty() && values.size() != static_cast<std::size_t>(w) * h * nc)
        throw std::logic_error("precompute: unexpected size of table " + t.name);
      umbra::tables::Table table = toTable(values, w, h, nc, this->channels);
      std::decay_t<decltype(values)>().swap(values);
      return table;
    };
    if (t.name == "transmittance") return checked(result.transmittance.values);
    if (t.name == "multiple-scattering") return checked(result.multipleScattering.values);
    if (t.name == "direct-irradiance") return checked(result.directIrradiance.values);
    if (t.name == "irradiance") return checked(result.irradiance.values);
    const auto i = std::find(components.begin(), components.end(), t.parameters.at("component")) - components.begin();
    return checked(result.singleScattering.at(static_cast<std::size_t>(i)).values);
  }
};

/// The smallest run that makes `po`'s transmittance: no scattering worth the name.
umbra::atmosphere::PrecomputeOptions transmittanceOnly(umbra::atmosphere::PrecomputeOptions po) {
  po.scatteringR = po.scatteringMuS = po.scatteringNu = 2;
  po.scatteringMu = 4;
  po.irradianceWidth = po.irradianceHeight = 2;
  po.orders = 1;
  return po;
}

/// A block of `output` named `name`, with its cache parameters and kind.
void setBlock(vtkMultiBlockDataSet* output, unsigned& block, vtkImageData* image, ParameterMap parameters,
              const std::string& kind, const std::string& name) {
  parameters["kind"] = kind;
  umbra::filters::setFieldParameters(image, parameters);
  output->SetBlock(block, image);
  output->GetMetaData(block)->Set(vtkCompositeDataSet::NAME(), name.c_str());
  ++block;
}

/// The Bruneton tables `made` (requests[i] asks for made[i]) as files in rank 0's `scratch`
/// (vtkAtmosphereTablesSource::SetFileBacked): read from the cache, or computed by `po` a
/// batch of wavelengths at a time. Over ranks (`overRanks`, collective), rank 0 looks in
/// the cache for all; on a miss rank r computes the batches b with b % ranks == r (po's
/// batch), each rank putting its own batches' 4D tables in files as they are made (rank 0
/// in the tables' files, the others in unlinked files of their temporary directory), and
/// then the others send theirs to rank 0 alone, one batch of one table at a time; the small
/// 2D tables (zero outside a rank's channels) are summed on rank 0. No rank holds a whole
/// 4D table; the files are those of one process to the byte.
void makeBrunetonFiles(vtkAtmosphereTablesSource* source, const umbra::atmosphere::Atmosphere& atm,
                       const umbra::tables::TableCache& cache, bool useCache, const umbra::tables::TableCache& scratch,
                       const BrunetonSet& set, const std::vector<BrunetonTable*>& made,
                       const std::vector<umbra::tables::TableRequest>& requests,
                       umbra::atmosphere::PrecomputeOptions po, bool overRanks, umbra::tables::CacheOutcome& outcome,
                       int& precomputeCalls) {
  using namespace umbra;
  parallel::Ranks& ranks = parallel::Ranks::world();
  const bool spread = overRanks && ranks.size() > 1, root = ranks.root() || !spread;
  // From the cache when every needed table is there as asked (checked one at a time, each
  // then dropped), copied as it is.
  const auto fromCache = [&] {
    for (const tables::TableRequest& r : requests) {
      if (!r.needed) continue;
      const std::optional<tables::Table> t = cache.load(r.kind, r.parameters);
      if (!t || t->width != r.width || t->height != r.height || t->channels != r.channels) return false;
    }
    for (const tables::TableRequest& r : requests)
      if (r.needed) scratch.copyFrom(cache, r.kind, r.parameters);
    return true;
  };
  std::unique_ptr<tables::TableCache::Lock> lock;
  bool hit = false;
  if (useCache && root) {
    hit = fromCache();
    if (!hit && !requests.empty()) {  // made by one process at a time, as cachedOrComputed does
      lock = cache.lock(requests.front().kind, requests.front().parameters);
      if (lock) hit = fromCache();
    }
  }
  if (spread) hit = ranks.broadcast(hit ? "1" : "") == "1";
  if (hit) {
    for (const tables::TableRequest& r : requests) outcome.hits += r.needed ? 1 : 0;
    return;
  }

  ++precomputeCalls;
  const int nl = static_cast<int>(set.channels.size());
  if (spread) po.batchShareIndex = ranks.rank(), po.batchShareCount = ranks.size();
  // The 4D tables: in files on rank 0; another rank's batches held until they are sent.
  std::vector<std::unique_ptr<tables::PlanarTableFile>> planes(requests.size());
  // Another rank's finished batches wait in unlinked files of its temporary directory
  // (a few r slices in memory at a time), not in its memory beside the next batch's work.
  struct Held {
    std::size_t table;
    int first;
    std::unique_ptr<tables::PlanarTableFile> file;
  };
  std::vector<Held> held;
  if (root)
    for (std::size_t i = 0; i < requests.size(); ++i)
      if (made[i]->depth > 1)
        planes[i] = std::make_unique<tables::PlanarTableFile>(scratch.directory(), requests[i].width,
                                                              requests[i].height, requests[i].channels);
  // Whether a 4D table the precomputation hands on (that component's single scattering, or
  // after them the multiple) is made[i].
  const auto isTable = [&](std::size_t i, int table) {
    if (made[i]->depth <= 1) return false;
    return table == static_cast<int>(set.components.size())
               ? made[i]->name == "multiple-scattering"
               : made[i]->parameters.count("component") && made[i]->parameters.at("component") == set.components.at(table);
  };
  atmosphere::AtmosphereTables result;
  std::string error;
  try {
    result = atmosphere::precompute(
        atm, po,
        [source, root](double f, const std::string&) {
          if (root) source->UpdateProgress(0.9 * f);
          return !source->GetAbortExecute();
        },
        [&](int first, int table, const atmosphere::FloatTable3D& values) {
          for (std::size_t i = 0; i < requests.size(); ++i) {
            if (!isTable(i, table)) continue;
            if (!root) {
              const std::vector<std::string>& all = requests[i].channels;
              auto file = std::make_unique<tables::PlanarTableFile>(
                  std::filesystem::temp_directory_path().string(), requests[i].width, requests[i].height,
                  std::vector<std::string>(all.begin() + first, all.begin() + first + values.channels));
              file->put(0, values.channels, values.values.data());
              held.push_back({i, first, std::move(file)});
            } else if (first == 0 && values.channels == nl) {
              // Every wavelength at once: the table is whole, written as it is (no planes).
              tables::Table shape;
              shape.width = requests[i].width, shape.height = requests[i].height, shape.channels = requests[i].channels;
              scratch.store(requests[i].kind, requests[i].parameters, shape, values.values.data());
              planes[i].reset();
            } else {
              planes[i]->put(first, values.channels, values.values.data());
            }
          }
        });
  } catch (const std::exception& e) {
    if (!spread) throw;
    error = e.what();
  }
  if (spread) {
    if (const std::string errors = ranks.finish(error); !errors.empty()) throw std::runtime_error(errors);
    // The other ranks' batches to rank 0, one batch of one table at a time, in an order
    // every rank knows.
    const int batch = po.wavelengthBatch > 0 ? std::min(po.wavelengthBatch, nl) : nl;
    for (std::size_t i = 0; i < requests.size(); ++i) {
      if (made[i]->depth <= 1) continue;
      for (int first = 0; first < nl; first += batch) {
        const int owner = (first / batch) % ranks.size();
        if (owner == 0) continue;
        std::vector<float> mine;
        if (ranks.rank() == owner)
          for (Held& h : held)
            if (h.table == i && h.first == first && h.file) {
              h.file->rows(0, h.file->height(), mine);
              h.file.reset();
            }
        const std::vector<float> got = ranks.gather(mine);
        if (root && !got.empty()) planes[i]->put(first, std::min(batch, nl - first), got.data());
      }
    }
  }
  for (std::size_t i = 0; i < requests.size(); ++i) {
    const tables::TableRequest& r = requests[i];
    if (made[i]->depth <= 1) {
      tables::Table t = set.takeTable(result, *made[i]);
      if (spread) {  // each rank's channels, zero elsewhere: summed on rank 0
        const std::vector<float> all = ranks.gather(t.data);
        if (root)
          for (std::size_t k = t.data.size(); k < all.size(); ++k) t.data[k % t.data.size()] += all[k];
      }
      if (root) scratch.store(r.kind, r.parameters, t);
    } else if (planes[i]) {
      scratch.store(r.kind, r.parameters, *planes[i]);
      planes[i].reset();
    }
    if (!root) continue;
    source->UpdateProgress(0.9 + 0.1 * static_cast<double>(i + 1) / static_cast<double>(requests.size()));
    outcome.computed += r.needed ? 1 : 0;
    if (!useCache) continue;
    try {
      cache.copyFrom(scratch, r.kind, r.parameters);
    } catch (const std::exception& e) {
      if (outcome.warning.empty()) outcome.warning = e.what();
    }
  }
}

} // namespace

vtkAtmosphereTablesSource::vtkAtmosphereTablesSource() { this->SetNumberOfInputPorts(0); }

void vtkAtmosphereTablesSource::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Atmosphere: " << this->Atmosphere << "\n" << indent << "Tables: " << this->Tables << "\n"
     << indent << "Orders: " << this->Orders << "\n" << indent << "Wavelengths: " << this->Wavelengths << "\n"
     << indent << "MuSMin: " << this->MuSMin << "\n" << indent << "MinimumDensityDirections: " << this->MinimumDensityDirections
     << "\n" << indent << "RefractedPaths: " << this->RefractedPaths << "\n";
}

void vtkAtmosphereTablesSource::SetAtmosphereModel(umbra::atmosphere::AtmosphereModelPtr model) {
  if (model == this->Model && model && model->name() == this->Atmosphere) return;
  this->Model = model;
  this->Atmosphere = model ? model->name() : std::string();
  this->Modified();
}

umbra::atmosphere::AtmosphereModelPtr vtkAtmosphereTablesSource::GetAtmosphereModel() const {
  return umbra::atmosphere::modelNamed(this->Atmosphere, this->Model);
}

int vtkAtmosphereTablesSource::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) {
  using namespace umbra;
  vtkMultiBlockDataSet* output = vtkMultiBlockDataSet::GetData(out);
  this->CacheHits = this->Computed = this->PrecomputeCalls = 0;
  this->Error.clear();
  this->CacheWarning.clear();
  try {
    const std::vector<double> wavelengthsNm = this->Wavelengths == 3 ? atmosphere::WavelengthSet::rgb().nm
                                                                     : atmosphere::WavelengthSet::uniform(this->Wavelengths).nm;
    const atmosphere::AtmosphereModelPtr model = this->GetAtmosphereModel();
    if (!model) throw std::invalid_argument("no atmosphere (SetAtmosphere)");
    const atmosphere::Atmosphere& atm = model->at(wavelengthsNm);
    const tables::TableCache cache(this->CacheDirectory.empty() ? tables::TableCache::defaultDirectory()
                                                                : this->CacheDirectory);
    unsigned block = 0;
    if (this->Tables & Bruneton) this->AddBrunetonBlocks(atm, cache, output, block);
    if (this->Tables & Refraction) this->AddRefractionBlock(atm, cache, output, block);
  } catch (const atmosphere::PrecomputeCancelled& e) {
    // Asked for: no message, and success for the executive (which would print one);
    // the output is empty.
    this->Error = e.what();
    output->Initialize();
    return 1;
  } catch (const std::exception& e) {
    this->Error = e.what();
    vtkErrorMacro(<< e.what());
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

umbra::atmosphere::PrecomputeOptions vtkAtmosphereTablesSource::PrecomputeOptionsFor(
    const umbra::atmosphere::Atmosphere& atm) const {
  umbra::atmosphere::PrecomputeOptions po;
  po.transmittanceWidth = this->TransmittanceSize[0];
  po.transmittanceHeight = this->TransmittanceSize[1];
  po.scatteringR = this->ScatteringSize[0];
  po.scatteringMu = this->ScatteringSize[1];
  po.scatteringMuS = this->ScatteringSize[2];
  po.scatteringNu = this->ScatteringSize[3];
  po.irradianceWidth = this->IrradianceSize[0];
  po.irradianceHeight = this->IrradianceSize[1];
  po.orders = this->Orders;
  po.muSMin = this->MuSMin;
  if (this->MinimumDensityDirections > 0)
    po.sphereSamples = std::max(this->MinimumDensityDirections, umbra::atmosphere::densityDirectionsFor(atm));
  if (this->DensityDirections > 0) po.sphereSamples = this->DensityDirections;
  po.singleScatteringSamples = this->QuadratureSamples[0];
  po.multipleScatteringSamples = this->QuadratureSamples[1];
  po.irradianceSamples = this->QuadratureSamples[2];
  po.refraction = this->RefractedPaths;
  po.refractionStepM = this->RefractionStepM;
  po.threads = this->Threads;
  po.wavelengthBatch = this->WavelengthBatch;
  po.spillTables = this->SpillTables && this->FileBacked;
  if (const std::string e = po.validate(); !e.empty()) throw std::invalid_argument("precompute options: " + e);
  return po;
}

void vtkAtmosphereTablesSource::Count(const umbra::tables::CacheOutcome& outcome) {
  this->CacheHits += outcome.hits;
  this->Computed += outcome.computed;
  if (this->CacheWarning.empty()) this->CacheWarning = outcome.warning;
}

void vtkAtmosphereTablesSource::AddBrunetonBlocks(const umbra::atmosphere::Atmosphere& atm,
                                                  const umbra::tables::TableCache& cache, vtkMultiBlockDataSet* output,
                                                  unsigned& block) {
  using namespace umbra;
  BrunetonSet set(atm, this->PrecomputeOptionsFor(atm));
  // Transmittance alone: the smallest run, and only it stored; else every table of the
  // run is stored, needed now or not.
  const int requested = this->Tables & Bruneton;
  const bool onlyTransmittance = requested == Transmittance;
  std::vector<BrunetonTable*> made;
  std::vector<tables::TableRequest> requests;
  for (auto& [bit, t] : set.all) {
    if (onlyTransmittance && bit != Transmittance) continue;
    const auto [w, h] = set.sizeOf(t);
    made.push_back(&t);
    requests.push_back({"atmosphere-" + t.name, t.parameters, w, h, set.channels, (requested & bit) != 0});
  }
  const bool overRanks = this->SpreadOverRanks && parallel::Ranks::world().size() > 1;
  std::optional<tables::TableCache> scratch;
  if (this->FileBacked) {
    if (this->ScratchDirectory.empty()) throw std::invalid_argument("FileBacked: no ScratchDirectory");
    scratch.emplace(this->ScratchDirectory, 0);
  }
  // The blocks of the requested tables as files in the scratch directory.
  const auto fileBlocks = [&] {
    for (std::size_t i = 0; i < made.size(); ++i) {
      if (!requests[i].needed) continue;
      ParameterMap parameters = made[i]->parameters;
      parameters["file"] = scratch->pathFor(requests[i].kind, parameters);
      setBlock(output, block, imageOf(requests[i].width, requests[i].height, made[i]->depth), parameters,
               requests[i].kind, made[i]->name);
    }
  };
  // Over ranks: wavelength batches of ceil(wavelengths / ranks) unless the batch is given.
  const int nl = static_cast<int>(set.channels.size());
  const auto batchFor = [&](int count) {
    return set.po.wavelengthBatch > 0 ? set.po.wavelengthBatch : std::max(1, (nl + count - 1) / count);
  };
  if (this->FileBacked) {
    tables::CacheOutcome outcome;
    atmosphere::PrecomputeOptions po = onlyTransmittance ? transmittanceOnly(set.po) : set.po;
    if (overRanks) po.wavelengthBatch = batchFor(parallel::Ranks::world().size());
    makeBrunetonFiles(this, atm, cache, this->UseCache, *scratch, set, made, requests, po, overRanks, outcome,
                      this->PrecomputeCalls);
    this->Count(outcome);
    fileBlocks();
    return;
  }
  tables::CacheOutcome outcome;
  std::vector<tables::Table> values = filters::spreadChannelsOrCached(
      cache, this->UseCache != 0, requests, this->SpreadOverRanks,
      [&](int channel, int count) { return (channel / batchFor(count)) % count; },
      [&](int index, int count) {
        ++this->PrecomputeCalls;
        atmosphere::PrecomputeOptions po = onlyTransmittance ? transmittanceOnly(set.po) : set.po;
        if (count > 1) {
          po.wavelengthBatch = batchFor(count);
          po.batchShareIndex = index;
          po.batchShareCount = count;
        }
        atmosphere::AtmosphereTables result = atmosphere::precompute(
            atm, po, [this](double f, const std::string&) {
              this->UpdateProgress(0.95 * f);
              return !this->GetAbortExecute();  // SetAbortExecute(1) from another thread cancels
            });
        std::vector<tables::Table> out;
        for (const BrunetonTable* t : made) out.push_back(set.takeTable(result, *t));
        return out;
      },
      outcome);
  this->Count(outcome);
  for (std::size_t i = 0; i < made.size(); ++i)
    if (requests[i].needed) made[i]->table = std::move(values[i]);
  values.clear();
  for (auto& [bit, t] : set.all)
    if (requested & bit) {
      setBlock(output, block, blockOf(*t.table, t.depth), t.parameters, "atmosphere-" + t.name, t.name);
      t.table.reset();  // the block holds it now
    }
}

void vtkAtmosphereTablesSource::AddRefractionBlock(const umbra::atmosphere::Atmosphere& atm,
                                                   const umbra::tables::TableCache& cache, vtkMultiBlockDataSet* output,
                                                   unsigned& block) {
  using namespace umbra;
  auto parameters = atmosphere::refractionParameters(atm, atm.refractivityReferenceWavelengthNm);
  parameters["width"] = std::to_string(this->RefractionWidth);
  parameters["height"] = std::to_string(this->RefractionHeight);
  parameters["stepM"] = formatNumber(this->RefractionStepM);
  parameters["layout"] = "x = x_mu, y = x_r (Bruneton 2017 transmittance parametrisation, texel centres on the ends)";
  const std::vector<std::string> channels = {"deviation_rad", "contact_altitude_m"};
  tables::CacheOutcome outcome;
  std::vector<tables::Table> made = tables::cachedOrComputed(
      cache, this->UseCache != 0, {{kRefractionKind, parameters, this->RefractionWidth, this->RefractionHeight, channels}},
      [&] {
        // After the Bruneton tables made now (0 to 0.95), the rest: progress never goes back.
        const double from = this->GetProgress() < 1.0 ? this->GetProgress() : 0.0;
        const atmosphere::RefractionTable r = atmosphere::buildRefractionTable(
            atmosphere::refractiveMedium(atm, atm.refractivityReferenceWavelengthNm), this->RefractionWidth,
            this->RefractionHeight, this->RefractionStepM,
            [this, from](double f) { this->UpdateProgress(from + (1.0 - from) * f); });
        tables::Table t;
        t.width = r.width;
        t.height = r.height;
        t.channels = channels;
        t.data.resize(2 * r.deviationRad.size());
        for (std::size_t i = 0; i < r.deviationRad.size(); ++i) {
          t.data[2 * i] = r.deviationRad[i];
          t.data[2 * i + 1] = r.contactAltitudeM[i];
        }
        return std::vector<tables::Table>{std::move(t)};
      },
      outcome);
  this->Count(outcome);
  const tables::Table& table = made.front();
  auto image = unitRangeImage(table.width, table.height);
  std::vector<float> deviation(table.data.size() / 2), contact(table.data.size() / 2);
  for (std::size_t i = 0; i < deviation.size(); ++i) {
    deviation[i] = table.data[2 * i];
    contact[i] = table.data[2 * i + 1];
  }
  addArray(image, "deviation_rad", deviation);
  addArray(image, "contact_altitude_m", contact);
  image->GetPointData()->SetActiveScalars("deviation_rad");
  setBlock(output, block, image, parameters, kRefractionKind, "refraction");
}
