// The Trackers panel's OpenIGTLink side on the real window (QTest under Xvfb): a loopback
// server streams TRANSFORMs for two tool names and the panel, connected through its own
// widgets, moves the ribbon; a connect to a port that does not answer leaves the event loop
// turning, and so does a connected server that never sends (the view keeps rendering); "Send to
// Slicer" makes a loopback receiver get the session's surface as POLYDATA and a newer one during
// and after a bend; a server that goes away ends the connection and Connect reconnects. A device
// kind registered in the device table appears in the panel's device list and connects like any
// other. A server that sends no button messages (PLUS's default): G and Space held grab and release
// with the hands. Loopback 127.0.0.1 on ephemeral ports only.

#include "AppTestUtilities.h"
#include "BendPanel.h"
#include "BenderSession.h"
#include "GestureController.h"
#include "IgtlProtocol.h"
#include "IgtlSender.h"
#include "MainWindow.h"
#include "SimulatedDevice.h"
#include "TrackerDeviceRegistry.h"
#include "TrackersPanel.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QAbstractItemModel>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QCompleter>
#include <QDir>
#include <QElapsedTimer>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalSpy>
#include <QSpinBox>
#include <QSurfaceFormat>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QTimer>
#include <QVTKOpenGLNativeWidget.h>
#include <QtTest>

#include <vtkCellArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

namespace
{

// A loopback listening socket on an ephemeral port.
int ListenLoopback(int backlog, int& port)
{
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
    ::listen(fd, backlog) != 0)
  {
    return -1;
  }
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  port = ntohs(a.sin_port);
  return fd;
}

// Accepts one client, polling `stop` every 50 ms; -1 when stopped.
int AcceptUnlessStopped(int listenFd, const std::atomic<bool>& stop)
{
  while (!stop)
  {
    pollfd p{ listenFd, POLLIN, 0 };
    if (::poll(&p, 1, 50) > 0)
    {
      return ::accept(listenFd, nullptr, nullptr);
    }
  }
  return -1;
}

bool SendAll(int fd, const std::vector<std::uint8_t>& bytes)
{
  std::size_t sent = 0;
  while (sent < bytes.size())
  {
    const ssize_t n = ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0)
      return false;
    sent += std::size_t(n);
  }
  return true;
}

// A PLUS-like server: streams TRANSFORMs (LPS given, sent in RAS) for two tool names, plus
// one message of a type the device does not read, until stopped or the client goes away.
class TrackerServer
{
public:
  TrackerServer(std::string left, std::string right)
    : Left(std::move(left))
    , Right(std::move(right))
  {
    this->Listen = ListenLoopback(4, this->PortNumber);
    this->Thread = std::thread([this]() { this->Run(); });
  }
  ~TrackerServer()
  {
    this->Stop = true;
    this->Thread.join();
    ::close(this->Listen);
  }
  int Port() const { return this->PortNumber; }
  std::atomic<double> LeftX{ -100.0 };

private:
  void Run()
  {
    const int fd = AcceptUnlessStopped(this->Listen, this->Stop);
    if (fd < 0)
      return;
    SendAll(fd, bender::EncodeIgtlMessage("IMAGE", "Ultrasound", std::vector<std::uint8_t>(16, 0)));
    const bender::Quaternion facing{ 0, 0, 0, 1 }; // the right hand's x towards the left hand
    while (!this->Stop)
    {
      std::vector<std::uint8_t> bytes =
        bender::EncodeIgtlTransformMessage(this->Left, { this->LeftX.load(), 0, 0 }, {});
      const auto right = bender::EncodeIgtlTransformMessage(this->Right, { 100, 0, 0 }, facing);
      bytes.insert(bytes.end(), right.begin(), right.end());
      if (!SendAll(fd, bytes))
        break;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ::close(fd);
  }

  std::string Left, Right;
  int Listen = -1;
  int PortNumber = 0;
  std::atomic<bool> Stop{ false };
  std::thread Thread;
};

// A Slicer-like receiver: accepts one sender and keeps every message it decodes.
class Receiver
{
public:
  Receiver()
  {
    this->Listen = ListenLoopback(4, this->PortNumber);
    this->Thread = std::thread([this]() { this->Run(); });
  }
  ~Receiver()
  {
    this->Stop = true;
    this->Thread.join();
    ::close(this->Listen);
  }
  int Port() const { return this->PortNumber; }
  std::vector<bender::IgtlMessage> Messages(const std::string& type)
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    std::vector<bender::IgtlMessage> out;
    for (const auto& m : this->Received)
      if (m.type == type)
        out.push_back(m);
    return out;
  }

private:
  void Run()
  {
    const int fd = AcceptUnlessStopped(this->Listen, this->Stop);
    if (fd < 0)
      return;
    bender::IgtlStreamDecoder decoder;
    std::uint8_t buffer[65536];
    while (!this->Stop)
    {
      pollfd p{ fd, POLLIN, 0 };
      if (::poll(&p, 1, 50) <= 0)
        continue;
      const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
      if (n <= 0)
        break;
      decoder.Feed(buffer, std::size_t(n));
      while (auto message = decoder.Next())
      {
        std::lock_guard<std::mutex> lock(this->Mutex);
        this->Received.push_back(std::move(*message));
      }
    }
    ::close(fd);
  }

  int Listen = -1;
  int PortNumber = 0;
  std::atomic<bool> Stop{ false };
  std::thread Thread;
  std::mutex Mutex;
  std::vector<bender::IgtlMessage> Received;
};

// NPOINTS, the first field of a POLYDATA body (big-endian uint32, OpenIGTLink v2 POLYDATA).
std::uint32_t PolyDataPointCount(const bender::IgtlMessage& message)
{
  if (message.content.size() < 4)
    return 0;
  const auto* b = message.content.data();
  return (std::uint32_t(b[0]) << 24) | (std::uint32_t(b[1]) << 16) | (std::uint32_t(b[2]) << 8) |
    std::uint32_t(b[3]);
}

bender::RibbonSpec StraightRibbon(double x0, double x1)
{
  bender::RibbonSpec ribbon;
  ribbon.start.position = { x0, 0, 0 };
  ribbon.end.position = { x1, 0, 0 };
  return ribbon;
}

// A device kind of the test's own: the simulator, with counters for the panel.
class PanelDummyDevice : public bender::SimulatedDevice
{
public:
  using SimulatedDevice::SimulatedDevice;
  std::string CountersText() const override { return "panel dummy: counting"; }
};

bender::TrackerDeviceKind PanelDummyKind()
{
  bender::TrackerDeviceKind kind;
  kind.name = "paneldummy";
  kind.syntax = "paneldummy";
  kind.help = "the Trackers panel test's device";
  kind.parse = [](const std::string&, bender::TrackerDeviceSpec&) { return std::string(); };
  kind.create = [](const bender::TrackerDeviceSpec&, const bender::TrackerDeviceOptions& options)
  {
    bender::SimulatedDevice::Options sim;
    sim.stations = options.stations;
    return std::make_unique<PanelDummyDevice>(sim);
  };
  return kind;
}

} // namespace

class IgtlAppTest : public QObject
{
  Q_OBJECT

private:
  QTemporaryDir Folder;
  std::unique_ptr<MainWindow> Window;
  std::unique_ptr<TrackerServer> Server;

  TrackersPanel* panel() { return this->Window->trackersPanel(); }
  template<typename T>
  T* child(const char* name)
  {
    T* widget = this->panel()->findChild<T*>(name);
    if (!widget)
      qFatal("no widget %s in the Trackers panel", name);
    return widget;
  }
  QString artefact(const QString& name)
  {
    QDir().mkpath(BENDER_ARTIFACT_DIR);
    return QString(BENDER_ARTIFACT_DIR) + "/" + name;
  }
  // A click on the check box's indicator (the box spans the panel's width).
  void clickToggle()
  {
    auto* toggle = this->child<QCheckBox>("sendToSlicer");
    QTest::mouseClick(toggle, Qt::LeftButton, {}, QPoint(8, toggle->height() / 2));
  }
  void fillIgtl(int port)
  {
    this->child<QComboBox>("trackerKind")->setCurrentIndex(1);
    this->child<QLineEdit>("igtlHost")->setText("127.0.0.1");
    this->child<QSpinBox>("igtlPort")->setValue(port);
    this->child<QLineEdit>("igtlTool1")->setText("LeftToolToTracker");
    this->child<QLineEdit>("igtlTool2")->setText("RightToolToTracker");
  }

private slots:
  void initTestCase()
  {
    QVERIFY(this->Folder.isValid());
    bender::RegisterTrackerDeviceKind(PanelDummyKind()); // before the panel lists the kinds
    this->Window = std::make_unique<MainWindow>(bendertest::TestWindowOptions(this->Folder.path()));
    QVERIFY(bendertest::ShowTestWindow(*this->Window, false));
    // The lumen guard on: the tube ends where the bends' ribbons end (x = 50), so they turn
    // its end whole (a ribbon ending mid-tube would shear the tube beyond it: a waist the
    // guard holds).
    QVERIFY(this->Window->session().GetLumenGuard().enabled);
    auto* panels = this->Window->findChild<QTabWidget*>("panels");
    QVERIFY(panels);
    panels->setCurrentWidget(this->panel());
    bender::BenderSession& session = this->Window->session();
    QVERIFY(session.SetSurface(bendertest::Tube(-150, 50, 10, 41, 16), "tube"));
    bender::WarpParameters parameters = session.GetParameters();
    parameters.radius = 30;
    QVERIFY(session.SetParameters(parameters));
  }

  void cleanupTestCase()
  {
    this->Window->close();
    this->Window.reset();
    this->Server.reset();
  }

  void connectingToASilentPortKeepsTheEventLoopTurning()
  {
    // A listener with a full backlog that never accepts: the kernel drops the device's SYNs,
    // so its connect waits for its timeout (3 s).
    int port = 0;
    const int silent = ListenLoopback(0, port);
    QVERIFY(silent >= 0);
    std::vector<int> fillers;
    for (int i = 0; i < 3; ++i)
    {
      const int c = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
      sockaddr_in a{};
      a.sin_family = AF_INET;
      a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
      a.sin_port = htons(std::uint16_t(port));
      ::connect(c, reinterpret_cast<sockaddr*>(&a), sizeof a);
      fillers.push_back(c);
    }
    this->fillIgtl(port);
    QSignalSpy finished(this->panel(), &TrackersPanel::connectFinished);
    int turnsWhileConnecting = 0;
    QTimer ticker;
    ticker.setInterval(0);
    connect(&ticker,
      &QTimer::timeout,
      [this, &turnsWhileConnecting]()
      {
        if (this->panel()->isConnecting())
          ++turnsWhileConnecting;
      });
    ticker.start();
    QTest::mouseClick(this->child<QPushButton>("trackerConnect"), Qt::LeftButton);
    QVERIFY(this->panel()->isConnecting());
    QVERIFY(!this->child<QPushButton>("trackerConnect")->isEnabled());
    QVERIFY(finished.wait(20000));
    ticker.stop();
    QCOMPARE(finished.last().first().toBool(), false);
    QVERIFY(!this->Window->trackers().IsConnected());
    // The GUI thread ran its timers while the device waited for the host.
    QVERIFY(turnsWhileConnecting > 10);
    QVERIFY(this->child<QLabel>("trackerStatus")->text().contains(QString::number(port)));
    QVERIFY(this->child<QPushButton>("trackerConnect")->isEnabled());
    for (int c : fillers)
      ::close(c);
    ::close(silent);
  }

  void aConnectedPeerThatNeverAnswersLeavesTheWindowDrawing()
  {
    // A server that accepts and then sends nothing (issue 25): the panel connects, the device
    // waits for bytes on its reader thread, and the GUI thread keeps rendering the 3D view;
    // Disconnect returns at once.
    int port = 0;
    const int listener = ListenLoopback(1, port);
    QVERIFY(listener >= 0);
    std::atomic<bool> stop{ false };
    std::thread server(
      [listener, &stop]()
      {
        const int fd = AcceptUnlessStopped(listener, stop);
        while (!stop)
          std::this_thread::sleep_for(std::chrono::milliseconds(10));
        if (fd >= 0)
          ::close(fd);
      });
    this->fillIgtl(port);
    QSignalSpy finished(this->panel(), &TrackersPanel::connectFinished);
    QTest::mouseClick(this->child<QPushButton>("trackerConnect"), Qt::LeftButton);
    QVERIFY(finished.wait(20000));
    QCOMPARE(finished.last().first().toBool(), true);
    auto* view = this->Window->findChild<QVTKOpenGLNativeWidget*>();
    QVERIFY(view);
    int renders = 0;
    QTimer ticker;
    ticker.setInterval(10);
    connect(&ticker,
      &QTimer::timeout,
      [view, &renders]()
      {
        view->renderWindow()->Render();
        ++renders;
      });
    ticker.start();
    QTest::qWait(1000);
    ticker.stop();
    QVERIFY(this->Window->trackers().IsConnected());
    QVERIFY2(renders > 10, qPrintable(QString("%1 renders in 1 s").arg(renders)));
    QElapsedTimer disconnecting;
    disconnecting.start();
    QTest::mouseClick(this->child<QPushButton>("trackerDisconnect"), Qt::LeftButton);
    QVERIFY(!this->Window->trackers().IsConnected());
    QVERIFY(disconnecting.elapsed() < 2000);
    stop = true;
    server.join();
    ::close(listener);
  }

  void igtlServerDrivesTheRibbon()
  {
    this->Server = std::make_unique<TrackerServer>("LeftToolToTracker", "RightToolToTracker");
    this->fillIgtl(this->Server->Port());
    QSignalSpy finished(this->panel(), &TrackersPanel::connectFinished);
    QTest::mouseClick(this->child<QPushButton>("trackerConnect"), Qt::LeftButton);
    QVERIFY(finished.wait(20000));
    QCOMPARE(finished.last().first().toBool(), true);
    QVERIFY(this->Window->trackers().IsConnected());
    QVERIFY(this->Window->trackers().GetDevice()->Name().find(
              ":" + std::to_string(this->Server->Port())) != std::string::npos);

    // Both hands seen: the widget shows the hands' ribbon.
    auto* representation = this->Window->ribbonWidget()->GetRibbonRepresentation();
    QTRY_VERIFY_WITH_TIMEOUT(this->Window->trackers().CurrentRibbon().has_value(), 20000);
    QTRY_VERIFY_WITH_TIMEOUT(this->Window->ribbonWidget()->GetEnabled(), 20000);
    const double before = representation->GetRibbon().start.position.x;
    // The left hand moves 20 mm along LPS x: the ribbon's start follows (motion scale 1).
    this->Server->LeftX = -80.0;
    QTRY_VERIFY_WITH_TIMEOUT(
      std::abs(representation->GetRibbon().start.position.x - (before + 20.0)) < 1e-3, 20000);
    QCOMPARE(representation->GetRibbon().end.position.x,
      this->Window->trackers().CurrentRibbon()->end.position.x);

    // The panel shows the names seen and the skipped IMAGE.
    QTRY_VERIFY_WITH_TIMEOUT(
      this->child<QLabel>("igtlCounters")->text().contains("LeftToolToTracker"), 20000);
    const QString counters = this->child<QLabel>("igtlCounters")->text();
    QVERIFY(counters.contains("RightToolToTracker"));
    QVERIFY2(counters.contains("skipped messages 1"), qPrintable(counters));
    QVERIFY(!this->child<QComboBox>("trackerKind")->isEnabled());
    QVERIFY(!this->child<QLineEdit>("igtlHost")->isEnabled());
  }

  void sendToSlicerSendsTheSurfaceAndTheBend()
  {
    bender::BenderSession& session = this->Window->session();
    Receiver slicer;
    this->child<QLineEdit>("slicerHost")->setText("127.0.0.1");
    this->child<QSpinBox>("slicerPort")->setValue(slicer.Port());
    this->clickToggle();
    QVERIFY(this->panel()->isSendingToSlicer());
    QTRY_VERIFY_WITH_TIMEOUT(slicer.Messages("POLYDATA").size() >= 1, 20000);
    const auto first = slicer.Messages("POLYDATA").front();
    QCOMPARE(first.deviceName, std::string("BenderVessel"));
    QCOMPARE(std::int64_t(PolyDataPointCount(first)),
      std::int64_t(session.GetSurface()->GetNumberOfPoints()));

    // A bend: live frames while grabbed, then the committed shape after the release.
    QVERIFY(session.Grab(StraightRibbon(-50, 50)));
    bender::RibbonSpec bent = StraightRibbon(-50, 50);
    bent.end.position = { 45, 20, 0 };
    QVERIFY(session.MoveFinal(bent));
    QTRY_VERIFY_WITH_TIMEOUT(slicer.Messages("POLYDATA").size() >= 2, 20000);
    const auto live = slicer.Messages("POLYDATA").back();
    QVERIFY(live.content != first.content);
    QTRY_VERIFY_WITH_TIMEOUT(!slicer.Messages("TRANSFORM").empty(), 20000);
    bool sawStart = false, sawEnd = false;
    for (const auto& m : slicer.Messages("TRANSFORM"))
    {
      sawStart |= m.deviceName == "BenderRibbonStart";
      sawEnd |= m.deviceName == "BenderRibbonEnd";
    }
    QVERIFY(sawStart && sawEnd);
    const std::size_t beforeRelease = slicer.Messages("POLYDATA").size();
    QVERIFY(session.Release());
    QCOMPARE(session.GetHistoryPosition(), std::size_t(1));
    QTRY_VERIFY_WITH_TIMEOUT(slicer.Messages("POLYDATA").size() > beforeRelease, 20000);
    const auto committed = slicer.Messages("POLYDATA").back();
    QVERIFY(committed.content != first.content);
    QCOMPARE(std::int64_t(PolyDataPointCount(committed)),
      std::int64_t(session.GetSurface()->GetNumberOfPoints()));
    // Every surface sent arrived (the panel's counter catches up at its next refresh).
    const QString sent = QString("connected to 127.0.0.1:%1: %2 surfaces")
                           .arg(slicer.Port())
                           .arg(slicer.Messages("POLYDATA").size());
    QTRY_VERIFY_WITH_TIMEOUT(this->child<QLabel>("slicerCounters")->text().contains(sent), 20000);

    // The panel with both sides of OpenIGTLink in use (docs/screenshots/trackers-openigtlink.png).
    QVERIFY(this->panel()->grab().save(this->artefact("trackers-openigtlink.png")));

    this->clickToggle();
    QVERIFY(!this->panel()->isSendingToSlicer());
    QVERIFY(this->child<QLineEdit>("slicerHost")->isEnabled());
  }

  void aSendErrorSwitchesTheToggleOff()
  {
    // Nobody listens on the port: one error line, the toggle goes off, and it can be retried.
    int port = 0;
    const int closed = ListenLoopback(1, port);
    ::close(closed);
    this->child<QSpinBox>("slicerPort")->setValue(port);
    auto* toggle = this->child<QCheckBox>("sendToSlicer");
    const std::size_t messages = this->Window->session().GetMessages().size();
    this->clickToggle();
    QTRY_VERIFY_WITH_TIMEOUT(!toggle->isChecked(), 20000);
    QVERIFY(!this->panel()->isSendingToSlicer());
    const auto& all = this->Window->session().GetMessages();
    QVERIFY(all.size() > messages);
    QVERIFY(all.back().text.rfind("Send to Slicer: ", 0) == 0);
    QVERIFY(all.back().text.find(std::to_string(port)) != std::string::npos);
    QVERIFY(toggle->isEnabled());
  }

  void aClosedServerDisconnectsAndConnectReconnects()
  {
    // The server goes away: the panel ends the connection, the committed shape stays, and
    // Connect reconnects to a server that is back (here on a new port).
    QVERIFY(this->Window->trackers().IsConnected());
    const std::size_t position = this->Window->session().GetHistoryPosition();
    this->Server.reset();
    QTRY_VERIFY_WITH_TIMEOUT(!this->Window->trackers().IsConnected(), 20000);
    QTRY_VERIFY_WITH_TIMEOUT(this->child<QPushButton>("trackerConnect")->isEnabled(), 20000);
    QVERIFY(!this->child<QPushButton>("trackerDisconnect")->isEnabled());
    QCOMPARE(this->Window->session().GetHistoryPosition(), position);
    QVERIFY(this->Window->session().GetState() != bender::GrabState::Grabbed);

    this->Server = std::make_unique<TrackerServer>("LeftToolToTracker", "RightToolToTracker");
    this->child<QSpinBox>("igtlPort")->setValue(this->Server->Port());
    QSignalSpy finished(this->panel(), &TrackersPanel::connectFinished);
    QTest::mouseClick(this->child<QPushButton>("trackerConnect"), Qt::LeftButton);
    QVERIFY(finished.wait(20000));
    QCOMPARE(finished.last().first().toBool(), true);
    QTRY_VERIFY_WITH_TIMEOUT(this->Window->trackers().CurrentRibbon().has_value(), 20000);

    QTest::mouseClick(this->child<QPushButton>("trackerDisconnect"), Qt::LeftButton);
    QVERIFY(!this->Window->trackers().IsConnected());
    QVERIFY(this->child<QComboBox>("trackerKind")->isEnabled());
    QVERIFY(this->child<QLineEdit>("igtlHost")->isEnabled());
  }

  void aRegisteredDeviceKindIsInThePanelsListAndConnects()
  {
    this->child<QComboBox>("trackerKind")->setCurrentIndex(0);
    auto* device = this->child<QLineEdit>("trackerDevice");
    QVERIFY(device->isEnabled());
    QVERIFY(device->completer());
    QStringList listed;
    const QAbstractItemModel* model = device->completer()->model();
    for (int row = 0; row < model->rowCount(); ++row)
      listed << model->index(row, 0).data().toString();
    // Every kind of the table, the registered one included, in the table's order.
    QStringList expected;
    for (const bender::TrackerDeviceKind& kind : bender::TrackerDeviceKinds())
      expected << QString::fromStdString(kind.name);
    QCOMPARE(listed.size(), expected.size());
    for (int i = 0; i < expected.size(); ++i)
      QVERIFY2(listed[i].startsWith(expected[i]), qPrintable(listed.join(' ')));
    QVERIFY(listed.contains("paneldummy"));
    QVERIFY(device->toolTip().contains("paneldummy"));

    // Connected through the panel's own button, its counters shown by the panel.
    this->panel()->setDeviceSpec("paneldummy");
    QSignalSpy finished(this->panel(), &TrackersPanel::connectFinished);
    QTest::mouseClick(this->child<QPushButton>("trackerConnect"), Qt::LeftButton);
    QCOMPARE(finished.count(), 1);
    QCOMPARE(finished.last().first().toBool(), true);
    QVERIFY(this->Window->trackers().IsConnected());
    QTRY_COMPARE_WITH_TIMEOUT(
      this->child<QLabel>("igtlCounters")->text(), QString("panel dummy: counting"), 5000);
    QVERIFY(this->child<QLabel>("igtlCounters")->isVisible());
    QTest::mouseClick(this->child<QPushButton>("trackerDisconnect"), Qt::LeftButton);
    QVERIFY(!this->Window->trackers().IsConnected());
    QVERIFY(!this->child<QLabel>("igtlCounters")->isVisible());
    this->panel()->setDeviceSpec("sim");
  }

  void withoutButtonsGAndSpaceGrabWithTheHands()
  {
    // PLUS sends no button messages (issue 22, item 9): with a ribbon placed the hands are
    // anchored to it; G on the view grabs with the hands, the ribbon's start follows the left
    // hand, G again commits that warp. Holding Space (what a foot pedal sends) does the same,
    // released on letting go. The panel says which keys these are.
    bender::BenderSession& session = this->Window->session();
    QVERIFY(this->child<QLabel>("trackerGrabKeys")->text().contains("hold Space"));
    QVERIFY(this->child<QLabel>("trackerGrabKeys")->text().contains("<b>G</b>"));
    const bender::RibbonSpec placed = StraightRibbon(-50, 50);
    this->Window->gesture()->showRibbon(placed, 10.0);
    QVERIFY(session.GetRibbon().has_value());
    this->Server = std::make_unique<TrackerServer>("LeftToolToTracker", "RightToolToTracker");
    this->fillIgtl(this->Server->Port());
    QSignalSpy finished(this->panel(), &TrackersPanel::connectFinished);
    QTest::mouseClick(this->child<QPushButton>("trackerConnect"), Qt::LeftButton);
    QVERIFY(finished.wait(20000));
    QCOMPARE(finished.last().first().toBool(), true);
    QVERIFY(this->Window->trackers().IsRelative());
    QTRY_VERIFY_WITH_TIMEOUT(this->Window->trackers().MappedHands().has_value(), 20000);
    auto* representation = this->Window->ribbonWidget()->GetRibbonRepresentation();
    QWidget* view = this->Window->view();
    // The keys go to the active window, as a user's do.
    this->Window->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(this->Window.get()));
    const auto startX = [&]() { return representation->GetRibbon().start.position.x; };

    // G: the hands hold the ribbon; the left hand moves 20 mm along LPS x, the start follows
    // (auto scale: the hands' 200 mm span is the ribbon's 100 mm, so by 10 mm).
    std::size_t position = session.GetHistoryPosition();
    view->setFocus();
    QTest::keyClick(view, Qt::Key_G);
    QVERIFY2(
      session.GetState() == bender::GrabState::Grabbed, session.GetMessages().back().text.c_str());
    QVERIFY(this->Window->trackers().HandsPressed());
    this->Server->LeftX = -80.0;
    QTRY_VERIFY_WITH_TIMEOUT(std::abs(startX() - (placed.start.position.x + 10.0)) < 1e-3, 20000);
    QVERIFY(std::abs(session.GetFinalRibbon().start.position.x - startX()) < 1e-9);
    QTest::keyClick(view, Qt::Key_G);
    QVERIFY(this->Window->waitUntilIdle(60000));
    QCOMPARE(session.GetHistoryPosition(), position + 1);
    QVERIFY(!this->Window->trackers().HandsPressed());
    const bender::WarpSpec first = session.GetPlan().warps.back();
    QVERIFY(bender::Distance(first.initial.start.position, placed.start.position) < 1e-9);
    QVERIFY(std::abs(first.final.start.position.x - (placed.start.position.x + 10.0)) < 1e-3);
    // Released: the ribbon stays where the hands left it while they move freely.
    this->Server->LeftX = -100.0;
    QTest::qWait(300);
    QVERIFY(std::abs(startX() - first.final.start.position.x) < 1e-9);

    // Space held (a foot pedal): the hands, back at -100, hold the ribbon from where it is
    // (anchored again: 1 mm of hand motion is now the 90 mm ribbon over the 200 mm span); the
    // left hand moves 20 mm back, the start follows; letting go commits.
    position = session.GetHistoryPosition();
    const double scale =
      bender::Distance(first.final.start.position, first.final.end.position) / 200.0;
    const double expected = first.final.start.position.x - 20.0 * scale;
    QTest::simulateEvent(view, true, Qt::Key_Space, Qt::NoModifier, " ", false);
    QCOMPARE(session.GetState(), bender::GrabState::Grabbed);
    QVERIFY(this->Window->trackers().HandsPressed());
    this->Server->LeftX = -120.0;
    QTRY_VERIFY_WITH_TIMEOUT(std::abs(startX() - expected) < 1e-3, 20000);
    QTest::simulateEvent(view, false, Qt::Key_Space, Qt::NoModifier, " ", false);
    QVERIFY(this->Window->waitUntilIdle(60000));
    QCOMPARE(session.GetHistoryPosition(), position + 1);
    QVERIFY(std::abs(session.GetPlan().warps.back().final.start.position.x - expected) < 1e-3);
    QTest::mouseClick(this->child<QPushButton>("trackerDisconnect"), Qt::LeftButton);
    this->Server.reset();
  }
};

int main(int argc, char** argv)
{
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  QCoreApplication::setOrganizationName("BenderTests");
  QCoreApplication::setApplicationName("IgtlAppTest");
  IgtlAppTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "IgtlAppTest.moc"
