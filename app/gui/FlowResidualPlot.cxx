#include "FlowResidualPlot.h"

#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>

namespace
{
QColor FieldColour(const std::string& field)
{
  if (field == "p")
  {
    return QColor(240, 200, 70);
  }
  if (field == "Ux")
  {
    return QColor(230, 90, 90);
  }
  if (field == "Uy")
  {
    return QColor(110, 200, 110);
  }
  if (field == "Uz")
  {
    return QColor(100, 150, 240);
  }
  return QColor(200, 200, 200);
}
} // namespace

FlowResidualPlot::FlowResidualPlot(QWidget* parent)
  : QWidget(parent)
{
  this->setObjectName("flowResidualPlot");
  this->setToolTip("The solver's initial residuals per iteration (log scale): the original solid, "
                   "the current shape dashed");
}

void FlowResidualPlot::addIteration(int series, const bender::CfdIteration& iteration)
{
  if (series < 0 || series > 1)
  {
    return;
  }
  for (const auto& [field, value] : iteration.residuals)
  {
    if (std::isfinite(value) && value > 0.0)
    {
      this->Series[series][field].emplace_back(iteration.iteration, value);
    }
  }
  ++this->Count[series];
  this->update();
}

void FlowResidualPlot::clear()
{
  this->Series[0].clear();
  this->Series[1].clear();
  this->Count[0] = this->Count[1] = 0;
  this->update();
}

int FlowResidualPlot::iterations(int series) const
{
  return series == 0 || series == 1 ? this->Count[series] : 0;
}

double FlowResidualPlot::lastResidual(int series, const std::string& field) const
{
  if (series < 0 || series > 1)
  {
    return -1.0;
  }
  const auto it = this->Series[series].find(field);
  return it == this->Series[series].end() || it->second.empty() ? -1.0 : it->second.back().second;
}

void FlowResidualPlot::paintEvent(QPaintEvent*)
{
  QPainter painter(this);
  painter.setRenderHint(QPainter::Antialiasing);
  painter.fillRect(this->rect(), QColor(24, 26, 32));
  QFont font = painter.font();
  font.setPointSizeF(std::max(6.0, font.pointSizeF() * 0.8));
  painter.setFont(font);
  int last = 1;
  double low = 1.0, high = 1.0;
  for (const auto& series : this->Series)
  {
    for (const auto& [field, curve] : series)
    {
      for (const auto& [iteration, value] : curve)
      {
        last = std::max(last, iteration);
        low = std::min(low, value);
        high = std::max(high, value);
      }
    }
  }
  if (this->Count[0] + this->Count[1] == 0)
  {
    painter.setPen(QColor(150, 150, 150));
    painter.drawText(this->rect(), Qt::AlignCenter, "residuals: no run yet");
    return;
  }
  const double top = std::ceil(std::log10(high)), bottom = std::floor(std::log10(low));
  const double decades = std::max(1.0, top - bottom);
  const QRectF area(34, 6, this->width() - 40, this->height() - 24);
  const auto toPoint = [&](int iteration, double value)
  {
    return QPointF(area.left() + area.width() * iteration / last,
      area.top() + area.height() * (top - std::log10(value)) / decades);
  };
  // Decades and their labels, the iteration axis.
  for (double d = bottom; d <= top; d += 1.0)
  {
    const QPointF at = toPoint(0, std::pow(10.0, d));
    painter.setPen(QColor(60, 64, 74));
    painter.drawLine(QPointF(area.left(), at.y()), QPointF(area.right(), at.y()));
    painter.setPen(QColor(170, 170, 170));
    painter.drawText(QRectF(0, at.y() - 7, 32, 14),
      Qt::AlignRight | Qt::AlignVCenter,
      QString("1e%1").arg(static_cast<int>(d)));
  }
  painter.drawText(QRectF(area.left(), area.bottom() + 2, area.width(), 14),
    Qt::AlignRight | Qt::AlignVCenter,
    QString("iteration %1").arg(last));
  // The curves, then the legend (one entry per field).
  std::map<std::string, QColor> legend;
  for (int s = 0; s < 2; ++s)
  {
    for (const auto& [field, curve] : this->Series[s])
    {
      QPainterPath path;
      for (std::size_t i = 0; i < curve.size(); ++i)
      {
        const QPointF p = toPoint(curve[i].first, curve[i].second);
        i == 0 ? path.moveTo(p) : path.lineTo(p);
      }
      painter.setPen(QPen(FieldColour(field), 1.5, s == 0 ? Qt::SolidLine : Qt::DashLine));
      painter.drawPath(path);
      legend[field] = FieldColour(field);
    }
  }
  qreal x = area.left() + 4;
  for (const auto& [field, colour] : legend)
  {
    painter.setPen(colour);
    const QString text = QString::fromStdString(field);
    painter.drawText(QPointF(x, area.top() + 12), text);
    x += painter.fontMetrics().horizontalAdvance(text) + 8;
  }
}
