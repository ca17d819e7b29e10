#include "SerialTransport.h"

#include "TrackingErrors.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

namespace bender
{

namespace
{
speed_t BaudConstant(unsigned baud)
{
  switch (baud)
  {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    default:
      throw TrackingConfigurationError("serial: unsupported baud rate " + std::to_string(baud) +
        " (use 9600, 19200, 38400, 57600, 115200 or 230400)");
  }
}

std::string ErrnoText(int error)
{
  return std::string(std::strerror(error));
}
} // namespace

SerialSettings SerialSettings::Parse(const std::string& text)
{
  SerialSettings settings;
  const std::size_t comma = text.find(',');
  const std::string baud = text.substr(0, comma);
  if (baud.empty() || baud.find_first_not_of("0123456789") != std::string::npos || baud.size() > 7)
  {
    throw TrackingConfigurationError("serial: bad baud rate '" + baud + "' in '" + text + "'");
  }
  settings.baud = unsigned(std::stoul(baud));
  BaudConstant(settings.baud);
  if (comma != std::string::npos)
  {
    const std::string frame = text.substr(comma + 1);
    if (frame.size() != 3 || (frame[0] != '7' && frame[0] != '8') ||
      std::string("NEO").find(frame[1]) == std::string::npos ||
      (frame[2] != '1' && frame[2] != '2'))
    {
      throw TrackingConfigurationError(
        "serial: bad frame format '" + frame + "' (expected e.g. 8N1, 7E1, 8O2)");
    }
    settings.dataBits = frame[0] - '0';
    settings.parity = frame[1];
    settings.stopBits = frame[2] - '0';
  }
  return settings;
}

std::string SerialSettings::ToString() const
{
  return std::to_string(this->baud) + " " + std::to_string(this->dataBits) + this->parity +
    std::to_string(this->stopBits);
}

SerialTransport::SerialTransport(const std::string& path, const SerialSettings& settings)
  : Path(path)
{
  const speed_t speed = BaudConstant(settings.baud);
  this->Fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (this->Fd < 0)
  {
    const int error = errno;
    if (error == ENOENT || error == ENODEV || error == ENXIO)
    {
      throw DeviceNotFoundError("serial " + path + ": no such port (" + ErrnoText(error) +
        "); check the cable or adapter and the path (ls /dev/ttyS* /dev/ttyUSB*)");
    }
    if (error == EACCES || error == EPERM)
    {
      throw DeviceAccessError("serial " + path + ": permission denied; add yourself to the " +
        "dialout group (sudo usermod -aG dialout $USER) and log in again");
    }
    throw TransportError("serial " + path + ": cannot open (" + ErrnoText(error) + ")");
  }
  termios tio{};
  if (::tcgetattr(this->Fd, &tio) != 0)
  {
    const int error = errno;
    ::close(this->Fd);
    this->Fd = -1;
    throw TransportError("serial " + path + ": not a serial port (" + ErrnoText(error) + ")");
  }
  ::cfmakeraw(&tio);
  tio.c_cflag &= ~tcflag_t(CSIZE | PARENB | PARODD | CSTOPB | CRTSCTS);
  tio.c_cflag |= CLOCAL | CREAD | (settings.dataBits == 7 ? CS7 : CS8);
  if (settings.parity != 'N')
  {
    tio.c_cflag |= PARENB | (settings.parity == 'O' ? PARODD : 0);
  }
  if (settings.stopBits == 2)
  {
    tio.c_cflag |= CSTOPB;
  }
  tio.c_iflag &= ~tcflag_t(IXON | IXOFF | IXANY);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  if (::cfsetispeed(&tio, speed) != 0 || ::cfsetospeed(&tio, speed) != 0 ||
    ::tcsetattr(this->Fd, TCSANOW, &tio) != 0)
  {
    const int error = errno;
    ::close(this->Fd);
    this->Fd = -1;
    throw TransportError(
      "serial " + path + ": cannot set " + settings.ToString() + " (" + ErrnoText(error) + ")");
  }
  ::tcflush(this->Fd, TCIOFLUSH);
}

SerialTransport::~SerialTransport()
{
  this->Close();
}

std::size_t SerialTransport::Read(std::uint8_t* buffer,
  std::size_t capacity,
  std::chrono::milliseconds timeout)
{
  this->CheckOpen(this->Fd >= 0);
  pollfd p{ this->Fd, POLLIN, 0 };
  int ready;
  do
  {
    ready = ::poll(&p, 1, int(timeout.count()));
  } while (ready < 0 && errno == EINTR);
  if (ready < 0)
  {
    throw TransportError(this->Name() + ": poll failed (" + ErrnoText(errno) + ")");
  }
  if (ready == 0)
  {
    return 0;
  }
  if ((p.revents & POLLIN) == 0 && (p.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0)
  {
    throw DeviceDisconnectedError(this->Name() + ": the line hung up (adapter unplugged?)");
  }
  const ssize_t n = ::read(this->Fd, buffer, capacity);
  if (n < 0)
  {
    const int error = errno;
    if (error == EAGAIN || error == EINTR)
    {
      return 0;
    }
    if (error == EIO || error == ENXIO || error == ENODEV)
    {
      throw DeviceDisconnectedError(
        this->Name() + ": read failed, device gone (" + ErrnoText(error) + ")");
    }
    throw TransportError(this->Name() + ": read failed (" + ErrnoText(error) + ")");
  }
  if (n == 0)
  {
    throw DeviceDisconnectedError(this->Name() + ": end of file on the port (hang-up)");
  }
  return std::size_t(n);
}

void SerialTransport::Write(const std::uint8_t* data,
  std::size_t size,
  std::chrono::milliseconds timeout)
{
  this->CheckOpen(this->Fd >= 0);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::size_t done = 0;
  while (done < size)
  {
    const ssize_t n = ::write(this->Fd, data + done, size - done);
    if (n > 0)
    {
      done += std::size_t(n);
      continue;
    }
    const int error = errno;
    if (n < 0 && error != EAGAIN && error != EINTR)
    {
      if (error == EIO || error == ENXIO || error == ENODEV)
      {
        throw DeviceDisconnectedError(
          this->Name() + ": write failed, device gone (" + ErrnoText(error) + ")");
      }
      throw TransportError(this->Name() + ": write failed (" + ErrnoText(error) + ")");
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
      deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0)
    {
      throw TransportError(this->Name() + ": write timed out after " +
        std::to_string(timeout.count()) + " ms (flow control, or the unit is off?)");
    }
    pollfd p{ this->Fd, POLLOUT, 0 };
    ::poll(&p, 1, int(left.count()));
  }
}

void SerialTransport::Flush()
{
  this->CheckOpen(this->Fd >= 0);
  ::tcflush(this->Fd, TCIFLUSH);
}

void SerialTransport::Close()
{
  if (this->Fd >= 0)
  {
    ::close(this->Fd);
    this->Fd = -1;
  }
}

} // namespace bender
