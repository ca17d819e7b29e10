#include "TrackersPanel.h"

#include "BenderSession.h"
#include "BenderView.h"
#include "TrackerSession.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>
#include <QTimer>
#include <QVBoxLayout>

TrackersPanel::TrackersPanel(QWidget* parent)
  : QWidget(parent)
{
  auto* layout = new QVBoxLayout(this);
  auto* form = new QFormLayout;
  layout->addLayout(form);
  auto* deviceRow = new QHBoxLayout;
  this->Device = new QLineEdit("sim", this);
  this->Device->setObjectName("trackerDevice");
  this->Device->setToolTip("usb, usb:N, serial:/dev/ttyUSB0@115200, replay:FILE or sim");
  deviceRow->addWidget(this->Device);
  auto* browse = new QPushButton("Replay...", this);
  deviceRow->addWidget(browse);
  form->addRow("Device", deviceRow);
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
  this->Scale->setRange(0.01, 100.0);
  this->Scale->setDecimals(3);
  this->Scale->setValue(1.0);
  this->Scale->setToolTip("Model millimetres per millimetre of hand motion");
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
  this->AlignButton->setToolTip("Moves the calibration so that the hands' midpoint maps to the "
                                "middle of the ribbon shown now");
  layout->addWidget(this->AlignButton);
  this->Clutch = new QCheckBox("Clutch (move the hands without moving the ribbon)", this);
  layout->addWidget(this->Clutch);
  this->Status = new QLabel("not connected", this);
  this->Status->setObjectName("trackerStatus");
  this->Status->setWordWrap(true);
  layout->addWidget(this->Status);
  layout->addStretch(1);
  this->setConnected(false);

  connect(browse,
    &QPushButton::clicked,
    this,
    [this]()
    {
      const QString file = QFileDialog::getOpenFileName(
        this, "Tracker recording", QString(), "Fastrak recordings (*.fastrak);;All files (*)");
      if (!file.isEmpty())
      {
        this->Device->setText("replay:" + file);
      }
    });
  connect(this->ConnectButton, &QPushButton::clicked, this, &TrackersPanel::connectDevice);
  connect(this->DisconnectButton, &QPushButton::clicked, this, &TrackersPanel::disconnectDevice);
  connect(this->AlignButton,
    &QPushButton::clicked,
    this,
    [this]()
    {
      if (this->Trackers)
        this->Trackers->AlignTo(this->View->ribbonWidget()->GetRibbonRepresentation()->GetRibbon());
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

QString TrackersPanel::deviceSpec() const
{
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
  this->ConnectButton->setEnabled(!connected);
  this->DisconnectButton->setEnabled(connected);
  this->AlignButton->setEnabled(connected);
  this->Clutch->setEnabled(connected);
  this->Device->setEnabled(!connected);
  if (!connected)
  {
    this->Clutch->setChecked(false);
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
}

bool TrackersPanel::connectDevice()
{
  if (!this->Trackers)
    return false;
  bender::TrackerDeviceOptions options;
  options.stations = { this->leftStation(), this->rightStation() };
  options.realtime = true;
  options.simulatorRealtime = true;
  bender::HandMapping hands;
  hands.leftStation = this->leftStation();
  hands.rightStation = this->rightStation();
  bender::TrackerCalibration calibration;
  try
  {
    calibration =
      bender::TrackerCalibration(bender::Quaternion{}, bender::Vec3{}, this->motionScale());
  }
  catch (const std::exception& e)
  {
    this->Session->AddMessage(bender::MessageSeverity::Error, e.what());
    return false;
  }
  if (!this->Trackers->Connect(this->deviceSpec().toStdString(), options, hands, calibration))
  {
    return false;
  }
  this->setConnected(true);
  this->Timer->start();
  return true;
}

void TrackersPanel::disconnectDevice()
{
  this->Timer->stop();
  if (this->Trackers)
    this->Trackers->Disconnect();
  this->setConnected(false);
  this->setStatus("not connected");
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
  if (const auto ribbon = this->Trackers->CurrentRibbon())
  {
    // The widget shows what the hands hold; the live warp already moved in Poll.
    widget->GetRibbonRepresentation()->SetRibbon(*ribbon);
    if (!widget->GetEnabled() && this->Session->HasSurface())
    {
      widget->On();
    }
  }
  // A release started the commit on the worker; its end shows the committed ribbon.
  this->setStatus(QString::fromStdString(this->Trackers->StatusText()));
  if (result.ended)
  {
    this->Timer->stop();
    this->setConnected(false);
  }
  this->View->render();
}
