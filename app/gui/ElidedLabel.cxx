#include "ElidedLabel.h"

#include <QEvent>
#include <QFontMetrics>
#include <QHelpEvent>
#include <QPainter>
#include <QStyle>
#include <QStyleOption>
#include <QToolTip>

ElidedLabel::ElidedLabel(const QString& text, QWidget* parent)
  : QLabel(text, parent)
{
  this->setTextFormat(Qt::PlainText);
  this->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
}

QSize ElidedLabel::minimumSizeHint() const
{
  return QSize(40, this->fontMetrics().height());
}

QSize ElidedLabel::sizeHint() const
{
  const QSize whole = QLabel::sizeHint();
  return QSize(std::min(whole.width(), 600), whole.height());
}

QString ElidedLabel::shownText() const
{
  const int width = this->contentsRect().width();
  return this->fontMetrics().elidedText(
    this->text().simplified(), Qt::ElideRight, std::max(0, width));
}

bool ElidedLabel::isElided() const
{
  return this->shownText() != this->text().simplified();
}

void ElidedLabel::paintEvent(QPaintEvent*)
{
  QPainter painter(this);
  QStyleOption option;
  option.initFrom(this);
  this->style()->drawItemText(&painter,
    this->contentsRect(),
    static_cast<int>(this->alignment()),
    option.palette,
    this->isEnabled(),
    this->shownText(),
    this->foregroundRole());
}

bool ElidedLabel::event(QEvent* event)
{
  if (event->type() == QEvent::ToolTip && this->toolTip().isEmpty() && this->isElided())
  {
    QToolTip::showText(static_cast<QHelpEvent*>(event)->globalPos(), this->text(), this);
    return true;
  }
  return QLabel::event(event);
}
