#include "vtkShadowProfileFilter.h"

#include "ShadowLutData.h"

#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkObjectFactory.h>
#include <vtkTable.h>

#include <cmath>
#include <string>

vtkStandardNewMacro(vtkShadowProfileFilter);

void vtkShadowProfileFilter::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ReceiverDistanceM: " << this->ReceiverDistanceM << "\n"
     << indent << "Samples: " << this->Samples << " Exact: " << this->Exact << "\n";
}

int vtkShadowProfileFilter::FillInputPortInformation(int, vtkInformation* info) {
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);  // Exact mode needs no LuT
  return 1;
}

int vtkShadowProfileFilter::RequestData(vtkInformation*, vtkInformationVector** in,
                                        vtkInformationVector* out) {
  using namespace umbra;
  vtkImageData* input = vtkImageData::GetData(in[0]);
  if (!input && !this->Exact) {
    vtkErrorMacro("no shadow LuT on the input (connect one, or turn Exact on)");
    return 0;
  }
  vtkTable* output = vtkTable::GetData(out);

  // Bodies: explicit settings win, else the LuT's field data.
  const auto fields = input ? filters::fieldParameters(input) : std::map<std::string, std::string>{};
  const auto pick = [&](double value, const char* key) {
    if (value > 0.0) return value;
    const auto it = fields.find(key);
    return it == fields.end() ? 0.0 : std::stod(it->second);
  };
  const eclipse::SunOccluderSystem system{pick(this->SunRadiusM, "sunRadiusM"),
                                          pick(this->OccluderRadiusM, "occluderRadiusM"),
                                          pick(this->SunOccluderDistanceM, "sunOccluderDistanceM")};
  if (!(system.sunRadiusM > 0 && system.occluderRadiusM > 0 && system.sunOccluderDistanceM > system.sunRadiusM) ||
      !(this->ReceiverDistanceM > 0.0) || !std::isfinite(this->ReceiverDistanceM)) {
    vtkErrorMacro("the Sun, the occluder and the receiver distance must be positive and finite");
    return 0;
  }
  const double maxOffset = this->MaxOffsetM > 0.0
      ? this->MaxOffsetM
      : 1.25 * eclipse::shadowConeRadii(system, this->ReceiverDistanceM).penumbraRadiusM;

  eclipse::ShadowLut lut;
  if (!this->Exact) {
    try {
      lut = filters::fromImageData(input);
    } catch (const std::exception& e) {
      vtkErrorMacro(<< e.what());
      return 0;
    }
  }
  const auto samples = eclipse::shadowProfile(system, this->ReceiverDistanceM, maxOffset, this->Samples,
                                              this->Exact ? nullptr : &lut, this->LimbDarkening);

  output->ShallowCopy(filters::profileTable(samples));
  return 1;
}
