#include "HistogramWidget.h"

#include <QMouseEvent>
#include <QPainter>

#include <algorithm>
#include <cmath>
#include <limits>

HistogramWidget::HistogramWidget(QWidget* parent)
  : QWidget(parent)
{
  this->setObjectName("intensityHistogram");
  this->setToolTip("Intensities of the loaded volume (counts on a log scale); the voxels at or "
                   "above the lumen threshold are red. Click to set the threshold.");
}

void HistogramWidget::setValues(const std::vector<float>& values, int bins)
{
  this->Counts.clear();
  this->Total = 0;
  this->Values = values.empty() ? nullptr : &values;
  double low = std::numeric_limits<double>::max();
  double high = std::numeric_limits<double>::lowest();
  for (float v : values)
  {
    if (std::isfinite(v))
    {
      low = std::min(low, static_cast<double>(v));
      high = std::max(high, static_cast<double>(v));
    }
  }
  if (low > high || bins < 1)
  {
    this->Minimum = this->Maximum = 0.0;
    this->update();
    return;
  }
  this->Minimum = low;
  this->Maximum = high;
  this->Counts.assign(static_cast<std::size_t>(bins), 0);
  const double width = high > low ? (high - low) / bins : 1.0;
  for (float v : values)
  {
    if (std::isfinite(v))
    {
      const int bin = std::min(bins - 1, static_cast<int>((v - low) / width));
      ++this->Counts[static_cast<std::size_t>(std::max(0, bin))];
      ++this->Total;
    }
  }
  this->update();
}

void HistogramWidget::setThreshold(double threshold)
{
  this->Threshold = threshold;
  this->update();
}

std::size_t HistogramWidget::countAtOrAbove(double threshold) const
{
  if (!this->Values)
  {
    return 0;
  }
  return static_cast<std::size_t>(std::count_if(this->Values->begin(),
    this->Values->end(),
    [threshold](float v) { return std::isfinite(v) && v >= threshold; }));
}

double HistogramWidget::valueAt(int x) const
{
  const double fraction =
    std::clamp(static_cast<double>(x) / std::max(1, this->width() - 1), 0.0, 1.0);
  return this->Minimum + fraction * (this->Maximum - this->Minimum);
}

void HistogramWidget::paintEvent(QPaintEvent*)
{
  QPainter painter(this);
  painter.fillRect(this->rect(), QColor(24, 26, 32));
  if (this->Counts.empty())
  {
    painter.setPen(QColor(150, 150, 150));
    painter.drawText(this->rect(), Qt::AlignCenter, "no volume loaded");
    return;
  }
  const double top =
    std::log1p(static_cast<double>(*std::max_element(this->Counts.begin(), this->Counts.end())));
  const int w = this->width(), h = this->height() - 14;
  const std::size_t n = this->Counts.size();
  const double range = std::max(this->Maximum - this->Minimum, 1e-300);
  for (std::size_t i = 0; i < n; ++i)
  {
    const int x0 = static_cast<int>(std::floor(static_cast<double>(i) * w / n));
    const int x1 = static_cast<int>(std::floor(static_cast<double>(i + 1) * w / n));
    const int bar = top > 0
      ? static_cast<int>(std::lround(h * std::log1p(static_cast<double>(this->Counts[i])) / top))
      : 0;
    const double binLow = this->Minimum + range * static_cast<double>(i) / n;
    const QColor colour = binLow >= this->Threshold ? QColor(230, 70, 70) : QColor(150, 160, 180);
    painter.fillRect(x0, h - bar, std::max(1, x1 - x0), bar, colour);
  }
  const int tx = static_cast<int>(std::lround((this->Threshold - this->Minimum) / range * (w - 1)));
  if (tx >= 0 && tx < w)
  {
    painter.setPen(QPen(QColor(255, 220, 80), 2));
    painter.drawLine(tx, 0, tx, h);
  }
  painter.setPen(QColor(190, 190, 190));
  QFont font = painter.font();
  font.setPointSizeF(std::max(6.0, font.pointSizeF() * 0.8));
  painter.setFont(font);
  painter.drawText(QRect(2, h, w / 2, 14),
    Qt::AlignLeft | Qt::AlignVCenter,
    QString::number(this->Minimum, 'g', 4));
  painter.drawText(QRect(w / 2, h, w / 2 - 2, 14),
    Qt::AlignRight | Qt::AlignVCenter,
    QString::number(this->Maximum, 'g', 4));
}

void HistogramWidget::mousePressEvent(QMouseEvent* event)
{
  if (!this->Counts.empty() && event->button() == Qt::LeftButton)
  {
    emit this->thresholdPicked(this->valueAt(event->pos().x()));
  }
}

void HistogramWidget::mouseMoveEvent(QMouseEvent* event)
{
  if (!this->Counts.empty() && (event->buttons() & Qt::LeftButton))
  {
    emit this->thresholdPicked(this->valueAt(event->pos().x()));
  }
}
