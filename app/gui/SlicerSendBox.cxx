#include "SlicerSendBox.h"

#include "BenderSession.h"
#include "BenderView.h"
#include "SlicerLink.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QCheckBox>
#include <QFormLayout>
#include <QLabel>
#include <QLineEdit>
#include <QSpinBox>
#include <QTimer>

#include <vtkPolyData.h>

#include <optional>

namespace
{
constexpr double SlicerRateHz = 10.0;
}

SlicerSendBox::SlicerSendBox(QWidget* parent)
  : QGroupBox("3D Slicer (OpenIGTLink)", parent)
{
  auto* slicerForm = new QFormLayout(this);
  this->SendToSlicer = new QCheckBox("Send to Slicer", this);
  this->SendToSlicer->setObjectName("sendToSlicer");
  this->SendToSlicer->setToolTip(
    "Sends the vessel (POLYDATA BenderVessel, RAS) and the ribbon's end frames "
    "(BenderRibbonStart/End) to an OpenIGTLinkIF connector in server mode, live during a bend");
  slicerForm->addRow(this->SendToSlicer);
  this->SlicerHost = new QLineEdit("127.0.0.1", this);
  this->SlicerHost->setObjectName("slicerHost");
  slicerForm->addRow("Host", this->SlicerHost);
  this->SlicerPort = new QSpinBox(this);
  this->SlicerPort->setObjectName("slicerPort");
  this->SlicerPort->setRange(1, 65535);
  this->SlicerPort->setValue(18944);
  slicerForm->addRow("Port", this->SlicerPort);
  this->SlicerCounters = new QLabel("not sending", this);
  this->SlicerCounters->setObjectName("slicerCounters");
  this->SlicerCounters->setWordWrap(true);
  slicerForm->addRow(this->SlicerCounters);
  connect(this->SendToSlicer, &QCheckBox::toggled, this, &SlicerSendBox::setSending);
  this->SnapshotTimer = new QTimer(this);
  this->SnapshotTimer->setSingleShot(true);
  connect(this->SnapshotTimer, &QTimer::timeout, this, [this]() { this->sendSnapshot(false); });
  auto* countersTimer = new QTimer(this);
  countersTimer->setInterval(250);
  connect(countersTimer, &QTimer::timeout, this, &SlicerSendBox::showCounters);
  countersTimer->start();
}

SlicerSendBox::~SlicerSendBox()
{
  // The sender threads end within their connect/write timeouts.
  this->Link.reset();
  this->Retired.clear();
}

void SlicerSendBox::attach(bender::BenderSession* session, BenderView* view)
{
  this->Session = session;
  this->View = view;
}

void SlicerSendBox::showCounters()
{
  this->pruneRetired();
  if (this->Link)
  {
    const bender::SlicerLink::Counters sent = this->Link->GetCounters();
    this->SlicerCounters->setText(QString("%1 %2:%3: %4 surfaces, %5 messages, %6 kB sent")
                                    .arg(sent.connected ? "connected to" : "connecting to")
                                    .arg(this->SlicerHost->text().trimmed())
                                    .arg(this->SlicerPort->value())
                                    .arg(sent.surfaces)
                                    .arg(sent.messages)
                                    .arg(double(sent.bytes) / 1024.0, 0, 'f', 1));
  }
}

void SlicerSendBox::pruneRetired()
{
  for (auto it = this->Retired.begin(); it != this->Retired.end();)
  {
    it = (*it)->Ended() ? this->Retired.erase(it) : it + 1;
  }
}

bool SlicerSendBox::isSending() const
{
  return this->Link != nullptr;
}

unsigned long long SlicerSendBox::messagesSent() const
{
  return this->Link ? this->Link->GetCounters().messages : 0;
}

void SlicerSendBox::setSending(bool on)
{
  this->SnapshotTimer->stop();
  if (this->Link)
  {
    // Its thread may still be connecting or writing (bounded by the timeouts): it ends on its
    // own and is joined later, never on the GUI thread's time.
    this->Link->RequestStop();
    this->Retired.push_back(std::move(this->Link));
  }
  this->SlicerHost->setEnabled(!on);
  this->SlicerPort->setEnabled(!on);
  if (!on)
  {
    this->SlicerCounters->setText("not sending");
    return;
  }
  bender::SlicerLink::Options options;
  options.sender.host = this->SlicerHost->text().trimmed().toStdString();
  options.sender.port = this->SlicerPort->value();
  options.sender.maxSurfaceRateHz = SlicerRateHz;
  if (options.sender.host.empty())
  {
    this->Session->AddMessage(bender::MessageSeverity::Error, "Send to Slicer: no host");
    QTimer::singleShot(0, this, [this]() { this->SendToSlicer->setChecked(false); });
    return;
  }
  const unsigned generation = ++this->LinkGeneration;
  this->Link = std::make_unique<bender::SlicerLink>(options,
    [this, generation](std::string problem)
    {
      QMetaObject::invokeMethod(
        this,
        [this, problem, generation]()
        {
          if (!this->Link || generation != this->LinkGeneration)
            return; // switched off meanwhile (perhaps on again: a newer sender)
          this->Session->AddMessage(bender::MessageSeverity::Error, "Send to Slicer: " + problem);
          this->SendToSlicer->setChecked(false);
        },
        Qt::QueuedConnection);
    });
  this->SentSurface = nullptr;
  this->showCounters();
  this->sendSnapshot(true);
}

void SlicerSendBox::sessionChanged()
{
  if (!this->Link || !this->Session || this->Session->IsBusy() || !this->Session->HasSurface())
    return;
  if (this->Session->GetState() == bender::GrabState::Grabbed)
  {
    // At most SlicerRateHz snapshots a second on the GUI thread; the newest shape is taken
    // when the timer fires.
    if (!this->SnapshotTimer->isActive())
    {
      this->SnapshotTimer->start(int(1000.0 / SlicerRateHz));
    }
    this->SentWhileGrabbed = true;
    return;
  }
  vtkPolyData* committed = this->Session->GetSurface();
  if (this->SentWhileGrabbed || committed != this->SentSurface ||
    committed->GetMTime() != this->SentSurfaceTime ||
    this->Session->GetHistoryPosition() != this->SentHistoryPosition)
  {
    this->sendSnapshot(true);
  }
}

void SlicerSendBox::sendSnapshot(bool final)
{
  if (!this->Link || !this->Session || this->Session->IsBusy() || !this->Session->HasSurface())
    return;
  const bool grabbed = this->Session->GetState() == bender::GrabState::Grabbed;
  std::optional<bender::RibbonSpec> ribbon;
  if (grabbed)
  {
    ribbon = this->Session->GetFinalRibbon();
  }
  else if (this->View && this->View->ribbonWidget()->GetEnabled())
  {
    ribbon = this->View->ribbonWidget()->GetRibbonRepresentation()->GetRibbon();
  }
  std::shared_ptr<bender::SlicerLink::Frame> frame;
  try
  {
    frame = bender::SlicerLink::MakeFrame(this->Session->GetDisplaySurface(),
      this->Session->GetSurfaceName().empty() ? "the surface" : this->Session->GetSurfaceName(),
      ribbon,
      final && !grabbed);
  }
  catch (const std::exception& e)
  {
    this->Session->AddMessage(
      bender::MessageSeverity::Error, std::string("Send to Slicer: ") + e.what());
    this->SendToSlicer->setChecked(false);
    return;
  }
  if (!grabbed)
  {
    vtkPolyData* committed = this->Session->GetSurface();
    this->SentSurface = committed;
    this->SentSurfaceTime = committed->GetMTime();
    this->SentHistoryPosition = this->Session->GetHistoryPosition();
    this->SentWhileGrabbed = false;
  }
  this->Link->Submit(std::move(frame));
}
