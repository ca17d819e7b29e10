#include "SweepControls.h"

#include "SweepWindow.h"
#include "WorkRunner.h"

#include "BenderErrors.h"
#include "BenderSession.h"
#include "PolyDataCopy.h"
#include "SweepStudy.h"

#include <QApplication>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPointer>
#include <QPushButton>
#include <QSpinBox>

#include <memory>
#include <thread>

namespace
{
QDoubleSpinBox* FractionBox(QWidget* parent, const char* name, double value)
{
  auto* box = new QDoubleSpinBox(parent);
  box->setObjectName(name);
  box->setRange(-2.0, 4.0); // RunSweep's fractions
  box->setDecimals(2);
  box->setSingleStep(0.25);
  box->setValue(value);
  return box;
}
} // namespace

SweepControls::SweepControls(bender::BenderSession& session,
  WorkRunner* worker,
  std::function<bender::CfdCaseOptions()> caseOptions,
  QWidget* parent)
  : QGroupBox("Sweep (what if the bend went less or further)", parent)
  , Session(session)
  , Worker(worker)
  , CaseOptions(std::move(caseOptions))
{
  this->setObjectName("sweepControls");
  auto* form = new QFormLayout(this);
  auto* folderRow = new QHBoxLayout;
  this->Folder = new QLineEdit(this);
  this->Folder->setObjectName("sweepFolder");
  this->Folder->setPlaceholderText("a sweep folder (bender-cli sweep -o), or an empty one");
  this->Folder->setToolTip("Open reads a sweep made here or on a cluster; Sweep runs into it "
                           "(a sweep run again keeps what is finished with the same inputs)");
  folderRow->addWidget(this->Folder, 1);
  auto* browse = new QPushButton("...", this);
  browse->setObjectName("sweepBrowse");
  browse->setToolTip("Choose the sweep folder");
  folderRow->addWidget(browse);
  form->addRow("Folder", folderRow);

  auto* range = new QHBoxLayout;
  this->From = FractionBox(this, "sweepFrom", 0.0);
  this->To = FractionBox(this, "sweepTo", 1.5);
  this->Count = new QSpinBox(this);
  this->Count->setObjectName("sweepCount");
  this->Count->setRange(2, 50);
  this->Count->setValue(7);
  this->Count->setToolTip("Candidates, evenly spaced from From to To (both included); fraction "
                          "0 is the original, 1 the bend as it is");
  range->addWidget(this->From);
  range->addWidget(new QLabel("to", this));
  range->addWidget(this->To);
  range->addWidget(new QLabel("in", this));
  range->addWidget(this->Count);
  form->addRow("Fraction", range);
  this->Jobs = new QSpinBox(this);
  this->Jobs->setObjectName("sweepJobs");
  this->Jobs->setRange(1, std::max(1, static_cast<int>(std::thread::hardware_concurrency())));
  this->Jobs->setToolTip("Cases solved at a time on this machine");
  form->addRow("Jobs", this->Jobs);

  auto* buttons = new QHBoxLayout;
  this->Open = new QPushButton("Open", this);
  this->Open->setObjectName("openSweep");
  this->Open->setToolTip("Show the folder's sweep: its plot, its table, a candidate beside the "
                         "original");
  this->Start = new QPushButton("Sweep the bend", this);
  this->Start->setObjectName("startSweep");
  this->Start->setToolTip("Solve the current bend at each fraction on this machine (the case "
                          "settings above), as a job");
  this->CancelButton = new QPushButton("Cancel", this);
  this->CancelButton->setObjectName("cancelSweep");
  this->CancelButton->setEnabled(false);
  buttons->addWidget(this->Open);
  buttons->addWidget(this->Start);
  buttons->addWidget(this->CancelButton);
  form->addRow(buttons);
  this->Status = new QLabel(this);
  this->Status->setObjectName("sweepStatus");
  this->Status->setWordWrap(true);
  form->addRow(this->Status);

  this->Window = new SweepWindow(this);

  connect(browse,
    &QPushButton::clicked,
    this,
    [this]()
    {
      const QString folder =
        QFileDialog::getExistingDirectory(this, "Sweep folder", this->Folder->text());
      if (!folder.isEmpty())
      {
        this->Folder->setText(folder);
      }
    });
  connect(this->Open, &QPushButton::clicked, this, &SweepControls::openSweep);
  connect(this->Start, &QPushButton::clicked, this, &SweepControls::startSweep);
  connect(this->CancelButton, &QPushButton::clicked, this, &SweepControls::cancel);
  // A sweep job that failed or was cancelled (the worker said why in the status bar).
  connect(this->Worker,
    &WorkRunner::finished,
    this,
    [this](bool ok)
    {
      if (!ok && this->Running)
      {
        this->done(false, "Sweep stopped: cancelled or failed (see the status bar).");
      }
    });
}

SweepControls::~SweepControls() = default;

void SweepControls::setViewRenderer(vtkRenderer* renderer)
{
  this->Window->setViewRenderer(renderer);
}

void SweepControls::setStatus(const QString& text)
{
  this->Status->setText(text);
  this->Status->setToolTip(text);
}

bool SweepControls::show(const QString& folder)
{
  bender::SweepFolder sweep;
  try
  {
    sweep = bender::ReadSweepFolder(folder.toStdString());
  }
  catch (const bender::InputError& e)
  {
    this->setStatus(QString("Sweep: %1").arg(e.what()));
    return false;
  }
  this->Window->setSweep(sweep);
  this->Window->show();
  this->Window->raise();
  return true;
}

bool SweepControls::openSweep()
{
  const QString folder = this->Folder->text().trimmed();
  if (folder.isEmpty())
  {
    this->setStatus("Sweep: type or choose a sweep folder first.");
    return false;
  }
  if (!this->show(folder))
  {
    return false;
  }
  std::size_t solved = 0;
  for (const bender::SweepRow& row : this->Window->sweep().rows)
  {
    solved += row.state == "solved" ? 1 : 0;
  }
  this->setStatus(QString("Sweep: %1 of %2 candidates solved.")
                    .arg(solved)
                    .arg(this->Window->sweep().rows.size()));
  return true;
}

bool SweepControls::startSweep()
{
  const QString folder = this->Folder->text().trimmed();
  if (this->Running)
  {
    this->setStatus("Sweep: one is under way (Cancel stops it).");
    return false;
  }
  if (folder.isEmpty())
  {
    this->setStatus("Sweep: type or choose a folder for the sweep first.");
    return false;
  }
  if (!this->Session.HasSurface() || this->Session.GetPlan().warps.empty())
  {
    this->setStatus("Sweep: bend the vessel first (the sweep varies the bend).");
    return false;
  }
  if (this->Session.GetState() == bender::GrabState::Grabbed)
  {
    this->setStatus("Sweep: release the bend first.");
    return false;
  }
  if (this->Worker->refuseWhenBusy(this->Session))
  {
    this->setStatus("Sweep: wait for the current task or cancel it.");
    return false;
  }
  auto input = std::make_shared<bender::SessionSweepInput>();
  input->first = bender::DeepCopyOf(this->Session.GetFirstSurface());
  input->plan = this->Session.GetPlan();
  if (!this->Session.GetSurfaceName().empty())
  {
    input->name = this->Session.GetSurfaceName();
  }
  bender::SessionSweepOptions options;
  options.folder = QDir(folder).absolutePath().toStdString();
  options.vary.parameter = bender::SweepParameter::Fraction;
  options.vary.from = this->From->value();
  options.vary.to = this->To->value();
  options.vary.count = this->Count->value();
  options.caseOptions = this->CaseOptions();
  options.jobs = this->Jobs->value();
  QPointer<SweepControls> self(this);
  options.onLine = [self](const std::string& line)
  {
    QMetaObject::invokeMethod(
      qApp,
      [self, line]()
      {
        if (self && self->Running)
        {
          self->setStatus("Sweep: " + QString::fromStdString(line));
        }
      },
      Qt::QueuedConnection);
  };
  this->Running = true;
  this->Start->setEnabled(false);
  this->Open->setEnabled(false);
  this->CancelButton->setEnabled(true);
  this->setStatus("Sweep: preparing the candidates...");
  const bool started = this->Worker->run("Sweep of the bend",
    [self, input, options](const bender::ProgressReporter& progress) -> WorkRunner::Finisher
    {
      bender::SessionSweepOptions run = options;
      run.progress = progress;
      try
      {
        const bender::SweepResult result = bender::RunSessionSweep(*input, run);
        std::size_t solved = 0;
        for (const bender::SweepRow& row : result.rows)
        {
          solved += row.state == "solved" ? 1 : 0;
        }
        const QString line =
          QString("Sweep done: %1 of %2 candidates solved (%3 this time, %4 kept).")
            .arg(solved)
            .arg(result.rows.size())
            .arg(result.solved)
            .arg(result.kept);
        return [self, line]()
        {
          if (self)
          {
            self->done(true, line);
          }
        };
      }
      catch (const bender::Cancelled&)
      {
        throw; // the worker says so
      }
      catch (const bender::Error& e)
      {
        const QString what = QString("Sweep failed: %1").arg(e.what());
        return [self, what]()
        {
          if (self)
          {
            self->Session.AddMessage(bender::MessageSeverity::Error, what.toStdString());
            self->Worker->markFailed();
            self->done(false, what);
          }
        };
      }
    });
  if (!started)
  {
    this->done(false, "Sweep: the worker is busy; nothing was run.");
  }
  return this->Running;
}

void SweepControls::cancel()
{
  if (this->Running)
  {
    this->Worker->cancel();
    this->setStatus("Sweep: cancelling...");
  }
}

void SweepControls::done(bool ok, const QString& why)
{
  if (!this->Running)
  {
    return;
  }
  this->Running = false;
  this->Start->setEnabled(true);
  this->Open->setEnabled(true);
  this->CancelButton->setEnabled(false);
  // What the sweep left (all of it, or what was finished before it stopped).
  const QString folder = this->Folder->text().trimmed();
  QString line = why;
  if (QFileInfo::exists(QDir(folder).filePath("sweep.json")) && this->show(folder))
  {
    // summary.png, drawn here: the window renders on this thread only.
    const bender::SweepFolder& sweep = this->Window->sweep();
    try
    {
      bender::WriteSweepPlot(
        sweep.rows, sweep.parameter, QDir(folder).filePath("summary.png").toStdString());
    }
    catch (const bender::Error& e)
    {
      line += QString(" No summary.png: %1").arg(e.what());
    }
  }
  this->setStatus(line);
  if (ok)
  {
    this->Session.AddMessage(bender::MessageSeverity::Info, line.toStdString());
  }
  emit this->sweepFinished(ok);
}
