#pragma once
// The plot panel: the cross-section of the occluder's shadow at the receiver's distance
// (vtkShadowProfileFilter over vtkEclipseShadowLutSource), drawn in a vtkChartXY with
// umbra::plot::addProfileLines, and a marker for the receiver: its centre (a line and a
// point at the shadow factor there) and its extent (a band of +- its radius).
//
// The LuT source is built once per LuT size (from the table cache when it is there); a
// change of time only changes the profile filter's parameters. When the occluder has an
// atmosphere and the 3D view shades with its atmospheric shadow LuT, the profile comes
// from that table (its columns around the receiver's distance) through the same filter, on
// a log scale, as `umbra profile shadow --atmosphere` plots it (the occluder's radius is
// then the atmosphere's bottom radius, from the table's field data).
#include "scene/ReceiverShadow.hpp"

#include <vtkSmartPointer.h>

#include <string>

class QVTKOpenGLNativeWidget;
class vtkChartXY;
class vtkContextView;
class vtkEclipseShadowLutSource;
class vtkImageData;
class vtkPlot;
class vtkShadowProfileFilter;
class vtkTable;

namespace umbra::gui {

class ProfilePanel {
public:
  /// Draws into the widget's render window.
  explicit ProfilePanel(QVTKOpenGLNativeWidget* widget);
  ~ProfilePanel();
  ProfilePanel(const ProfilePanel&) = delete;
  ProfilePanel& operator=(const ProfilePanel&) = delete;

  /// The shadow LuT of this size for this occluder (the airless LuT is the same for every
  /// occluder; the bodies only travel in its field data). Builds or reads it from the cache
  /// when the size changed. Throws std::runtime_error when it cannot be computed.
  vtkImageData* prepareLut(int size, const scene::ReceiverShadow& geometry);

  /// The atmospheric shadow LuT of `occluder` (SceneView::atmosphereShadowLut: a part of
  /// the table) to plot while the geometry's occluder is that body; null: the airless one.
  void setAtmosphereShadowLut(vtkImageData* lut, const std::string& occluder);

  /// Recomputes the profile for this geometry and redraws. Returns the shadow factor
  /// (luminance, I / I_sun) at the receiver's centre; 1 when there is no valid geometry.
  double update(const scene::ReceiverShadow& geometry);

  /// Re-renders the chart.
  void render();

  /// The last profile (columns offset_km, r, g, b, luminance).
  vtkTable* profile() const;

private:
  QVTKOpenGLNativeWidget* widget;
  vtkSmartPointer<vtkContextView> view;
  vtkSmartPointer<vtkChartXY> chart;
  vtkSmartPointer<vtkEclipseShadowLutSource> lutSource;
  vtkSmartPointer<vtkShadowProfileFilter> filter;
  vtkSmartPointer<vtkTable> table;      // deep copy of the filter's output, shown by the lines
  vtkSmartPointer<vtkTable> band;       // x, y0, y1: the receiver's extent
  vtkSmartPointer<vtkTable> centre;     // x, y: a vertical line at the receiver's centre
  vtkSmartPointer<vtkTable> point;      // x, y: the shadow factor at the centre
  vtkPlot* bandPlot = nullptr;
  vtkPlot* centrePlot = nullptr;
  vtkPlot* pointPlot = nullptr;
  vtkSmartPointer<vtkImageData> atmosphereLut;
  std::string atmosphereOccluder;
  int lutSize = 0;
  bool linesAdded = false;
};

} // namespace umbra::gui
