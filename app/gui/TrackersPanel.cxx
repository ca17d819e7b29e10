#include "TrackersPanel.h"

#include "FileOpener.h"
#include "HandMarkers.h"
#include "SlicerSendBox.h"

#include "BenderSession.h"
#include "BenderView.h"
#include "TrackerSession.h"
#include "TrackerStream.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QCheckBox>
#include <QComboBox>
#include <QCompleter>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QFutureWatcher>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>
#include <QTimer>
#include <QVBoxLayout>
#include <QtConcurrent/QtConcurrent>

#include <vtkPolyData.h>

#include <optional>

namespace
{
// A device opened on the pool thread, or why it could not be, for the GUI thread.
struct OpenedDevice
{
  std::unique_ptr<bender::TrackerStream> stream;
  std::string problem;
};

bender::HandMapping Hands(int left, int right)
{
  bender::HandMapping hands;
  hands.leftStation = left;
  hands.rightStation = right;
  return hands;
}

// The absolute mapping (no ribbon yet): the automatic scale (0) is 1 there.
bender::TrackerCalibration Calibration(double scale)
{
  return bender::TrackerCalibration(
    bender::Quaternion{}, bender::Vec3{}, scale > 0.0 ? scale : 1.0);
}

const char* const AlignTip =
  "Anchors the hands, as they are now, to the ribbon shown: the left hand holds its start, the "
  "right hand its end, and the orange hand markers jump onto them; from then on the ribbon "
  "moves by the hands' displacements while the stylus is pressed. Nothing is bent. (Each "
  "stylus press anchors them too, so the ribbon never jumps.)";
// The keys of TrackerSession::PressHands (GestureController routes G and Space to it while a
// tracker is connected); docs/tracking.md says the same.
const char* const GrabKeysText =
  "Grab with the hands: the stylus button, or, for devices that send no button (OpenIGTLink "
  "from PLUS), <b>G</b> (press to grab, again to release) or <b>hold Space</b> (released on "
  "letting go: a USB foot pedal set to send Space).";
const char* const AlignDisabledTip =
  "Connect a tracker first: Align anchors the connected hands to the ribbon shown";
}

TrackersPanel::TrackersPanel(QWidget* parent)
  : QWidget(parent)
  , Markers(std::make_unique<HandMarkers>())
{
  auto* layout = new QVBoxLayout(this);
  auto* form = new QFormLayout;
  layout->addLayout(form);
  this->Kind = new QComboBox(this);
  this->Kind->setObjectName("trackerKind");
  this->Kind->addItem("Fastrak, replay or simulator");
  this->Kind->addItem("OpenIGTLink (PLUS, 3D Slicer)");
  form->addRow("Source", this->Kind);
  auto* deviceRow = new QHBoxLayout;
  this->Device = new QLineEdit("sim", this);
  this->Device->setObjectName("trackerDevice");
  // The device table's kinds: the completer lists them, the tooltip shows their forms.
  QStringList kinds;
  for (const bender::TrackerDeviceKind& kind : bender::TrackerDeviceKinds())
  {
    const bool argument = kind.argument == bender::TrackerDeviceKind::Argument::Required;
    kinds << QString::fromStdString(kind.name + (argument ? ":" : ""));
  }
  this->Device->setCompleter(new QCompleter(kinds, this->Device));
  this->Device->setToolTip(QString::fromStdString(bender::TrackerDeviceForms()));
  deviceRow->addWidget(this->Device);
  auto* browse = new QPushButton("Replay...", this);
  deviceRow->addWidget(browse);
  form->addRow("Device", deviceRow);
  this->IgtlHost = new QLineEdit("127.0.0.1", this);
  this->IgtlHost->setObjectName("igtlHost");
  this->IgtlHost->setToolTip("Host of the OpenIGTLink server (PLUS Server, or 3D Slicer's "
                             "OpenIGTLinkIF connector in server mode)");
  form->addRow("OpenIGTLink host", this->IgtlHost);
  this->IgtlPort = new QSpinBox(this);
  this->IgtlPort->setObjectName("igtlPort");
  this->IgtlPort->setRange(1, 65535);
  this->IgtlPort->setValue(18944);
  form->addRow("OpenIGTLink port", this->IgtlPort);
  this->IgtlTool1 = new QLineEdit("StylusToTracker", this);
  this->IgtlTool1->setObjectName("igtlTool1");
  this->IgtlTool1->setMaxLength(20);
  this->IgtlTool1->setToolTip("Device name of the left hand's TRANSFORM messages (station 1)");
  form->addRow("Left hand tool name", this->IgtlTool1);
  this->IgtlTool2 = new QLineEdit("Stylus2ToTracker", this);
  this->IgtlTool2->setObjectName("igtlTool2");
  this->IgtlTool2->setMaxLength(20);
  this->IgtlTool2->setToolTip("Device name of the right hand's TRANSFORM messages (station 2)");
  form->addRow("Right hand tool name", this->IgtlTool2);
  this->Left = new QSpinBox(this);
  this->Left->setRange(1, 4);
  this->Left->setValue(1);
  form->addRow("Left hand (start) station", this->Left);
  this->Right = new QSpinBox(this);
  this->Right->setRange(1, 4);
  this->Right->setValue(2);
  form->addRow("Right hand (end) station", this->Right);
  this->Scale = new QDoubleSpinBox(this);
  this->Scale->setObjectName("motionScale");
  this->Scale->setRange(0.0, 100.0);
  this->Scale->setDecimals(3);
  this->Scale->setSingleStep(0.05);
  this->Scale->setSpecialValueText("auto (hands' span = ribbon length)");
  this->Scale->setValue(0.0);
  this->Scale->setToolTip(
    "Model millimetres per millimetre of hand motion; auto: the distance between the hands "
    "maps onto the ribbon's length when they are anchored to it (at connect and at each grab)");
  form->addRow("Motion scale", this->Scale);

  auto* buttons = new QHBoxLayout;
  this->ConnectButton = new QPushButton("Connect", this);
  this->ConnectButton->setObjectName("trackerConnect");
  this->DisconnectButton = new QPushButton("Disconnect", this);
  this->DisconnectButton->setObjectName("trackerDisconnect");
  buttons->addWidget(this->ConnectButton);
  buttons->addWidget(this->DisconnectButton);
  layout->addLayout(buttons);
  this->AlignButton = new QPushButton("Align hands to the ribbon", this);
  this->AlignButton->setObjectName("trackerAlign");
  this->AlignButton->setToolTip(AlignDisabledTip);
  layout->addWidget(this->AlignButton);
  this->Clutch = new QCheckBox("Clutch (move the hands without moving the ribbon)", this);
  this->Clutch->setObjectName("trackerClutch");
  this->Clutch->setToolTip("While a bend is held by the stylus: the ribbon stays where it is and "
                           "the hands move freely; off again, the hands hold it from there");
  layout->addWidget(this->Clutch);
  auto* keys = new QLabel(GrabKeysText, this);
  keys->setObjectName("trackerGrabKeys");
  keys->setWordWrap(true);
  layout->addWidget(keys);
  this->Status = new QLabel("not connected", this);
  this->Status->setObjectName("trackerStatus");
  this->Status->setWordWrap(true);
  layout->addWidget(this->Status);
  this->IgtlCounters = new QLabel(this);
  this->IgtlCounters->setObjectName("igtlCounters");
  this->IgtlCounters->setWordWrap(true);
  layout->addWidget(this->IgtlCounters);

  this->Slicer = new SlicerSendBox(this);
  layout->addWidget(this->Slicer);
  layout->addStretch(1);
  this->setConnected(false);

  connect(this->Kind,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    [this]() { this->setConnected(this->Trackers && this->Trackers->IsConnected()); });
  this->CountersTimer = new QTimer(this);
  this->CountersTimer->setInterval(250);
  connect(this->CountersTimer, &QTimer::timeout, this, &TrackersPanel::showCounters);
  this->CountersTimer->start();

  connect(browse,
    &QPushButton::clicked,
    this,
    [this]()
    {
      const QString file = QFileDialog::getOpenFileName(this,
        "Tracker recording",
        FileOpener::lastFolder("recording"),
        "Fastrak recordings (*.fastrak);;All files (*)");
      if (!file.isEmpty())
      {
        FileOpener::rememberFolder("recording", file);
        this->Device->setText("replay:" + file);
      }
    });
  connect(this->ConnectButton, &QPushButton::clicked, this, &TrackersPanel::connectDevice);
  connect(this->DisconnectButton, &QPushButton::clicked, this, &TrackersPanel::disconnectDevice);
  connect(this->AlignButton, &QPushButton::clicked, this, &TrackersPanel::alignHands);
  connect(this->Scale,
    QOverload<double>::of(&QDoubleSpinBox::valueChanged),
    this,
    [this](double scale)
    {
      if (this->Trackers)
        this->Trackers->SetRelativeScale(scale);
    });
  connect(this->Clutch,
    &QCheckBox::toggled,
    this,
    [this](bool engaged)
    {
      if (this->Trackers)
        this->Trackers->SetClutch(engaged);
    });
  this->Timer = new QTimer(this);
  this->Timer->setInterval(16);
  connect(this->Timer, &QTimer::timeout, this, &TrackersPanel::poll);
}

TrackersPanel::~TrackersPanel() = default;

QString TrackersPanel::deviceSpec() const
{
  if (this->Kind->currentIndex() == 1)
  {
    return QString("igtl:%1:%2").arg(this->IgtlHost->text().trimmed()).arg(this->IgtlPort->value());
  }
  return this->Device->text().trimmed();
}

void TrackersPanel::setDeviceSpec(const QString& spec)
{
  this->Device->setText(spec);
}

int TrackersPanel::leftStation() const
{
  return this->Left->value();
}

int TrackersPanel::rightStation() const
{
  return this->Right->value();
}

double TrackersPanel::motionScale() const
{
  return this->Scale->value();
}

void TrackersPanel::setMotionScale(double scale)
{
  this->Scale->setValue(scale);
}

void TrackersPanel::setConnected(bool connected)
{
  const bool idle = !connected && !this->Connecting;
  const bool igtl = this->Kind->currentIndex() == 1;
  this->ConnectButton->setEnabled(idle);
  this->DisconnectButton->setEnabled(connected);
  this->AlignButton->setEnabled(connected);
  this->AlignButton->setToolTip(connected ? AlignTip : AlignDisabledTip);
  this->Clutch->setEnabled(connected);
  this->Kind->setEnabled(idle);
  this->Device->setEnabled(idle && !igtl);
  this->IgtlHost->setEnabled(idle && igtl);
  this->IgtlPort->setEnabled(idle && igtl);
  this->IgtlTool1->setEnabled(idle && igtl);
  this->IgtlTool2->setEnabled(idle && igtl);
  if (!connected)
  {
    this->Clutch->setChecked(false);
    if (this->Markers->shown())
    {
      this->Markers->hide();
      if (this->View)
        this->View->render();
    }
  }
}

void TrackersPanel::setStatus(const QString& status)
{
  this->Status->setText(status);
}

void TrackersPanel::attach(bender::TrackerSession* trackers,
  bender::BenderSession* session,
  BenderView* view,
  std::function<bool()> release)
{
  this->Trackers = trackers;
  this->Session = session;
  this->View = view;
  this->Trackers->SetReleaseHandler(std::move(release));
  this->Markers->attach(view->ribbonRenderer());
  this->Slicer->attach(session, view);
}

bool TrackersPanel::connectWith(std::unique_ptr<bender::TrackerDevice> device)
{
  if (!this->Trackers || this->Connecting || this->Trackers->IsConnected())
    return false;
  this->Trackers->SetRelativeScale(this->motionScale());
  const bool connected = this->Trackers->Connect(std::move(device),
    Hands(this->leftStation(), this->rightStation()),
    Calibration(this->motionScale()));
  this->finishConnect(connected);
  return connected;
}

bool TrackersPanel::alignHands()
{
  if (!this->Trackers || !this->Trackers->IsConnected())
  {
    if (this->Session)
      this->Session->AddMessage(bender::MessageSeverity::Error, "Align: connect a tracker first");
    return false;
  }
  vtkBenderRibbonWidget* widget = this->View->ribbonWidget();
  if (!widget->GetEnabled())
  {
    this->Session->AddMessage(
      bender::MessageSeverity::Error, "Align: place a ribbon first (P, then click on the vessel)");
    return false;
  }
  const bender::RibbonSpec ribbon = widget->GetRibbonRepresentation()->GetRibbon();
  if (!this->Trackers->AlignTo(ribbon))
    return false;
  // Seen at once: the hand markers sit on the ribbon's ends.
  widget->GetRibbonRepresentation()->SetRibbon(ribbon);
  this->setStatus(QString::fromStdString(this->Trackers->StatusText()));
  this->updateHandMarkers();
  this->View->render();
  return true;
}

void TrackersPanel::updateHandMarkers()
{
  if (!this->View)
    return;
  const std::optional<bender::RibbonSpec> hands =
    this->Trackers && this->Trackers->IsConnected() ? this->Trackers->MappedHands() : std::nullopt;
  if (!hands)
  {
    this->Markers->hide();
    return;
  }
  std::optional<bender::RibbonSpec> held;
  vtkBenderRibbonWidget* widget = this->View->ribbonWidget();
  if (widget->GetEnabled())
  {
    held = widget->GetRibbonRepresentation()->GetRibbon();
  }
  this->Markers->show(*hands, held);
}

bool TrackersPanel::handMarkersShown() const
{
  return this->Markers->shown();
}

bool TrackersPanel::handMarkerPosition(int hand, double position[3]) const
{
  return this->Markers->position(hand, position);
}

bool TrackersPanel::connectDevice()
{
  if (!this->Trackers || this->Connecting || this->Trackers->IsConnected())
    return false;
  bender::TrackerDeviceOptions options;
  options.stations = { this->leftStation(), this->rightStation() };
  options.realtime = true;
  options.simulatorRealtime = true;
  options.igtlToolNames = { this->IgtlTool1->text().trimmed().toStdString(),
    this->IgtlTool2->text().trimmed().toStdString() };
  const std::string spec = this->deviceSpec().toStdString();
  this->Trackers->SetRelativeScale(this->motionScale());
  auto opened = std::make_shared<OpenedDevice>();
  try
  {
    // Refused here, before any thread: a bad spec, scale, tool names or port.
    Calibration(this->motionScale());
    opened->stream = std::make_unique<bender::TrackerStream>(spec, options);
    opened->stream->Create();
  }
  catch (const std::exception& e)
  {
    this->Session->AddMessage(bender::MessageSeverity::Error, "Tracker " + spec + ": " + e.what());
    return false;
  }
  if (!opened->stream->IsLive())
  {
    // Files and the simulator open at once.
    if (!this->Trackers->Connect(opened->stream->TakeDevice(),
          Hands(this->leftStation(), this->rightStation()),
          Calibration(this->motionScale())))
      return false;
    this->finishConnect(true);
    return true;
  }
  this->Connecting = true;
  this->setConnected(false);
  this->setStatus(QString("connecting to %1 ...").arg(QString::fromStdString(spec)));
  auto* watcher = new QFutureWatcher<void>(this);
  connect(watcher,
    &QFutureWatcher<void>::finished,
    this,
    [this, watcher, opened]()
    {
      watcher->deleteLater();
      this->Connecting = false;
      if (!opened->problem.empty())
      {
        this->Session->AddMessage(bender::MessageSeverity::Error, opened->problem);
        this->setStatus(QString::fromStdString(opened->problem));
        this->finishConnect(false);
        return;
      }
      this->finishConnect(this->Trackers->Connect(opened->stream->TakeDevice(),
        Hands(this->leftStation(), this->rightStation()),
        Calibration(this->motionScale())));
    });
  watcher->setFuture(QtConcurrent::run(
    [spec, opened]()
    {
      try
      {
        opened->stream->Open();
      }
      catch (const std::exception& e)
      {
        opened->problem = "Tracker " + spec + ": " + e.what();
      }
    }));
  return true;
}

void TrackersPanel::finishConnect(bool connected)
{
  this->setConnected(connected);
  if (connected)
  {
    this->Timer->start();
    this->setStatus(QString::fromStdString(this->Trackers->StatusText()));
  }
  this->showCounters();
  emit this->connectFinished(connected);
}

void TrackersPanel::disconnectDevice()
{
  this->Timer->stop();
  if (this->Trackers)
    this->Trackers->Disconnect();
  this->setConnected(false);
  this->setStatus("not connected");
  this->showCounters();
}

void TrackersPanel::poll()
{
  if (!this->Trackers || !this->Trackers->IsConnected())
  {
    return;
  }
  bender::TrackerSession::PollResult result;
  // The session's changes during the poll do not render: one frame at its end.
  this->View->quietly([this, &result]() { result = this->Trackers->Poll(); });
  vtkBenderRibbonWidget* widget = this->View->ribbonWidget();
  const bool grabbed = this->Session->GetState() == bender::GrabState::Grabbed;
  if (const auto ribbon = this->Trackers->CurrentRibbon();
      ribbon && (grabbed || !this->Trackers->IsRelative()))
  {
    // The widget shows what the hands hold; the live warp already moved in Poll. Anchored to
    // the ribbon (relative), the hands move it only while the stylus holds it.
    widget->GetRibbonRepresentation()->SetRibbon(*ribbon);
    if (!widget->GetEnabled() && this->Session->HasSurface())
    {
      widget->On();
    }
  }
  if (result.cancelled && !grabbed && this->Session->GetRibbon() && widget->GetEnabled())
  {
    // A bend cancelled by the device: the ribbon goes back onto the surface.
    widget->GetRibbonRepresentation()->SetRibbon(*this->Session->GetRibbon());
  }
  // A release started the commit on the worker; its end shows the committed ribbon.
  this->setStatus(QString::fromStdString(this->Trackers->StatusText()));
  if (result.ended)
  {
    this->Timer->stop();
    this->setConnected(false);
  }
  else
  {
    this->updateHandMarkers();
  }
  this->View->render();
  if (result.grabbed && this->Session->GetState() == bender::GrabState::Grabbed)
  {
    emit this->trackerGrabbed();
  }
  else if (result.moved && this->Session->GetState() == bender::GrabState::Grabbed)
  {
    emit this->trackerMoved();
  }
}

void TrackersPanel::showCounters()
{
  const bender::TrackerDevice* device = this->Trackers ? this->Trackers->GetDevice() : nullptr;
  const std::string counters = device ? device->CountersText() : std::string();
  this->IgtlCounters->setText(QString::fromStdString(counters));
  this->IgtlCounters->setVisible(!counters.empty());
}

bool TrackersPanel::isSendingToSlicer() const
{
  return this->Slicer->isSending();
}

unsigned long long TrackersPanel::slicerMessagesSent() const
{
  return this->Slicer->messagesSent();
}

void TrackersPanel::sessionChanged()
{
  this->Slicer->sessionChanged();
}
