#pragma once
// Parameters of a table carried in a VTK data object's field data, as string key/value
// pairs: what the EXR header holds, kept with the data through the pipeline.
#include <map>
#include <string>

class vtkDataObject;

namespace umbra::filters {

void setFieldParameters(vtkDataObject* data, const std::map<std::string, std::string>& parameters);
std::map<std::string, std::string> fieldParameters(vtkDataObject* data);

} // namespace umbra::filters
