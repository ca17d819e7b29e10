#include "AutosaveController.h"

#include "BendPanel.h"
#include "BenderSession.h"
#include "BenderView.h"
#include "GestureController.h"
#include "SegmentPanel.h"
#include "SessionAutosave.h"
#include "StringUtil.h"
#include "VolumeIO.h"
#include "WorkRunner.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QDir>
#include <QFileInfo>
#include <QMessageBox>
#include <QPushButton>
#include <QStandardPaths>
#include <QTimer>

AutosaveController::AutosaveController(const WindowParts& parts)
  : QObject(parts.window)
  , Session(parts.session)
  , Segmentation(parts.segmentation)
  , Worker(parts.worker)
  , View(parts.view)
  , Gesture(parts.gesture)
  , Bend(parts.bend)
  , Segment(parts.segment)
  , Window(parts.window)
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
}

AutosaveController::~AutosaveController()
{
  this->Copies->Wait();
}

void AutosaveController::startAutosave(const QString& path, bool offerRecovery)
{
  // Every autosave also keeps the volume, the segmentation parameters and the ribbon.
  this->Session.SetAutosaveDecorator(
    [this](bender::SessionSnapshot& snapshot) { this->fillSnapshot(snapshot); });
  QString autosave = path;
  if (autosave.isEmpty())
  {
    const QString folder = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation);
    QDir().mkpath(folder);
    autosave = folder + "/autosave.bender-session.json";
  }
  this->Session.SetAutosavePath(autosave.toStdString());
  if (offerRecovery && QFileInfo::exists(autosave))
  {
    QTimer::singleShot(0, this, &AutosaveController::offerRecovery);
  }
}

void AutosaveController::offerRecovery()
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
    parts << QString::fromStdString(bender::CountOf(snapshot.plan.warps.size(), "warp"));
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

void AutosaveController::waitForAutosaveCopies()
{
  this->Copies->Wait();
}

void AutosaveController::discardAutosave()
{
  // A copy being written would land after its removal: it ends first.
  this->Copies->Forget();
  ++this->CopiesGeneration;
  this->Session.DiscardAutosave();
  bender::RemoveSessionSideFiles(this->Session.GetAutosavePath());
}

bool AutosaveController::recoverSession(const QString& path)
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

void AutosaveController::finishRecovery(const bender::SessionSnapshot& snapshot,
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
    const bender::SessionRibbon& kept = *snapshot.ribbon;
    this->Gesture->showRibbon(kept.ribbon, kept.radius, kept.decay, kept.vesselRadius);
  }
  this->View->resetCamera();
  emit this->panelWanted(this->Bend);
  std::string text = "Recovered the surface " +
    (this->Session.GetSurfaceName().empty() ? std::string()
                                            : "\"" + this->Session.GetSurfaceName() + "\"") +
    ", " + bender::CountOf(snapshot.plan.warps.size(), "warp");
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

void AutosaveController::fillSnapshot(bender::SessionSnapshot& snapshot)
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
      kept.path = this->keepCopy(
        volume,
        bender::SessionVolumeCopyPath(this->Session.GetAutosavePath()),
        [volume](const std::string& path) { bender::WriteVolume(*volume, path); },
        "the volume");
    }
    // The segmentation's mask (the slice views' overlay): written once per mask.
    const auto& mask = this->Segmentation.GetMask();
    if (!kept.path.empty() && mask && !this->Session.GetAutosavePath().empty())
    {
      kept.maskPath = this->keepCopy(
        mask,
        bender::SessionMaskCopyPath(this->Session.GetAutosavePath()),
        [mask](const std::string& path) { bender::WriteLabelMap(*mask, path); },
        "the segmentation's mask");
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

std::string AutosaveController::keepCopy(const std::shared_ptr<const void>& object,
  const std::string& path,
  const std::function<void(const std::string&)>& write,
  const std::string& what)
{
  std::string problem;
  const std::string kept = this->Copies->CopyOf(
    object,
    path,
    [write, hook = this->CopyHook](const std::string& to)
    {
      if (hook)
      {
        hook();
      }
      write(to);
    },
    problem);
  if (!problem.empty())
  {
    this->Session.AddMessage(
      bender::MessageSeverity::Warning, "Autosave: " + what + " is not kept (" + problem + ")");
  }
  return kept;
}
