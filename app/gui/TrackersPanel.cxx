#include "TrackersPanel.h"

#include "FileOpener.h"

#include "BenderSession.h"
#include "BenderView.h"
#include "IgtlDevice.h"
#include "IgtlSender.h"
#include "IgtlSurfaceFromMesh.h"
#include "TrackerSession.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFileDialog>
#include <QFormLayout>
#include <QFutureWatcher>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>
#include <QTimer>
#include <QVBoxLayout>
#include <QtConcurrent/QtConcurrent>

#include <vtkActor.h>
#include <vtkBillboardTextActor3D.h>
#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkSphereSource.h>
#include <vtkTextProperty.h>

#include <algorithm>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

namespace
{
const char* const SlicerSurfaceName = "BenderVessel";
const char* const SlicerRibbonPrefix = "BenderRibbon";
constexpr double SlicerRateHz = 10.0;

// What a connect on the pool thread hands back to the GUI thread.
struct OpenedDevice
{
  std::unique_ptr<bender::TrackerDevice> device;
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
}

/// The sender thread of "Send to Slicer": connects, then sends the newest frame handed to it
/// (Submit replaces a frame not yet sent, so nothing queues up). A live frame goes through
/// IgtlSender::SendSurfaceIfDue; when it is not due the thread waits the rest of the interval
/// (or for a newer frame) and tries again, so the last frame of a bend is always sent. A final
/// frame (after a change of the committed surface) is sent at once.
class TrackersPanel::SlicerLink
{
public:
  struct Frame
  {
    bender::IgtlSurface surface;
    std::optional<bender::RibbonSpec> ribbon;
    bool final = false;
  };

  SlicerLink(bender::IgtlSender::Options options, std::function<void(std::string)> onError)
    : Options(std::move(options))
    , OnError(std::move(onError))
  {
    this->Thread = std::thread([this]() { this->Loop(); });
  }
  ~SlicerLink()
  {
    this->RequestStop();
    this->Thread.join();
  }
  void RequestStop()
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->Stop = true;
    this->Wake.notify_all();
  }
  void Submit(std::shared_ptr<Frame> frame)
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    if (this->Pending && this->Pending->final)
    {
      frame->final = true; // a newer shape replaces a final one: still sent without waiting
    }
    this->Pending = std::move(frame);
    this->Wake.notify_all();
  }
  bool Ended() const { return this->Done.load(); }

  std::atomic<unsigned long long> Messages{ 0 };
  std::atomic<unsigned long long> Bytes{ 0 };
  std::atomic<unsigned long long> Surfaces{ 0 };
  std::atomic<bool> Connected{ false };

private:
  void Loop()
  {
    try
    {
      bender::IgtlSender sender(this->Options);
      sender.Connect();
      this->Connected = true;
      std::unique_lock<std::mutex> lock(this->Mutex);
      for (;;)
      {
        this->Wake.wait(lock, [this]() { return this->Stop || this->Pending; });
        if (this->Stop)
        {
          break;
        }
        const std::shared_ptr<Frame> frame = this->Pending;
        lock.unlock();
        bool sent = true;
        if (frame->final)
        {
          sender.SendSurface(frame->surface, SlicerSurfaceName);
        }
        else
        {
          sent = sender.SendSurfaceIfDue(frame->surface, SlicerSurfaceName);
        }
        if (sent && frame->ribbon)
        {
          sender.SendRibbonEnds(*frame->ribbon, SlicerRibbonPrefix);
        }
        this->Messages = sender.MessagesSent();
        this->Bytes = sender.BytesSent();
        lock.lock();
        if (sent)
        {
          ++this->Surfaces;
          if (this->Pending == frame)
          {
            this->Pending.reset();
          }
        }
        else
        {
          this->Wake.wait_for(lock,
            std::chrono::milliseconds(int(1000.0 / SlicerRateHz) / 4 + 1),
            [this, &frame]() { return this->Stop || this->Pending != frame; });
        }
      }
    }
    catch (const std::exception& e)
    {
      this->Connected = false;
      this->Done = true;
      this->OnError(e.what());
      return;
    }
    this->Connected = false;
    this->Done = true;
  }

  bender::IgtlSender::Options Options;
  std::function<void(std::string)> OnError;
  std::mutex Mutex;
  std::condition_variable Wake;
  std::shared_ptr<Frame> Pending;
  bool Stop = false;
  std::atomic<bool> Done{ false };
  std::thread Thread;
};

/// Where the two hands map now, drawn in the view's ribbon layer (above the surface): an
/// orange ball per hand with its label, and a line from each ball to the ribbon end that hand
/// holds (nothing when they coincide, after an anchoring).
class TrackersPanel::HandMarkers
{
public:
  HandMarkers()
  {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    vtkNew<vtkCellArray> lines;
    this->TetherData->SetPoints(points);
    this->TetherData->SetLines(lines);
    this->TetherMapper->SetInputData(this->TetherData);
    this->Tether->SetMapper(this->TetherMapper);
    this->Tether->GetProperty()->SetColor(1.0, 0.62, 0.15);
    this->Tether->GetProperty()->SetLineWidth(2.0);
    this->Tether->PickableOff();
    this->Tether->VisibilityOff();
    const char* const names[2] = { "left hand", "right hand" };
    for (int h = 0; h < 2; ++h)
    {
      this->Sphere[h]->SetThetaResolution(20);
      this->Sphere[h]->SetPhiResolution(14);
      this->Mapper[h]->SetInputConnection(this->Sphere[h]->GetOutputPort());
      this->Ball[h]->SetMapper(this->Mapper[h]);
      this->Ball[h]->GetProperty()->SetColor(1.0, 0.62, 0.15);
      this->Ball[h]->GetProperty()->SetOpacity(0.55);
      this->Ball[h]->PickableOff();
      this->Ball[h]->VisibilityOff();
      this->Label[h]->SetInput(names[h]);
      this->Label[h]->GetTextProperty()->SetFontSize(14);
      this->Label[h]->GetTextProperty()->SetColor(1.0, 0.75, 0.35);
      this->Label[h]->GetTextProperty()->ShadowOn();
      this->Label[h]->GetTextProperty()->SetJustificationToCentered();
      this->Label[h]->PickableOff();
      this->Label[h]->VisibilityOff();
    }
  }
  ~HandMarkers()
  {
    if (this->Layer)
    {
      this->Layer->RemoveActor(this->Tether);
      for (int h = 0; h < 2; ++h)
      {
        this->Layer->RemoveActor(this->Ball[h]);
        this->Layer->RemoveViewProp(this->Label[h]);
      }
    }
  }
  void attach(vtkRenderer* layer)
  {
    this->Layer = layer;
    layer->AddActor(this->Tether);
    for (int h = 0; h < 2; ++h)
    {
      layer->AddActor(this->Ball[h]);
      layer->AddViewProp(this->Label[h]);
    }
  }
  /// `hands`: where the hands map (start: left); `held`: the ribbon whose ends they hold.
  void show(const bender::RibbonSpec& hands, const std::optional<bender::RibbonSpec>& held)
  {
    const bender::RibbonSpec& scaleOf = held ? *held : hands;
    const double length = bender::Distance(scaleOf.start.position, scaleOf.end.position);
    const double radius = std::clamp(0.09 * length, 0.3, 25.0);
    const bender::Vec3 at[2] = { hands.start.position, hands.end.position };
    vtkPoints* points = this->TetherData->GetPoints();
    points->Reset();
    vtkCellArray* lines = this->TetherData->GetLines();
    lines->Reset();
    for (int h = 0; h < 2; ++h)
    {
      this->Position[h][0] = at[h].x;
      this->Position[h][1] = at[h].y;
      this->Position[h][2] = at[h].z;
      this->Sphere[h]->SetCenter(this->Position[h]);
      this->Sphere[h]->SetRadius(radius);
      this->Ball[h]->VisibilityOn();
      this->Label[h]->SetPosition(at[h].x, at[h].y, at[h].z);
      this->Label[h]->SetDisplayOffset(0, 18);
      this->Label[h]->VisibilityOn();
      if (held)
      {
        const bender::Vec3 end = h == 0 ? held->start.position : held->end.position;
        if (bender::Distance(end, at[h]) > 1e-6 * std::max(1.0, length))
        {
          const vtkIdType ids[2] = { points->InsertNextPoint(this->Position[h]),
            points->InsertNextPoint(end.x, end.y, end.z) };
          lines->InsertNextCell(2, ids);
        }
      }
    }
    points->Modified();
    lines->Modified();
    this->TetherData->Modified();
    this->Tether->SetVisibility(lines->GetNumberOfCells() > 0);
    this->Shown = true;
  }
  void hide()
  {
    this->Tether->VisibilityOff();
    for (int h = 0; h < 2; ++h)
    {
      this->Ball[h]->VisibilityOff();
      this->Label[h]->VisibilityOff();
    }
    this->Shown = false;
  }

  bool Shown = false;
  double Position[2][3] = { { 0, 0, 0 }, { 0, 0, 0 } };

private:
  // Held: the view may be deleted before the panel (Qt deletes the central widget first).
  vtkSmartPointer<vtkRenderer> Layer;
  vtkNew<vtkSphereSource> Sphere[2];
  vtkNew<vtkPolyDataMapper> Mapper[2];
  vtkNew<vtkActor> Ball[2];
  vtkNew<vtkBillboardTextActor3D> Label[2];
  vtkNew<vtkPolyData> TetherData;
  vtkNew<vtkPolyDataMapper> TetherMapper;
  vtkNew<vtkActor> Tether;
};

namespace
{
const char* const AlignTip =
  "Anchors the hands, as they are now, to the ribbon shown: the left hand holds its start, the "
  "right hand its end, and the orange hand markers jump onto them; from then on the ribbon "
  "moves by the hands' displacements while the stylus is pressed. Nothing is bent. (Each "
  "stylus press anchors them too, so the ribbon never jumps.)";
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
  this->Device->setToolTip("usb, usb:N, serial:/dev/ttyUSB0@115200, replay:FILE or sim");
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
  this->Status = new QLabel("not connected", this);
  this->Status->setObjectName("trackerStatus");
  this->Status->setWordWrap(true);
  layout->addWidget(this->Status);
  this->IgtlCounters = new QLabel(this);
  this->IgtlCounters->setObjectName("igtlCounters");
  this->IgtlCounters->setWordWrap(true);
  layout->addWidget(this->IgtlCounters);

  auto* slicer = new QGroupBox("3D Slicer (OpenIGTLink)", this);
  auto* slicerForm = new QFormLayout(slicer);
  this->SendToSlicer = new QCheckBox("Send to Slicer", slicer);
  this->SendToSlicer->setObjectName("sendToSlicer");
  this->SendToSlicer->setToolTip(
    "Sends the vessel (POLYDATA BenderVessel, RAS) and the ribbon's end frames "
    "(BenderRibbonStart/End) to an OpenIGTLinkIF connector in server mode, live during a bend");
  slicerForm->addRow(this->SendToSlicer);
  this->SlicerHost = new QLineEdit("127.0.0.1", slicer);
  this->SlicerHost->setObjectName("slicerHost");
  slicerForm->addRow("Host", this->SlicerHost);
  this->SlicerPort = new QSpinBox(slicer);
  this->SlicerPort->setObjectName("slicerPort");
  this->SlicerPort->setRange(1, 65535);
  this->SlicerPort->setValue(18944);
  slicerForm->addRow("Port", this->SlicerPort);
  this->SlicerCounters = new QLabel("not sending", slicer);
  this->SlicerCounters->setObjectName("slicerCounters");
  this->SlicerCounters->setWordWrap(true);
  slicerForm->addRow(this->SlicerCounters);
  layout->addWidget(slicer);
  layout->addStretch(1);
  this->setConnected(false);

  connect(this->Kind,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    [this]() { this->setConnected(this->Trackers && this->Trackers->IsConnected()); });
  connect(this->SendToSlicer, &QCheckBox::toggled, this, &TrackersPanel::setSendToSlicer);
  this->SnapshotTimer = new QTimer(this);
  this->SnapshotTimer->setSingleShot(true);
  connect(this->SnapshotTimer, &QTimer::timeout, this, [this]() { this->sendSnapshot(false); });
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

TrackersPanel::~TrackersPanel()
{
  // The sender threads end within their connect/write timeouts.
  this->Link.reset();
  this->Retired.clear();
}

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
    if (this->Markers->Shown)
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
  return this->Markers->Shown;
}

bool TrackersPanel::handMarkerPosition(int hand, double position[3]) const
{
  if (!this->Markers->Shown || hand < 0 || hand > 1)
    return false;
  std::copy(this->Markers->Position[hand], this->Markers->Position[hand] + 3, position);
  return true;
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
  try
  {
    // Refused here, before any thread: a bad spec, scale or tool names.
    Calibration(this->motionScale());
    const bender::TrackerDeviceSpec parsed = bender::TrackerDeviceSpec::Parse(spec);
    if (parsed.kind == bender::TrackerDeviceSpec::Kind::Replay ||
      parsed.kind == bender::TrackerDeviceSpec::Kind::Simulator)
    {
      // Files and the simulator open at once.
      if (!this->Trackers->Connect(spec,
            options,
            Hands(this->leftStation(), this->rightStation()),
            Calibration(this->motionScale())))
        return false;
      this->finishConnect(true);
      return true;
    }
    bender::CreateTrackerDevice(parsed, options); // validates names and port; opens nothing
  }
  catch (const std::exception& e)
  {
    this->Session->AddMessage(bender::MessageSeverity::Error, "Tracker " + spec + ": " + e.what());
    return false;
  }
  this->Connecting = true;
  this->setConnected(false);
  this->setStatus(QString("connecting to %1 ...").arg(QString::fromStdString(spec)));
  auto opened = std::make_shared<OpenedDevice>();
  auto* watcher = new QFutureWatcher<void>(this);
  connect(watcher,
    &QFutureWatcher<void>::finished,
    this,
    [this, watcher, opened]()
    {
      watcher->deleteLater();
      this->Connecting = false;
      if (!opened->device)
      {
        this->Session->AddMessage(bender::MessageSeverity::Error, opened->problem);
        this->setStatus(QString::fromStdString(opened->problem));
        this->finishConnect(false);
        return;
      }
      this->finishConnect(this->Trackers->Connect(std::move(opened->device),
        Hands(this->leftStation(), this->rightStation()),
        Calibration(this->motionScale())));
    });
  watcher->setFuture(QtConcurrent::run(
    [spec, options, opened]()
    {
      try
      {
        opened->device = bender::TrackerSession::OpenDevice(spec, options);
      }
      catch (const std::exception& e)
      {
        opened->problem = e.what();
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
  this->pruneRetired();
  const auto* igtl =
    this->Trackers ? dynamic_cast<const bender::IgtlDevice*>(this->Trackers->GetDevice()) : nullptr;
  if (igtl)
  {
    const bender::IgtlStatistics stats = igtl->IgtlStats();
    std::ostringstream text;
    text << "OpenIGTLink: ";
    if (stats.names.empty())
    {
      text << "no poses yet";
    }
    else
    {
      text << "names seen:";
      const char* separator = " ";
      for (const auto& [name, count] : stats.names)
      {
        text << separator << name << " (" << count << ")";
        separator = ", ";
      }
    }
    text << "\nCRC errors " << stats.decoder.crcErrors << ", garbage bytes "
         << stats.decoder.garbageBytes << ", skipped messages " << stats.unknownTypes
         << ", invalid poses " << stats.invalidPoses;
    text << "\nlast STATUS: " << (stats.lastStatus.empty() ? "OK" : stats.lastStatus);
    this->IgtlCounters->setText(QString::fromStdString(text.str()));
    this->IgtlCounters->show();
  }
  else
  {
    this->IgtlCounters->clear();
    this->IgtlCounters->hide();
  }
  if (this->Link)
  {
    this->SlicerCounters->setText(QString("%1 %2:%3: %4 surfaces, %5 messages, %6 kB sent")
                                    .arg(this->Link->Connected ? "connected to" : "connecting to")
                                    .arg(this->SlicerHost->text().trimmed())
                                    .arg(this->SlicerPort->value())
                                    .arg(this->Link->Surfaces.load())
                                    .arg(this->Link->Messages.load())
                                    .arg(double(this->Link->Bytes.load()) / 1024.0, 0, 'f', 1));
  }
}

void TrackersPanel::pruneRetired()
{
  for (auto it = this->Retired.begin(); it != this->Retired.end();)
  {
    it = (*it)->Ended() ? this->Retired.erase(it) : it + 1;
  }
}

bool TrackersPanel::isSendingToSlicer() const
{
  return this->Link != nullptr;
}

unsigned long long TrackersPanel::slicerMessagesSent() const
{
  return this->Link ? this->Link->Messages.load() : 0;
}

void TrackersPanel::setSendToSlicer(bool on)
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
  bender::IgtlSender::Options options;
  options.host = this->SlicerHost->text().trimmed().toStdString();
  options.port = this->SlicerPort->value();
  options.maxSurfaceRateHz = SlicerRateHz;
  if (options.host.empty())
  {
    this->Session->AddMessage(bender::MessageSeverity::Error, "Send to Slicer: no host");
    QTimer::singleShot(0, this, [this]() { this->SendToSlicer->setChecked(false); });
    return;
  }
  const unsigned generation = ++this->LinkGeneration;
  this->Link = std::make_unique<SlicerLink>(options,
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

void TrackersPanel::sessionChanged()
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

void TrackersPanel::sendSnapshot(bool final)
{
  if (!this->Link || !this->Session || this->Session->IsBusy() || !this->Session->HasSurface())
    return;
  const bool grabbed = this->Session->GetState() == bender::GrabState::Grabbed;
  auto frame = std::make_shared<SlicerLink::Frame>();
  try
  {
    frame->surface = bender::MakeIgtlSurface(this->Session->GetDisplaySurface(),
      this->Session->GetSurfaceName().empty() ? "the surface" : this->Session->GetSurfaceName());
  }
  catch (const std::exception& e)
  {
    this->Session->AddMessage(
      bender::MessageSeverity::Error, std::string("Send to Slicer: ") + e.what());
    this->SendToSlicer->setChecked(false);
    return;
  }
  std::optional<bender::RibbonSpec> ribbon;
  if (grabbed)
  {
    ribbon = this->Session->GetFinalRibbon();
  }
  else if (this->View && this->View->ribbonWidget()->GetEnabled())
  {
    ribbon = this->View->ribbonWidget()->GetRibbonRepresentation()->GetRibbon();
  }
  if (ribbon)
  {
    try
    {
      bender::IgtlRibbonEndFrame(ribbon->start); // a degenerate frame is not sent
      bender::IgtlRibbonEndFrame(ribbon->end);
      frame->ribbon = ribbon;
    }
    catch (const std::exception&)
    {
    }
  }
  frame->final = final && !grabbed;
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
