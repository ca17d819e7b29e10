#ifndef bender_TrackingTestUtilities_h
#define bender_TrackingTestUtilities_h

// Helpers shared by the tracking tests: byte-stream fixtures built from the protocol, an
// in-memory Transport, and a scratch directory.

#include "FastrakEncoding.h"
#include "TrackingErrors.h"
#include "Transport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <mutex>
#include <string>
#include <unistd.h>
#include <vector>

namespace bender::test
{

using Bytes = std::vector<std::uint8_t>;

inline Quaternion AxisAngle(const Vec3& axis, double angle)
{
  const Vec3 k = Normalized(axis);
  return { std::cos(angle / 2),
    k.x * std::sin(angle / 2),
    k.y * std::sin(angle / 2),
    k.z * std::sin(angle / 2) };
}

inline TrackerPose MakePose(int station, Vec3 mm, Quaternion q, bool button, char status = ' ')
{
  TrackerPose p;
  p.station = station;
  p.position = mm;
  p.orientation = q;
  p.button = button;
  p.status = status;
  return p;
}

/// A few poses with distinct values on stations 1 and 2.
inline std::vector<TrackerPose> SamplePoses()
{
  return { MakePose(1, { 300.1, -1507.0, 12.5 }, AxisAngle({ 0, 0, 1 }, 0.3), false),
    MakePose(2, { -45.25, 250.0, -999.0 }, AxisAngle({ 1, 1, 0 }, -1.2), true),
    MakePose(1, { 0.0, 0.5, 7.75 }, { 1, 0, 0, 0 }, true),
    MakePose(2, { 1234.5, -0.25, 80.0 }, AxisAngle({ 0, 1, 0 }, 3.0), false) };
}

inline Bytes Encode(const std::vector<TrackerPose>& poses, FastrakFormat format)
{
  Bytes out;
  for (const TrackerPose& p : poses)
  {
    const Bytes r = EncodeFastrakRecord(p, format);
    out.insert(out.end(), r.begin(), r.end());
  }
  return out;
}

/// v rounded to float32 and back. Through a volatile so that the optimiser cannot vectorise
/// the round trip away (GCC 12 -O3 did, for the x and y of a braced Vec3).
inline double Float32(double v)
{
  volatile float f = float(v);
  return double(f);
}

/// What the parser must produce for a binary record: float32 centimetres times 10,
/// the float32 quaternion normalised in double.
inline TrackerPose ExpectedBinary(const TrackerPose& p)
{
  TrackerPose e = p;
  e.position = { Float32(p.position.x / 10.0) * 10.0,
    Float32(p.position.y / 10.0) * 10.0,
    Float32(p.position.z / 10.0) * 10.0 };
  const double q[4] = { Float32(p.orientation.w),
    Float32(p.orientation.x),
    Float32(p.orientation.y),
    Float32(p.orientation.z) };
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  e.orientation = { q[0] / n, q[1] / n, q[2] / n, q[3] / n };
  return e;
}

inline void ExpectPoseEq(const TrackerPose& expected, const TrackerPose& actual, double tol = 0.0)
{
  EXPECT_EQ(expected.station, actual.station);
  EXPECT_EQ(expected.button, actual.button);
  EXPECT_EQ(expected.status, actual.status);
  if (tol == 0.0)
  {
    EXPECT_DOUBLE_EQ(expected.position.x, actual.position.x);
    EXPECT_DOUBLE_EQ(expected.position.y, actual.position.y);
    EXPECT_DOUBLE_EQ(expected.position.z, actual.position.z);
    EXPECT_DOUBLE_EQ(expected.orientation.w, actual.orientation.w);
    EXPECT_DOUBLE_EQ(expected.orientation.x, actual.orientation.x);
    EXPECT_DOUBLE_EQ(expected.orientation.y, actual.orientation.y);
    EXPECT_DOUBLE_EQ(expected.orientation.z, actual.orientation.z);
  }
  else
  {
    EXPECT_NEAR(expected.position.x, actual.position.x, tol);
    EXPECT_NEAR(expected.position.y, actual.position.y, tol);
    EXPECT_NEAR(expected.position.z, actual.position.z, tol);
    EXPECT_NEAR(expected.orientation.w, actual.orientation.w, tol);
    EXPECT_NEAR(expected.orientation.x, actual.orientation.x, tol);
    EXPECT_NEAR(expected.orientation.y, actual.orientation.y, tol);
    EXPECT_NEAR(expected.orientation.z, actual.orientation.z, tol);
  }
}

/// A Transport fed from the test: chunks to read, a disconnect, all writes recorded.
class ScriptedTransport : public Transport
{
public:
  struct Shared
  {
    std::mutex mutex;
    std::condition_variable cv;
    std::deque<Bytes> incoming;
    std::string written;
    bool disconnect = false;
    bool closed = false;
    int opens = 0;
    /// Replies to 'P' with these bytes (the device's single record).
    Bytes pollReply;
  };

  explicit ScriptedTransport(std::shared_ptr<Shared> shared)
    : S(std::move(shared))
  {
    std::lock_guard<std::mutex> lock(this->S->mutex);
    ++this->S->opens;
    this->S->closed = false;
  }
  std::string Name() const override { return "scripted"; }
  std::size_t Read(std::uint8_t* buffer,
    std::size_t capacity,
    std::chrono::milliseconds timeout) override
  {
    std::unique_lock<std::mutex> lock(this->S->mutex);
    this->S->cv.wait_for(
      lock, timeout, [&] { return !this->S->incoming.empty() || this->S->disconnect; });
    if (this->S->incoming.empty() && this->S->disconnect)
    {
      throw DeviceDisconnectedError("scripted: unplugged");
    }
    if (this->S->incoming.empty())
    {
      return 0;
    }
    Bytes& front = this->S->incoming.front();
    const std::size_t n = std::min(capacity, front.size());
    std::copy(front.begin(), front.begin() + std::ptrdiff_t(n), buffer);
    front.erase(front.begin(), front.begin() + std::ptrdiff_t(n));
    if (front.empty())
    {
      this->S->incoming.pop_front();
    }
    return n;
  }
  void Write(const std::uint8_t* data, std::size_t size, std::chrono::milliseconds) override
  {
    std::lock_guard<std::mutex> lock(this->S->mutex);
    if (this->S->disconnect)
    {
      throw DeviceDisconnectedError("scripted: unplugged");
    }
    this->S->written.append(reinterpret_cast<const char*>(data), size);
    if (size == 1 && data[0] == 'P' && !this->S->pollReply.empty())
    {
      this->S->incoming.push_back(this->S->pollReply);
      this->S->cv.notify_all();
    }
  }
  void Flush() override
  {
    std::lock_guard<std::mutex> lock(this->S->mutex);
    this->S->incoming.clear();
  }
  void Close() override
  {
    std::lock_guard<std::mutex> lock(this->S->mutex);
    this->S->closed = true;
  }

  static void Push(Shared& s, Bytes bytes)
  {
    std::lock_guard<std::mutex> lock(s.mutex);
    s.incoming.push_back(std::move(bytes));
    s.cv.notify_all();
  }

private:
  std::shared_ptr<Shared> S;
};

/// A fresh scratch directory under TMPDIR, removed at the end of the test.
class ScratchDir
{
public:
  ScratchDir()
  {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/bender-tracking-XXXXXX";
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    if (::mkdtemp(buffer.data()) == nullptr)
    {
      throw std::runtime_error("cannot create a scratch directory");
    }
    this->Path = buffer.data();
  }
  ~ScratchDir()
  {
    std::error_code ignored;
    std::filesystem::remove_all(this->Path, ignored);
  }
  std::string File(const std::string& name) const { return this->Path + "/" + name; }

private:
  std::string Path;
};

} // namespace bender::test

#endif
