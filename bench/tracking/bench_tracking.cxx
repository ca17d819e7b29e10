// bench_tracking: load, soak and latency of the tracker input (issue 25).
//
// 1. Fastrak soak: two sensors at the Fastrak's full rate (120 records a second shared by the
//    active receivers, so 60 Hz each) for 30 minutes of simulated time: 216 000 binary records
//    encoded with EncodeFastrakRecord, handed to a FastrakDevice in 64-byte reads (the USB
//    packet size) as fast as the reader takes them (time compressed), and taken by a consumer
//    as the command line does (a pose queue of 4096, WaitForActivity every 100 ms at most). The
//    live drop policy (PoseStore): a full queue drops its oldest pose and counts it
//    (queueOverflows); every other pose must reach the consumer. Counted: records encoded,
//    decoded, published, consumed and dropped, and any pose unaccounted for.
// 2. OpenIGTLink soak: a peer on a localhost socket sending a TRANSFORM for each hand every
//    millisecond of simulated time (1 kHz) for 10 minutes (1.2 M messages), as fast as the
//    socket takes them (time compressed), to an IgtlDevice with the same consumer and counts.
// 3. Latency pose -> warped frame: the demo vessel (data/external/aneurysm_data.stl) in a
//    BenderSession with the demo plan's first ribbon placed on it, an IgtlDevice driven by a
//    localhost peer, a TrackerSession polling in a tight loop. The peer grabs (STRING "down"),
//    then sends one pose of the right hand at a time and waits for its frame: latency = from
//    the peer's send to the warped frame shown (the decimated copy while dragging a large
//    surface, as the window draws it) and to the full surface warped. The window polls on a
//    16 ms timer, which adds 0 to 16 ms to these figures.
// Memory: the resident set size (VmRSS) before and after each part.
//
// usage: bench_tracking [--tiny]   (--tiny: a few seconds of each, for the ctest that proves it
//                                  runs; no figure is checked)

#include "BenderSession.h"
#include "FastrakDevice.h"
#include "FastrakEncoding.h"
#include "IgtlDevice.h"
#include "IgtlProtocol.h"
#include "TrackerSession.h"
#include "WarpPlanIO.h"

#include "BenchMachine.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;
using bender_bench::Percentile;
using bender_bench::ResidentMiB;
using Bytes = std::vector<std::uint8_t>;

// The first three fields of /proc/loadavg: other work on the machine shows in the latency.
std::string LoadAverage()
{
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

double Seconds(Clock::time_point since)
{
  return std::chrono::duration<double>(Clock::now() - since).count();
}

// A hand moving on a slow circle, so that every record differs.
bender::TrackerPose HandPose(int station, std::uint64_t k)
{
  bender::TrackerPose pose;
  pose.station = station;
  const double a = 1e-3 * double(k);
  pose.position = { (station == 1 ? -100.0 : 100.0) + 5.0 * std::cos(a), 5.0 * std::sin(a), 20.0 };
  pose.orientation = { std::cos(a / 2), 0.0, 0.0, std::sin(a / 2) };
  pose.button = false;
  return pose;
}

// Takes poses as the command line does: a bounded wait for activity, then everything queued,
// until the device stops streaming (what it queued before is taken too).
struct Consumer
{
  std::uint64_t consumed = 0;
  std::uint64_t events = 0;
  std::thread thread;

  void Start(bender::TrackerDevice& device)
  {
    this->thread = std::thread(
      [this, &device]
      {
        for (bool last = false; !last;)
        {
          device.WaitForActivity(std::chrono::milliseconds(100));
          last = !device.IsStreaming();
          this->events += device.TakeEvents().size();
          this->consumed += device.TakePoses().size();
        }
      });
  }
  void Join()
  {
    if (this->thread.joinable())
    {
      this->thread.join();
    }
  }
};

// The simulated Fastrak: the encoded records of both sensors, handed out in 64-byte reads.
// With a speed > 0, byte k is not handed out before k / (4080 B/s * speed) seconds: the
// Fastrak's 120 records of 34 bytes a second, `speed` times faster.
class SoakTransport : public bender::Transport
{
public:
  SoakTransport(const Bytes* stream, double speed)
    : Stream(stream)
    , BytesPerSecond(4080.0 * speed)
    , Begin(Clock::now())
  {
  }
  std::string Name() const override { return "soak"; }
  std::size_t Read(std::uint8_t* buffer, std::size_t capacity, Timeout timeout) override
  {
    std::size_t due = this->Stream->size();
    if (this->BytesPerSecond > 0.0)
    {
      due = std::min(due, std::size_t(Seconds(this->Begin) * this->BytesPerSecond));
      if (due <= this->At)
      {
        std::this_thread::sleep_for(
          std::min<Clock::duration>(timeout, std::chrono::milliseconds(1)));
        return 0;
      }
    }
    const std::size_t n = std::min({ capacity, std::size_t(64), due - this->At });
    std::memcpy(buffer, this->Stream->data() + this->At, n);
    this->At += n;
    return n;
  }
  void Write(const std::uint8_t*, std::size_t, Timeout) override {}
  void Flush() override {}
  void Close() override {}
  bool AtEnd() const override { return this->At == this->Stream->size(); }

private:
  const Bytes* Stream;
  double BytesPerSecond;
  Clock::time_point Begin;
  std::size_t At = 0;
};

// What a soak run counted, and the resident memory around it.
struct SoakCounts
{
  std::uint64_t sent = 0;
  std::uint64_t decoded = 0;
  std::uint64_t published = 0;
  std::uint64_t consumed = 0;
  std::uint64_t dropped = 0;
  double seconds = 0.0;
  double simulated = 0.0;
  double rssBefore = 0.0;
  double rssHalfway = 0.0;

  /// Published (the stations' samples), consumed and dropped (the queue's overflows).
  void Count(const bender::TrackerStatistics& s, std::uint64_t taken)
  {
    this->published = 0;
    for (const bender::StationStatistics& station : s.stations)
    {
      this->published += station.samples;
    }
    this->consumed = taken;
    this->dropped = s.queueOverflows;
  }
};

void PrintSoak(const std::string& title, const SoakCounts& c, const std::string& decoder)
{
  const long long unaccounted =
    (long long)c.published - (long long)c.consumed - (long long)c.dropped;
  std::printf("%s:\n  %llu sent, %llu decoded, %llu published, %llu consumed, %llu dropped by "
              "the queue's policy (oldest first), %lld unaccounted\n",
    title.c_str(),
    (unsigned long long)c.sent,
    (unsigned long long)c.decoded,
    (unsigned long long)c.published,
    (unsigned long long)c.consumed,
    (unsigned long long)c.dropped,
    unaccounted);
  std::printf("  %.1f s of simulated time in %.2f s (%.0fx real time, %.0f poses/s)\n",
    c.simulated,
    c.seconds,
    c.simulated / std::max(c.seconds, 1e-9),
    double(c.published) / std::max(c.seconds, 1e-9));
  std::printf("  %s; RSS %.1f MiB before, %.1f halfway, %.1f after\n",
    decoder.c_str(),
    c.rssBefore,
    c.rssHalfway,
    ResidentMiB());
}

// Waits for the end of the stream, noting the resident memory once `halfway` says so.
double WaitForEnd(const bender::TrackerDevice& device, const std::function<bool()>& halfway)
{
  double middle = 0.0;
  while (device.IsStreaming())
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (middle == 0.0 && halfway())
    {
      middle = ResidentMiB();
    }
  }
  return middle;
}

const char* Pace(double speed)
{
  static char text[64];
  if (speed > 0.0)
  {
    std::snprintf(text, sizeof text, "paced at %gx real time", speed);
    return text;
  }
  return "as fast as it goes";
}

void FastrakSoak(double minutes, double speed)
{
  const std::uint64_t records = std::uint64_t(minutes * 60.0 * 120.0);
  Bytes stream;
  stream.reserve(records * bender::FastrakParser::BinaryRecordSize);
  for (std::uint64_t k = 0; k < records; ++k)
  {
    const Bytes r =
      bender::EncodeFastrakRecord(HandPose(int(k % 2) + 1, k / 2), bender::FastrakFormat::Binary);
    stream.insert(stream.end(), r.begin(), r.end());
  }
  SoakCounts counts;
  counts.sent = records;
  counts.simulated = minutes * 60.0;
  counts.rssBefore = ResidentMiB();
  bender::FastrakOptions options;
  options.configure = false;
  options.measureLatency = false;
  bender::FastrakDevice device(
    "soak",
    [&stream, speed]() -> std::unique_ptr<bender::Transport>
    { return std::make_unique<SoakTransport>(&stream, speed); },
    options);
  device.EnablePoseQueue(4096, false);
  device.Open();
  Consumer consumer;
  const auto start = Clock::now();
  device.Start();
  consumer.Start(device);
  counts.rssHalfway =
    WaitForEnd(device, [&] { return device.Statistics().parser.records >= records / 2; });
  consumer.Join();
  counts.seconds = Seconds(start);
  const bender::TrackerStatistics s = device.Statistics();
  device.Close();
  counts.decoded = s.parser.records;
  counts.Count(s, consumer.consumed);
  PrintSoak(std::string("Fastrak, 2 sensors at 120 records/s, ") + Pace(speed),
    counts,
    "parser: " + std::to_string(s.parser.malformed) + " malformed, " +
      std::to_string(s.parser.garbageBytes) + " garbage bytes, " +
      std::to_string(s.parser.dropped) + " dropped records");
}

// A listening socket on 127.0.0.1 and an ephemeral port.
struct Listener
{
  int fd = -1;
  int port = 0;
  Listener()
  {
    this->fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::bind(this->fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
      ::listen(this->fd, 1) != 0)
    {
      std::perror("bench_tracking: listen");
      std::exit(1);
    }
    socklen_t len = sizeof a;
    ::getsockname(this->fd, reinterpret_cast<sockaddr*>(&a), &len);
    this->port = ntohs(a.sin_port);
  }
  ~Listener() { ::close(this->fd); }
};

bool SendAll(int fd, const Bytes& bytes)
{
  std::size_t sent = 0;
  while (sent < bytes.size())
  {
    const ssize_t n = ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0)
    {
      return false;
    }
    sent += std::size_t(n);
  }
  return true;
}

Bytes HandMessage(int hand, const bender::Vec3& ras, const bender::Quaternion& q)
{
  return bender::EncodeIgtlMessage("TRANSFORM",
    hand == 1 ? "StylusToTracker" : "Stylus2ToTracker",
    bender::EncodeIgtlTransform(ras, q));
}

bender::IgtlDevice::Options PeerOptions(int port)
{
  bender::IgtlDevice::Options options;
  options.port = port;
  return options;
}

void IgtlSoak(double minutes, double speed)
{
  const std::uint64_t ticks = std::uint64_t(minutes * 60.0 * 1000.0);
  Listener listener;
  SoakCounts counts;
  counts.simulated = minutes * 60.0;
  counts.rssBefore = ResidentMiB();
  std::uint64_t sent = 0;
  std::thread peer(
    [&]
    {
      const int fd = ::accept(listener.fd, nullptr, nullptr);
      const auto begin = Clock::now();
      Bytes batch;
      for (std::uint64_t k = 0; k < ticks; ++k)
      {
        // Tick k is due at k ms of simulated time.
        while (speed > 0.0 && Seconds(begin) * 1000.0 * speed < double(k))
        {
          std::this_thread::sleep_for(std::chrono::microseconds(500));
        }
        for (int hand = 1; hand <= 2; ++hand)
        {
          const bender::TrackerPose p = HandPose(hand, k);
          const Bytes m = HandMessage(hand, p.position, p.orientation);
          batch.insert(batch.end(), m.begin(), m.end());
          ++sent;
        }
        if (batch.size() >= (speed > 0.0 ? 1024u : 16384u) || k + 1 == ticks)
        {
          if (!SendAll(fd, batch))
          {
            break;
          }
          batch.clear();
        }
      }
      ::close(fd);
    });
  bender::IgtlDevice device(PeerOptions(listener.port));
  device.EnablePoseQueue(4096, false);
  device.Open();
  Consumer consumer;
  const auto start = Clock::now();
  device.Start();
  consumer.Start(device);
  counts.rssHalfway = WaitForEnd(device, [&] { return device.IgtlStats().poses >= ticks; });
  consumer.Join();
  peer.join();
  counts.seconds = Seconds(start);
  const bender::TrackerStatistics s = device.Statistics();
  const bender::IgtlStatistics igtl = device.IgtlStats();
  device.Close();
  counts.sent = sent;
  counts.decoded = igtl.decoder.messages;
  counts.Count(s, consumer.consumed);
  PrintSoak(std::string("OpenIGTLink, a TRANSFORM per hand at 1 kHz, ") + Pace(speed),
    counts,
    "decoder: " + std::to_string(igtl.decoder.crcErrors) + " CRC errors, " +
      std::to_string(igtl.decoder.garbageBytes) + " garbage bytes, at most " +
      std::to_string(igtl.decoder.peakBuffered) + " bytes held");
}

void Latency(int samples)
{
  bender::BenderSession session;
  const std::string vessel = std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl";
  const bender::WarpPlan plan = bender::ReadWarpPlan(BENDER_DEMO_PLAN);
  if (!session.LoadSurface(vessel) || plan.warps.empty() ||
    !session.PlaceRibbon(plan.warps.front().initial))
  {
    std::printf("latency: the demo vessel or plan could not be used (%s)\n",
      session.GetMessages().empty() ? "no plan" : session.GetMessages().back().text.c_str());
    return;
  }
  const double before = ResidentMiB();
  Listener listener;
  // The peer and the polling loop take turns: the peer sends, then waits until the loop has
  // seen what it sent (the hands, the grab, or the frame of the pose).
  std::mutex mutex;
  std::condition_variable cv;
  bool seen = false;
  Clock::time_point sentAt;
  std::atomic<bool> over{ false };
  const bender::Quaternion facing{ 0, 0, 0, 1 }; // right hand: local +x towards the left hand
  const auto send = [&](int fd, const Bytes& bytes)
  {
    {
      std::lock_guard<std::mutex> lock(mutex);
      seen = false;
      sentAt = Clock::now();
    }
    if (!SendAll(fd, bytes))
    {
      return false;
    }
    std::unique_lock<std::mutex> lock(mutex);
    return cv.wait_for(lock, std::chrono::seconds(10), [&] { return seen || over.load(); }) &&
      !over;
  };
  std::thread peer(
    [&]
    {
      const int fd = ::accept(listener.fd, nullptr, nullptr);
      Bytes hands = HandMessage(1, { -100, 0, 0 }, { 1, 0, 0, 0 });
      const Bytes right = HandMessage(2, { 100, 0, 0 }, facing);
      hands.insert(hands.end(), right.begin(), right.end());
      const Bytes down =
        bender::EncodeIgtlMessage("STRING", "StylusToTracker", { 0, 3, 0, 4, 'd', 'o', 'w', 'n' });
      bool going = send(fd, hands) && send(fd, down);
      for (int i = 1; going && i <= samples; ++i)
      {
        // Lifts of the right hand by a few mm keep every warp valid.
        going = send(fd, HandMessage(2, { 100, 0, 4.0 * std::sin(0.05 * i) }, facing));
      }
      ::close(fd);
    });
  bender::TrackerSession trackers(session);
  if (!trackers.Connect(std::make_unique<bender::IgtlDevice>(PeerOptions(listener.port))))
  {
    over = true;
    cv.notify_all();
    peer.join();
    std::printf("latency: %s\n", session.GetMessages().back().text.c_str());
    return;
  }
  const auto tell = [&]
  {
    std::lock_guard<std::mutex> lock(mutex);
    seen = true;
    cv.notify_all();
  };
  std::vector<double> polled, shown, full;
  int proxyFrames = 0;
  int phase = 0; // 0: waiting for both hands, 1: for the grab, 2: for frames
  const auto deadline = Clock::now() + std::chrono::seconds(30 + samples / 10);
  while (int(shown.size()) < samples && Clock::now() < deadline)
  {
    const bender::TrackerSession::PollResult r = trackers.Poll();
    if (r.ended)
    {
      break;
    }
    if (phase == 0 && trackers.CurrentRibbon())
    {
      phase = 1;
      tell();
    }
    else if (phase == 1 && r.grabbed)
    {
      phase = 2;
      tell();
    }
    else if (phase == 2 && r.moved)
    {
      Clock::time_point sent;
      {
        std::lock_guard<std::mutex> lock(mutex);
        sent = sentAt;
      }
      polled.push_back(std::chrono::duration<double, std::milli>(Clock::now() - sent).count());
      const bool proxy = session.IsDraggingProxy();
      if (proxy)
      {
        session.GetProxySurface();
      }
      else
      {
        session.GetDisplaySurface();
      }
      shown.push_back(std::chrono::duration<double, std::milli>(Clock::now() - sent).count());
      session.GetDisplaySurface();
      full.push_back(std::chrono::duration<double, std::milli>(Clock::now() - sent).count());
      proxyFrames += proxy ? 1 : 0;
      tell();
    }
    else
    {
      std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
  }
  over = true;
  cv.notify_all();
  trackers.Disconnect();
  peer.join();
  const vtkIdType triangles = session.GetSurface()->GetNumberOfPolys();
  std::printf("latency pose -> warped frame, demo vessel (%lld triangles), %zu poses (%d of them "
              "dragging the decimated copy):\n",
    (long long)triangles,
    shown.size(),
    proxyFrames);
  std::printf("  pose taken and ribbon moved (Poll): median %.2f ms, p99 %.2f ms, max %.2f ms\n",
    Percentile(polled, 0.5),
    Percentile(polled, 0.99),
    Percentile(polled, 1.0));
  std::printf("  frame shown: median %.2f ms, p99 %.2f ms, max %.2f ms\n",
    Percentile(shown, 0.5),
    Percentile(shown, 0.99),
    Percentile(shown, 1.0));
  std::printf("  full surface warped: median %.2f ms, p99 %.2f ms, max %.2f ms\n",
    Percentile(full, 0.5),
    Percentile(full, 0.99),
    Percentile(full, 1.0));
  std::printf("  RSS %.1f MiB before, %.1f after; load average %s\n",
    before,
    ResidentMiB(),
    LoadAverage().c_str());
}

} // namespace

int main(int argc, char** argv)
{
  const bool tiny = argc > 1 && std::strcmp(argv[1], "--tiny") == 0;
  char date[64];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  std::printf("bench_tracking: %s; %s%s\n",
    date,
    bender_bench::MachineLine().c_str(),
    tiny ? " (--tiny: a few seconds of each, figures not meaningful)" : "");
  std::printf("RSS at start: %.1f MiB; load average %s\n", ResidentMiB(), LoadAverage().c_str());
  // As fast as it goes (throughput; drops counted against the policy), then paced.
  for (const double speed : { 0.0, tiny ? 100.0 : 20.0 })
  {
    FastrakSoak(tiny ? 0.05 : 30.0, speed);
    IgtlSoak(tiny ? 0.01 : 10.0, speed);
  }
  Latency(tiny ? 10 : 500);
  return 0;
}
