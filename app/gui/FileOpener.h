#ifndef FileOpener_h
#define FileOpener_h

#include "WindowParts.h"

#include <QObject>
#include <QString>

#include <string>

class AutosaveController;

/// Brings data into a window: File > Open, Open Recent, Load plan, the demo, a volume's
/// segmentation and files dropped on the window. The kind of a file is bender::ClassifyFile's
/// (Logic); reading (a session job for a mesh), segmenting and replaying run on the window's
/// worker and their results go into the sessions on the GUI thread; a session file is
/// recovered by the AutosaveController.
///
/// No lost work: Open (a mesh, a volume, a session), Demo and segmenting again ask "Save
/// changes?" (Save plan / Discard / Cancel) while the session has unsaved warps
/// (BenderSession::HasUnsavedChanges). A mesh or a volume is read first and the question comes
/// once it has been read: a file that cannot be read changes nothing (the warps, their unsaved
/// state, the autosave). Another file is another patient: a mesh replaces the surface and drops
/// the volume; a volume other than the loaded one's file closes the surface with its history,
/// ribbon and centerlines (and the autosave that held them). A plan whose warps are already the
/// last ones committed
/// is not replayed again without asking (refused with a message when not interactive). The
/// file dialogs start in the folder used last (QSettings "folders/<kind>"); File > Open takes a
/// DICOM series by any file of its folder, File > Open DICOM folder by the folder (several
/// series: the largest, and the status bar says which).
class FileOpener : public QObject
{
  Q_OBJECT
public:
  /// `recovery` opens session files.
  FileOpener(const WindowParts& parts, AutosaveController* recovery);

  /// Opens a file by its kind (see MainWindow::openFile); false when refused at once.
  bool openFile(const QString& path);
  void startDemo();
  bool segmentVolume();
  /// Opens the DICOM series of `folder` (File > Open DICOM folder, after its dialog).
  bool openDicomFolder(const QString& folder);
  /// Dialogs may be shown (the window's MainWindowOptions::interactive); without, nothing is
  /// asked: unsaved work is replaced as before and a plan applied twice is refused.
  void setInteractive(bool interactive) { this->Interactive = interactive; }
  bool isInteractive() const { return this->Interactive; }
  /// Before `what` (Open, Demo, Quit, ...) replaces the work: true to go on. With unsaved
  /// warps and interactive, asks Save plan (then goes on when saved) / Discard / Cancel. The
  /// answer changes nothing else: the warps stay unsaved (and autosaved) until what replaces
  /// them is in, so that a replacement that fails loses nothing.
  bool confirmDiscard(const QString& what);
  /// The Open dialog's filters: all supported files (every readable mesh format of
  /// bender::MeshFormats, plans, sessions, volumes, DICOM), then each mesh format, DICOM, all.
  static QString openFilter();
  /// The folder a file dialog of `kind` ("open", "plan", "recording", ...) starts in: the one
  /// used last, else the home folder; rememberFolder stores the folder of `path`.
  static QString lastFolder(const QString& kind);
  static void rememberFolder(const QString& kind, const QString& path);

signals:
  /// The volume or its mask changed (the slice views follow).
  void volumeChanged();
  /// The panel the user goes on with.
  void panelWanted(QWidget* panel);

protected:
  /// Drag and drop on the window: the first local file dropped is opened.
  bool eventFilter(QObject* watched, QEvent* event) override;

private:
  bool openMesh(const QString& path);
  bool openVolume(const QString& path);
  bool openPlan(const QString& path);
  /// True when `volumePath` is the file of the volume loaded (the surface is that patient's).
  bool isSamePatient(const QString& volumePath) const;
  /// Another patient: the surface goes with its history, ribbon and autosave (`reason` said).
  void closePatient(const std::string& reason);

  bender::BenderSession& Session;
  bender::SegmentationSession& Segmentation;
  WorkRunner* Worker;
  MainActions* Actions;
  BenderView* View;
  GestureController* Gesture;
  BendPanel* Bend;
  SegmentPanel* Segment;
  QWidget* Window;
  AutosaveController* Recovery;
  bool Interactive = false;
};

#endif
