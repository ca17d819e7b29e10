#include "IgtlDevice.h"

#include "StringUtil.h"
#include "TrackingErrors.h"

#include <algorithm>
#include <sstream>

namespace bender
{

IgtlDevice::IgtlDevice(Options options)
  : Opts(std::move(options))
  , Decoder(Opts.maxBodyBytes)
{
  const std::string prefix = "igtl:" + this->Opts.host + ":" + std::to_string(this->Opts.port);
  for (const std::string& name : this->Opts.toolNames)
  {
    if (name.empty() || name.size() > 20)
    {
      throw TrackingConfigurationError(
        prefix + ": tool name '" + name + "' must have 1 to 20 characters");
    }
  }
  if (this->Opts.toolNames[0] == this->Opts.toolNames[1])
  {
    throw TrackingConfigurationError(
      prefix + ": both hands use the tool name '" + this->Opts.toolNames[0] + "'");
  }
  if (this->Opts.port < 1 || this->Opts.port > 65535 || this->Opts.host.empty())
  {
    throw TrackingConfigurationError(prefix + ": expected a host and a port in 1..65535");
  }
}

IgtlDevice::~IgtlDevice()
{
  this->Close();
}

void IgtlDevice::Open()
{
  if (this->Link.IsOpen())
  {
    return;
  }
  this->Link.Connect(this->Opts.host, this->Opts.port, this->Opts.connectTimeout);
  this->Decoder.Reset();
  this->Store.Clear();
  this->Buttons = {};
  this->LastPoses = {};
  std::lock_guard<std::mutex> lock(this->StatsMutex);
  this->Stats = IgtlStatistics{};
  this->Filtered = 0;
  this->Named.clear();
}

void IgtlDevice::Start()
{
  if (!this->Link.IsOpen())
  {
    throw TrackingError(this->Name() + ": Start() before Open()");
  }
  if (!this->ReaderRunning())
  {
    this->StartReader([this] { this->ReaderLoop(); });
  }
}

void IgtlDevice::Stop()
{
  this->StopReader();
}

void IgtlDevice::Close()
{
  this->Stop();
  this->Link.Close();
}

void IgtlDevice::ReaderLoop()
{
  using Clock = std::chrono::steady_clock;
  std::vector<std::uint8_t> buffer(65536);
  // Garbage counted at the last message, and when the held bytes last formed a message.
  std::uint64_t garbageAtMessage = 0;
  Clock::time_point progress = Clock::now();
  try
  {
    while (!this->StopRequested())
    {
      std::size_t received = 0;
      const IgtlConnection::ReadResult result =
        this->Link.Read(buffer.data(), buffer.size(), received, this->Opts.readTimeout);
      if (result == IgtlConnection::ReadResult::Closed)
      {
        std::string message = "the server closed the connection";
        if (this->Decoder.Pending() > 0)
        {
          message += " in the middle of a message (" + this->Decoder.PendingDescription() + ")";
          std::lock_guard<std::mutex> lock(this->StatsMutex);
          ++this->Stats.truncated;
        }
        this->ReaderEnded();
        this->Store.PublishEvent(
          { TrackerEventType::Disconnected, 0, this->ReaderTime(), message });
        return;
      }
      if (result == IgtlConnection::ReadResult::Data)
      {
        this->Decoder.Feed(buffer.data(), received);
        while (std::optional<IgtlMessage> message = this->Decoder.Next())
        {
          this->Handle(*message);
          garbageAtMessage = this->Decoder.Statistics().garbageBytes;
          progress = Clock::now();
        }
        std::lock_guard<std::mutex> lock(this->StatsMutex);
        this->Stats.decoder = this->Decoder.Statistics();
      }
      const Clock::time_point now = Clock::now();
      if (this->Decoder.Pending() == 0)
      {
        progress = now;
      }
      const std::string drop =
        this->DropReason(this->Decoder.Statistics().garbageBytes - garbageAtMessage,
          std::chrono::duration_cast<std::chrono::milliseconds>(now - progress));
      if (!drop.empty())
      {
        this->Link.Shutdown();
        this->ReaderEnded();
        this->Store.PublishEvent({ TrackerEventType::ReadError,
          0,
          this->ReaderTime(),
          "dropped the connection: " + drop });
        return;
      }
    }
  }
  catch (const std::exception& e) // the reader thread's boundary: TransportError, std's
  {
    this->ReaderEnded();
    this->Store.PublishEvent({ TrackerEventType::ReadError, 0, this->ReaderTime(), e.what() });
    return;
  }
  this->ReaderEnded();
}

std::string IgtlDevice::DropReason(std::uint64_t sinceMessage,
  std::chrono::milliseconds stalled) const
{
  if (!this->Decoder.Refusal().empty())
  {
    return this->Decoder.Refusal();
  }
  if (sinceMessage > this->Opts.maxGarbageBytes)
  {
    return std::to_string(sinceMessage) +
      " bytes without a valid OpenIGTLink message (is this an OpenIGTLink server?)";
  }
  if (stalled > this->Opts.stallTimeout)
  {
    return "no complete message for " + std::to_string(stalled.count()) + " ms (" +
      this->Decoder.PendingDescription() + ")";
  }
  return {};
}

void IgtlDevice::Handle(const IgtlMessage& message)
{
  const double now = this->ReaderTime();
  const auto hand = [this](const std::string& name)
  {
    for (int i = 0; i < 2; ++i)
    {
      if (name == this->Opts.toolNames[std::size_t(i)])
      {
        return i;
      }
    }
    return -1;
  };
  if (message.type == "STRING")
  {
    const int h = hand(message.deviceName);
    const std::optional<std::string> text = DecodeIgtlString(message);
    const std::string word = text ? ToLower(Trim(*text)) : std::string();
    const bool down = word == "down" || word == "pressed" || word == "1";
    const bool up = word == "up" || word == "released" || word == "0";
    if (h < 0 || !(down || up))
    {
      std::lock_guard<std::mutex> lock(this->StatsMutex);
      ++this->Stats.unknownTypes;
      ++this->Stats.skippedTypes["STRING"];
      return;
    }
    {
      std::lock_guard<std::mutex> lock(this->StatsMutex);
      ++this->Stats.buttonMessages;
    }
    this->Buttons[std::size_t(h)] = down;
    if (std::optional<TrackerPose>& last = this->LastPoses[std::size_t(h)])
    {
      last->button = down;
      last->time = now;
      this->Store.Publish(*last);
    }
    return;
  }
  if (message.type == "STATUS")
  {
    const std::optional<IgtlStatus> status = DecodeIgtlStatus(message);
    std::lock_guard<std::mutex> lock(this->StatsMutex);
    ++this->Stats.statusMessages;
    if (status && status->code != 1)
    {
      this->Stats.lastStatus = "'" + message.deviceName + "' code " + std::to_string(status->code) +
        (status->errorName.empty() ? "" : " " + status->errorName) +
        (status->text.empty() ? "" : ": " + status->text);
    }
    return;
  }
  if (message.type != "TRANSFORM" && message.type != "POSITION" && message.type != "QTDATA" &&
    message.type != "TDATA")
  {
    std::lock_guard<std::mutex> lock(this->StatsMutex);
    ++this->Stats.unknownTypes;
    ++this->Stats.skippedTypes[message.type];
    return;
  }
  std::vector<IgtlToolPose> poses;
  std::string problem;
  if (!DecodeIgtlPoses(message, poses, problem))
  {
    std::lock_guard<std::mutex> lock(this->StatsMutex);
    ++this->Stats.invalidPoses;
    this->Stats.lastStatus = problem;
    return;
  }
  for (const IgtlToolPose& tool : poses)
  {
    const int h = hand(tool.name);
    TrackerPose pose;
    pose.station = h + 1;
    pose.position = RasToLps(tool.position);
    pose.orientation = RasToLps(tool.orientation);
    pose.time = now;
    if (h >= 0)
    {
      pose.button = this->Buttons[std::size_t(h)];
      this->LastPoses[std::size_t(h)] = pose;
    }
    {
      std::lock_guard<std::mutex> lock(this->StatsMutex);
      ++this->Stats.poses;
      ++this->Stats.names[tool.name];
      if (h < 0)
      {
        ++this->Filtered;
      }
      if (this->NamedCapacity > 0)
      {
        if (this->Named.size() >= this->NamedCapacity)
        {
          this->Named.pop_front();
        }
        this->Named.push_back({ tool.name, pose });
      }
    }
    if (h >= 0)
    {
      this->Store.Publish(pose);
    }
  }
}

TrackerStatistics IgtlDevice::Statistics() const
{
  TrackerStatistics s = this->Store.Statistics();
  std::lock_guard<std::mutex> lock(this->StatsMutex);
  s.parser.records = this->Stats.poses;
  s.parser.dropped = this->Stats.invalidPoses;
  s.parser.malformed = this->Stats.decoder.crcErrors + this->Stats.decoder.malformed;
  s.parser.garbageBytes = this->Stats.decoder.garbageBytes;
  s.parser.truncated = this->Stats.truncated;
  s.filtered = this->Filtered;
  return s;
}

IgtlStatistics IgtlDevice::IgtlStats() const
{
  std::lock_guard<std::mutex> lock(this->StatsMutex);
  return this->Stats;
}

bool IgtlDevice::EnableNamedQueue(std::size_t capacity)
{
  std::lock_guard<std::mutex> lock(this->StatsMutex);
  this->NamedCapacity = capacity;
  return true;
}

std::vector<NamedTrackerPose> IgtlDevice::TakeNamedPoses()
{
  std::lock_guard<std::mutex> lock(this->StatsMutex);
  std::vector<NamedTrackerPose> out(this->Named.begin(), this->Named.end());
  this->Named.clear();
  return out;
}

std::vector<std::string> IgtlDevice::SummaryLines() const
{
  const IgtlStatistics s = this->IgtlStats();
  std::vector<std::string> lines;
  std::ostringstream igtl;
  igtl << "igtl: " << s.decoder.messages << " messages, " << s.poses << " poses, " << s.invalidPoses
       << " invalid, " << s.decoder.crcErrors << " CRC errors, " << s.decoder.malformed
       << " malformed, " << s.unknownTypes << " skipped (" << s.buttonMessages << " button, "
       << s.statusMessages << " status messages)";
  lines.push_back(igtl.str());
  for (const auto& [name, n] : s.names)
  {
    lines.push_back("device '" + name + "': " + std::to_string(n) + " poses" +
      (name == this->Opts.toolNames[0]      ? " (hand 1)"
          : name == this->Opts.toolNames[1] ? " (hand 2)"
                                            : " (not a hand: see --tools)"));
  }
  for (const auto& [type, n] : s.skippedTypes)
  {
    lines.push_back("skipped " + type + ": " + std::to_string(n));
  }
  if (!s.lastStatus.empty())
  {
    lines.push_back("last problem: " + s.lastStatus);
  }
  return lines;
}

std::string IgtlDevice::CountersText() const
{
  const IgtlStatistics stats = this->IgtlStats();
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
  return text.str();
}

} // namespace bender
