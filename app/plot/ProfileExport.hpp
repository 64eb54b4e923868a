#pragma once
// Export of shadow cross-sections (vtkShadowProfileFilter's table): CSV with the header
// `offset_km,r,g,b,luminance`, and plots as PNG (vtkChartXY, needs an X display) or SVG
// (written directly, no display). Every file is written atomically.
#include <string>

class vtkChartXY;
class vtkTable;

namespace umbra::plot {

/// The CSV header, exactly.
inline constexpr const char* kProfileCsvHeader = "offset_km,r,g,b,luminance";

void writeProfileCsv(vtkTable* profile, const std::string& path);

/// Plot r, g, b and luminance over the offset; the type follows the extension
/// (.png or .svg). Throws std::runtime_error naming the path on failure.
void writeProfilePlot(vtkTable* profile, const std::string& path, const std::string& title);

/// The lines of a profile plot, added to a chart (shared by the PNG export and the GUI).
void addProfileLines(vtkChartXY* chart, vtkTable* profile);

} // namespace umbra::plot
