#include "FileOpener.h"

#include "AutosaveController.h"
#include "BendPanel.h"
#include "BenderSession.h"
#include "BenderView.h"
#include "FileIdentity.h"
#include "FileKind.h"
#include "GestureController.h"
#include "MainActions.h"
#include "MeshFormats.h"
#include "SegmentPanel.h"
#include "SegmentationSession.h"
#include "StringUtil.h"
#include "WarpPlanIO.h"
#include "WorkRunner.h"
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

FileOpener::FileOpener(const WindowParts& parts, AutosaveController* recovery)
  : QObject(parts.window)
  , Session(parts.session)
  , Segmentation(parts.segmentation)
  , Worker(parts.worker)
  , Actions(parts.actions)
  , View(parts.view)
  , Gesture(parts.gesture)
  , Bend(parts.bend)
  , Segment(parts.segment)
  , Window(parts.window)
  , Recovery(recovery)
{
  MainActions* actions = parts.actions;
  connect(actions->Open,
    &QAction::triggered,
    this,
    [this]()
    {
      const QString file = QFileDialog::getOpenFileName(
        this->Window, "Open", FileOpener::lastFolder("open"), FileOpener::openFilter());
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
  this->Window->setAcceptDrops(true);
  this->Window->installEventFilter(this);
}

bool FileOpener::openFile(const QString& path)
{
  if (this->Worker->refuseWhenBusy(this->Session))
  {
    return false;
  }
  const std::string file = path.toStdString();
  const bender::FileKind kind = bender::ClassifyFile(file, QFileInfo(path).isDir());
  switch (kind)
  {
    case bender::FileKind::Session:
      // A session file replaces the work as a whole: asked first (a recovery that fails
      // changes nothing: the work stays unsaved and autosaved).
      return this->confirmDiscard("Open " + QFileInfo(path).fileName()) &&
        this->Recovery->recoverSession(path);
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
    const QString text = QString("%1: its %2 are the last ones applied to this surface; "
                                 "replaying it would bend the bent surface again")
                           .arg(QFileInfo(path).fileName())
                           .arg(QString::fromStdString(bender::CountOf(plan.warps.size(), "warp")));
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
    // The warps stay unsaved until what replaces them is in: a replacement that fails
    // leaves them as they were (and a quit without them is the window's to settle).
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

QString FileOpener::openFilter()
{
  QStringList meshes;
  for (const std::string& extension : bender::MeshExtensions(bender::MeshAccess::Read))
  {
    meshes << "*" + QString::fromStdString(extension);
  }
  QStringList filters{ "All supported (" + meshes.join(' ') +
    " *.json *.nrrd *.nhdr *.nii *.nii.gz *.mha *.mhd *.vti *.dcm)" };
  for (const std::string& filter : bender::MeshFormatFilters(bender::MeshAccess::Read))
  {
    filters << QString::fromStdString(filter);
  }
  filters << "DICOM series: pick any file of its folder (*.dcm *)"
          << "All files (*)";
  return filters.join(";;");
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
  auto job = this->Session.BeginLoadSurface(path.toStdString());
  if (!job)
  {
    return false;
  }
  return this->Worker->runReporting(this->Session,
    QString::fromStdString(job->GetTitle()),
    [this, job, path](const bender::ProgressReporter& progress)
    {
      job->Run(progress);
      return WorkRunner::Finisher(
        [this, job, path]()
        {
          // Read first, asked then: a file that cannot be read changes nothing (the warps,
          // their unsaved state, the autosave).
          if (job->GetOutcome() == bender::SessionJob::Outcome::Done &&
            !this->confirmDiscard("Open " + QFileInfo(path).fileName()))
          {
            this->Session.Abandon(*job, "not opened, the work is unchanged");
            return;
          }
          if (!this->Session.Finish(*job))
          {
            return;
          }
          this->Actions->addRecentFile(path);
          // Another file is another patient: a mesh file has no volume behind it, and the
          // ribbon lay on the previous surface.
          this->Segmentation.Clear();
          this->View->ribbonWidget()->Off();
          emit this->volumeChanged();
          this->View->resetCamera();
        });
    });
}

bool FileOpener::isSamePatient(const QString& volumePath) const
{
  return this->Segmentation.HasVolume() &&
    bender::SameFile(this->Segmentation.GetVolumeSource().path, volumePath.toStdString());
}

void FileOpener::closePatient(const std::string& reason)
{
  if (!this->Session.HasSurface())
  {
    return;
  }
  this->Session.Clear(reason);
  // The autosave held the closed work: a crash now must not offer it back with this patient.
  this->Recovery->discardAutosave();
  this->View->ribbonWidget()->Off();
}

bool FileOpener::openVolume(const QString& path)
{
  auto job = this->Segmentation.BeginRead(path.toStdString());
  return this->Worker->runReporting(this->Session,
    "Reading " + QFileInfo(path).fileName(),
    [this, job, path](const bender::ProgressReporter& progress)
    {
      job->Run(progress); // throws when the volume cannot be read: nothing changes
      return WorkRunner::Finisher(
        [this, job, path]()
        {
          // Another volume file is another patient: the surface, its warps, ribbon and
          // centerlines go (asked first when unsaved), once the volume has been read.
          const bool newPatient = this->Session.HasSurface() && !this->isSamePatient(path);
          const std::string name = QFileInfo(path).fileName().toStdString();
          if (newPatient && !this->confirmDiscard("Open " + QFileInfo(path).fileName()))
          {
            this->Session.AddMessage(
              bender::MessageSeverity::Info, name + ": not opened, the work is unchanged");
            return;
          }
          this->Actions->addRecentFile(path);
          this->Segmentation.FinishRead(*job);
          if (newPatient)
          {
            this->closePatient("another patient's volume, " + name + ", was opened");
          }
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
          const std::string warning = job->warning.empty()
            ? std::string()
            : job->warning + " Pick a lower threshold on the histogram and segment again.";
          this->Segment->showWarning(warning);
          if (this->Session.SetSurface(job->surface, "segmented vessel"))
          {
            this->View->resetCamera();
            emit this->panelWanted(this->Bend);
          }
          if (!warning.empty())
          {
            // Back to the Segment panel and its histogram, the warning as the last word.
            this->Session.AddMessage(bender::MessageSeverity::Warning, warning);
            emit this->panelWanted(this->Segment);
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
            this->Gesture->showRibbon(warp.initial, warp.radius, warp.decay, 4.0 / 1.2);
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
