#include "FieldParameters.h"

#include <vtkDataObject.h>
#include <vtkFieldData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>

namespace umbra::filters {
namespace {
constexpr const char* kFieldKeys = "umbra_parameter_keys";
constexpr const char* kFieldValues = "umbra_parameter_values";
} // namespace

void setFieldParameters(vtkDataObject* data, const std::map<std::string, std::string>& parameters) {
  auto keys = vtkSmartPointer<vtkStringArray>::New();
  auto values = vtkSmartPointer<vtkStringArray>::New();
  keys->SetName(kFieldKeys);
  values->SetName(kFieldValues);
  for (const auto& [k, v] : parameters) {
    keys->InsertNextValue(k);
    values->InsertNextValue(v);
  }
  data->GetFieldData()->AddArray(keys);
  data->GetFieldData()->AddArray(values);
}

std::map<std::string, std::string> fieldParameters(vtkDataObject* data) {
  std::map<std::string, std::string> out;
  auto* keys = vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray(kFieldKeys));
  auto* values = vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray(kFieldValues));
  if (!keys || !values) return out;
  for (vtkIdType i = 0; i < keys->GetNumberOfValues() && i < values->GetNumberOfValues(); ++i)
    out[keys->GetValue(i)] = values->GetValue(i);
  return out;
}

} // namespace umbra::filters
