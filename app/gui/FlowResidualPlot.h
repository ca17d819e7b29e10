#ifndef FlowResidualPlot_h
#define FlowResidualPlot_h

#include "CfdResidualMonitor.h"

#include <QString>
#include <QWidget>

#include <map>
#include <string>
#include <utility>
#include <vector>

/// The solver's initial residuals against the iteration, live while a flow case runs: one
/// curve per field (Ux, Uy, Uz, p; a colour each) and per shape (the original solid, the
/// current shape dashed), on a logarithmic scale.
class FlowResidualPlot : public QWidget
{
  Q_OBJECT
public:
  explicit FlowResidualPlot(QWidget* parent = nullptr);

  /// Adds an iteration of shape `series` (0 the original, 1 the current shape) and repaints.
  void addIteration(int series, const bender::CfdIteration& iteration);
  /// Forgets every curve.
  void clear();
  /// Iterations received for `series`.
  int iterations(int series) const;
  /// The last iteration's residual of `field` in `series`; negative when none.
  double lastResidual(int series, const std::string& field) const;

  QSize sizeHint() const override { return QSize(300, 150); }
  QSize minimumSizeHint() const override { return QSize(160, 100); }

protected:
  void paintEvent(QPaintEvent* event) override;

private:
  using Curve = std::vector<std::pair<int, double>>;
  std::map<std::string, Curve> Series[2];
  int Count[2] = { 0, 0 };
};

#endif
