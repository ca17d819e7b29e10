#ifndef SweepCandidateTable_h
#define SweepCandidateTable_h

#include "Sweep.h"

#include <QTableWidget>

#include <string>
#include <vector>

/// A sweep's table in the window: one row per candidate in the sweep's order (the rows of
/// summary.csv: the varied value, the state, the bend measures, the pressure drop, each outlet's
/// split, the wall shear stress, the mesh and iterations, why a row is not solved). Each number
/// cell keeps its value unrounded in Qt::UserRole; a row not solved is greyed. Choosing a row
/// (a click, the arrow keys) emits candidateChosen with its index in the rows.
class SweepCandidateTable : public QTableWidget
{
  Q_OBJECT
public:
  explicit SweepCandidateTable(QWidget* parent = nullptr);

  void setRows(const std::vector<bender::SweepRow>& rows, const std::string& parameter);
  /// The column titled `title` ("Pressure drop (Pa)", "Split outlet (%)"); -1 when none.
  int columnOf(const QString& title) const;

signals:
  void candidateChosen(int index);
};

#endif
