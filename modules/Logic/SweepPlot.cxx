// The charts of a sweep (SweepPlot.h): three VTK charts side by side (pressure drop, flow split
// per outlet, low-WSS area) against the varied value, each with the original drawn as a dashed
// line; summary.png draws them off screen.

#include "SweepPlot.h"
#include "BenderErrors.h"
#include "RenderToPng.h"

#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartMatrix.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotLine.h>
#include <vtkPlotPoints.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>
#include <vtkVector.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>

namespace bender
{

namespace
{
using Value = std::function<double(const SweepRow&)>;

constexpr std::array<std::array<unsigned char, 3>, 6> Colors = { { { 31, 119, 180 },
  { 214, 39, 40 },
  { 44, 160, 44 },
  { 255, 127, 14 },
  { 148, 103, 189 },
  { 140, 86, 75 } } };

vtkSmartPointer<vtkTable> Table(const std::vector<std::pair<double, double>>& xy)
{
  auto table = vtkSmartPointer<vtkTable>::New();
  vtkNew<vtkDoubleArray> x, y;
  x->SetName("x");
  y->SetName("y");
  for (const auto& [a, b] : xy)
  {
    x->InsertNextValue(a);
    y->InsertNextValue(b);
  }
  table->AddColumn(x);
  table->AddColumn(y);
  return table;
}

// One series: the solved rows' (value, y) in value order, as a line with points, and the
// original's y as a dashed line across the values.
void AddSeries(vtkChartXY* chart,
  const std::vector<SweepRow>& rows,
  const Value& y,
  const std::string& label,
  std::size_t color,
  const std::string& highlight)
{
  std::vector<std::pair<double, double>> points;
  std::vector<std::pair<double, double>> chosen;
  double originalY = std::numeric_limits<double>::quiet_NaN();
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const SweepRow& row : rows)
  {
    if (row.state != "solved" || !std::isfinite(y(row)))
    {
      continue;
    }
    if (row.original)
    {
      originalY = y(row);
    }
    if (!row.original || row.parameter == "fraction")
    {
      points.emplace_back(row.value, y(row));
      if (row.id == highlight)
      {
        chosen.emplace_back(row.value, y(row));
      }
      lo = std::min(lo, row.value);
      hi = std::max(hi, row.value);
    }
  }
  std::sort(points.begin(), points.end());
  const auto& c = Colors[color % Colors.size()];
  if (!points.empty())
  {
    vtkPlot* line = chart->AddPlot(vtkChart::LINE);
    line->SetInputData(Table(points), 0, 1);
    line->SetColor(c[0], c[1], c[2], 255);
    line->SetWidth(2.0);
    line->SetLabel(label);
    if (auto* l = vtkPlotLine::SafeDownCast(line))
    {
      l->SetMarkerStyle(vtkPlotPoints::CIRCLE);
      l->SetMarkerSize(8.0);
    }
  }
  if (std::isfinite(originalY) && std::isfinite(lo))
  {
    vtkPlot* original = chart->AddPlot(vtkChart::LINE);
    original->SetInputData(Table({ { lo, originalY }, { hi, originalY } }), 0, 1);
    original->SetColor(c[0], c[1], c[2], 160);
    original->SetWidth(1.5);
    original->GetPen()->SetLineType(vtkPen::DASH_LINE);
    original->SetLabel(label + " (original)");
  }
  if (!chosen.empty())
  {
    auto* point = vtkPlotPoints::SafeDownCast(chart->AddPlot(vtkChart::POINTS));
    point->SetInputData(Table(chosen), 0, 1);
    point->SetColor(c[0], c[1], c[2], 255);
    point->SetMarkerStyle(vtkPlotPoints::DIAMOND);
    point->SetMarkerSize(18.0);
    point->SetLabel(label + " (" + highlight + ")");
  }
}

void Style(vtkChartXY* chart, const std::string& title, const std::string& x, const std::string& y)
{
  chart->SetTitle(title);
  chart->GetTitleProperties()->SetFontSize(16);
  chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(x);
  chart->GetAxis(vtkAxis::LEFT)->SetTitle(y);
  chart->SetShowLegend(true);
  chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::LEFT);
  chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
}

std::string AxisTitle(const std::string& parameter)
{
  if (parameter == "fraction")
  {
    return "fraction of the plan's motion";
  }
  return parameter == "radius" ? "radius of influence R (mm)" : "plan (index)";
}
} // namespace

void AddSweepCharts(vtkChartMatrix* matrix,
  const std::vector<SweepRow>& rows,
  const std::string& parameter,
  const std::string& highlight)
{
  matrix->SetSize(vtkVector2i(3, 1));
  matrix->SetGutter(vtkVector2f(70.0f, 60.0f));
  const std::string x = AxisTitle(parameter);

  auto* drop = vtkChartXY::SafeDownCast(matrix->GetChart(vtkVector2i(0, 0)));
  Style(drop, "Pressure drop", x, "inlet - outlets (Pa)");
  AddSeries(
    drop, rows, [](const SweepRow& r) { return r.pressureDrop; }, "pressure drop", 0, highlight);

  auto* split = vtkChartXY::SafeDownCast(matrix->GetChart(vtkVector2i(1, 0)));
  Style(split, "Flow split", x, "% of the inlet's flow");
  split->GetAxis(vtkAxis::LEFT)->SetBehavior(vtkAxis::FIXED);
  split->GetAxis(vtkAxis::LEFT)->SetRange(0.0, 105.0);
  std::vector<std::string> outlets;
  for (const SweepRow& row : rows)
  {
    for (const SweepOutlet& o : row.outlets)
    {
      if (std::find(outlets.begin(), outlets.end(), o.name) == outlets.end())
      {
        outlets.push_back(o.name);
      }
    }
  }
  for (std::size_t k = 0; k < outlets.size(); ++k)
  {
    const std::string name = outlets[k];
    AddSeries(
      split,
      rows,
      [name](const SweepRow& r)
      {
        for (const SweepOutlet& o : r.outlets)
        {
          if (o.name == name)
          {
            return o.splitPercent;
          }
        }
        return std::numeric_limits<double>::quiet_NaN();
      },
      name,
      k + 1,
      highlight);
  }

  auto* wss = vtkChartXY::SafeDownCast(matrix->GetChart(vtkVector2i(2, 0)));
  Style(wss, "Low wall shear stress (< 0.4 Pa)", x, "wall area (mm^2)");
  AddSeries(
    wss,
    rows,
    [](const SweepRow& r)
    { return r.wallShearStress ? r.lowWssArea : std::numeric_limits<double>::quiet_NaN(); },
    "low-WSS area",
    4,
    highlight);
}

void WriteSweepPlot(const std::vector<SweepRow>& rows,
  const std::string& parameter,
  const std::string& path)
{
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    throw EnvironmentError(path + ": no display to draw the plot (DISPLAY is not set)");
  }
  vtkNew<vtkContextView> view;
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  view->GetRenderWindow()->SetOffScreenRendering(1);
  view->GetRenderWindow()->SetSize(1500, 500);
  view->GetRenderWindow()->SetMultiSamples(0);
  vtkNew<vtkChartMatrix> matrix;
  view->GetScene()->AddItem(matrix);
  AddSweepCharts(matrix, rows, parameter);
  WriteRenderWindowPng(view->GetRenderWindow(), path);
}

} // namespace bender
