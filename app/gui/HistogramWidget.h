#ifndef HistogramWidget_h
#define HistogramWidget_h

#include <QWidget>

#include <cstddef>
#include <vector>

/// The intensity histogram of a volume with a threshold line: counts on a logarithmic scale,
/// the bins at or above the threshold drawn in the segmentation's red. A click or drag on it
/// emits thresholdPicked with the intensity under the cursor.
class HistogramWidget : public QWidget
{
  Q_OBJECT
public:
  explicit HistogramWidget(QWidget* parent = nullptr);

  /// Counts `values` into `bins` equal bins over [min, max] of the finite values (non-finite
  /// values are left out). An empty input clears the histogram.
  void setValues(const std::vector<float>& values, int bins = 128);
  void setThreshold(double threshold);

  const std::vector<std::size_t>& counts() const { return this->Counts; }
  double minimum() const { return this->Minimum; }
  double maximum() const { return this->Maximum; }
  /// Values counted (the finite ones) and, of them, those at or above the threshold.
  std::size_t total() const { return this->Total; }
  std::size_t countAtOrAbove(double threshold) const;
  const std::vector<float>* values() const { return this->Values; }

  QSize sizeHint() const override { return QSize(300, 110); }
  QSize minimumSizeHint() const override { return QSize(120, 70); }

signals:
  void thresholdPicked(double threshold);

protected:
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;

private:
  double valueAt(int x) const;

  std::vector<std::size_t> Counts;
  double Minimum = 0.0;
  double Maximum = 0.0;
  std::size_t Total = 0;
  double Threshold = 0.0;
  const std::vector<float>* Values = nullptr;
};

#endif
