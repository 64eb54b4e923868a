#include "ProfilePanel.hpp"

#include "ProfileExport.hpp"
#include "vtkEclipseShadowLutSource.h"
#include "vtkShadowProfileFilter.h"

#include <QVTKOpenGLNativeWidget.h>
#include <vtkAxis.h>
#include <vtkBrush.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkImageData.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotArea.h>
#include <vtkPlotPoints.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace umbra::gui {
namespace {

constexpr double kTop = 1.05;  // the chart's fixed y range is [0, 1.05] (addProfileLines)
constexpr unsigned char kMarker[3] = {230, 140, 0};

vtkSmartPointer<vtkTable> makeTable(std::initializer_list<const char*> names, vtkIdType rows) {
  auto t = vtkSmartPointer<vtkTable>::New();
  for (const char* name : names) {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->SetNumberOfTuples(rows);
    a->Fill(0.0);
    t->AddColumn(a);
  }
  return t;
}

void setColumn(vtkTable* t, const char* name, std::initializer_list<double> values) {
  auto* a = vtkDoubleArray::SafeDownCast(t->GetColumnByName(name));
  vtkIdType i = 0;
  for (double v : values) a->SetValue(i++, v);
  a->Modified();
}

/// Linear interpolation of `y` over the increasing `x`, clamped to the ends.
double interpolate(vtkDoubleArray* x, vtkDoubleArray* y, double at) {
  const vtkIdType n = x->GetNumberOfTuples();
  if (n == 0) return 1.0;
  if (at <= x->GetValue(0)) return y->GetValue(0);
  if (at >= x->GetValue(n - 1)) return y->GetValue(n - 1);
  const double* xs = x->GetPointer(0);
  const vtkIdType k = std::upper_bound(xs, xs + n, at) - xs;  // xs[k-1] <= at < xs[k]
  const double t = (at - xs[k - 1]) / (xs[k] - xs[k - 1]);
  return (1.0 - t) * y->GetValue(k - 1) + t * y->GetValue(k);
}

std::string km(double m) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(0) << m / 1e3 << " km";
  return s.str();
}

} // namespace

ProfilePanel::ProfilePanel(QVTKOpenGLNativeWidget* w) : widget(w) {
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  this->widget->setRenderWindow(window);
  this->view = vtkSmartPointer<vtkContextView>::New();
  this->view->SetRenderWindow(window);
  this->view->SetInteractor(this->widget->interactor());
  this->view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);

  this->chart = vtkSmartPointer<vtkChartXY>::New();
  this->chart->GetTitleProperties()->SetFontSize(14);
  this->chart->SetTitle("no shadow to show");
  this->chart->SetRenderEmpty(true);  // the title says why when no plot is shown
  this->view->GetScene()->AddItem(this->chart);

  this->filter = vtkSmartPointer<vtkShadowProfileFilter>::New();
  this->filter->SetSamples(1001);
  this->table = vtkSmartPointer<vtkTable>::New();
  // vtkPlotArea (VTK 9.1) fills nothing with fewer than three x values.
  this->band = makeTable({"x", "y0", "y1"}, 3);
  this->centre = makeTable({"x", "y"}, 2);
  this->point = makeTable({"x", "y"}, 1);
}

ProfilePanel::~ProfilePanel() = default;

vtkTable* ProfilePanel::profile() const { return this->table; }

vtkImageData* ProfilePanel::prepareLut(int size, const scene::ReceiverShadow& g) {
  if (!this->lutSource || size != this->lutSize) {
    auto source = vtkSmartPointer<vtkEclipseShadowLutSource>::New();
    source->SetWidth(size);
    source->SetHeight(size);
    if (g.valid) {
      source->SetOccluderName(g.occluder.c_str());
      source->SetOccluderRadiusM(g.occluderRadiusM);
      source->SetSunRadiusM(g.sunRadiusM);
      source->SetSunOccluderDistanceM(g.sunOccluderDistanceM);
    }
    source->Update();
    if (source->GetOutput()->GetNumberOfPoints() == 0)
      throw std::runtime_error("the shadow LuT (" + std::to_string(size) + "x" + std::to_string(size) +
                               ") could not be computed");
    this->lutSource = source;
    this->lutSize = size;
    this->filter->SetInputConnection(source->GetOutputPort());
  }
  return this->lutSource->GetOutput();
}

void ProfilePanel::setAtmosphereShadowLut(vtkImageData* lut, const std::string& occluder) {
  this->atmosphereLut = lut;
  this->atmosphereOccluder = lut ? occluder : std::string();
}

double ProfilePanel::update(const scene::ReceiverShadow& g) {
  const bool show = g.valid && this->lutSource;
  if (!show) {
    this->chart->SetTitle(g.why.empty() ? "no shadow to show" : g.why);
    for (vtkIdType i = 0; i < this->chart->GetNumberOfPlots(); ++i) this->chart->GetPlot(i)->SetVisible(false);
    this->render();
    return 1.0;
  }

  // The profile reaches past the penumbra and past the receiver's far edge.
  const double maxOffset = std::max(1.25 * g.penumbraRadiusM, 1.05 * (g.offsetM + g.receiverRadiusM));
  const bool atmospheric = this->atmosphereLut && g.occluder == this->atmosphereOccluder;
  if (atmospheric) {
    this->filter->SetInputData(this->atmosphereLut);
  } else if (this->filter->GetInputAlgorithm() != this->lutSource.Get()) {
    this->filter->SetInputConnection(this->lutSource->GetOutputPort());
  }
  this->filter->SetSunRadiusM(g.sunRadiusM);
  this->filter->SetOccluderRadiusM(atmospheric ? 0.0 : g.occluderRadiusM);  // 0: the table's (bottom radius)
  this->filter->SetSunOccluderDistanceM(g.sunOccluderDistanceM);
  this->filter->SetReceiverDistanceM(g.receiverDistanceM);
  this->filter->SetMaxOffsetM(maxOffset);
  this->filter->Update();
  vtkTable* out = this->filter->GetOutput();
  if (out->GetNumberOfRows() < 2) throw std::runtime_error("the shadow profile could not be computed");
  this->table->DeepCopy(out);
  this->table->Modified();

  auto* x = vtkDoubleArray::SafeDownCast(this->table->GetColumnByName("offset_km"));
  auto* lum = vtkDoubleArray::SafeDownCast(this->table->GetColumnByName("luminance"));
  const double centreKm = g.offsetM / 1e3;
  const double factor = interpolate(x, lum, centreKm);

  // Through an atmosphere the umbra is lit at 1e-3 .. 1e-2 of the Sun: a log scale.
  const double bottomY = atmospheric ? plot::logAxisMinimum(this->table) : 0.0;
  vtkAxis* left = this->chart->GetAxis(vtkAxis::LEFT);
  left->SetLogScale(atmospheric);
  left->SetRange(bottomY, kTop);
  left->SetBehavior(vtkAxis::FIXED);
  const double xMax = maxOffset / 1e3;
  const double lo = std::max(0.0, (g.offsetM - g.receiverRadiusM) / 1e3);
  const double hi = std::min(xMax, (g.offsetM + g.receiverRadiusM) / 1e3);
  setColumn(this->band, "x", {lo, 0.5 * (lo + hi), hi});
  setColumn(this->band, "y0", {bottomY, bottomY, bottomY});
  setColumn(this->band, "y1", {kTop, kTop, kTop});
  this->band->Modified();
  setColumn(this->centre, "x", {centreKm, centreKm});
  setColumn(this->centre, "y", {bottomY, kTop});
  this->centre->Modified();
  setColumn(this->point, "x", {centreKm});
  setColumn(this->point, "y", {factor});
  this->point->Modified();

  if (!this->linesAdded) {
    // The receiver's extent under the lines, then the profile, then the centre on top.
    this->bandPlot = this->chart->AddPlot(vtkChart::AREA);
    this->bandPlot->SetInputData(this->band);
    this->bandPlot->SetInputArray(0, "x");
    this->bandPlot->SetInputArray(1, "y0");
    this->bandPlot->SetInputArray(2, "y1");
    this->bandPlot->SetColor(kMarker[0], kMarker[1], kMarker[2], 60);
    this->bandPlot->GetPen()->SetLineType(vtkPen::NO_PEN);
    plot::addProfileLines(this->chart, this->table);
    this->centrePlot = this->chart->AddPlot(vtkChart::LINE);
    this->centrePlot->SetInputData(this->centre, "x", "y");
    this->centrePlot->SetColor(kMarker[0], kMarker[1], kMarker[2], 255);
    this->centrePlot->SetWidth(2.0f);
    this->centrePlot->GetPen()->SetLineType(vtkPen::DASH_LINE);
    this->pointPlot = this->chart->AddPlot(vtkChart::POINTS);
    this->pointPlot->SetInputData(this->point, "x", "y");
    this->pointPlot->SetColor(kMarker[0], kMarker[1], kMarker[2], 255);
    this->pointPlot->SetWidth(3.0f);
    if (auto* points = vtkPlotPoints::SafeDownCast(this->pointPlot)) {
      points->SetMarkerStyle(vtkPlotPoints::CIRCLE);
      points->SetMarkerSize(12.0f);
    }
    this->linesAdded = true;
  }
  // The profile rises from its lowest (left) to 1 (right), on a log scale too: the legend
  // goes to the empty corner farther from the rise, top left when the penumbra's middle is
  // in the right half of the plot, else bottom right.
  const bool riseOnTheRight = 0.5 * (std::max(g.umbraRadiusM, g.antumbraRadiusM) + g.penumbraRadiusM) > 0.5 * maxOffset;
  this->chart->GetLegend()->SetHorizontalAlignment(riseOnTheRight ? vtkChartLegend::LEFT : vtkChartLegend::RIGHT);
  this->chart->GetLegend()->SetVerticalAlignment(riseOnTheRight ? vtkChartLegend::TOP : vtkChartLegend::BOTTOM);
  this->bandPlot->SetLabel(g.receiver + " (extent)");
  this->centrePlot->SetLabel(g.receiver + " (centre)");
  this->pointPlot->SetLabel("shadow factor at the centre");
  for (vtkIdType i = 0; i < this->chart->GetNumberOfPlots(); ++i) this->chart->GetPlot(i)->SetVisible(true);

  vtkAxis* bottom = this->chart->GetAxis(vtkAxis::BOTTOM);
  bottom->SetRange(0.0, xMax);
  bottom->SetBehavior(vtkAxis::FIXED);
  // (Through the atmosphere the penumbra's edge is plain on the log scale: left out, to fit.)
  const std::string cone = (g.antumbraRadiusM > 0.0 ? "antumbra " : "umbra ") + km(std::max(g.umbraRadiusM, g.antumbraRadiusM));
  this->chart->SetTitle(atmospheric ? g.occluder + "'s shadow through its atmosphere at " + km(g.receiverDistanceM) + " (" + cone + ")"
                                    : g.occluder + "'s shadow at " + km(g.receiverDistanceM) + " (" + cone + ", penumbra " +
                                          km(g.penumbraRadiusM) + ")");
  this->render();
  return factor;
}

void ProfilePanel::render() {
  this->chart->Modified();
  this->widget->renderWindow()->Render();
}

} // namespace umbra::gui
