#include "ShadowLutData.h"

#include "umbra/tables/Table.h"

#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkDoubleArray.h>
#include <vtkPointData.h>
#include <vtkTable.h>

#include <charconv>
#include <stdexcept>

namespace umbra::filters {
namespace {
std::string number(double x) {  // shortest text that reads back as the same double
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}
} // namespace

std::string formatNumber(double x) { return number(x); }

std::map<std::string, std::string> airlessLutParameters(const eclipse::ShadowLutParams& p) {
  std::map<std::string, std::string> out{{"kind", kAirlessShadowLutKind},
          {"model", "limb-darkened Sun (Eq. 1), spherical airless occluder; v1"},
          {"width", std::to_string(p.width)},
          {"height", std::to_string(p.height)},
          {"limbDarkening", number(p.limbDarkening)},
          {"relativeTolerance", number(p.relativeTolerance)},
          {"values", "I/I_sun at texel centres u=(i+0.5)/width, v=(j+0.5)/height (Eq. 4)"}};
  addLutRange(out, {p.uMin, p.uMax, p.vMin, p.vMax, p.vLowFraction});
  return out;
}

void addLutRange(std::map<std::string, std::string>& p, const eclipse::LutRange& r) {
  if (r.uMin == 0.0 && r.uMax == 1.0 && r.vMin == 0.0 && r.vMax == 1.0 && r.vLowFraction == 0.0) return;
  p["uMin"] = number(r.uMin), p["uMax"] = number(r.uMax);
  p["vMin"] = number(r.vMin), p["vMax"] = number(r.vMax);
  p["vLowFraction"] = number(r.vLowFraction);
  p["rangeCentres"] = "u=uMin+(uMax-uMin)(i+0.5)/width; t=(j+0.5)/height, f=vLowFraction: v=vMin t/f for t<f, "
                      "else vMin+(vMax-vMin)(t-f)/(1-f)";
}

eclipse::LutRange lutRangeOf(const eclipse::ShadowLut& lut) {
  return {lut.uMin, lut.uMax, lut.vMin, lut.vMax, lut.vLowFraction};
}

eclipse::LutRange lutRangeOf(const std::map<std::string, std::string>& p, const std::string& origin) {
  eclipse::LutRange r;
  const char* keys[5] = {"uMin", "uMax", "vMin", "vMax", "vLowFraction"};
  double* values[5] = {&r.uMin, &r.uMax, &r.vMin, &r.vMax, &r.vLowFraction};
  int found = 0;
  try {
    for (int k = 0; k < 5; ++k)
      if (const auto it = p.find(keys[k]); it != p.end()) *values[k] = std::stod(it->second), ++found;
    if (found != 0 && found != 5) throw std::invalid_argument("incomplete");
    eclipse::checkLutRange(r.uMin, r.uMax, r.vMin, r.vMax, r.vLowFraction);
  } catch (const std::exception&) {
    throw std::runtime_error(origin + ": bad ranges (uMin, uMax, vMin, vMax, vLowFraction) of the shadow LuT");
  }
  return r;
}

tables::Table toTable(const eclipse::ShadowLut& lut, const std::map<std::string, std::string>& parameters) {
  tables::Table t;
  t.width = lut.width;
  t.height = lut.height;
  t.channels = {"R", "G", "B"};
  t.data = lut.rgb;
  t.parameters = parameters;
  addLutRange(t.parameters, lutRangeOf(lut));
  return t;
}

eclipse::ShadowLut fromTable(const tables::Table& t, const std::string& origin) {
  if (t.channels != std::vector<std::string>{"R", "G", "B"})
    throw std::runtime_error(origin + ": a shadow LuT needs channels R, G, B");
  if (t.width < 2 || t.height < 2)
    throw std::runtime_error(origin + ": a shadow LuT needs at least 2x2 texels");
  eclipse::ShadowLut lut;
  lut.width = t.width;
  lut.height = t.height;
  lut.rgb = t.data;
  const eclipse::LutRange r = lutRangeOf(t.parameters, origin);
  lut.uMin = r.uMin, lut.uMax = r.uMax, lut.vMin = r.vMin, lut.vMax = r.vMax, lut.vLowFraction = r.vLowFraction;
  return lut;
}

vtkSmartPointer<vtkImageData> toImageData(const eclipse::ShadowLut& lut) {
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(lut.width, lut.height, 1);
  // A split v axis is not evenly spaced: y is then the texture coordinate.
  const bool split = lut.vLowFraction > 0.0;
  const double du = (lut.uMax - lut.uMin) / lut.width, dv = split ? 1.0 / lut.height : (lut.vMax - lut.vMin) / lut.height;
  image->SetSpacing(du, dv, 1.0);
  image->SetOrigin(lut.uMin + 0.5 * du, (split ? 0.0 : lut.vMin) + 0.5 * dv, 0.0);
  auto values = vtkSmartPointer<vtkFloatArray>::New();
  values->SetName(kShadowLutArrayName);
  values->SetNumberOfComponents(3);
  values->SetNumberOfTuples(static_cast<vtkIdType>(lut.width) * lut.height);
  std::copy(lut.rgb.begin(), lut.rgb.end(), values->GetPointer(0));
  image->GetPointData()->SetScalars(values);
  std::map<std::string, std::string> range;
  addLutRange(range, lutRangeOf(lut));
  if (!range.empty()) setFieldParameters(image, range);
  return image;
}

eclipse::ShadowLut fromImageData(vtkImageData* image) {
  if (!image) throw std::runtime_error("shadow LuT: no image");
  int dims[3];
  image->GetDimensions(dims);
  auto* values = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  if (dims[2] != 1 || dims[0] < 2 || dims[1] < 2 || !values || values->GetNumberOfComponents() != 3)
    throw std::runtime_error("shadow LuT: expected a 2D image of float RGB point scalars");
  eclipse::ShadowLut lut;
  lut.width = dims[0];
  lut.height = dims[1];
  lut.rgb.assign(values->GetPointer(0), values->GetPointer(0) + 3 * static_cast<std::size_t>(dims[0]) * dims[1]);
  const auto fields = fieldParameters(image);
  eclipse::LutRange r = lutRangeOf(fields, "shadow LuT");
  // A part of the whole table: the ranges of its texels (texel i of n spans [i, i + 1] / n).
  int ext[6];
  image->GetExtent(ext);
  auto whole = [&](const char* key, int n) {
    const auto it = fields.find(key);
    return it == fields.end() ? n : std::stoi(it->second);
  };
  const int width = whole("width", dims[0]), height = whole("height", dims[1]);
  if (ext[0] < 0 || ext[1] >= width || ext[2] < 0 || ext[3] >= height)
    throw std::runtime_error("shadow LuT: extent outside the table's " + std::to_string(width) + "x" +
                             std::to_string(height) + " texels");
  if (ext[0] > 0 || ext[1] < width - 1) {
    const double span = r.uMax - r.uMin, uMin = r.uMin;
    r.uMin = uMin + span * ext[0] / width;
    r.uMax = uMin + span * (ext[1] + 1) / width;
  }
  if (ext[2] > 0 || ext[3] < height - 1) {
    if (r.vLowFraction > 0.0) throw std::runtime_error("shadow LuT: a part of the rows of a split v axis");
    const double span = r.vMax - r.vMin, vMin = r.vMin;
    r.vMin = vMin + span * ext[2] / height;
    r.vMax = vMin + span * (ext[3] + 1) / height;
  }
  lut.uMin = r.uMin, lut.uMax = r.uMax, lut.vMin = r.vMin, lut.vMax = r.vMax, lut.vLowFraction = r.vLowFraction;
  return lut;
}

vtkSmartPointer<vtkTable> profileTable(const std::vector<eclipse::ProfileSample>& samples) {
  auto table = vtkSmartPointer<vtkTable>::New();
  const char* names[] = {"offset_km", "r", "g", "b", "luminance"};
  vtkDoubleArray* columns[5];
  for (int c = 0; c < 5; ++c) {
    auto column = vtkSmartPointer<vtkDoubleArray>::New();
    column->SetName(names[c]);
    column->SetNumberOfTuples(static_cast<vtkIdType>(samples.size()));
    table->AddColumn(column);
    columns[c] = column;
  }
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const auto& s = samples[k];
    const double row[5] = {s.offsetM / 1e3, s.rgb.r, s.rgb.g, s.rgb.b, s.luminance};
    for (int c = 0; c < 5; ++c) columns[c]->SetValue(static_cast<vtkIdType>(k), row[c]);
  }
  return table;
}

} // namespace umbra::filters
