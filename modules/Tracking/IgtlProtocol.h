#ifndef bender_IgtlProtocol_h
#define bender_IgtlProtocol_h

#include "TrackerPose.h"

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace bender
{

/// One OpenIGTLink message as it came off the wire, its header checked and its CRC verified.
///
/// Header version 1 (protocols 1 and 2): the body is the content. Header version 2
/// (protocol 3, what 3D Slicer sends by default): the body is a 12-byte extended header,
/// the content, a metadata index and the metadata; `content` is then the content alone and
/// `metadata` the key/value pairs.
struct IgtlMessage
{
  int headerVersion = 1;
  std::string type;            ///< "TRANSFORM", "POSITION", "QTDATA", "STRING", ...
  std::string deviceName;      ///< up to 20 characters
  std::uint64_t timestamp = 0; ///< 32.32 fixed point seconds, 0 when the sender set none
  std::vector<std::uint8_t> content;
  std::vector<std::pair<std::string, std::string>> metadata;
  std::uint32_t messageId = 0; ///< header version 2 only
};

/// Counters of IgtlStreamDecoder.
struct IgtlDecoderStatistics
{
  std::uint64_t messages = 0;     ///< messages passed on (any type)
  std::uint64_t crcErrors = 0;    ///< headers whose body CRC did not match (bytes skipped)
  std::uint64_t malformed = 0;    ///< v2 bodies whose extended header/metadata do not fit
  std::uint64_t garbageBytes = 0; ///< bytes skipped while hunting for a valid header
  std::uint64_t oversized = 0;    ///< headers announcing a body above the size limit
  std::uint64_t peakBuffered = 0; ///< the most bytes held while waiting for more (Buffered())
};

/// Splits a TCP byte stream into OpenIGTLink messages.
///
/// Feed() takes bytes as they arrive, in pieces of any size; Next() returns the complete
/// messages in order. A header is accepted when its version is 1 or 2, its type and device
/// name are printable ASCII padded with NULs, its body size is at most `maxBodyBytes` and, for
/// version-1 TRANSFORM/POSITION/QTDATA/TDATA, the size of that content; anything else is
/// skipped one byte at a time (counted in garbageBytes) until a valid header appears, so that
/// a stream recovers from garbage. A message whose CRC does not match is counted (crcErrors)
/// and the hunt resumes at the byte after its header's start (its bytes then count as
/// garbage), so that a false header found in garbage never swallows the messages after it.
///
/// Memory: once Next() has returned nothing, the decoder holds only the bytes of the message
/// it waits for (Buffered() == Pending()), fewer than BufferCap() = 58 + maxBodyBytes: a
/// header and the body it announces. Bytes already passed on or skipped are released then.
///
/// In step: at the start of the stream and right after a message, the next bytes are a header
/// if the peer speaks OpenIGTLink. A header found there that announces more than
/// `maxBodyBytes` is not garbage but a peer sending what Bender will not hold: Refusal() then
/// describes it (the decoder goes on hunting, as for garbage; IgtlDevice drops the connection).
class IgtlStreamDecoder
{
public:
  explicit IgtlStreamDecoder(std::uint64_t maxBodyBytes = 64ull << 20)
    : MaxBody(maxBodyBytes)
  {
  }

  void Feed(const std::uint8_t* data, std::size_t size);
  /// The next complete message, or nothing when more bytes are needed.
  std::optional<IgtlMessage> Next();

  /// Bytes held that do not yet form a complete message (a partial header or body).
  std::size_t Pending() const { return this->Buffer.size() - this->Start; }
  /// Bytes held in all, pending or not yet released (see the class comment).
  std::size_t Buffered() const { return this->Buffer.size(); }
  /// The most Buffered() can be once Next() has returned nothing: a header and the largest
  /// body accepted.
  std::uint64_t BufferCap() const { return 58 + this->MaxBody; }
  /// Empty, or one line saying which in-step header announced a body above the limit
  /// ("IMAGE message 'x' announces 1152921504606846976 body bytes, more than the 67108864
  /// accepted"); kept until Reset().
  const std::string& Refusal() const { return this->Refused; }
  /// When a valid header is held: its type, device name and the body bytes still missing.
  std::string PendingDescription() const;
  const IgtlDecoderStatistics& Statistics() const { return this->Stats; }
  void Reset();

private:
  bool HeaderAt(std::size_t offset) const;
  void Release();

  std::vector<std::uint8_t> Buffer;
  std::size_t Start = 0;
  std::uint64_t MaxBody;
  IgtlDecoderStatistics Stats;
  bool InStep = true;
  std::string Refused;
};

/// Builds one message's bytes: header version 1 when `metadata` is empty and `headerVersion`
/// is 1, otherwise header version 2 with the extended header and the metadata. The CRC is
/// computed with the OpenIGTLink library (crc64).
std::vector<std::uint8_t> EncodeIgtlMessage(const std::string& type,
  const std::string& deviceName,
  const std::vector<std::uint8_t>& content,
  int headerVersion = 1,
  const std::vector<std::pair<std::string, std::string>>& metadata = {},
  std::uint64_t timestamp = 0,
  std::uint32_t messageId = 0);

/// A pose carried by a tracking message, still in the sender's frame (RAS for OpenIGTLink).
struct IgtlToolPose
{
  std::string name;       ///< the message's device name, or the QTDATA/TDATA element name
  Vec3 position;          ///< mm
  Quaternion orientation; ///< (w, x, y, z), tool -> sender frame
};

/// Decodes the poses of a TRANSFORM (12 floats: the 3x3 rotation by columns, then the
/// translation), POSITION (3, 6 or 7 floats: position then quaternion x, y, z[, w]), QTDATA
/// (50-byte elements) or TDATA (70-byte elements) message. Returns false with `problem` set
/// when the content has the wrong size, is not finite, a rotation is not orthonormal within
/// 1e-2 (e.g. a scaled calibration matrix), or an element's name is not printable ASCII padded
/// with NULs (as a header's device name must be); true with no poses for other types.
bool DecodeIgtlPoses(const IgtlMessage& message,
  std::vector<IgtlToolPose>& poses,
  std::string& problem);

/// The text of a STRING message (encoding and length checked); nothing when malformed.
std::optional<std::string> DecodeIgtlString(const IgtlMessage& message);

/// STATUS: code (1 = OK), error name and status text; nothing when malformed. The names and
/// texts come from the peer and are shown: each is cut at its first NUL and at 200 characters
/// ("..." then ends it), and every byte outside printable ASCII becomes '?'.
struct IgtlStatus
{
  int code = 0;
  std::int64_t subcode = 0;
  std::string errorName;
  std::string text;
};
std::optional<IgtlStatus> DecodeIgtlStatus(const IgtlMessage& message);

/// OpenIGTLink (and 3D Slicer) work in RAS millimetres, Bender in LPS millimetres: x and y
/// change sign. The rotation becomes diag(-1,-1,1) * R: the tool's own axes are unchanged, only
/// expressed in LPS (a 180-degree turn about z, so it stays a proper rotation).
Vec3 RasToLps(const Vec3& p);
Quaternion RasToLps(const Quaternion& q);
/// The same change of sign, which is its own inverse.
inline Vec3 LpsToRas(const Vec3& p)
{
  return RasToLps(p);
}
inline Quaternion LpsToRas(const Quaternion& q)
{
  return RasToLps(q);
}

/// The 12 floats of a TRANSFORM content (big-endian) for a pose: rotation columns, then the
/// translation.
std::vector<std::uint8_t> EncodeIgtlTransform(const Vec3& position, const Quaternion& orientation);

} // namespace bender

#endif
