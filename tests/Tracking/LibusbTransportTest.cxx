// LibusbTransport through a fake UsbBackend: descriptor matching, the firmware-missing
// product id, flush, packet handling, zero-length packets, timeouts and disconnects.
#include "LibusbTransport.h"
#include "FastrakDevice.h"
#include "TrackerCommand.h"
#include "TrackingTestUtilities.h"

#include <sstream>
#include <thread>

namespace bender::test
{
namespace
{

struct FakeUsb
{
  struct Transfer
  {
    std::uint8_t endpoint;
    Bytes data;
  };
  std::mutex mutex;
  std::vector<UsbDeviceInfo> devices;
  std::deque<Bytes> inPackets; ///< each one IN transfer; an empty one times out
  std::vector<Transfer> outTransfers;
  std::vector<std::uint8_t> inEndpointsUsed;
  std::vector<int> claimed;
  bool unplugged = false;
  bool denyAccess = false;
  int stallsLeft = 0;
  Bytes pollReply; ///< queued as one packet when 'P' is written
};

class FakeHandle : public UsbDeviceHandle
{
public:
  explicit FakeHandle(std::shared_ptr<FakeUsb> usb)
    : Usb(std::move(usb))
  {
  }
  void ClaimInterface(int number) override { this->Usb->claimed.push_back(number); }
  void ReleaseInterface(int) override {}
  UsbTransferResult BulkTransfer(std::uint8_t endpoint,
    std::uint8_t* data,
    int length,
    unsigned timeoutMs) override
  {
    std::unique_lock<std::mutex> lock(this->Usb->mutex);
    if (this->Usb->unplugged)
    {
      return { UsbStatus::NoDevice, 0, {} };
    }
    if (endpoint & 0x80)
    {
      this->Usb->inEndpointsUsed.push_back(endpoint);
      if (this->Usb->stallsLeft > 0)
      {
        --this->Usb->stallsLeft;
        return { UsbStatus::Pipe, 0, {} };
      }
      if (this->Usb->inPackets.empty())
      {
        lock.unlock();
        std::this_thread::sleep_for(std::chrono::milliseconds(std::min(timeoutMs, 5u)));
        return { UsbStatus::Timeout, 0, {} };
      }
      Bytes packet = this->Usb->inPackets.front();
      this->Usb->inPackets.pop_front();
      if (packet.size() > std::size_t(length))
      {
        return { UsbStatus::Overflow, 0, {} };
      }
      std::copy(packet.begin(), packet.end(), data);
      return { packet.empty() ? UsbStatus::Timeout : UsbStatus::Ok, int(packet.size()), {} };
    }
    this->Usb->outTransfers.push_back({ endpoint, Bytes(data, data + length) });
    if (length == 1 && data[0] == 'P' && !this->Usb->pollReply.empty())
    {
      this->Usb->inPackets.push_back(this->Usb->pollReply);
    }
    return { UsbStatus::Ok, length, {} };
  }
  void ClearHalt(std::uint8_t) override {}

private:
  std::shared_ptr<FakeUsb> Usb;
};

class FakeBackend : public UsbBackend
{
public:
  explicit FakeBackend(std::shared_ptr<FakeUsb> usb)
    : Usb(std::move(usb))
  {
  }
  std::vector<UsbDeviceInfo> ListDevices(std::uint16_t vendorId) override
  {
    std::lock_guard<std::mutex> lock(this->Usb->mutex);
    std::vector<UsbDeviceInfo> found;
    for (const UsbDeviceInfo& d : this->Usb->devices)
    {
      if (d.vendorId == vendorId && !this->Usb->unplugged)
      {
        found.push_back(d);
      }
    }
    return found;
  }
  std::unique_ptr<UsbDeviceHandle> Open(const UsbDeviceInfo& device) override
  {
    if (this->Usb->denyAccess)
    {
      throw DeviceAccessError("USB fake: permission denied");
    }
    (void)device;
    return std::make_unique<FakeHandle>(this->Usb);
  }

private:
  std::shared_ptr<FakeUsb> Usb;
};

// A Fastrak whose bulk endpoints are not the first ones and not at the usual addresses:
// interface 0 has only an interrupt endpoint, interface 1 has bulk IN 0x86 and OUT 0x04.
UsbDeviceInfo Fastrak(std::uint16_t product, std::uint16_t outPacket = 64)
{
  UsbDeviceInfo d;
  d.vendorId = 0x0F44;
  d.productId = product;
  d.bus = 3;
  d.address = 7;
  d.interfaces.push_back({ 0, { { 0x81, 0x03, 8 } } });
  d.interfaces.push_back(
    { 1, { { 0x02, 0x03, 8 }, { 0x86, 0x02, 64 }, { 0x04, 0x02, outPacket } } });
  return d;
}

std::shared_ptr<FakeUsb> MakeUsb(std::vector<UsbDeviceInfo> devices)
{
  auto usb = std::make_shared<FakeUsb>();
  usb->devices = std::move(devices);
  return usb;
}

TEST(LibusbTransport, NoDeviceGivesAClearMessage)
{
  auto usb = MakeUsb({});
  try
  {
    LibusbTransport transport(std::make_shared<FakeBackend>(usb));
    FAIL() << "opened a device that is not there";
  }
  catch (const DeviceNotFoundError& e)
  {
    EXPECT_NE(std::string(e.what()).find("no Polhemus Fastrak found on USB (vendor 0x0f44)"),
      std::string::npos)
      << e.what();
  }
}

TEST(LibusbTransport, OtherVendorsAndProductsAreNotTaken)
{
  UsbDeviceInfo liberty = Fastrak(0xff20);
  UsbDeviceInfo other = Fastrak(0x0002);
  other.vendorId = 0x1234;
  auto usb = MakeUsb({ liberty, other });
  EXPECT_THROW(LibusbTransport(std::make_shared<FakeBackend>(usb)), DeviceNotFoundError);
}

TEST(LibusbTransport, FirmwareMissingProductIdIsExplained)
{
  auto usb = MakeUsb({ Fastrak(0x0001) });
  try
  {
    LibusbTransport transport(std::make_shared<FakeBackend>(usb));
    FAIL() << "opened a Fastrak without firmware";
  }
  catch (const FirmwareMissingError& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("0f44:0001"), std::string::npos) << what;
    EXPECT_NE(what.find("firmware"), std::string::npos) << what;
    EXPECT_NE(what.find("resources/fastrak"), std::string::npos) << what;
  }
}

TEST(LibusbTransport, EndpointsComeFromTheDescriptorsAndStaleInputIsFlushed)
{
  for (std::uint16_t product : { 0x0002, 0x0003 })
  {
    auto usb = MakeUsb({ Fastrak(0x0001), Fastrak(product) });
    usb->inPackets = { Bytes{ 'o', 'l', 'd' }, Bytes(64, 'x') };
    LibusbTransport transport(std::make_shared<FakeBackend>(usb));
    EXPECT_EQ(transport.InEndpoint(), 0x86);
    EXPECT_EQ(transport.OutEndpoint(), 0x04);
    EXPECT_EQ(transport.Interface(), 1);
    EXPECT_EQ(usb->claimed, std::vector<int>{ 1 });
    EXPECT_TRUE(usb->inPackets.empty()) << "stale packets not flushed on open";
    std::uint8_t buffer[16];
    EXPECT_EQ(transport.Read(buffer, sizeof buffer, std::chrono::milliseconds(10)), 0u);
    for (std::uint8_t ep : usb->inEndpointsUsed)
    {
      EXPECT_EQ(ep, 0x86);
    }
  }
}

TEST(LibusbTransport, NoBulkEndpointsIsAnError)
{
  UsbDeviceInfo d = Fastrak(0x0002);
  d.interfaces.pop_back();
  auto usb = MakeUsb({ d });
  EXPECT_THROW(LibusbTransport(std::make_shared<FakeBackend>(usb)), TransportError);
}

TEST(LibusbTransport, AccessDeniedIsReported)
{
  auto usb = MakeUsb({ Fastrak(0x0002) });
  usb->denyAccess = true;
  EXPECT_THROW(LibusbTransport(std::make_shared<FakeBackend>(usb)), DeviceAccessError);
}

TEST(LibusbTransport, ReadsHandOutPacketsInPiecesAndTimeOut)
{
  auto usb = MakeUsb({ Fastrak(0x0002) });
  LibusbTransport transport(std::make_shared<FakeBackend>(usb));
  usb->inPackets = { Bytes{ 1, 2, 3, 4, 5 }, Bytes{}, Bytes{ 6 } };
  std::uint8_t buffer[3];
  ASSERT_EQ(transport.Read(buffer, 3, std::chrono::milliseconds(10)), 3u);
  EXPECT_EQ(buffer[2], 3);
  ASSERT_EQ(transport.Read(buffer, 3, std::chrono::milliseconds(10)), 2u);
  EXPECT_EQ(buffer[1], 5);
  EXPECT_EQ(transport.Read(buffer, 3, std::chrono::milliseconds(10)), 0u); // timed out
  ASSERT_EQ(transport.Read(buffer, 3, std::chrono::milliseconds(10)), 1u);
  EXPECT_EQ(buffer[0], 6);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(transport.Read(buffer, 3, std::chrono::milliseconds(10)), 0u);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
}

TEST(LibusbTransport, StallIsClearedOnce)
{
  auto usb = MakeUsb({ Fastrak(0x0002) });
  LibusbTransport transport(std::make_shared<FakeBackend>(usb));
  usb->inPackets = { Bytes{ 9 } };
  usb->stallsLeft = 1;
  std::uint8_t b = 0;
  EXPECT_EQ(transport.Read(&b, 1, std::chrono::milliseconds(10)), 1u);
  usb->stallsLeft = 2;
  EXPECT_THROW(transport.Read(&b, 1, std::chrono::milliseconds(10)), TransportError);
}

TEST(LibusbTransport, ZeroLengthPacketEndsAWriteOnAPacketBoundary)
{
  auto usb = MakeUsb({ Fastrak(0x0002, 8) });
  LibusbTransport transport(std::make_shared<FakeBackend>(usb));
  transport.WriteText("O1,2,11,16,0\r", std::chrono::milliseconds(100)); // 13 bytes
  ASSERT_EQ(usb->outTransfers.size(), 1u);
  EXPECT_EQ(usb->outTransfers[0].endpoint, 0x04);
  transport.WriteText("l1,1\rl2,1\r", std::chrono::milliseconds(100)); // 10 bytes
  EXPECT_EQ(usb->outTransfers.size(), 2u);
  transport.WriteText("12345678", std::chrono::milliseconds(100)); // exactly one packet
  ASSERT_EQ(usb->outTransfers.size(), 4u);
  EXPECT_EQ(usb->outTransfers[2].data.size(), 8u);
  EXPECT_TRUE(usb->outTransfers[3].data.empty()) << "no zero-length packet";
}

TEST(LibusbTransport, UnplugRaisesDisconnected)
{
  auto usb = MakeUsb({ Fastrak(0x0002) });
  LibusbTransport transport(std::make_shared<FakeBackend>(usb));
  usb->unplugged = true;
  std::uint8_t b;
  EXPECT_THROW(transport.Read(&b, 1, std::chrono::milliseconds(10)), DeviceDisconnectedError);
  EXPECT_THROW(transport.WriteText("c", std::chrono::milliseconds(10)), DeviceDisconnectedError);
  transport.Close();
  EXPECT_THROW(transport.Read(&b, 1, std::chrono::milliseconds(10)), TransportError);
}

// The whole device over fake USB: configuration commands, records split across packets,
// an unplug mid-stream raising Disconnected, and a reopen after replugging.
TEST(LibusbTransport, FastrakDeviceStreamsDisconnectsAndReopens)
{
  auto usb = MakeUsb({ Fastrak(0x0002) });
  const std::vector<TrackerPose> poses = SamplePoses();
  usb->pollReply = Encode({ poses[0], poses[1] }, FastrakFormat::Binary);
  auto backend = std::make_shared<FakeBackend>(usb);
  FastrakDevice device("usb", [backend] { return std::make_unique<LibusbTransport>(backend); });
  device.EnablePoseQueue(100, false);
  device.Open();
  std::string written;
  for (const auto& t : usb->outTransfers)
  {
    written.append(t.data.begin(), t.data.end());
  }
  for (const char* command : { "c",
         "u",
         "f",
         "l1,1\r",
         "l2,1\r",
         "l3,0\r",
         "l4,0\r",
         "H1,1,0,0\r",
         "O1,2,11,16,0\r",
         "O2,2,11,16,0\r",
         "P" })
  {
    EXPECT_NE(written.find(command), std::string::npos) << "missing command " << command;
  }
  EXPECT_LT(written.find("O2,2,11,16,0\r"), written.find("P"));
  ASSERT_TRUE(device.Statistics().latencyMs.has_value());

  device.Start();
  EXPECT_EQ(usb->outTransfers.back().data, Bytes{ 'C' });
  const Bytes stream = Encode(poses, FastrakFormat::Binary);
  {
    std::lock_guard<std::mutex> lock(usb->mutex);
    // 136 bytes in packets of 50, 50 and 36: records straddle packets.
    usb->inPackets.push_back(Bytes(stream.begin(), stream.begin() + 50));
    usb->inPackets.push_back(Bytes(stream.begin() + 50, stream.begin() + 100));
    usb->inPackets.push_back(Bytes(stream.begin() + 100, stream.end()));
  }
  std::vector<TrackerPose> got;
  std::vector<TrackerEvent> buttonEvents;
  for (int i = 0; i < 200 && got.size() < poses.size(); ++i)
  {
    device.WaitForActivity(std::chrono::milliseconds(10));
    for (const TrackerEvent& e : device.TakeEvents())
    {
      buttonEvents.push_back(e);
    }
    for (const TrackerPose& p : device.TakePoses())
    {
      got.push_back(p);
    }
  }
  for (const TrackerEvent& e : device.TakeEvents())
  {
    buttonEvents.push_back(e);
  }
  // Station 2 pressed then released; station 1 pressed.
  ASSERT_EQ(buttonEvents.size(), 3u);
  EXPECT_EQ(buttonEvents[0].type, TrackerEventType::Grab);
  EXPECT_EQ(buttonEvents[0].station, 2);
  EXPECT_EQ(buttonEvents[1].type, TrackerEventType::Grab);
  EXPECT_EQ(buttonEvents[1].station, 1);
  EXPECT_EQ(buttonEvents[2].type, TrackerEventType::Release);
  EXPECT_EQ(buttonEvents[2].station, 2);
  ASSERT_EQ(got.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    ExpectPoseEq(ExpectedBinary(poses[i]), got[i]);
  }
  ASSERT_TRUE(device.LatestPose(2).has_value());
  ExpectPoseEq(ExpectedBinary(poses[3]), *device.LatestPose(2));

  {
    std::lock_guard<std::mutex> lock(usb->mutex);
    usb->unplugged = true;
  }
  std::vector<TrackerEvent> events;
  for (int i = 0; i < 200; ++i)
  {
    device.WaitForActivity(std::chrono::milliseconds(10));
    for (const TrackerEvent& e : device.TakeEvents())
    {
      events.push_back(e);
    }
    if (!events.empty() && events.back().type == TrackerEventType::Disconnected)
    {
      break;
    }
  }
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().type, TrackerEventType::Disconnected);
  EXPECT_NE(events.back().message.find("unplugged"), std::string::npos);
  EXPECT_FALSE(device.IsStreaming());

  // Reopening while it is still gone fails cleanly; after replugging it works.
  device.Close();
  EXPECT_THROW(device.Open(), DeviceNotFoundError);
  {
    std::lock_guard<std::mutex> lock(usb->mutex);
    usb->unplugged = false;
  }
  device.Open();
  device.Start();
  EXPECT_TRUE(device.IsStreaming());
  device.Close();
  EXPECT_FALSE(device.IsOpen());
}

TEST(LibusbTransport, SilentUnitFailsFastInsteadOfHanging)
{
  auto usb = MakeUsb({ Fastrak(0x0002) });
  auto backend = std::make_shared<FakeBackend>(usb);
  FastrakOptions options;
  options.replyTimeout = std::chrono::milliseconds(100);
  FastrakDevice device(
    "usb", [backend] { return std::make_unique<LibusbTransport>(backend); }, options);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW(device.Open(), DeviceNotRespondingError);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
  EXPECT_FALSE(device.IsOpen());
}

TEST(TrackerCli, UsbWithoutADeviceExitsNonZeroWithAClearMessage)
{
  std::ostringstream out, err;
  const int rc =
    RunTrackerCli({ "--device", "usb" }, out, err, std::make_shared<FakeBackend>(MakeUsb({})));
  EXPECT_EQ(rc, 1);
  EXPECT_TRUE(out.str().empty());
  EXPECT_NE(err.str().find("no Polhemus Fastrak found on USB (vendor 0x0f44)"), std::string::npos)
    << err.str();
}

TEST(TrackerCli, UsbWithRealLibusbAndNoDeviceFailsFast)
{
  // This machine has no Fastrak: whatever libusb finds (or fails to initialise), the
  // command must fail with a message and not hang.
  std::ostringstream out, err;
  const auto start = std::chrono::steady_clock::now();
  const int rc = RunTrackerCli({ "--device", "usb", "--count", "1" }, out, err);
  EXPECT_NE(rc, 0);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
  EXPECT_NE(err.str().find("USB"), std::string::npos) << err.str();
}

} // namespace
} // namespace bender::test
