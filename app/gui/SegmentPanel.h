#ifndef SegmentPanel_h
#define SegmentPanel_h

#include "SegmentationSession.h"

#include <QWidget>

#include <cstddef>
#include <memory>
#include <string>

class HistogramWidget;
class MainActions;
class QComboBox;
class QDoubleSpinBox;
class QLabel;

/// The Segment panel: method (threshold / vesselness), lumen threshold with the volume's
/// intensity histogram (the share of voxels the threshold keeps, a click on the histogram sets
/// it), smoothing, the Segment action, and the warning of a segmentation that kept implausibly
/// little (bender::SegmentationWarning, the segmentation's own result).
class SegmentPanel : public QWidget
{
  Q_OBJECT
public:
  SegmentPanel(MainActions* actions, QWidget* parent = nullptr);
  /// The parameters to segment with: the panel's method, threshold and smoothing over the
  /// parameters last set with setSettings (those the panel does not show are kept).
  bender::SegmentationSettings settings() const;
  /// Shows `settings` (a recovered session's): method, threshold, smoothing; the rest is kept
  /// for settings().
  void setSettings(const bender::SegmentationSettings& settings);

  /// Shows the histogram of `volume` (null clears it); computed once per volume.
  void showVolume(const std::shared_ptr<const bender::Volume>& volume);
  /// Shows the last segmentation's warning under the histogram; empty hides it.
  void showWarning(const std::string& warning);

  HistogramWidget* histogram() const { return this->Histogram; }
  QLabel* warningLabel() const { return this->Warning; }
  /// Whether the loaded volume holds only integers in [0, 255].
  bool isEightBit() const { return this->EightBit; }

private:
  void showKept();

  QComboBox* Method;
  QDoubleSpinBox* Threshold;
  QDoubleSpinBox* Smoothing;
  HistogramWidget* Histogram;
  QLabel* Kept;
  QLabel* Warning;
  std::shared_ptr<const bender::Volume> Volume;
  bender::SegmentationSettings Base;
  // The spin boxes' (rounded) values when Base was shown: unchanged, Base's exact values stand.
  double ShownThreshold = 0.0;
  double ShownSmoothing = 0.0;
  bool EightBit = false;
};

#endif
