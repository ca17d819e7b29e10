#ifndef ExportPanel_h
#define ExportPanel_h

#include "ExportSurface.h"

#include <QWidget>

class MainActions;
class QCheckBox;
class QComboBox;
class QPlainTextEdit;

/// The Export panel: format, caps, STL patches, frame (LPS or RAS, millimetres), the Check and
/// Export actions and the check report.
class ExportPanel : public QWidget
{
  Q_OBJECT
public:
  ExportPanel(MainActions* actions, QWidget* parent = nullptr);
  /// The export options for `path` (the format follows its extension).
  bender::ExportSurfaceOptions options(const QString& path) const;
  void showReport(const QString& text);
  /// The file dialog's filter.
  static QString fileFilter();

private:
  QComboBox* Format;
  QCheckBox* Cap;
  QComboBox* Patches;
  QComboBox* Frame;
  QPlainTextEdit* Report;
};

#endif
