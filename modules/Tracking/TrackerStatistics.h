#ifndef bender_TrackerStatistics_h
#define bender_TrackerStatistics_h

#include <cstdint>
#include <optional>
#include <vector>

namespace bender
{

/// Samples seen on one station and the rate measured from their timestamps.
struct StationStatistics
{
  int station = 0;
  std::uint64_t samples = 0;
  double firstTime = 0.0; ///< seconds
  double lastTime = 0.0;  ///< seconds
  /// (samples - 1) / (lastTime - firstTime) in Hz; 0 with fewer than two samples.
  double RateHz() const
  {
    const double span = this->lastTime - this->firstTime;
    return (this->samples > 1 && span > 0.0) ? double(this->samples - 1) / span : 0.0;
  }
};

/// Counters of the stream decoder (see FastrakParser for their exact meaning).
struct FastrakParserStatistics
{
  std::uint64_t records = 0;      ///< poses decoded and passed on
  std::uint64_t dropped = 0;      ///< well-formed records rejected (NaN, bad station, ...)
  std::uint64_t malformed = 0;    ///< record headers whose record did not check out
  std::uint64_t truncated = 0;    ///< a record cut off by the end of the stream
  std::uint64_t garbageBytes = 0; ///< bytes skipped while hunting for a record
  std::uint64_t warnings = 0;     ///< records passed on with a warning status letter
};

/// What a device measured while streaming.
struct TrackerStatistics
{
  std::vector<StationStatistics> stations; ///< in station order, only stations seen
  FastrakParserStatistics parser;          ///< zero for the simulator
  std::uint64_t filtered = 0;              ///< decoded poses of stations not asked for
  std::uint64_t queueOverflows = 0;        ///< poses dropped from a full pose queue (live devices)
  /// Median round trip of a single-record request ('P' to the last byte of its reply),
  /// measured at start on live devices; empty when not measured.
  std::optional<double> latencyMs;
};

} // namespace bender

#endif
