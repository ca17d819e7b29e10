#ifndef SweepPlotView_h
#define SweepPlotView_h

#include "Sweep.h"

#include <QWidget>

#include <vtkNew.h>

#include <string>
#include <vector>

class QVTKOpenGLNativeWidget;
class vtkChartMatrix;
class vtkChartXY;
class vtkContextView;
class vtkGenericOpenGLRenderWindow;

/// A sweep's plot in the window: the charts of summary.png (bender::AddSweepCharts: pressure
/// drop, flow split per outlet, low-WSS area against the varied value, the original dashed),
/// with the candidate shown in the views marked on each chart.
class SweepPlotView : public QWidget
{
  Q_OBJECT
public:
  explicit SweepPlotView(QWidget* parent = nullptr);
  ~SweepPlotView() override;

  /// Draws `rows`; `highlight` is the id of the candidate marked (empty: none).
  void setRows(const std::vector<bender::SweepRow>& rows,
    const std::string& parameter,
    const std::string& highlight = {});
  /// Chart 0 pressure drop, 1 flow split, 2 low-WSS area.
  vtkChartXY* chart(int which) const;
  QVTKOpenGLNativeWidget* view() const { return this->View; }

private:
  QVTKOpenGLNativeWidget* View = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> Window;
  vtkNew<vtkContextView> Context;
  vtkNew<vtkChartMatrix> Charts;
};

#endif
