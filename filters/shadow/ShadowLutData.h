#pragma once
// Conversions of the airless shadow LuT between its three forms: the physics library's
// ShadowLut, the EXR table file (umbra::tables::Table) and VTK's vtkImageData. The
// parameters that define a LuT are listed here once, for the cache key and the header.
#include "FieldParameters.h"
#include "ShadowLut.hpp"

#include <vtkSmartPointer.h>

#include <map>
#include <string>

class vtkImageData;
class vtkTable;
namespace umbra::tables { struct Table; }

namespace umbra::filters {

/// Name of the point-data array that holds I / I_sun.
inline constexpr const char* kShadowLutArrayName = "I_over_Isun";
/// `kind` of the airless shadow LuT in the table cache and the EXR header.
inline constexpr const char* kAirlessShadowLutKind = "eclipse-shadow-airless";
/// `kind` of the atmospheric shadow LuT and of the limb-luminance LuT.
inline constexpr const char* kAtmosphereShadowLutKind = "eclipse-shadow-atmosphere";
inline constexpr const char* kLimbLuminanceLutKind = "eclipse-limb-luminance";

/// Shortest decimal text that reads back as the same double (for headers and keys).
std::string formatNumber(double x);

/// Every parameter that changes an airless LuT's values, as written to its EXR header and
/// hashed for the cache. Bodies are not among them: Eq. 4 makes the airless LuT the same
/// for every Sun and occluder.
std::map<std::string, std::string> airlessLutParameters(const eclipse::ShadowLutParams& params);

/// Records u and v ranges other than [0, 1] as "uMin", "uMax", "vMin", "vMax",
/// "vLowFraction" (eclipse::ShadowLut; and the
/// texel centres in "rangeCentres"); [0, 1]^2 adds nothing, so that such a LuT's header and
/// key stay as before.
void addLutRange(std::map<std::string, std::string>& parameters, const eclipse::LutRange& range);
eclipse::LutRange lutRangeOf(const eclipse::ShadowLut& lut);
/// The ranges recorded by addLutRange ([0, 1] when absent); throws std::runtime_error naming
/// `origin` when they are not 0 <= min < max <= 1.
eclipse::LutRange lutRangeOf(const std::map<std::string, std::string>& parameters, const std::string& origin);

tables::Table toTable(const eclipse::ShadowLut& lut, const std::map<std::string, std::string>& parameters);
/// Throws std::runtime_error naming `origin` if the table is not an RGB LuT. The u range
/// comes from the header (uRangeOf).
eclipse::ShadowLut fromTable(const tables::Table& table, const std::string& origin);

/// Image with point coordinates (u, v) = texel centres (in the LuT's ranges) and float RGB
/// point scalars; the ranges also go to field data (addLutRange).
vtkSmartPointer<vtkImageData> toImageData(const eclipse::ShadowLut& lut);
/// Throws std::runtime_error if the image is not a 2D float RGB LuT. The ranges come from
/// the field data (lutRangeOf). A part of a table (an update extent of
/// vtkEclipseShadowLutSource: its field data's "width" and "height" are the whole table's)
/// becomes a LuT over its texels' part of the ranges (same texel centres); a part of the
/// rows of a split v axis cannot (throws).
eclipse::ShadowLut fromImageData(vtkImageData* image);

/// A shadow profile as a table: columns offset_km, r, g, b, luminance.
vtkSmartPointer<vtkTable> profileTable(const std::vector<eclipse::ProfileSample>& samples);


} // namespace umbra::filters
