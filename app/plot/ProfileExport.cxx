#include "ProfileExport.hpp"

#include "EglRenderWindow.h"
#include "OutputFile.hpp"

#include <vtkAxis.h>
#include <vtkRect.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace umbra::plot {
namespace {

/// A profile's lines: r, g, b and luminance (the thicker).
const std::vector<PlotLine>& profileLines() {
  static const std::vector<PlotLine> lines{{"r", "red", 220, 50, 47, 1.5f},
                                           {"g", "green", 60, 160, 60, 1.5f},
                                           {"b", "blue", 40, 100, 220, 1.5f},
                                           {"luminance", "luminance", 30, 30, 30, 2.5f}};
  return lines;
}
const std::vector<PlotLine>& linesOr(const std::vector<PlotLine>& lines) { return lines.empty() ? profileLines() : lines; }

vtkDoubleArray* column(vtkTable* t, const char* name) {
  auto* c = vtkDoubleArray::SafeDownCast(t->GetColumnByName(name));
  if (!c) throw std::runtime_error(std::string("the plotted table has no column '") + name + "'");
  return c;
}

std::string xmlEscaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

/// An axis tick's label: whole numbers from 100 up, else three significant digits.
std::string tickText(double v, double span) {
  if (span >= 100.0) return std::to_string(std::lround(v));
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

void writeSvg(vtkTable* t, const std::string& path, const std::string& title, const ProfilePlotStyle& style) {
  const double notesWidth = style.notes.empty() ? 0.0 : 420.0;
  const double W = 800 + notesWidth, H = 500, left = 70, right = 20 + notesWidth, top = 40, bottom = 60;
  auto* x = column(t, style.xColumn.c_str());
  const vtkIdType n = x->GetNumberOfTuples();
  const double xMax = std::max(x->GetValue(n - 1), 1e-12);
  const double xMin = style.xLogScale ? std::max(x->GetValue(0), 1e-300) : std::min(0.0, x->GetValue(0));
  const std::vector<PlotLine>& lines = linesOr(style.lines);
  const double yLo = style.logScale ? logAxisMinimum(t, lines) : 0.0, yHi = style.yMax;
  const auto px = [&](double v) {
    const double f = style.xLogScale ? std::log(std::max(v, xMin) / xMin) / std::log(xMax / xMin)
                                     : (v - xMin) / (xMax - xMin);
    return left + (W - left - right) * f;
  };
  // Linear: [0, yHi]; log: [yLo, yHi] in log10.
  const auto yFraction = [&](double v) {
    if (!style.logScale) return std::clamp(v, 0.0, yHi) / yHi;
    const double l = std::log10(std::clamp(v, yLo, yHi));
    return (l - std::log10(yLo)) / (std::log10(yHi) - std::log10(yLo));
  };
  const auto py = [&](double v) { return H - bottom - (H - top - bottom) * yFraction(v); };

  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << W / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" << xmlEscaped(title) << "</text>\n";
  if (!style.subtitle.empty())
    s << "<text x=\"" << W / 2 << "\" y=\"36\" text-anchor=\"middle\" fill=\"#555\">" << xmlEscaped(style.subtitle)
      << "</text>\n";
  for (int k = 0; k <= 5; ++k) {  // axes and vertical grid
    const double xv = style.xLogScale ? xMin * std::pow(xMax / xMin, k / 5.0) : xMin + (xMax - xMin) * k / 5;
    s << "<line x1=\"" << px(xv) << "\" y1=\"" << py(yLo) << "\" x2=\"" << px(xv) << "\" y2=\"" << py(yHi)
      << "\" stroke=\"#ddd\"/>\n<text x=\"" << px(xv) << "\" y=\"" << py(yLo) + 18 << "\" text-anchor=\"middle\">"
      << tickText(xv, style.xLogScale ? xv : xMax - xMin) << "</text>\n";
  }
  std::vector<double> yTicks;
  if (style.logScale)
    for (double v = yLo; v <= yHi / 1.05 * (1.0 + 1e-9); v *= 10.0) yTicks.push_back(v);
  else
    for (int k = 0; k <= 5; ++k) yTicks.push_back(0.2 * k * yHi / 1.05);
  for (double yv : yTicks)
    s << "<line x1=\"" << px(xMin) << "\" y1=\"" << py(yv) << "\" x2=\"" << px(xMax) << "\" y2=\"" << py(yv)
      << "\" stroke=\"#ddd\"/>\n<text x=\"" << px(xMin) - 8 << "\" y=\"" << py(yv) + 4 << "\" text-anchor=\"end\">"
      << yv << "</text>\n";
  for (const auto& [km, label] : style.markersKm)
    s << "<line x1=\"" << px(km) << "\" y1=\"" << py(yLo) << "\" x2=\"" << px(km) << "\" y2=\"" << py(yHi)
      << "\" stroke=\"#555\" stroke-dasharray=\"6,4\"/>\n<text x=\"" << px(km) + 4 << "\" y=\"" << top + 12
      << "\" fill=\"#555\">" << xmlEscaped(label) << "</text>\n";
  s << "<text x=\"" << (left + W - right) / 2 << "\" y=\"" << H - 15 << "\" text-anchor=\"middle\">"
    << xmlEscaped(style.xLabel) << "</text>\n"
    << "<text transform=\"translate(18," << H / 2 << ") rotate(-90)\" text-anchor=\"middle\">" << xmlEscaped(style.yLabel)
    << "</text>\n";
  int legend = 0;
  for (const PlotLine& line : lines) {
    auto* y = column(t, line.column.c_str());
    char colour[8];
    std::snprintf(colour, sizeof colour, "#%02x%02x%02x", line.r, line.g, line.b);
    s << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.5\" points=\"";
    for (vtkIdType i = 0; i < n; ++i) s << px(x->GetValue(i)) << "," << py(y->GetValue(i)) << " ";
    const double legendY = style.legendTop ? top + 24 + 16 * legend
                                           : H - bottom - 10 - 16 * (static_cast<int>(lines.size()) - 1 - legend);
    ++legend;
    s << "\"/>\n<text x=\"" << W - right - 10 << "\" y=\"" << legendY
      << "\" text-anchor=\"end\" fill=\"" << colour << "\">" << xmlEscaped(line.label) << "</text>\n";
  }
  for (std::size_t k = 0; k < style.notes.size(); ++k)
    s << "<text x=\"" << W - notesWidth + 10 << "\" y=\"" << top + 30 + 18 * k << "\" fill=\"#333\">"
      << xmlEscaped(style.notes[k]) << "</text>\n";
  s << "</svg>\n";

  output::OutputFile out(path);
  {
    std::ofstream f(out.tempPath());
    f << s.str();
    if (!f.flush()) throw std::runtime_error(path + ": cannot write");
  }
  out.commit();
}

void writePng(vtkTable* t, const std::string& path, const std::string& title, const ProfilePlotStyle& style) {
  try {
    umbra::render::useEglWithoutDisplay();  // no X display: EGL
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what() + " - or write .svg");
  }
  vtkNew<vtkContextView> view;
  view->GetRenderWindow()->SetOffScreenRendering(1);
  const int notesWidth = style.notes.empty() ? 0 : 420;
  view->GetRenderWindow()->SetSize(800 + notesWidth, 500);
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  vtkNew<vtkChartXY> chart;
  chart->SetTitle(style.subtitle.empty() ? title : title + "\n" + style.subtitle);
  chart->GetTitleProperties()->SetFontSize(16);
  view->GetScene()->AddItem(chart);
  addProfileLines(chart, t, style.xColumn, style.xLabel, style.lines);
  if (notesWidth > 0) {  // the chart keeps 800 pixels; the notes take the rest, on its right
    chart->SetAutoSize(false);
    chart->SetSize(vtkRectf(0.0f, 0.0f, 800.0f, 500.0f));
  }
  vtkNew<vtkTextActor> notes;
  if (!style.notes.empty()) {
    std::string text;
    for (const std::string& line : style.notes) text += (text.empty() ? "" : "\n") + line;
    notes->SetInput(text.c_str());
    notes->GetTextProperty()->SetFontSize(13);
    notes->GetTextProperty()->SetColor(0.2, 0.2, 0.2);
    notes->GetTextProperty()->SetJustificationToLeft();
    notes->GetTextProperty()->SetVerticalJustificationToTop();
    notes->SetDisplayPosition(810, 440);
    view->GetRenderer()->AddActor2D(notes);
  }
  if (style.xLogScale) chart->GetAxis(vtkAxis::BOTTOM)->SetLogScale(true);
  chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
  chart->GetLegend()->SetVerticalAlignment(style.legendTop ? vtkChartLegend::TOP : vtkChartLegend::BOTTOM);
  const double yLo = style.logScale ? logAxisMinimum(t, style.lines) : 0.0;
  chart->GetAxis(vtkAxis::LEFT)->SetTitle(style.yLabel);
  chart->GetAxis(vtkAxis::LEFT)->SetRange(yLo, style.yMax);
  if (style.logScale) chart->GetAxis(vtkAxis::LEFT)->SetLogScale(true);
  std::vector<vtkSmartPointer<vtkTable>> markers;  // kept alive until rendered
  for (const auto& [km, label] : style.markersKm) {
    auto m = vtkSmartPointer<vtkTable>::New();
    vtkNew<vtkDoubleArray> mx, my;
    mx->SetName(style.xColumn.c_str());
    my->SetName(label.c_str());
    for (double yv : {std::max(yLo, 1e-12), style.yMax}) mx->InsertNextValue(km), my->InsertNextValue(yv);
    m->AddColumn(mx);
    m->AddColumn(my);
    vtkPlot* plot = chart->AddPlot(vtkChart::LINE);
    plot->SetInputData(m, 0, 1);
    plot->SetColor(90, 90, 90, 255);
    plot->GetPen()->SetLineType(vtkPen::DASH_LINE);
    plot->SetLabel(label);
    markers.push_back(m);
  }
  view->GetRenderWindow()->Render();

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(view->GetRenderWindow());
  grab->ReadFrontBufferOff();
  grab->Update();
  output::OutputFile out(path);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(out.tempPath().c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode() != 0) throw std::runtime_error(path + ": cannot write PNG");
  out.commit();
}

} // namespace

void addProfileLines(vtkChartXY* chart, vtkTable* t, const std::string& xColumn, const std::string& xLabel,
                     const std::vector<PlotLine>& lines) {
  column(t, xColumn.c_str());
  for (const PlotLine& line : linesOr(lines)) {
    column(t, line.column.c_str());
    vtkPlot* plot = chart->AddPlot(vtkChart::LINE);
    plot->SetInputData(t, xColumn, line.column);
    plot->SetColor(line.r, line.g, line.b, 255);
    plot->SetWidth(line.width);
    plot->SetLabel(line.label);
  }
  chart->SetShowLegend(true);
  chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(xLabel);
  chart->GetAxis(vtkAxis::LEFT)->SetTitle("I / I_sun");
  chart->GetAxis(vtkAxis::LEFT)->SetRange(0.0, 1.05);
  chart->GetAxis(vtkAxis::LEFT)->SetBehavior(vtkAxis::FIXED);
}

void writeProfileCsv(vtkTable* t, const std::string& path) {
  vtkDoubleArray* cols[5];
  const char* names[5] = {"offset_km", "r", "g", "b", "luminance"};
  for (int c = 0; c < 5; ++c) cols[c] = column(t, names[c]);
  for (vtkIdType i = 0; i < cols[0]->GetNumberOfTuples(); ++i)
    for (int c = 0; c < 5; ++c)
      if (!std::isfinite(cols[c]->GetValue(i)))
        throw std::runtime_error(path + ": not written: the shadow profile's " + names[c] + " is not finite at row " +
                                 std::to_string(i));
  output::OutputFile out(path);
  {
    std::ofstream f(out.tempPath());
    f << kProfileCsvHeader << "\n";
    char buf[64];
    for (vtkIdType i = 0; i < cols[0]->GetNumberOfTuples(); ++i) {
      for (int c = 0; c < 5; ++c) {
        std::snprintf(buf, sizeof buf, c == 0 ? "%.6f" : ",%.10g", cols[c]->GetValue(i));
        f << buf;
      }
      f << "\n";
    }
    if (!f.flush()) throw std::runtime_error(path + ": cannot write");
  }
  out.commit();
}

void writeProfilePlot(vtkTable* t, const std::string& path, const std::string& title, const ProfilePlotStyle& style) {
  const std::string ext = output::extensionOf(path);
  if (ext == ".svg") return writeSvg(t, path, title, style);
  if (ext == ".png") return writePng(t, path, title, style);
  throw std::runtime_error(path + ": unsupported plot type (expected .png or .svg)");
}

double logAxisMinimum(vtkTable* t, const std::vector<PlotLine>& lines) {
  double lo = 1.0;
  for (const PlotLine& line : linesOr(lines)) {
    auto* y = column(t, line.column.c_str());
    for (vtkIdType i = 0; i < y->GetNumberOfTuples(); ++i)
      if (y->GetValue(i) > 0.0) lo = std::min(lo, y->GetValue(i));
  }
  return std::pow(10.0, std::floor(std::log10(std::max(lo, 1e-9))));
}

} // namespace umbra::plot
