#ifndef BendPanel_h
#define BendPanel_h

#include "BenderSession.h"

#include <QWidget>

class MainActions;
class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QSpinBox;

/// The Bend panel: region of influence R (with r_min and the space-inversion warning), decay
/// bell/plateau and plateau width, the screw-direction toggle of paper 3.8 (enabled when a flip
/// occurred), adaptive subdivision at release, and the gesture buttons (the window's shared
/// Place, Grab and Cancel actions).
class BendPanel : public QWidget
{
  Q_OBJECT
public:
  explicit BendPanel(MainActions* actions, QWidget* parent = nullptr);

  bender::WarpParameters parameters() const;
  void setParameters(const bender::WarpParameters& parameters);
  /// Refreshes the live information (r_min, risk, flip, state) from the session;
  /// `placingRibbon`: "place ribbon" waits for a click (Esc cancels it).
  void showState(const bender::BenderSession& session, bool placingRibbon = false);

signals:
  void parametersChanged();

private:
  QDoubleSpinBox* Radius;
  QLabel* MinimumRadius;
  QComboBox* Decay;
  QDoubleSpinBox* Plateau;
  QCheckBox* ReverseScrews;
  QCheckBox* Subdivide;
  QDoubleSpinBox* Tolerance;
  MainActions* Actions;
  QLabel* State;
  bool Updating = false;
};

#endif
