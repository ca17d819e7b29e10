#ifndef SweepWindow_h
#define SweepWindow_h

#include "SweepStudy.h"

#include <QString>
#include <QWidget>

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <string>

class FlowViews;
class QLabel;
class SweepCandidateTable;
class SweepPlotView;
class vtkRenderer;

/// A sweep in its own window (issue 24, "In the application"): the plot of summary.png
/// (SweepPlotView), the table of the candidates (SweepCandidateTable) and, for the row chosen,
/// that candidate beside the original in the linked views of the Flow panel (FlowViews, each
/// read from its case's results).
class SweepWindow : public QWidget
{
  Q_OBJECT
public:
  explicit SweepWindow(QWidget* parent = nullptr);
  ~SweepWindow() override;

  /// Shows `sweep`: its plot and table; the views show its first solved candidate that is not
  /// the original (none: the original alone).
  void setSweep(const bender::SweepFolder& sweep);
  const bender::SweepFolder& sweep() const { return this->Sweep; }
  /// Shows row `index` beside the original; false (with the reason in the caption) when that
  /// candidate or the original has no results to show.
  bool showCandidate(int index);
  /// The renderer whose camera the views first take their viewpoint from (the main view's:
  /// the shapes seen as they were bent); not owned.
  void setViewRenderer(vtkRenderer* renderer) { this->ViewRenderer = renderer; }
  /// The id of the candidate in the right view (empty: none).
  const std::string& shownCandidate() const { return this->Shown; }

  SweepPlotView* plot() const { return this->Plot; }
  SweepCandidateTable* table() const { return this->Table; }
  FlowViews* views() const { return this->Views; }
  QLabel* caption() const { return this->Caption; }

private:
  /// The original's results surface, read once per sweep (null: none solved).
  vtkPolyData* originalSurface(QString& problem);

  bender::SweepFolder Sweep;
  std::string Shown;
  vtkRenderer* ViewRenderer = nullptr;
  /// The views have been framed for this sweep: a candidate chosen next keeps the viewpoint.
  bool Framed = false;
  vtkSmartPointer<vtkPolyData> Original;
  SweepPlotView* Plot = nullptr;
  SweepCandidateTable* Table = nullptr;
  FlowViews* Views = nullptr;
  QLabel* Caption = nullptr;
};

#endif
