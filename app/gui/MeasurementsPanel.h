#ifndef MeasurementsPanel_h
#define MeasurementsPanel_h

#include "VesselSession.h"

#include <QWidget>

class MainActions;
class QLabel;
class QTableWidget;

/// The vessel measurements: the centerline state (with the Show centerline toggle), the branch
/// held under the ribbon (its stretch between the ribbon's ends before the grab, now, and the
/// change, live during a bend) and the plan's before/after table (every branch matched by its
/// outlets: the original surface against the committed one). The measures shown are the rows
/// of the vessel measure table marked Panel (VesselMeasureTable.h), in its order.
class MeasurementsPanel : public QWidget
{
  Q_OBJECT
public:
  explicit MeasurementsPanel(MainActions* actions, QWidget* parent = nullptr);

  /// `state`: one line on the centerlines (computing, their count, or why there are none).
  void showState(const bender::VesselSession& vessels, const QString& state);
  /// The held stretch before the grab and now (now invalid: not bending).
  void showHeld(const bender::HeldBranchMeasures& before, const bender::HeldBranchMeasures& now);

  QTableWidget* heldTable() const { return this->Held; }
  QTableWidget* planTable() const { return this->Plan; }
  QLabel* stateLabel() const { return this->State; }

private:
  QLabel* State;
  QTableWidget* Held;
  QTableWidget* Plan;
};

#endif
