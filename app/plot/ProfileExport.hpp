#pragma once
// Export of shadow cross-sections (vtkShadowProfileFilter's table): CSV with the header
// `offset_km,r,g,b,luminance`, and plots as PNG (vtkChartXY, needs an X display) or SVG
// (written directly, no display). Every file is written atomically.
#include <string>
#include <utility>
#include <vector>

class vtkChartXY;
class vtkTable;

namespace umbra::plot {

/// The CSV header, exactly.
inline constexpr const char* kProfileCsvHeader = "offset_km,r,g,b,luminance";

void writeProfileCsv(vtkTable* profile, const std::string& path);

/// A line of a plot: its table column, its legend, its colour and width.
struct PlotLine {
  std::string column, label;
  unsigned char r = 0, g = 0, b = 0;
  float width = 1.5f;
};

/// How a profile is drawn: linear I / I_sun in [0, 1.05] (default), or logarithmic from the
/// decade below the smallest value (the eclipse paper's Figure 12), with vertical lines
/// at given offsets (e.g. the umbra's and the penumbra's edges).
struct ProfilePlotStyle {
  bool logScale = false;
  std::vector<std::pair<double, std::string>> markersKm;  ///< offset, label
  /// A line under the title: how the values were made (e.g. "sampled from the 256x256
  /// shadow LuT as the renderer reads it" or "computed point by point").
  std::string subtitle;
  /// The column along the horizontal axis, and its title (a sweep's parameter instead of
  /// the offset).
  std::string xColumn = "offset_km";
  std::string xLabel = "offset from the shadow axis [km]";
  bool xLogScale = false;  ///< (its values then > 0)
  /// The vertical axis: its title and top (linear from 0, log from the decade below the
  /// smallest value). The shadow's I / I_sun by default; a sky's radiance in its units.
  std::string yLabel = "I / I_sun";
  double yMax = 1.05;
  bool legendTop = false;  ///< the legend in the top right corner (curves that fall to the right)
  /// Lines of text beside the plot, on its right (e.g. the Danjon scale).
  std::vector<std::string> notes;
  /// The lines drawn; none: the profile's r, g, b and luminance.
  std::vector<PlotLine> lines;
};

/// Plot r, g, b and luminance (or style.lines) over the offset (or style.xColumn, from 0 or from its first
/// value where that is negative), the legend in the bottom right corner (the
/// curves rise to 1 away from the axis: that corner stays empty; or as the style says); the type follows the
/// extension (.png or .svg). Throws std::runtime_error naming the path on failure.
void writeProfilePlot(vtkTable* profile, const std::string& path, const std::string& title,
                      const ProfilePlotStyle& style = {});

/// The lower end of a log-scale axis for a profile: the decade below its smallest
/// positive value (>= 1e-9).
double logAxisMinimum(vtkTable* profile, const std::vector<PlotLine>& lines = {});

/// The lines of a profile plot, added to a chart (shared by the PNG export and the GUI),
/// against `xColumn` titled `xLabel`.
void addProfileLines(vtkChartXY* chart, vtkTable* profile, const std::string& xColumn = "offset_km",
                     const std::string& xLabel = "offset from the shadow axis [km]",
                     const std::vector<PlotLine>& lines = {});

} // namespace umbra::plot
