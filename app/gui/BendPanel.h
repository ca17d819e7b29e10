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
/// occurred), adaptive subdivision at release, the lumen guard's threshold, and the gesture
/// buttons (the window's shared Place, Grab and Cancel actions), which stay where they are when
/// the warning appears (its lines are reserved).
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
  /// The lumen guard as set here: off, or the largest narrowing that passes (a fraction).
  bender::LumenGuardOptions lumenGuard() const;
  /// Sets the threshold in percent (0: off), as `bender --max-narrowing` does.
  void setMaxNarrowing(double percent);

signals:
  void parametersChanged();
  void lumenGuardChanged();

private:
  QDoubleSpinBox* Radius;
  QLabel* MinimumRadius;
  QComboBox* Decay;
  QDoubleSpinBox* Plateau;
  QCheckBox* ReverseScrews;
  QCheckBox* Subdivide;
  QDoubleSpinBox* Tolerance;
  QDoubleSpinBox* MaxNarrowing;
  MainActions* Actions;
  QLabel* State;
  bool Updating = false;
};

#endif
