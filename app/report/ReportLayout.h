#ifndef bender_ReportLayout_h
#define bender_ReportLayout_h

// Flowing layout on the pages of a QPdfWriter: headings, wrapped paragraphs, tables with
// highlighted rows and pictures, top to bottom, a new page when the next block does not fit.
// Lengths in the writer's device pixels; fonts in points.

#include <QColor>
#include <QImage>
#include <QString>
#include <QStringList>

#include <vector>

class QPainter;
class QPdfWriter;

namespace bender
{

/// A table row: its cells and whether it is highlighted (a tinted background, bold text).
struct ReportRow
{
  QStringList cells;
  bool highlighted = false;
};

class ReportLayout
{
public:
  /// Lays out on `writer` through `painter` (begun on the writer).
  ReportLayout(QPdfWriter& writer, QPainter& painter);

  /// A heading (bold, `points` tall); keeps at least `keep` pixels below it on its page.
  void Heading(const QString& text, double points, int keep = 0);
  /// A paragraph, wrapped to the page width.
  void Paragraph(const QString& text, double points = 9.5, const QColor& color = Qt::black);
  /// A table: the first row is the header; `widths` are fractions of the page width; columns
  /// after the first are right-aligned. Rows split across pages with the header repeated.
  void Table(const std::vector<ReportRow>& rows, const std::vector<double>& widths);
  /// A picture scaled to the page width (or `heightFraction` of the page height, whichever is
  /// smaller), with its title and a caption above.
  void Picture(const QImage& image,
    const QString& title,
    const QString& caption,
    double heightFraction = 0.42);
  /// Space below the last block, in points.
  void Skip(double points);
  /// Starts a new page.
  void NewPage();
  int Pages() const { return this->PageCount; }

private:
  void Fit(int height);
  int Pixels(double points) const;

  QPdfWriter& Writer;
  QPainter& Painter;
  int Y = 0;
  int PageCount = 1;
};

} // namespace bender

#endif
