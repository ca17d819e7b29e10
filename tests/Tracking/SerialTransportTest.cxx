// SerialTransport on a pseudo-terminal: the test holds the master side, the transport
// opens the slave side as it would open /dev/ttyS0.
#include "SerialTransport.h"
#include "FastrakDevice.h"
#include "TrackingTestUtilities.h"

#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <termios.h>

namespace bender::test
{
namespace
{

class Pty
{
public:
  Pty()
  {
    this->Master = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (this->Master < 0 || ::grantpt(this->Master) != 0 || ::unlockpt(this->Master) != 0)
    {
      throw std::runtime_error("no pseudo-terminal");
    }
    this->SlavePath = ::ptsname(this->Master);
  }
  ~Pty() { this->CloseMaster(); }
  void CloseMaster()
  {
    if (this->Master >= 0)
    {
      ::close(this->Master);
      this->Master = -1;
    }
  }
  void Send(const Bytes& bytes) const
  {
    ASSERT_EQ(::write(this->Master, bytes.data(), bytes.size()), ssize_t(bytes.size()));
  }
  std::string Receive(std::size_t n) const
  {
    std::string got;
    char buffer[256];
    while (got.size() < n)
    {
      pollfd p{ this->Master, POLLIN, 0 };
      if (::poll(&p, 1, 1000) <= 0)
      {
        break;
      }
      const ssize_t k = ::read(this->Master, buffer, sizeof buffer);
      if (k <= 0)
      {
        break;
      }
      got.append(buffer, std::size_t(k));
    }
    return got;
  }
  int Master = -1;
  std::string SlavePath;
};

TEST(SerialSettings, ParsesAndRejects)
{
  const SerialSettings s = SerialSettings::Parse("9600,7E2");
  EXPECT_EQ(s.baud, 9600u);
  EXPECT_EQ(s.dataBits, 7);
  EXPECT_EQ(s.parity, 'E');
  EXPECT_EQ(s.stopBits, 2);
  EXPECT_EQ(SerialSettings::Parse("115200").ToString(), "115200 8N1");
  for (const char* bad : { "", "fast", "12345", "115200,8X1", "115200,9N1", "115200,8N", "-1" })
  {
    EXPECT_THROW(SerialSettings::Parse(bad), TrackingConfigurationError) << bad;
  }
}

TEST(SerialTransport, MissingPortIsNotFound)
{
  try
  {
    SerialTransport serial("/dev/does-not-exist-ttyS99");
    FAIL();
  }
  catch (const DeviceNotFoundError& e)
  {
    EXPECT_NE(std::string(e.what()).find("/dev/does-not-exist-ttyS99"), std::string::npos);
  }
}

TEST(SerialTransport, NotATtyIsRejected)
{
  EXPECT_THROW(SerialTransport("/dev/null"), TransportError);
}

TEST(SerialTransport, ConfiguresRawModeAndMovesBytesBothWays)
{
  Pty pty;
  SerialTransport serial(pty.SlavePath);
  // Raw 8N1: no echo, no canonical mode, no CR translation.
  const int slave = ::open(pty.SlavePath.c_str(), O_RDWR | O_NOCTTY);
  ASSERT_GE(slave, 0);
  termios tio{};
  ASSERT_EQ(::tcgetattr(slave, &tio), 0);
  ::close(slave);
  EXPECT_EQ(tio.c_lflag & (ICANON | ECHO), 0u);
  EXPECT_EQ(tio.c_iflag & (ICRNL | IXON), 0u);
  EXPECT_EQ(tio.c_cflag & CSIZE, tcflag_t(CS8));
  EXPECT_EQ(tio.c_cflag & PARENB, 0u);
  EXPECT_EQ(cfgetispeed(&tio), speed_t(B115200));

  Bytes binary = { '0', '1', ' ', 0x00, 0x0d, 0x0a, 0xff, 0x11, 0x13 };
  pty.Send(binary);
  Bytes got;
  std::uint8_t buffer[64];
  for (int i = 0; i < 20 && got.size() < binary.size(); ++i)
  {
    const std::size_t n = serial.Read(buffer, sizeof buffer, std::chrono::milliseconds(50));
    got.insert(got.end(), buffer, buffer + n);
  }
  EXPECT_EQ(got, binary);

  serial.WriteText("O1,2,11,16,0\r", std::chrono::milliseconds(200));
  EXPECT_EQ(pty.Receive(13), "O1,2,11,16,0\r");
}

TEST(SerialTransport, ReadTimesOutAndFlushDiscards)
{
  Pty pty;
  SerialTransport serial(pty.SlavePath);
  std::uint8_t buffer[8];
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(serial.Read(buffer, sizeof buffer, std::chrono::milliseconds(30)), 0u);
  const auto waited = std::chrono::steady_clock::now() - start;
  EXPECT_GE(waited, std::chrono::milliseconds(25));
  EXPECT_LT(waited, std::chrono::seconds(1));
  pty.Send({ 'x', 'y' });
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  serial.Flush();
  EXPECT_EQ(serial.Read(buffer, sizeof buffer, std::chrono::milliseconds(30)), 0u);
}

TEST(SerialTransport, HangUpIsADisconnect)
{
  Pty pty;
  SerialTransport serial(pty.SlavePath);
  pty.CloseMaster();
  std::uint8_t buffer[8];
  EXPECT_THROW(
    serial.Read(buffer, sizeof buffer, std::chrono::milliseconds(100)), DeviceDisconnectedError);
}

TEST(SerialTransport, FastrakDeviceOverSerialDecodesStreamedRecords)
{
  Pty pty;
  FastrakOptions options;
  options.configure = false; // nobody answers the commands on this pty
  const std::string path = pty.SlavePath;
  FastrakDevice device(
    "serial:" + path,
    [path] { return std::make_unique<SerialTransport>(path, SerialSettings::Parse("115200,8N1")); },
    options);
  device.EnablePoseQueue(16, false);
  device.Open();
  device.Start();
  const std::vector<TrackerPose> poses = SamplePoses();
  const Bytes stream = Encode(poses, FastrakFormat::Binary);
  pty.Send(Bytes(stream.begin(), stream.begin() + 17));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  pty.Send(Bytes(stream.begin() + 17, stream.end()));
  std::vector<TrackerPose> got;
  for (int i = 0; i < 100 && got.size() < poses.size(); ++i)
  {
    device.WaitForActivity(std::chrono::milliseconds(20));
    device.TakeEvents(); // button events are not what this test is about
    for (const TrackerPose& p : device.TakePoses())
    {
      got.push_back(p);
    }
  }
  ASSERT_EQ(got.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    ExpectPoseEq(ExpectedBinary(poses[i]), got[i]);
  }
  device.Close();
}

} // namespace
} // namespace bender::test
