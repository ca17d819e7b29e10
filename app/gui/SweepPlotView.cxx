#include "SweepPlotView.h"

#include "SweepPlot.h"

#include <QVBoxLayout>
#include <QVTKOpenGLNativeWidget.h>

#include <vtkChartMatrix.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkVector.h>

SweepPlotView::SweepPlotView(QWidget* parent)
  : QWidget(parent)
{
  this->setObjectName("sweepPlot");
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  this->View = new QVTKOpenGLNativeWidget(this);
  this->View->setObjectName("sweepPlotView");
  this->View->setMinimumSize(600, 200);
  this->View->setRenderWindow(this->Window);
  this->Window->SetMultiSamples(0);
  this->Context->SetRenderWindow(this->Window);
  this->Context->SetInteractor(this->View->interactor()); // zoom and pan the charts
  this->Context->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  this->Context->GetScene()->AddItem(this->Charts);
  layout->addWidget(this->View);
}

SweepPlotView::~SweepPlotView() = default;

void SweepPlotView::setRows(const std::vector<bender::SweepRow>& rows,
  const std::string& parameter,
  const std::string& highlight)
{
  // Drawn anew on the same charts.
  for (int i = 0; i < 3; ++i)
  {
    if (vtkChartXY* chart = this->chart(i))
    {
      chart->ClearPlots();
    }
  }
  bender::AddSweepCharts(this->Charts, rows, parameter, highlight);
  this->Window->Render();
}

vtkChartXY* SweepPlotView::chart(int which) const
{
  return vtkChartXY::SafeDownCast(this->Charts->GetChart(vtkVector2i(which, 0)));
}
