#ifndef ElidedLabel_h
#define ElidedLabel_h

#include <QLabel>

/// A one-line QLabel that never widens its window: a text longer than the label is drawn cut
/// with "..." at the end, and the whole text is the tooltip (the label's own tooltip when one
/// is set, else its text). text() stays the whole text. Used for the status bar's messages.
class ElidedLabel : public QLabel
{
  Q_OBJECT
public:
  explicit ElidedLabel(const QString& text, QWidget* parent = nullptr);

  QSize minimumSizeHint() const override;
  QSize sizeHint() const override;
  /// Whether the text is drawn cut at the current width.
  bool isElided() const;
  /// The text as drawn at the current width.
  QString shownText() const;

protected:
  void paintEvent(QPaintEvent* event) override;
  bool event(QEvent* event) override;
};

#endif
