#ifndef ExportPanel_h
#define ExportPanel_h

#include "ExportSurface.h"
#include "MeshFormats.h"
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
/// silent change of format). The formats are bender::MeshFormats' writable rows, in table
/// order: one entry each ("STL" with a choice of encoding: "STL (binary)" and "STL (ASCII)").
class ExportOptionsForm : public QWidget
{
  Q_OBJECT
public:
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
  /// The Formats entry of the format called `name` (its ASCII entry for `ascii`, formats with
  /// a choice of encoding); -1 when there is none.
  int formatIndex(const std::string& name, bool ascii = false) const;
  /// The chosen format's row, and whether its ASCII entry is chosen.
  bender::MeshFormat format() const;
  bool isAscii() const;
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
/// labelled caps: bender::PrepareForCfd), the export options (ExportOptionsForm), the Check and
/// Export actions and the report.
///
/// The ends table has a row per vessel end: before Prepare, the ends of the centerlines
/// (showCenterlineEnds: the name and role Prepare will give, as predicted from the inscribed
/// radius at the cut, the largest being the inlet; that radius; the extension factor; where the
/// end is cut, in mm along the centerline from the end, also set by dragging the end's disc in
/// the 3D view); after Prepare, the ends it made (showEnds). Names, extension factors and cut
/// distances are editable; what was edited goes to the next Prepare (prepareOptions).
class ExportPanel : public QWidget
{
  Q_OBJECT
public:
  /// The ends table's columns.
  enum EndColumn
  {
    NameColumn = 0,
    RoleColumn,
    RadiusColumn,
    FactorColumn,
    CutColumn
  };
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
  /// Lists the ends of a prepared surface (name editable, role, radius, extension factor, cut
  /// distance).
  void showEnds(const std::vector<bender::CfdEnd>& ends);
  /// Lists the vessel ends of the centerlines before Prepare (see the class comment), cut at
  /// their default distances.
  void showCenterlineEnds(const std::vector<bender::CenterlineEndPath>& paths);
  /// Forgets the listed ends (a new surface).
  void clearEnds();
  /// True while the rows are the centerline ends (before Prepare).
  bool listsCenterlineEnds() const { return this->BeforePrepare; }
  /// Sets a row's cut distance (mm from the end, as a drag in the view moved it); it goes to
  /// the next Prepare. No signal.
  void setCutDistance(int row, double distance);
  /// The row's cut distance (mm from the end); -1 for an end that is not clipped.
  double cutDistance(int row) const;
  /// The row's name as shown, and whether it is (or is predicted to be) the inlet.
  QString endName(int row) const;
  bool endIsInlet(int row) const;

  QCheckBox* Clip;
  QDoubleSpinBox* InletFactor;
  QDoubleSpinBox* OutletFactor;
  QPushButton* Prepare;
  QTableWidget* Ends;

signals:
  void prepareRequested();
  /// The user typed a cut distance (mm from the end, clamped to the end's range).
  void cutDistanceEdited(int row, double distance);
  /// A name was edited (the view's labels follow).
  void endNamesChanged();
  /// The panel was shown or hidden (its tab chosen or left): the view's ends follow.
  void shownChanged(bool shown);

protected:
  void showEvent(QShowEvent* event) override;
  void hideEvent(QHideEvent* event) override;

private:
  /// One row of the ends table.
  struct EndRow
  {
    bender::CenterlineEndPath path; ///< before Prepare
    bender::CfdEnd prepared;        ///< after Prepare
    std::string autoName;           ///< the name shown unless edited
    bool inlet = false;             ///< the row's role (predicted before Prepare)
    double distance = -1.0;         ///< the cut, mm from the end; < 0: not clipped
    double maximumDistance = 0.0;
    bool nameEdited = false;
    bool factorEdited = false;
    bool distanceChosen = false;
  };
  void endEdited(int row, int column);
  void defaultFactorsChanged();
  void fillRow(int row);
  /// Where an end is cut now: its rim's centre after Prepare, the clip plane's centre before.
  std::array<double, 3> rowPosition(const EndRow& row) const;

  ExportOptionsForm* Form;
  QPlainTextEdit* Report;
  std::vector<EndRow> Rows;
  bool BeforePrepare = false;
  bool Filling = false;
};

#endif
