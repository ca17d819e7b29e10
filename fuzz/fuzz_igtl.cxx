// libFuzzer harness for the OpenIGTLink stream decoder (the one decoder that takes bytes from
// the network) and the decoders of every message type Bender reads. The first byte picks the
// body size limit, whether the rest is the stream itself or a description of messages to
// encode (bit 6: each message then has a valid CRC, so that mutations reach the content
// decoders instead of stopping at the CRC), and how many of the next bytes give the chunk
// sizes (cycled) in which the stream is fed, so that headers and bodies split anywhere.
// Checked:
// - chunking changes nothing: the messages, counters and refusal equal those of one Feed;
// - memory: once Next() has returned nothing, the decoder holds only its pending bytes, fewer
//   than BufferCap();
// - every message re-encodes (EncodeIgtlMessage) to bytes that decode to the same message;
// - poses are finite with unit quaternions; every text the device shows (problems, pending
//   description, STATUS names and texts, element names) is one printable line.

#include "FuzzSupport.h"
#include "IgtlProtocol.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{

struct Decoded
{
  std::vector<bender::IgtlMessage> messages;
  bender::IgtlDecoderStatistics statistics;
  std::string refusal;
  std::size_t pending = 0;
};

void Fail(const char* what)
{
  std::fprintf(stderr, "finding: %s\n", what);
  std::abort();
}

bool Same(const bender::IgtlMessage& a, const bender::IgtlMessage& b)
{
  return a.headerVersion == b.headerVersion && a.type == b.type && a.deviceName == b.deviceName &&
    a.timestamp == b.timestamp && a.content == b.content && a.metadata == b.metadata &&
    a.messageId == b.messageId;
}

bool SameCounters(const bender::IgtlDecoderStatistics& a, const bender::IgtlDecoderStatistics& b)
{
  return a.messages == b.messages && a.crcErrors == b.crcErrors && a.malformed == b.malformed &&
    a.garbageBytes == b.garbageBytes && a.oversized == b.oversized;
}

void CheckPrintable(const std::string& text)
{
  if (!text.empty())
  {
    bender_fuzz::CheckMessage(text);
  }
}

void Drain(bender::IgtlStreamDecoder& decoder, Decoded& out)
{
  while (std::optional<bender::IgtlMessage> message = decoder.Next())
  {
    out.messages.push_back(std::move(*message));
  }
  if (decoder.Buffered() != decoder.Pending() || decoder.Buffered() >= decoder.BufferCap())
  {
    Fail("the decoder holds more than the message it waits for");
  }
}

Decoded Decode(const std::uint8_t* data,
  std::size_t size,
  std::uint64_t maxBody,
  const std::vector<std::size_t>& chunks)
{
  bender::IgtlStreamDecoder decoder(maxBody);
  Decoded out;
  bender_fuzz::FeedInChunks(data,
    size,
    chunks,
    [&](const std::uint8_t* bytes, std::size_t n)
    {
      decoder.Feed(bytes, n);
      Drain(decoder, out);
    });
  out.statistics = decoder.Statistics();
  out.refusal = decoder.Refusal();
  out.pending = decoder.Pending();
  if (decoder.Pending() > 0)
  {
    bender_fuzz::CheckMessage(decoder.PendingDescription());
  }
  CheckPrintable(out.refusal);
  return out;
}

void CheckPoses(const std::vector<bender::IgtlToolPose>& poses)
{
  for (const bender::IgtlToolPose& pose : poses)
  {
    CheckPrintable(pose.name);
    const bender::Quaternion& q = pose.orientation;
    const double norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (!std::isfinite(pose.position.x) || !std::isfinite(pose.position.y) ||
      !std::isfinite(pose.position.z) || !(std::abs(norm - 1.0) < 1e-6))
    {
      Fail("a pose that is not finite or whose quaternion is not of unit length");
    }
  }
}

void CheckMessageContent(const bender::IgtlMessage& message)
{
  // The header's type and name reach the window and the terminal.
  CheckPrintable(message.type);
  CheckPrintable(message.deviceName);
  const std::vector<std::uint8_t> bytes = bender::EncodeIgtlMessage(message.type,
    message.deviceName,
    message.content,
    message.headerVersion,
    message.metadata,
    message.timestamp,
    message.messageId);
  bender::IgtlStreamDecoder again;
  again.Feed(bytes.data(), bytes.size());
  const std::optional<bender::IgtlMessage> copy = again.Next();
  if (!copy || !Same(*copy, message) || again.Pending() != 0)
  {
    Fail("a message does not survive EncodeIgtlMessage and decoding");
  }
  std::vector<bender::IgtlToolPose> poses;
  std::string problem;
  if (bender::DecodeIgtlPoses(message, poses, problem))
  {
    CheckPoses(poses);
  }
  else
  {
    bender_fuzz::CheckMessage(problem);
  }
  if (const std::optional<std::string> text = bender::DecodeIgtlString(message))
  {
    if (text->size() + 4 > message.content.size())
    {
      Fail("a STRING longer than its content");
    }
  }
  if (const std::optional<bender::IgtlStatus> status = bender::DecodeIgtlStatus(message))
  {
    CheckPrintable(status->errorName);
    CheckPrintable(status->text);
  }
}

// Messages described by the input, each encoded with a valid CRC: a byte choosing the type
// (low 3 bits) and the header version (bit 3), a name (length byte, at most 20), a content
// (two length bytes), and for version 2 up to 3 metadata pairs (length byte and bytes each).
std::vector<std::uint8_t> EncodeDescribed(const std::uint8_t* data, std::size_t size)
{
  static const char* const types[] = {
    "TRANSFORM", "POSITION", "QTDATA", "TDATA", "STRING", "STATUS", "IMAGE", "POLYDATA"
  };
  std::size_t at = 0;
  const auto take = [&](std::size_t n)
  {
    const std::size_t k = std::min(n, size - at);
    std::string out(reinterpret_cast<const char*>(data + at), k);
    at += k;
    return out;
  };
  const auto byte = [&]() -> std::size_t { return at < size ? data[at++] : 0; };
  std::vector<std::uint8_t> stream;
  while (at < size)
  {
    const std::size_t kind = byte();
    const std::string name = take(byte() % 21);
    const std::size_t length = byte() << 8;
    const std::string content = take(length | byte());
    std::vector<std::pair<std::string, std::string>> metadata;
    const int version = (kind & 8) ? 2 : 1;
    if (version == 2)
    {
      for (std::size_t m = byte() % 4; m > 0; --m)
      {
        std::string key = take(byte());
        metadata.emplace_back(std::move(key), take(byte()));
      }
    }
    const std::vector<std::uint8_t> message = bender::EncodeIgtlMessage(types[kind & 7],
      name,
      std::vector<std::uint8_t>(content.begin(), content.end()),
      version,
      metadata,
      0,
      std::uint32_t(kind));
    stream.insert(stream.end(), message.begin(), message.end());
  }
  return stream;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0)
  {
    return 0;
  }
  const std::uint64_t limits[] = { 64ull << 20, 1024, 48, 0 };
  const std::uint64_t maxBody = limits[(data[0] >> 4) & 3];
  const bender_fuzz::ChunkedInput in = bender_fuzz::SplitChunks(data, size, data[0] & 0x0f);
  const std::vector<std::size_t>& chunks = in.sizes;
  const std::uint8_t* stream = in.stream;
  std::size_t streamSize = in.size;
  std::vector<std::uint8_t> encoded;
  if (data[0] & 0x40)
  {
    encoded = EncodeDescribed(stream, streamSize);
    stream = encoded.data();
    streamSize = encoded.size();
  }

  const Decoded whole = Decode(stream, streamSize, maxBody, {});
  const Decoded chunked = Decode(stream, streamSize, maxBody, chunks);
  if (whole.messages.size() != chunked.messages.size() ||
    !SameCounters(whole.statistics, chunked.statistics) || whole.refusal != chunked.refusal ||
    whole.pending != chunked.pending)
  {
    Fail("chunking changed what the decoder found");
  }
  for (std::size_t i = 0; i < whole.messages.size(); ++i)
  {
    if (!Same(whole.messages[i], chunked.messages[i]))
    {
      Fail("chunking changed a message");
    }
    CheckMessageContent(whole.messages[i]);
  }
  return 0;
}
