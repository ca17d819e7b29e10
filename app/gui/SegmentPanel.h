#ifndef SegmentPanel_h
#define SegmentPanel_h

#include "SegmentationSession.h"

#include <QWidget>

class MainActions;
class QComboBox;
class QDoubleSpinBox;

/// The Segment panel: method (threshold / vesselness), lumen threshold, smoothing, and the
/// Segment action.
class SegmentPanel : public QWidget
{
  Q_OBJECT
public:
  SegmentPanel(MainActions* actions, QWidget* parent = nullptr);
  bender::SegmentationSettings settings() const;

private:
  QComboBox* Method;
  QDoubleSpinBox* Threshold;
  QDoubleSpinBox* Smoothing;
};

#endif
