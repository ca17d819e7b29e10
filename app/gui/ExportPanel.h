#ifndef ExportPanel_h
#define ExportPanel_h

#include "ExportSurface.h"
#include "PrepareForCfd.h"

#include <QWidget>

class MainActions;
class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QPlainTextEdit;
class QPushButton;
class QTableWidget;

/// The export options, shared by the Export panel and the Ctrl+E export dialog: a preset
/// ("OpenFOAM (m, named solids)", "TetGen (.smesh, m)"), the format, caps, STL patches, frame,
/// unit and the patches sidecar. Named solids are ASCII STL: choosing them with "STL (binary)"
/// switches the format to "STL (ASCII)" and says so in the note below the form (never a
/// silent change of format).
class ExportOptionsForm : public QWidget
{
  Q_OBJECT
public:
  enum Format
  {
    StlBinary = 0,
    StlAscii,
    Vtp,
    Ply,
    Obj,
    TetgenSmesh
  };
  enum Preset
  {
    Custom = 0,
    OpenFoam,
    Tetgen
  };
  explicit ExportOptionsForm(QWidget* parent = nullptr);
  /// The options for `path` (whose extension decides the written format).
  bender::ExportSurfaceOptions options(const QString& path) const;
  /// The extension of the chosen format, with its dot (".stl", ".vtp", ".smesh", ...).
  QString suffix() const;
  /// Sets every control as in `other`.
  void copyFrom(const ExportOptionsForm& other);
  /// Sets the controls of a preset (Custom leaves them).
  void applyPreset(int preset);
  /// The note below the form ("" when there is nothing to say).
  QString note() const;

  QComboBox* Presets;
  QComboBox* Formats;
  QCheckBox* Cap;
  QComboBox* Patches;
  QComboBox* Frame;
  QComboBox* Unit;
  QCheckBox* Sidecar;

private:
  void formatChanged();
  void patchesChanged();
  void markCustom();

  QLabel* Note;
  bool Applying = false;
};

/// The Export panel: a "Prepare for CFD" step (clip the ends, name them, flow extensions, flat
/// labelled caps: bender::PrepareForCfd; the ends listed with editable names and extension
/// lengths), the export options (ExportOptionsForm), the Check and Export actions and the
/// report.
class ExportPanel : public QWidget
{
  Q_OBJECT
public:
  ExportPanel(MainActions* actions, QWidget* parent = nullptr);
  /// The export options for `path` (the format follows its extension).
  bender::ExportSurfaceOptions options(const QString& path) const;
  ExportOptionsForm* form() const { return this->Form; }
  void showReport(const QString& text);
  /// The file dialog's filter.
  static QString fileFilter();

  /// The options of the Prepare for CFD step: clip, default extension factors and, once ends
  /// are listed, their names and factors by position (the rim centre of each end).
  bender::PrepareForCfdOptions prepareOptions() const;
  /// Lists the ends of a prepared surface (name editable, role, radius, extension factor).
  void showEnds(const std::vector<bender::CfdEnd>& ends);
  /// Forgets the listed ends (a new surface).
  void clearEnds();

  QCheckBox* Clip;
  QDoubleSpinBox* InletFactor;
  QDoubleSpinBox* OutletFactor;
  QPushButton* Prepare;
  QTableWidget* Ends;

signals:
  void prepareRequested();

private:
  ExportOptionsForm* Form;
  QPlainTextEdit* Report;
  std::vector<bender::CfdEnd> Listed;
};

#endif
