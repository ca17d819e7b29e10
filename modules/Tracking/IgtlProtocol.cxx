#include "IgtlProtocol.h"

#include <igtl_util.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace bender
{

namespace
{
constexpr std::size_t HeaderSize = 58;
constexpr std::size_t TypeSize = 12;
constexpr std::size_t NameSize = 20;
constexpr std::size_t ExtendedHeaderSize = 12;

std::uint64_t ReadBig(const std::uint8_t* p, int bytes)
{
  std::uint64_t v = 0;
  for (int i = 0; i < bytes; ++i)
  {
    v = (v << 8) | p[i];
  }
  return v;
}

void WriteBig(std::vector<std::uint8_t>& out, std::uint64_t v, int bytes)
{
  for (int i = bytes - 1; i >= 0; --i)
  {
    out.push_back(std::uint8_t((v >> (8 * i)) & 0xff));
  }
}

float ReadFloat(const std::uint8_t* p)
{
  const std::uint32_t bits = std::uint32_t(ReadBig(p, 4));
  float f = 0.0f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

void WriteFloat(std::vector<std::uint8_t>& out, double value)
{
  const float f = float(value);
  std::uint32_t bits = 0;
  std::memcpy(&bits, &f, sizeof f);
  WriteBig(out, bits, 4);
}

// A NUL-padded field of printable ASCII (the padding may be followed by anything but must
// start right after the text; an all-NUL type is not a type).
bool PrintableField(const std::uint8_t* p, std::size_t size, bool allowEmpty)
{
  std::size_t n = 0;
  while (n < size && p[n] != 0)
  {
    if (p[n] < 0x20 || p[n] > 0x7e)
    {
      return false;
    }
    ++n;
  }
  if (n == 0 && !allowEmpty)
  {
    return false;
  }
  for (std::size_t i = n; i < size; ++i)
  {
    if (p[i] != 0)
    {
      return false;
    }
  }
  return true;
}

std::string Field(const std::uint8_t* p, std::size_t size)
{
  std::size_t n = 0;
  while (n < size && p[n] != 0)
  {
    ++n;
  }
  return std::string(reinterpret_cast<const char*>(p), n);
}

// A text from the peer made fit to show: up to the first NUL, at most 200 characters, bytes
// outside printable ASCII replaced by '?'.
std::string ShownText(const std::uint8_t* p, std::size_t size)
{
  constexpr std::size_t limit = 200;
  std::string out;
  for (std::size_t i = 0; i < size && p[i] != 0; ++i)
  {
    if (out.size() == limit)
    {
      return out + "...";
    }
    out.push_back(p[i] >= 0x20 && p[i] <= 0x7e ? char(p[i]) : '?');
  }
  return out;
}

std::uint64_t Crc(const std::uint8_t* data, std::size_t size)
{
  // The library's crc64 takes a non-const pointer but does not write through it.
  return crc64(const_cast<unsigned char*>(data), igtl_uint64(size), 0ULL);
}

bool Finite(const Vec3& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Quaternion of a rotation given by its columns, refusing what is not a rotation.
bool RotationFromColumns(const Vec3& c0,
  const Vec3& c1,
  const Vec3& c2,
  Quaternion& q,
  std::string& problem)
{
  if (!Finite(c0) || !Finite(c1) || !Finite(c2))
  {
    problem = "rotation is not finite";
    return false;
  }
  const double tolerance = 1e-2;
  const double n0 = Norm(c0), n1 = Norm(c1), n2 = Norm(c2);
  if (std::abs(n0 - 1.0) > tolerance || std::abs(n1 - 1.0) > tolerance ||
    std::abs(n2 - 1.0) > tolerance || std::abs(Dot(c0, c1)) > tolerance ||
    std::abs(Dot(c0, c2)) > tolerance || std::abs(Dot(c1, c2)) > tolerance ||
    Dot(Cross(c0, c1), c2) < 0.0)
  {
    problem = "rotation part is not a rotation (scaled, sheared or mirrored)";
    return false;
  }
  q = QuaternionFromColumns(c0, c1, c2);
  return true;
}

bool QuaternionFromXyzw(double x, double y, double z, double w, Quaternion& q, std::string& problem)
{
  const double n = std::sqrt(x * x + y * y + z * z + w * w);
  if (!std::isfinite(n) || std::abs(n - 1.0) > 1e-2)
  {
    problem = "quaternion is not of unit length";
    return false;
  }
  q = { w / n, x / n, y / n, z / n };
  return true;
}

// 12 floats: rotation columns then translation.
bool MatrixPose(const std::uint8_t* p, IgtlToolPose& pose, std::string& problem)
{
  float m[12];
  for (int i = 0; i < 12; ++i)
  {
    m[i] = ReadFloat(p + 4 * i);
  }
  pose.position = { m[9], m[10], m[11] };
  if (!Finite(pose.position))
  {
    problem = "translation is not finite";
    return false;
  }
  return RotationFromColumns(
    { m[0], m[1], m[2] }, { m[3], m[4], m[5] }, { m[6], m[7], m[8] }, pose.orientation, problem);
}
// Version-1 messages of the tracking types have known content sizes; a header of such a type
// with another size is garbage (so a false header cannot make the decoder wait for a body).
bool PlausibleBodySize(const std::uint8_t* header, std::uint64_t body)
{
  if (ReadBig(header, 2) != 1)
  {
    return true;
  }
  const std::string type = Field(header + 2, TypeSize);
  if (type == "TRANSFORM")
  {
    return body == 48;
  }
  if (type == "POSITION")
  {
    return body == 12 || body == 24 || body == 28;
  }
  if (type == "QTDATA")
  {
    return body % 50 == 0;
  }
  if (type == "TDATA")
  {
    return body % 70 == 0;
  }
  return true;
}
} // namespace

void IgtlStreamDecoder::Feed(const std::uint8_t* data, std::size_t size)
{
  this->Release();
  this->Buffer.insert(this->Buffer.end(), data, data + size);
}

void IgtlStreamDecoder::Release()
{
  if (this->Start > 0)
  {
    this->Buffer.erase(this->Buffer.begin(), this->Buffer.begin() + std::ptrdiff_t(this->Start));
    this->Start = 0;
  }
  // After a large message, give its room back rather than keep it for the whole session.
  constexpr std::size_t keep = 1 << 20;
  if (this->Buffer.capacity() > keep && this->Buffer.size() < this->Buffer.capacity() / 4)
  {
    std::vector<std::uint8_t> smaller;
    smaller.reserve(std::max(keep, 2 * this->Buffer.size()));
    smaller.assign(this->Buffer.begin(), this->Buffer.end());
    this->Buffer.swap(smaller);
  }
}

void IgtlStreamDecoder::Reset()
{
  this->Buffer.clear();
  this->Buffer.shrink_to_fit();
  this->Start = 0;
  this->Stats = {};
  this->InStep = true;
  this->Refused.clear();
}

bool IgtlStreamDecoder::HeaderAt(std::size_t offset) const
{
  const std::uint8_t* h = this->Buffer.data() + offset;
  const std::uint64_t version = ReadBig(h, 2);
  if (version != 1 && version != 2)
  {
    return false;
  }
  return PrintableField(h + 2, TypeSize, false) && PrintableField(h + 2 + TypeSize, NameSize, true);
}

std::string IgtlStreamDecoder::PendingDescription() const
{
  if (this->Pending() < HeaderSize || !this->HeaderAt(this->Start))
  {
    return std::to_string(this->Pending()) + " bytes of a message header";
  }
  const std::uint8_t* h = this->Buffer.data() + this->Start;
  const std::uint64_t body = ReadBig(h + 42, 8);
  const std::size_t have = this->Pending() - HeaderSize;
  return Field(h + 2, TypeSize) + " message '" + Field(h + 14, NameSize) + "' with " +
    std::to_string(have) + " of " + std::to_string(body) + " body bytes";
}

std::optional<IgtlMessage> IgtlStreamDecoder::Next()
{
  while (this->Pending() >= HeaderSize)
  {
    if (!this->HeaderAt(this->Start))
    {
      ++this->Start;
      ++this->Stats.garbageBytes;
      this->InStep = false;
      continue;
    }
    const std::uint8_t* h = this->Buffer.data() + this->Start;
    const std::uint64_t bodySize = ReadBig(h + 42, 8);
    if (bodySize > this->MaxBody || !PlausibleBodySize(h, bodySize))
    {
      if (bodySize > this->MaxBody && this->InStep && this->Refused.empty())
      {
        this->Refused = Field(h + 2, TypeSize) + " message '" + Field(h + 14, NameSize) +
          "' announces " + std::to_string(bodySize) + " body bytes, more than the " +
          std::to_string(this->MaxBody) + " accepted";
      }
      // Otherwise most likely garbage that looks like a header: hunt on from the next byte.
      ++this->Stats.oversized;
      ++this->Start;
      ++this->Stats.garbageBytes;
      this->InStep = false;
      continue;
    }
    if (this->Pending() < HeaderSize + bodySize)
    {
      break;
    }
    const std::uint8_t* body = h + HeaderSize;
    const std::uint64_t crc = ReadBig(h + 50, 8);
    IgtlMessage message;
    message.headerVersion = int(ReadBig(h, 2));
    message.type = Field(h + 2, TypeSize);
    message.deviceName = Field(h + 14, NameSize);
    message.timestamp = ReadBig(h + 34, 8);
    if (Crc(body, std::size_t(bodySize)) != crc)
    {
      // Either a damaged message or garbage that looked like a header: hunt again from the
      // next byte, so that a false header never swallows the real messages after it.
      ++this->Stats.crcErrors;
      ++this->Stats.garbageBytes;
      ++this->Start;
      this->InStep = false;
      continue;
    }
    this->Start += HeaderSize + std::size_t(bodySize);
    this->InStep = true;
    if (message.headerVersion == 1)
    {
      message.content.assign(body, body + bodySize);
    }
    else
    {
      // Extended header: its size, the metadata index size, the metadata size, message id.
      bool ok = bodySize >= ExtendedHeaderSize;
      std::uint64_t extSize = 0, indexSize = 0, dataSize = 0;
      if (ok)
      {
        extSize = ReadBig(body, 2);
        indexSize = ReadBig(body + 2, 2);
        dataSize = ReadBig(body + 4, 4);
        message.messageId = std::uint32_t(ReadBig(body + 8, 4));
        ok = extSize >= ExtendedHeaderSize && extSize + indexSize + dataSize <= bodySize;
      }
      if (ok)
      {
        const std::uint64_t contentEnd = bodySize - indexSize - dataSize;
        message.content.assign(body + extSize, body + contentEnd);
        if (indexSize > 0)
        {
          const std::uint8_t* index = body + contentEnd;
          const std::uint64_t count = indexSize >= 2 ? ReadBig(index, 2) : 0;
          ok = indexSize == 2 + 8 * count;
          const std::uint8_t* values = index + indexSize;
          std::uint64_t used = 0;
          for (std::uint64_t i = 0; ok && i < count; ++i)
          {
            const std::uint8_t* e = index + 2 + 8 * i;
            const std::uint64_t keySize = ReadBig(e, 2);
            const std::uint64_t valueSize = ReadBig(e + 4, 4);
            if (used + keySize + valueSize > dataSize)
            {
              ok = false;
              break;
            }
            std::string key(reinterpret_cast<const char*>(values + used), keySize);
            std::string value(reinterpret_cast<const char*>(values + used + keySize), valueSize);
            message.metadata.emplace_back(std::move(key), std::move(value));
            used += keySize + valueSize;
          }
        }
      }
      if (!ok)
      {
        ++this->Stats.malformed;
        continue;
      }
    }
    ++this->Stats.messages;
    return message;
  }
  this->Release();
  this->Stats.peakBuffered = std::max<std::uint64_t>(this->Stats.peakBuffered, this->Buffer.size());
  return std::nullopt;
}

std::vector<std::uint8_t> EncodeIgtlMessage(const std::string& type,
  const std::string& deviceName,
  const std::vector<std::uint8_t>& content,
  int headerVersion,
  const std::vector<std::pair<std::string, std::string>>& metadata,
  std::uint64_t timestamp,
  std::uint32_t messageId)
{
  std::vector<std::uint8_t> body;
  const int version = (headerVersion >= 2 || !metadata.empty()) ? 2 : 1;
  if (version == 1)
  {
    body = content;
  }
  else
  {
    std::uint64_t dataSize = 0;
    for (const auto& kv : metadata)
    {
      dataSize += kv.first.size() + kv.second.size();
    }
    const std::uint64_t indexSize = metadata.empty() ? 0 : 2 + 8 * metadata.size();
    WriteBig(body, ExtendedHeaderSize, 2);
    WriteBig(body, indexSize, 2);
    WriteBig(body, dataSize, 4);
    WriteBig(body, messageId, 4);
    body.insert(body.end(), content.begin(), content.end());
    if (!metadata.empty())
    {
      WriteBig(body, metadata.size(), 2);
      for (const auto& kv : metadata)
      {
        WriteBig(body, kv.first.size(), 2);
        WriteBig(body, 3, 2); // US-ASCII (IANA MIBenum 3)
        WriteBig(body, kv.second.size(), 4);
      }
      for (const auto& kv : metadata)
      {
        body.insert(body.end(), kv.first.begin(), kv.first.end());
        body.insert(body.end(), kv.second.begin(), kv.second.end());
      }
    }
  }
  std::vector<std::uint8_t> out;
  out.reserve(HeaderSize + body.size());
  WriteBig(out, std::uint64_t(version), 2);
  for (std::size_t i = 0; i < TypeSize; ++i)
  {
    out.push_back(i < type.size() ? std::uint8_t(type[i]) : 0);
  }
  for (std::size_t i = 0; i < NameSize; ++i)
  {
    out.push_back(i < deviceName.size() ? std::uint8_t(deviceName[i]) : 0);
  }
  WriteBig(out, timestamp, 8);
  WriteBig(out, body.size(), 8);
  WriteBig(out, Crc(body.data(), body.size()), 8);
  out.insert(out.end(), body.begin(), body.end());
  return out;
}

bool DecodeIgtlPoses(const IgtlMessage& message,
  std::vector<IgtlToolPose>& poses,
  std::string& problem)
{
  const std::vector<std::uint8_t>& c = message.content;
  const auto wrongSize = [&](const std::string& expected)
  {
    problem = message.type + " '" + message.deviceName + "': " + std::to_string(c.size()) +
      " content bytes, expected " + expected;
    return false;
  };
  const auto fail = [&](const std::string& why)
  {
    problem = message.type + " '" + message.deviceName + "': " + why;
    return false;
  };
  if (message.type == "TRANSFORM")
  {
    if (c.size() != 48)
    {
      return wrongSize("48");
    }
    IgtlToolPose pose;
    pose.name = message.deviceName;
    std::string why;
    if (!MatrixPose(c.data(), pose, why))
    {
      return fail(why);
    }
    poses.push_back(pose);
    return true;
  }
  if (message.type == "POSITION")
  {
    if (c.size() != 12 && c.size() != 24 && c.size() != 28)
    {
      return wrongSize("12, 24 or 28");
    }
    IgtlToolPose pose;
    pose.name = message.deviceName;
    pose.position = { ReadFloat(c.data()), ReadFloat(c.data() + 4), ReadFloat(c.data() + 8) };
    if (!Finite(pose.position))
    {
      return fail("position is not finite");
    }
    if (c.size() >= 24)
    {
      const double x = ReadFloat(c.data() + 12), y = ReadFloat(c.data() + 16),
                   z = ReadFloat(c.data() + 20);
      // Three components: w is the non-negative completion to unit length.
      const double w = c.size() == 28 ? double(ReadFloat(c.data() + 24))
                                      : std::sqrt(std::max(0.0, 1.0 - x * x - y * y - z * z));
      std::string why;
      if (!QuaternionFromXyzw(x, y, z, w, pose.orientation, why))
      {
        return fail(why);
      }
    }
    poses.push_back(pose);
    return true;
  }
  if (message.type == "QTDATA" || message.type == "TDATA")
  {
    const std::size_t element = message.type == "QTDATA" ? 50 : 70;
    if (c.size() % element != 0)
    {
      return wrongSize("a multiple of " + std::to_string(element));
    }
    for (std::size_t offset = 0; offset < c.size(); offset += element)
    {
      const std::uint8_t* e = c.data() + offset;
      if (!PrintableField(e, NameSize, true))
      {
        return fail(
          "element " + std::to_string(offset / element + 1) + ": name is not printable ASCII");
      }
      IgtlToolPose pose;
      pose.name = Field(e, NameSize);
      std::string why;
      if (element == 50)
      {
        pose.position = { ReadFloat(e + 22), ReadFloat(e + 26), ReadFloat(e + 30) };
        if (!Finite(pose.position))
        {
          return fail("'" + pose.name + "': position is not finite");
        }
        if (!QuaternionFromXyzw(ReadFloat(e + 34),
              ReadFloat(e + 38),
              ReadFloat(e + 42),
              ReadFloat(e + 46),
              pose.orientation,
              why))
        {
          return fail("'" + pose.name + "': " + why);
        }
      }
      else if (!MatrixPose(e + 22, pose, why))
      {
        return fail("'" + pose.name + "': " + why);
      }
      poses.push_back(pose);
    }
    return true;
  }
  return true;
}

std::optional<std::string> DecodeIgtlString(const IgtlMessage& message)
{
  const std::vector<std::uint8_t>& c = message.content;
  if (message.type != "STRING" || c.size() < 4)
  {
    return std::nullopt;
  }
  const std::uint64_t length = ReadBig(c.data() + 2, 2);
  if (4 + length > c.size())
  {
    return std::nullopt;
  }
  return std::string(reinterpret_cast<const char*>(c.data() + 4), length);
}

std::optional<IgtlStatus> DecodeIgtlStatus(const IgtlMessage& message)
{
  const std::vector<std::uint8_t>& c = message.content;
  // code (2), subcode (8), error name (20), then a NUL-terminated status string.
  if (message.type != "STATUS" || c.size() < 30)
  {
    return std::nullopt;
  }
  IgtlStatus status;
  status.code = int(ReadBig(c.data(), 2));
  status.subcode = std::int64_t(ReadBig(c.data() + 2, 8));
  status.errorName = ShownText(c.data() + 10, 20);
  status.text = ShownText(c.data() + 30, c.size() - 30);
  return status;
}

Vec3 RasToLps(const Vec3& p)
{
  return { -p.x, -p.y, p.z };
}

Quaternion RasToLps(const Quaternion& q)
{
  // (0, 0, 0, 1) * q: a half turn about z applied after q.
  const Quaternion halfTurn{ 0.0, 0.0, 0.0, 1.0 };
  return halfTurn * q;
}

std::vector<std::uint8_t> EncodeIgtlTransform(const Vec3& position, const Quaternion& orientation)
{
  std::vector<std::uint8_t> out;
  out.reserve(48);
  for (const Vec3& axis : { Vec3{ 1, 0, 0 }, Vec3{ 0, 1, 0 }, Vec3{ 0, 0, 1 } })
  {
    const Vec3 column = RotateByQuaternion(orientation, axis);
    WriteFloat(out, column.x);
    WriteFloat(out, column.y);
    WriteFloat(out, column.z);
  }
  WriteFloat(out, position.x);
  WriteFloat(out, position.y);
  WriteFloat(out, position.z);
  return out;
}

} // namespace bender
