#ifndef bender_FastrakParser_h
#define bender_FastrakParser_h

#include "TrackerPose.h"
#include "TrackerStatistics.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace bender
{

enum class FastrakFormat
{
  Binary, ///< 'f': 34-byte records
  Ascii   ///< 'F': 55-character records
};

/// Units the Fastrak was told to use: 'u' (centimetres, what FastrakDevice sends) or 'U'.
enum class FastrakUnits
{
  Centimetres,
  Inches
};

/// Decodes the Fastrak output list `O n,2,11,16,0` (position, quaternion, stylus switch,
/// trailing space) from arbitrary byte chunks: records may be split anywhere across chunks.
///
/// Binary record (34 bytes): '0', station '1'..'4', status (' ' or a letter), x y z as
/// little-endian float32, quaternion w x y z as little-endian float32, ' ', '0'|'1' (stylus),
/// ' '. ASCII record (55 characters): the same header, x y z as 7-column fixed-point fields
/// ("Sxxx.xx"), w x y z as 7-column fields ("Sx.xxxx"), " 0"|" 1", ' '. Fields may run
/// together ("  30.01-150.70"); CR/LF between ASCII records is skipped.
///
/// Resynchronisation: the parser hunts for '0', then checks the station digit, the status
/// byte, the stylus bytes and the trailing space before accepting a record; a candidate that
/// fails is skipped one byte at a time. Counters (FastrakParserStatistics):
/// - malformed: a '0' followed by a station digit '1'..'4' whose record did not check out;
/// - garbageBytes: other bytes skipped while hunting;
/// - dropped: a well-formed record whose content is rejected: station outside 1..4, a NaN or
///   infinite value, |coordinate| > maxAbsPositionMm, or a quaternion whose norm is further
///   than quaternionTolerance from 1. Dropped records are never passed on;
/// - truncated: Finish() found the start of a record cut off by the end of the stream;
/// - warnings: records passed on whose status byte is a letter (e.g. weak signal).
/// Positions are converted to millimetres, quaternions normalised.
class FastrakParser
{
public:
  static constexpr std::size_t BinaryRecordSize = 34;
  static constexpr std::size_t AsciiRecordSize = 55;

  struct Options
  {
    FastrakFormat format = FastrakFormat::Binary;
    FastrakUnits units = FastrakUnits::Centimetres;
    double maxAbsPositionMm = 10000.0; ///< > 0; the Fastrak's range is a few metres
    double quaternionTolerance = 0.05; ///< accepted | |q| - 1 |, in (0, 1)
  };

  FastrakParser();
  explicit FastrakParser(const Options& options);

  /// Decodes what `data` completes and appends the poses to `out`, stamped with `time`.
  void Feed(const std::uint8_t* data, std::size_t size, double time, std::vector<TrackerPose>& out);
  /// Convenience: decodes and returns the poses completed by `data`.
  std::vector<TrackerPose> Feed(const std::vector<std::uint8_t>& data, double time = 0.0);

  /// End of stream: counts what is left in the buffer (truncated record or garbage) and
  /// clears it.
  void Finish();
  /// Forgets buffered bytes and counters.
  void Reset();

  const FastrakParserStatistics& Statistics() const { return this->Stats; }
  const Options& GetOptions() const { return this->Opts; }
  std::size_t RecordSize() const;
  /// Bytes waiting for the rest of their record.
  std::size_t Buffered() const { return this->Buffer.size() - this->Begin; }

private:
  enum class Check
  {
    NotARecord,
    Malformed,
    Valid
  };
  Check CheckStructure(const std::uint8_t* record) const;
  bool Decode(const std::uint8_t* record, double time, TrackerPose& pose) const;

  Options Opts;
  FastrakParserStatistics Stats;
  std::vector<std::uint8_t> Buffer;
  std::size_t Begin = 0;
};

} // namespace bender

#endif
