// libFuzzer harness for the Fastrak stream parser under arbitrary chunking, as the bytes come
// from libusb transfers and serial reads of a device that may send garbage at full speed. The
// first byte picks the format and units and how many of the next bytes give the chunk sizes
// (cycled, 1 to 256 bytes each); the rest is the stream. Checked: chunking changes nothing
// (the poses and every counter equal those of one Feed of the whole stream, Finish() included),
// the parser never holds a whole record's worth of bytes between feeds, the counters account
// for no more bytes than the stream has, and every pose passed on is finite, within range and
// normalised.

#include "FastrakParser.h"
#include "FuzzSupport.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace
{

void Fail(const char* what)
{
  std::fprintf(stderr, "finding: %s\n", what);
  std::abort();
}

struct Parsed
{
  std::vector<bender::TrackerPose> poses;
  bender::FastrakParserStatistics statistics;
};

Parsed Parse(const bender::FastrakParser::Options& options,
  const std::uint8_t* data,
  std::size_t size,
  const std::vector<std::size_t>& chunks)
{
  bender::FastrakParser parser(options);
  Parsed out;
  double time = 0.0;
  bender_fuzz::FeedInChunks(data,
    size,
    chunks,
    [&](const std::uint8_t* bytes, std::size_t n)
    {
      parser.Feed(bytes, n, time, out.poses);
      time += 1.0;
      if (parser.Buffered() >= parser.RecordSize())
      {
        Fail("the parser holds a whole record's worth of bytes after a feed");
      }
    });
  parser.Finish();
  if (parser.Buffered() != 0)
  {
    Fail("bytes left after Finish()");
  }
  out.statistics = parser.Statistics();
  return out;
}

bool SamePose(const bender::TrackerPose& a, const bender::TrackerPose& b)
{
  return a.station == b.station && a.button == b.button && a.status == b.status &&
    a.position.x == b.position.x && a.position.y == b.position.y && a.position.z == b.position.z &&
    a.orientation.w == b.orientation.w && a.orientation.x == b.orientation.x &&
    a.orientation.y == b.orientation.y && a.orientation.z == b.orientation.z;
}

bool SameCounters(const bender::FastrakParserStatistics& a,
  const bender::FastrakParserStatistics& b)
{
  return a.records == b.records && a.dropped == b.dropped && a.malformed == b.malformed &&
    a.truncated == b.truncated && a.garbageBytes == b.garbageBytes && a.warnings == b.warnings;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0)
  {
    return 0;
  }
  // Bits 0 and 1 as in fuzz_fastrak: ASCII records, inches.
  bender::FastrakParser::Options options;
  options.format = bender::FastrakFormat(data[0] & 1);
  options.units = bender::FastrakUnits((data[0] >> 1) & 1);
  const bender_fuzz::ChunkedInput in = bender_fuzz::SplitChunks(data, size, (data[0] >> 2) & 0x0f);
  const std::uint8_t* stream = in.stream;
  const std::size_t streamSize = in.size;
  const std::vector<std::size_t>& chunks = in.sizes;

  const Parsed whole = Parse(options, stream, streamSize, {});
  const Parsed chunked = Parse(options, stream, streamSize, chunks);
  if (whole.poses.size() != chunked.poses.size() ||
    !SameCounters(whole.statistics, chunked.statistics))
  {
    Fail("chunking changed what the parser found");
  }
  // Every byte is counted at most once: in a record (passed on or dropped), as the start of a
  // malformed candidate, or as garbage.
  const bender::FastrakParserStatistics& s = whole.statistics;
  const std::uint64_t recordSize = bender::FastrakParser(options).RecordSize();
  if ((s.records + s.dropped) * recordSize + s.malformed + s.garbageBytes > streamSize ||
    s.truncated > 1 || s.warnings > s.records)
  {
    Fail("the counters account for more bytes than the stream has");
  }
  for (std::size_t i = 0; i < whole.poses.size(); ++i)
  {
    const bender::TrackerPose& pose = whole.poses[i];
    if (!SamePose(pose, chunked.poses[i]))
    {
      Fail("chunking changed a pose");
    }
    const bender::Quaternion& q = pose.orientation;
    const double norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (pose.station < 1 || pose.station > 4 || !(std::abs(pose.position.x) <= 1e4) ||
      !(std::abs(pose.position.y) <= 1e4) || !(std::abs(pose.position.z) <= 1e4) ||
      !(std::abs(norm - 1.0) < 1e-9))
    {
      Fail("a pose out of range or not normalised");
    }
  }
  return 0;
}
