#include "vtkAtmosphereTablesSource.h"

#include "Atmosphere.hpp"
#include "Describe.hpp"
#include "FieldParameters.h"
#include "Refraction.hpp"
#include "SightLines.hpp"
#include "umbra/tables/TableCache.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>

vtkStandardNewMacro(vtkAtmosphereTablesSource);

namespace {

using umbra::atmosphere::formatNumber;
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

} // namespace

vtkAtmosphereTablesSource::vtkAtmosphereTablesSource() { this->SetNumberOfInputPorts(0); }

void vtkAtmosphereTablesSource::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Atmosphere: " << this->Atmosphere << "\n" << indent << "Tables: " << this->Tables << "\n";
}

int vtkAtmosphereTablesSource::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) {
  using namespace umbra;
  vtkMultiBlockDataSet* output = vtkMultiBlockDataSet::GetData(out);
  this->CacheHits = this->Computed = 0;
  this->Error.clear();
  try {
    const atmosphere::Atmosphere atm = atmosphere::loadAtmosphere(this->Atmosphere, {680.0, 550.0, 440.0});
    const tables::TableCache cache(this->CacheDirectory.empty() ? tables::TableCache::defaultDirectory()
                                                                : this->CacheDirectory);
    unsigned block = 0;

    if (this->Tables & Refraction) {
      auto parameters = atmosphere::refractionParameters(atm, atm.refractivityReferenceWavelengthNm);
      parameters["width"] = std::to_string(this->RefractionWidth);
      parameters["height"] = std::to_string(this->RefractionHeight);
      parameters["stepM"] = formatNumber(this->RefractionStepM);
      parameters["layout"] = "x = x_mu, y = x_r (Bruneton 2017 transmittance parametrisation, texel centres on the ends)";
      std::optional<tables::Table> table = this->UseCache ? cache.load(kRefractionKind, parameters) : std::nullopt;
      if (table && table->channels != std::vector<std::string>{"deviation_rad", "contact_altitude_m"}) table.reset();
      if (table) {
        ++this->CacheHits;
      } else {
        const atmosphere::RefractionTable r = atmosphere::buildRefractionTable(
            atmosphere::refractiveMedium(atm, atm.refractivityReferenceWavelengthNm), this->RefractionWidth,
            this->RefractionHeight, this->RefractionStepM, [this](double f) { this->UpdateProgress(f); });
        table.emplace();
        table->width = r.width;
        table->height = r.height;
        table->channels = {"deviation_rad", "contact_altitude_m"};
        table->data.resize(2 * r.deviationRad.size());
        for (std::size_t i = 0; i < r.deviationRad.size(); ++i) {
          table->data[2 * i] = r.deviationRad[i];
          table->data[2 * i + 1] = r.contactAltitudeM[i];
        }
        table->parameters = parameters;
        ++this->Computed;
        if (this->UseCache) cache.store(kRefractionKind, parameters, *table);
      }
      auto image = unitRangeImage(table->width, table->height);
      std::vector<float> deviation(table->data.size() / 2), contact(table->data.size() / 2);
      for (std::size_t i = 0; i < deviation.size(); ++i) {
        deviation[i] = table->data[2 * i];
        contact[i] = table->data[2 * i + 1];
      }
      addArray(image, "deviation_rad", deviation);
      addArray(image, "contact_altitude_m", contact);
      image->GetPointData()->SetActiveScalars("deviation_rad");
      parameters["kind"] = kRefractionKind;
      filters::setFieldParameters(image, parameters);
      output->SetBlock(block, image);
      output->GetMetaData(block)->Set(vtkCompositeDataSet::NAME(), "refraction");
      ++block;
    }
  } catch (const std::exception& e) {
    this->Error = e.what();
    vtkErrorMacro(<< e.what());
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}
