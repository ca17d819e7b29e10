#ifndef FlowComparisonTable_h
#define FlowComparisonTable_h

#include "CfdComparison.h"

#include <QTableWidget>

/// The comparison of the original and the current shape's flow (bender::CompareCfdResults, the
/// table bender-cli compare prints): a row per quantity (pressure drop and split per named
/// outlet, WSS statistics, low / high WSS areas, mesh, run) with both values, the difference
/// and the relative difference in its unit; highlighted rows (CfdHighlightRule) are drawn
/// bold on amber, their note as the tooltip. Column 0 holds each row's key (Qt::UserRole).
class FlowComparisonTable : public QTableWidget
{
  Q_OBJECT
public:
  explicit FlowComparisonTable(QWidget* parent = nullptr);

  /// Fills the table; an empty comparison clears it.
  void setComparison(const bender::CfdComparison& comparison);
  const bender::CfdComparison& comparison() const { return this->Shown; }
  /// The table row of `key` ("pressureDrop.outlet_1"); -1 when none.
  int rowOf(const QString& key) const;
  /// Rows drawn highlighted.
  int highlightedRows() const;

private:
  bender::CfdComparison Shown;
};

#endif
