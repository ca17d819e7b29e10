#include "ReportLayout.h"

#include <QFont>
#include <QFontMetrics>
#include <QPainter>
#include <QPdfWriter>

#include <algorithm>
#include <cmath>

namespace bender
{

ReportLayout::ReportLayout(QPdfWriter& writer, QPainter& painter)
  : Writer(writer)
  , Painter(painter)
{
}

int ReportLayout::Pixels(double points) const
{
  return static_cast<int>(std::lround(points * this->Writer.resolution() / 72.0));
}

void ReportLayout::Fit(int height)
{
  if (this->Y > 0 && this->Y + height > this->Writer.height())
  {
    this->NewPage();
  }
}

void ReportLayout::NewPage()
{
  this->Writer.newPage();
  this->Y = 0;
  ++this->PageCount;
}

void ReportLayout::Skip(double points)
{
  this->Y += this->Pixels(points);
}

void ReportLayout::Heading(const QString& text, double points, int keep)
{
  QFont font("Sans", 1);
  font.setPointSizeF(points);
  font.setBold(true);
  this->Painter.setFont(font);
  const int height = QFontMetrics(font, &this->Writer).height();
  this->Fit(height + keep);
  this->Painter.setPen(Qt::black);
  this->Painter.drawText(QRect(0, this->Y, this->Writer.width(), height), Qt::AlignLeft, text);
  this->Y += height + this->Pixels(points * 0.35);
}

void ReportLayout::Paragraph(const QString& text, double points, const QColor& color)
{
  QFont font("Sans", 1);
  font.setPointSizeF(points);
  this->Painter.setFont(font);
  const QRect box =
    QFontMetrics(font, &this->Writer)
      .boundingRect(
        QRect(0, 0, this->Writer.width(), 1 << 20), Qt::TextWordWrap | Qt::AlignLeft, text);
  this->Fit(box.height());
  this->Painter.setPen(color);
  this->Painter.drawText(
    QRect(0, this->Y, this->Writer.width(), box.height()), Qt::TextWordWrap | Qt::AlignLeft, text);
  this->Painter.setPen(Qt::black);
  this->Y += box.height() + this->Pixels(points * 0.4);
}

void ReportLayout::Table(const std::vector<ReportRow>& rows, const std::vector<double>& widths)
{
  if (rows.empty())
  {
    return;
  }
  QFont font("Sans", 1);
  font.setPointSizeF(8.5);
  QFont bold = font;
  bold.setBold(true);
  const int rowHeight = static_cast<int>(QFontMetrics(font, &this->Writer).height() * 1.35);
  const int pad = this->Pixels(3);
  const int pageWidth = this->Writer.width();
  auto drawRow = [&](const ReportRow& row, bool header)
  {
    this->Fit(rowHeight);
    if (header || row.highlighted)
    {
      this->Painter.fillRect(QRect(0, this->Y, pageWidth, rowHeight),
        header ? QColor(225, 230, 240) : QColor(255, 236, 160));
    }
    this->Painter.setFont(header || row.highlighted ? bold : font);
    int x = 0;
    for (int c = 0; c < row.cells.size() && c < static_cast<int>(widths.size()); ++c)
    {
      const int w = static_cast<int>(widths[c] * pageWidth);
      const Qt::Alignment align = (c == 0 ? Qt::AlignLeft : Qt::AlignRight) | Qt::AlignVCenter;
      this->Painter.drawText(QRect(x + pad, this->Y, w - 2 * pad, rowHeight), align, row.cells[c]);
      x += w;
    }
    this->Painter.setPen(QColor(200, 200, 200));
    this->Painter.drawLine(0, this->Y + rowHeight, pageWidth, this->Y + rowHeight);
    this->Painter.setPen(Qt::black);
    this->Y += rowHeight;
  };
  this->Fit(2 * rowHeight);
  drawRow(rows.front(), true);
  for (size_t i = 1; i < rows.size(); ++i)
  {
    if (this->Y + rowHeight > this->Writer.height())
    {
      this->NewPage();
      drawRow(rows.front(), true);
    }
    drawRow(rows[i], false);
  }
  this->Y += this->Pixels(6);
}

void ReportLayout::Picture(const QImage& image,
  const QString& title,
  const QString& caption,
  double heightFraction)
{
  if (image.isNull())
  {
    return;
  }
  const double maxHeight = heightFraction * this->Writer.height();
  const double scale =
    std::min(static_cast<double>(this->Writer.width()) / image.width(), maxHeight / image.height());
  const QSize size(
    static_cast<int>(image.width() * scale), static_cast<int>(image.height() * scale));
  this->Heading(title, 10.5, size.height() + this->Pixels(12));
  this->Paragraph(caption, 8, QColor(90, 90, 90));
  this->Painter.drawImage(QRect(QPoint(0, this->Y), size), image);
  this->Y += size.height() + this->Pixels(8);
}

} // namespace bender
