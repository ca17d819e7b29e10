#include "FileOpener.h"

#include "BendPanel.h"
#include "BenderSession.h"
#include "BenderView.h"
#include "FileKind.h"
#include "GestureController.h"
#include "MainActions.h"
#include "MeshIO.h"
#include "SegmentPanel.h"
#include "SegmentationSession.h"
#include "SessionAutosave.h"
#include "VolumeIO.h"
#include "WarpPlanIO.h"
#include "WorkRunner.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QAction>
#include <QDir>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QMessageBox>
#include <QMimeData>
#include <QPushButton>
#include <QSettings>
#include <QUrl>

#include <vtkPolyData.h>

namespace
{
std::string Name(const QString& path)
{
  return QFileInfo(path).fileName().toStdString();
}

// A file of a DICOM series: the .dcm extension or the "DICM" magic after the 128-byte preamble.
bool IsDicomFile(const QString& path)
{
  const QFileInfo info(path);
  if (!info.isFile())
  {
    return false;
  }
  if (info.suffix().compare("dcm", Qt::CaseInsensitive) == 0)
  {
    return true;
  }
  QFile file(path);
  if (!file.open(QIODevice::ReadOnly) || file.size() < 132 || !file.seek(128))
  {
    return false;
  }
  return file.read(4) == "DICM";
}
}

FileOpener::FileOpener(bender::BenderSession& session,
  bender::SegmentationSession& segmentation,
  WorkRunner* worker,
  MainActions* actions,
  BenderView* view,
  GestureController* gesture,
  BendPanel* bend,
  SegmentPanel* segment,
  QWidget* window)
  : QObject(window)
  , Session(session)
  , Segmentation(segmentation)
  , Worker(worker)
  , Actions(actions)
  , View(view)
  , Gesture(gesture)
  , Bend(bend)
  , Segment(segment)
  , Window(window)
{
  // A copy beside the autosave ends on its own thread: the autosave that references it (or
  // says why it could not be written) is made on the GUI thread.
  // Not after the autosave was discarded meanwhile (the work saved): that would bring it back.
  this->Copies = std::make_unique<bender::AutosaveCopies>(
    [this]()
    {
      const int generation = this->CopiesGeneration.load();
      QMetaObject::invokeMethod(
        this,
        [this, generation]()
        {
          if (generation == this->CopiesGeneration.load())
          {
            this->Session.Autosave();
          }
        },
        Qt::QueuedConnection);
    });
  connect(actions->Open,
    &QAction::triggered,
    this,
    [this]()
    {
      const QString file = QFileDialog::getOpenFileName(this->Window,
        "Open",
        FileOpener::lastFolder("open"),
        "All supported (*.stl *.obj *.ply *.vtp *.vtk *.off *.json *.nrrd *.nhdr *.nii *.nii.gz "
        "*.mha *.mhd *.vti *.dcm);;DICOM series: pick any file of its folder (*.dcm *);;All "
        "files (*)");
      if (file.isEmpty())
        return;
      FileOpener::rememberFolder("open", file);
      // A DICOM file stands for its series: the folder is read as one volume.
      this->openFile(IsDicomFile(file) ? QFileInfo(file).absolutePath() : file);
    });
  connect(actions->OpenDicomFolder,
    &QAction::triggered,
    this,
    [this]()
    {
      const QString folder = QFileDialog::getExistingDirectory(
        this->Window, "Open DICOM folder", FileOpener::lastFolder("dicom"));
      if (folder.isEmpty())
        return;
      FileOpener::rememberFolder("dicom", folder);
      this->openDicomFolder(folder);
    });
  connect(actions, &MainActions::recentFileChosen, this, &FileOpener::openFile);
  connect(actions->Demo, &QAction::triggered, this, &FileOpener::startDemo);
  connect(actions->LoadPlan,
    &QAction::triggered,
    this,
    [this]()
    {
      const QString f = QFileDialog::getOpenFileName(
        this->Window, "Load plan", FileOpener::lastFolder("plan"), "Plans (*.bender.json *.json)");
      if (f.isEmpty())
        return;
      FileOpener::rememberFolder("plan", f);
      this->openFile(f);
    });
  connect(actions->Segment, &QAction::triggered, this, &FileOpener::segmentVolume);
  window->setAcceptDrops(true);
  window->installEventFilter(this);
}

bool FileOpener::openFile(const QString& path)
{
  if (this->Worker->refuseWhenBusy(this->Session))
  {
    return false;
  }
  const std::string file = path.toStdString();
  const bender::FileKind kind = bender::ClassifyFile(file, QFileInfo(path).isDir());
  if (kind == bender::FileKind::Plan)
  {
    return this->openPlan(path);
  }
  if (kind != bender::FileKind::Unknown &&
    !this->confirmDiscard("Open " + QFileInfo(path).fileName()))
  {
    return false;
  }
  switch (kind)
  {
    case bender::FileKind::Session:
      return this->recoverSession(path);
    case bender::FileKind::Plan:
      return this->openPlan(path);
    case bender::FileKind::Mesh:
      return this->openMesh(path);
    case bender::FileKind::Volume:
      return this->openVolume(path);
    case bender::FileKind::Unknown:
      break;
  }
  this->Session.AddMessage(
    bender::MessageSeverity::Error, bender::UnknownFileTypeMessage(Name(path)));
  return false;
}

bool FileOpener::openPlan(const QString& path)
{
  const std::string file = path.toStdString();
  bender::WarpPlan plan;
  try
  {
    plan = bender::ReadWarpPlan(file);
  }
  catch (const std::exception& e)
  {
    this->Session.AddMessage(bender::MessageSeverity::Error, e.what());
    return false;
  }
  if (this->Session.IsPlanApplied(plan))
  {
    const QString text = QString("%1: its %2 warps are the last ones applied to this surface; "
                                 "replaying it would bend the bent surface again")
                           .arg(QFileInfo(path).fileName())
                           .arg(plan.warps.size());
    if (!this->Interactive)
    {
      this->Session.AddMessage(
        bender::MessageSeverity::Warning, text.toStdString() + ": not applied again");
      return false;
    }
    if (QMessageBox::question(this->Window,
          "Plan already applied",
          text + ".\nApply it once more?",
          QMessageBox::Yes | QMessageBox::No,
          QMessageBox::No) != QMessageBox::Yes)
    {
      this->Session.AddMessage(
        bender::MessageSeverity::Info, text.toStdString() + ": not applied again");
      return false;
    }
  }
  return this->Worker->runSessionJob(this->Session,
    this->Session.BeginReplay(plan, Name(path)),
    [this, path](bender::SessionJob&, bool ok)
    {
      if (ok)
      {
        this->Actions->addRecentFile(path);
        this->Gesture->showSessionRibbon();
      }
    });
}

bool FileOpener::confirmDiscard(const QString& what)
{
  if (!this->Interactive || !this->Session.HasUnsavedChanges())
  {
    return true;
  }
  QMessageBox box(QMessageBox::Question,
    "Save changes?",
    QString("The surface has warps that are not saved in a plan (%1 committed)%2.\n%3 replaces "
            "them: save the plan first?")
      .arg(this->Session.GetHistoryPosition())
      .arg(this->Session.GetState() == bender::GrabState::Grabbed ? ", and a bend under way" : "")
      .arg(what),
    QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel,
    this->Window);
  box.setObjectName("saveChanges");
  box.button(QMessageBox::Save)->setText("Save plan...");
  box.setDefaultButton(QMessageBox::Save);
  const int answer = box.exec();
  if (answer == QMessageBox::Discard)
  {
    if (this->Session.GetState() == bender::GrabState::Grabbed)
    {
      this->Session.CancelGrab("discarded");
    }
    this->Session.MarkSaved(); // explicitly discarded: nothing left to keep
    return true;
  }
  if (answer != QMessageBox::Save)
  {
    return false;
  }
  const QString file = QFileDialog::getSaveFileName(this->Window,
    "Save plan",
    FileOpener::lastFolder("plan") + "/plan.bender.json",
    "Plans (*.bender.json)");
  if (file.isEmpty())
  {
    return false;
  }
  FileOpener::rememberFolder("plan", file);
  return this->Session.SavePlan(file.toStdString());
}

QString FileOpener::lastFolder(const QString& kind)
{
  const QString folder = QSettings().value("folders/" + kind).toString();
  return !folder.isEmpty() && QFileInfo(folder).isDir() ? folder : QDir::homePath();
}

void FileOpener::rememberFolder(const QString& kind, const QString& path)
{
  const QFileInfo info(path);
  QSettings().setValue(
    "folders/" + kind, info.isDir() ? info.absoluteFilePath() : info.absolutePath());
}

bool FileOpener::openMesh(const QString& path)
{
  this->Actions->addRecentFile(path);
  return this->Worker->runReporting(this->Session,
    "Reading " + QFileInfo(path).fileName(),
    [this, path](const bender::ProgressReporter&)
    {
      vtkSmartPointer<vtkPolyData> mesh = bender::ReadMesh(path.toStdString());
      return WorkRunner::Finisher(
        [this, mesh, path]()
        {
          if (this->Session.SetSurface(
                mesh, Name(path), QFileInfo(path).absoluteFilePath().toStdString()))
          {
            // A mesh file has no volume behind it.
            this->Segmentation.Clear();
            emit this->volumeChanged();
            this->View->resetCamera();
          }
        });
    });
}

bool FileOpener::openVolume(const QString& path)
{
  this->Actions->addRecentFile(path);
  auto job = this->Segmentation.BeginRead(path.toStdString());
  return this->Worker->runReporting(this->Session,
    "Reading " + QFileInfo(path).fileName(),
    [this, job, path](const bender::ProgressReporter& progress)
    {
      job->Run(progress);
      return WorkRunner::Finisher(
        [this, job, path]()
        {
          this->Segmentation.FinishRead(*job);
          emit this->volumeChanged();
          emit this->panelWanted(this->Segment);
          const auto& size = job->volume->geometry.size;
          const QString loaded = QString("Loaded volume %1: %2x%3x%4; segment it in the Segment "
                                         "panel")
                                   .arg(QString::fromStdString(this->Segmentation.GetVolumeName()))
                                   .arg(size[0])
                                   .arg(size[1])
                                   .arg(size[2]);
          // A folder of several series: which one was read is the last word.
          this->Session.AddMessage(bender::MessageSeverity::Info, loaded.toStdString());
          if (!job->note.empty())
          {
            this->Session.AddMessage(bender::MessageSeverity::Warning, job->note);
          }
          this->Session.Autosave(); // the volume is kept with the work (no-op without a surface)
        });
    });
}

bool FileOpener::segmentVolume()
{
  std::string problem;
  if (this->Worker->refuseWhenBusy(this->Session) || !this->confirmDiscard("Segmenting") ||
    !this->Segmentation.SetSettings(this->Segment->settings(), problem))
  {
    if (!problem.empty())
      this->Session.AddMessage(bender::MessageSeverity::Error, "Segment: " + problem);
    return false;
  }
  auto job = this->Segmentation.BeginSegment(problem);
  if (!job)
  {
    this->Session.AddMessage(bender::MessageSeverity::Error, problem);
    return false;
  }
  return this->Worker->runReporting(this->Session,
    "Segmenting",
    [this, job](const bender::ProgressReporter& progress)
    {
      job->Run(progress);
      return WorkRunner::Finisher(
        [this, job]()
        {
          this->Segmentation.FinishSegment(*job);
          emit this->volumeChanged();
          if (this->Session.SetSurface(job->surface, "segmented vessel"))
          {
            this->View->resetCamera();
            emit this->panelWanted(this->Bend);
          }
        });
    });
}

void FileOpener::startDemo()
{
  if (this->Worker->refuseWhenBusy(this->Session) || !this->confirmDiscard("The demo"))
  {
    return;
  }
  auto job = std::make_shared<bender::SegmentationSession::DemoJob>();
  this->Worker->runReporting(this->Session,
    "Demo",
    [this, job](const bender::ProgressReporter& progress)
    {
      job->Run(progress);
      return WorkRunner::Finisher(
        [this, job]()
        {
          if (!job->fallback.empty())
          {
            this->Session.AddMessage(bender::MessageSeverity::Warning,
              "Demo: segmentation unavailable (" + job->fallback + "); using the vessel surface");
          }
          this->Segmentation.FinishDemo(*job);
          emit this->volumeChanged();
          if (!this->Session.SetSurface(
                job->surface, job->fallback.empty() ? "demo vessel (segmented)" : "demo vessel"))
          {
            return;
          }
          if (!job->plan.warps.empty())
          {
            // The ribbon and parameters of the demo plan's first warp, ready to grab; handles
            // sized for the demo's branches (about 3.3 mm).
            const bender::WarpSpec& warp = job->plan.warps.front();
            bender::WarpParameters parameters = this->Bend->parameters();
            parameters.radius = warp.radius;
            parameters.decay = warp.decay;
            this->Bend->setParameters(parameters);
            this->Gesture->applyParameters();
            this->Gesture->showRibbon(warp.initial, 4.0 / 1.2);
          }
          this->View->resetCamera();
          emit this->panelWanted(this->Bend);
          this->Session.AddMessage(bender::MessageSeverity::Info,
            (job->fallback.empty() ? job->summary + ". " : std::string()) +
              "Ribbon placed on a branch: press G (or hold Space), drag the end handles, press G "
              "to release");
        });
    });
}

void FileOpener::offerRecovery()
{
  const QString path = QString::fromStdString(this->Session.GetAutosavePath());
  // What the autosave holds, in the question; an unreadable one is said and kept for a look.
  QStringList parts;
  try
  {
    const bender::SessionSnapshot snapshot = bender::ReadSessionFile(path.toStdString());
    const std::string surface = snapshot.surfaceName.empty()
      ? QFileInfo(QString::fromStdString(snapshot.sourcePath)).fileName().toStdString()
      : snapshot.surfaceName;
    parts << QString("the surface \"%1\"").arg(QString::fromStdString(surface));
    parts << QString("%1 warp%2")
               .arg(snapshot.plan.warps.size())
               .arg(snapshot.plan.warps.size() == 1 ? "" : "s");
    if (snapshot.volume)
    {
      parts << QString("the volume \"%1\" (%2)")
                 .arg(QString::fromStdString(snapshot.volume->name))
                 .arg(QString::fromStdString(
                   bender::DescribeVolumeGeometry(snapshot.volume->geometry)));
    }
    if (snapshot.segmentation)
    {
      parts << QString("the Segment panel's parameters (threshold %1, smoothing %2)")
                 .arg(snapshot.segmentation->segmentation.lower, 0, 'g', 6)
                 .arg(snapshot.segmentation->surface.smoothing, 0, 'g', 3);
    }
    if (snapshot.ribbon)
    {
      parts << QString("the ribbon (R = %1 mm)").arg(snapshot.ribbon->radius, 0, 'g', 4);
    }
  }
  catch (const std::exception& e)
  {
    this->Session.AddMessage(bender::MessageSeverity::Error,
      std::string("The autosave of the last session cannot be recovered: ") + e.what());
    return;
  }
  QMessageBox box(QMessageBox::Question,
    "Recover the last session?",
    "Bender did not close cleanly last time. Recover that session?",
    QMessageBox::Yes | QMessageBox::No,
    this->Window);
  box.setObjectName("recoverSession");
  box.setInformativeText("It holds:\n\u2022 " + parts.join("\n\u2022 "));
  box.button(QMessageBox::Yes)->setText("Recover");
  box.button(QMessageBox::No)->setText("Discard");
  box.setDefaultButton(QMessageBox::Yes);
  if (box.exec() == QMessageBox::Yes)
  {
    this->recoverSession(path);
  }
  else
  {
    this->discardAutosave();
  }
}

FileOpener::~FileOpener()
{
  this->Copies->Wait();
}

void FileOpener::waitForAutosaveCopies()
{
  this->Copies->Wait();
}

void FileOpener::discardAutosave()
{
  // A copy being written would land after its removal: it ends first.
  this->Copies->Forget();
  ++this->CopiesGeneration;
  this->Session.DiscardAutosave();
  bender::RemoveSessionSideFiles(this->Session.GetAutosavePath());
}

bool FileOpener::recoverSession(const QString& path)
{
  if (this->Worker->refuseWhenBusy(this->Session))
  {
    return false;
  }
  const std::string file = path.toStdString();
  auto snapshot = std::make_shared<bender::SessionSnapshot>();
  try
  {
    *snapshot = bender::ReadSessionFile(file);
  }
  catch (const std::exception& e)
  {
    this->Session.AddMessage(
      bender::MessageSeverity::Error, std::string("Recovery failed: ") + e.what());
    return false;
  }
  std::shared_ptr<bender::SegmentationSession::ReadJob> read;
  if (snapshot->volume)
  {
    read = this->Segmentation.BeginRead(snapshot->volume->path, snapshot->volume->dicomSeriesUid);
    read->maskPath = snapshot->volume->maskPath;
  }
  std::shared_ptr<bender::SessionJob> recover = this->Session.BeginRecover(file);
  if (!recover)
  {
    return false;
  }
  const bool started = this->Worker->runReporting(this->Session,
    "Recovering the session",
    [this, snapshot, read, recover](const bender::ProgressReporter& progress)
    {
      // The volume first: it is in place when the recovered session autosaves.
      auto problem = std::make_shared<std::string>();
      if (read)
      {
        try
        {
          read->Run(progress);
        }
        catch (const std::exception& e)
        {
          // A cancel here cancels the recovery below too (the same flag).
          *problem = e.what();
        }
      }
      recover->Run(progress); // never throws
      return WorkRunner::Finisher([this, snapshot, read, recover, problem]()
        { this->finishRecovery(*snapshot, read.get(), *problem, *recover); });
    });
  if (!started)
  {
    // Not run: the session must not stay busy with a job that never comes back.
    this->Session.Finish(*recover);
  }
  return started;
}
void FileOpener::finishRecovery(const bender::SessionSnapshot& snapshot,
  const bender::SegmentationSession::ReadJob* read,
  const std::string& volumeProblem,
  bender::SessionJob& recover)
{
  const bool cancelled = recover.GetOutcome() == bender::SessionJob::Outcome::Cancelled;
  std::string volumeNote;
  bool volumeLoaded = false;
  if (read && !cancelled)
  {
    const std::string name = snapshot.volume->name.empty()
      ? QFileInfo(QString::fromStdString(snapshot.volume->path)).fileName().toStdString()
      : snapshot.volume->name;
    if (!read->volume)
    {
      volumeNote = "the volume " + name + " could not be read (" + volumeProblem + ")";
    }
    else if (!bender::SameVolumeGeometry(read->volume->geometry, snapshot.volume->geometry))
    {
      volumeNote = "the volume " + name + " was not loaded: " + snapshot.volume->path +
        " now holds " + bender::DescribeVolumeGeometry(read->volume->geometry) +
        ", the session's was " + bender::DescribeVolumeGeometry(snapshot.volume->geometry);
    }
    else
    {
      this->Segmentation.FinishRead(*read, name);
      volumeLoaded = true;
      emit this->volumeChanged();
      if (!read->maskProblem.empty())
      {
        volumeNote = "the segmentation overlay could not be read (" + read->maskProblem + ")";
      }
    }
  }
  if (snapshot.segmentation && !cancelled)
  {
    std::string problem;
    // The panel shows them; the session takes them when they are valid (always, for a file
    // that ReadSessionFile accepted).
    this->Segment->setSettings(*snapshot.segmentation);
    this->Segmentation.SetSettings(*snapshot.segmentation, problem);
  }
  // The surface and the warps (the session says how that went); it autosaves with the above.
  if (!this->Session.Finish(recover))
  {
    this->Worker->markFailed();
    return;
  }
  if (snapshot.ribbon)
  {
    bender::WarpParameters parameters = this->Bend->parameters();
    parameters.radius = snapshot.ribbon->radius;
    parameters.decay = snapshot.ribbon->decay;
    this->Bend->setParameters(parameters);
    this->Gesture->applyParameters();
    if (snapshot.ribbon->vesselRadius > 0.0)
    {
      this->Gesture->showRibbon(snapshot.ribbon->ribbon, snapshot.ribbon->vesselRadius);
    }
    else
    {
      this->Gesture->setRibbon(snapshot.ribbon->ribbon);
      this->View->ribbonWidget()->On();
    }
  }
  this->View->resetCamera();
  emit this->panelWanted(this->Bend);
  const std::size_t warps = snapshot.plan.warps.size();
  std::string text = "Recovered the surface " +
    (this->Session.GetSurfaceName().empty() ? std::string()
                                            : "\"" + this->Session.GetSurfaceName() + "\"") +
    ", " + std::to_string(warps) + (warps == 1 ? " warp" : " warps");
  if (volumeLoaded)
  {
    text += ", the volume \"" + this->Segmentation.GetVolumeName() + "\"";
    if (this->Segmentation.GetMask())
    {
      text += " with its segmentation";
    }
  }
  if (snapshot.segmentation)
  {
    text += ", the Segment panel's parameters";
  }
  if (snapshot.ribbon)
  {
    text += ", the ribbon";
  }
  if (volumeNote.empty())
  {
    this->Session.AddMessage(bender::MessageSeverity::Info, text);
  }
  else
  {
    // One message: what is missing, and that the rest is back.
    this->Session.AddMessage(
      bender::MessageSeverity::Warning, "Recovery: " + volumeNote + ". " + text);
  }
}

void FileOpener::fillSnapshot(bender::SessionSnapshot& snapshot)
{
  const auto& volume = this->Segmentation.GetVolume();
  if (volume)
  {
    bender::SessionVolume kept;
    kept.name = this->Segmentation.GetVolumeName();
    kept.path = this->Segmentation.GetVolumeSource().path;
    kept.dicomSeriesUid = this->Segmentation.GetVolumeSource().dicomSeriesUid;
    kept.geometry = volume->geometry;
    if (kept.path.empty() && !this->Session.GetAutosavePath().empty())
    {
      // Made here (the demo): written once beside the autosave, off the GUI thread; until
      // the copy is complete this autosave leaves the volume out (the next one, when it is,
      // keeps it).
      std::string problem;
      kept.path = this->Copies->CopyOf(
        volume,
        bender::SessionVolumeCopyPath(this->Session.GetAutosavePath()),
        [volume, hook = this->CopyHook](const std::string& path)
        {
          if (hook)
          {
            hook();
          }
          bender::WriteVolume(*volume, path);
        },
        problem);
      if (!problem.empty())
      {
        this->Session.AddMessage(
          bender::MessageSeverity::Warning, "Autosave: the volume is not kept (" + problem + ")");
      }
    }
    // The segmentation's mask (the slice views' overlay): written once per mask.
    const auto& mask = this->Segmentation.GetMask();
    if (!kept.path.empty() && mask && !this->Session.GetAutosavePath().empty())
    {
      std::string problem;
      kept.maskPath = this->Copies->CopyOf(
        mask,
        bender::SessionMaskCopyPath(this->Session.GetAutosavePath()),
        [mask, hook = this->CopyHook](const std::string& path)
        {
          if (hook)
          {
            hook();
          }
          bender::WriteLabelMap(*mask, path);
        },
        problem);
      if (!problem.empty())
      {
        this->Session.AddMessage(bender::MessageSeverity::Warning,
          "Autosave: the segmentation's mask is not kept (" + problem + ")");
      }
    }
    if (!kept.path.empty())
    {
      snapshot.volume = kept;
    }
  }
  // The parameters the Segment panel shows (those of the last segmentation, or the user's
  // since): the panel shows them again after a recovery.
  snapshot.segmentation = this->Segment->settings();
  const auto& ribbon = this->Session.GetRibbon();
  if (ribbon)
  {
    bender::SessionRibbon placed;
    placed.ribbon = *ribbon;
    placed.radius = this->Session.GetParameters().radius;
    placed.decay = this->Session.GetParameters().decay;
    // GestureController::showRibbon's handles: 1.2 vessel radii long.
    placed.vesselRadius =
      this->View->ribbonWidget()->GetRibbonRepresentation()->GetHandleLength() / 1.2;
    snapshot.ribbon = placed;
  }
}

bool FileOpener::openDicomFolder(const QString& folder)
{
  if (!QFileInfo(folder).isDir())
  {
    this->Session.AddMessage(bender::MessageSeverity::Error,
      Name(folder) + ": not a folder (Open DICOM folder takes the folder of a series)");
    return false;
  }
  return this->openFile(folder);
}

bool FileOpener::eventFilter(QObject* watched, QEvent* event)
{
  if (watched == this->Window && event->type() == QEvent::DragEnter)
  {
    auto* enter = static_cast<QDragEnterEvent*>(event);
    if (enter->mimeData()->hasUrls())
    {
      enter->acceptProposedAction();
      return true;
    }
  }
  else if (watched == this->Window && event->type() == QEvent::Drop)
  {
    auto* drop = static_cast<QDropEvent*>(event);
    for (const QUrl& url : drop->mimeData()->urls())
    {
      if (url.isLocalFile())
      {
        this->openFile(url.toLocalFile());
        // One file at a time: the worker takes one task.
        break;
      }
    }
    drop->acceptProposedAction();
    return true;
  }
  return QObject::eventFilter(watched, event);
}
