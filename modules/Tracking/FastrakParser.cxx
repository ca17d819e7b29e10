#include "FastrakParser.h"

#include <cmath>
#include <cstring>

namespace bender
{

namespace
{
constexpr std::size_t AsciiFieldWidth = 7;

bool IsStationDigit(std::uint8_t b)
{
  return b >= '1' && b <= '4';
}

bool IsStatusByte(std::uint8_t b)
{
  return b == ' ' || (b >= 'A' && b <= 'Z') || (b >= 'a' && b <= 'z');
}

bool IsStylusTail(const std::uint8_t* tail)
{
  return tail[0] == ' ' && (tail[1] == '0' || tail[1] == '1') && tail[2] == ' ';
}

float LittleEndianFloat(const std::uint8_t* bytes)
{
  const std::uint32_t bits = std::uint32_t(bytes[0]) | (std::uint32_t(bytes[1]) << 8) |
    (std::uint32_t(bytes[2]) << 16) | (std::uint32_t(bytes[3]) << 24);
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

// One fixed-width ASCII field: spaces, an optional sign, digits, '.', digits. Parsed by hand
// (not strtod) so that the process locale's decimal separator cannot change the result.
bool ParseAsciiField(const std::uint8_t* field, double& value)
{
  std::size_t i = 0;
  while (i < AsciiFieldWidth && field[i] == ' ')
  {
    ++i;
  }
  double sign = 1.0;
  if (i < AsciiFieldWidth && (field[i] == '-' || field[i] == '+'))
  {
    sign = field[i] == '-' ? -1.0 : 1.0;
    ++i;
  }
  double mantissa = 0.0;
  int integerDigits = 0;
  int fractionDigits = 0;
  bool point = false;
  for (; i < AsciiFieldWidth; ++i)
  {
    const std::uint8_t c = field[i];
    if (c >= '0' && c <= '9')
    {
      mantissa = mantissa * 10.0 + double(c - '0');
      (point ? fractionDigits : integerDigits) += 1;
    }
    else if (c == '.' && !point)
    {
      point = true;
    }
    else
    {
      return false;
    }
  }
  if (!point || integerDigits == 0 || fractionDigits == 0)
  {
    return false;
  }
  value = sign * mantissa / std::pow(10.0, fractionDigits);
  return true;
}
} // namespace

FastrakParser::FastrakParser()
  : FastrakParser(Options{})
{
}

FastrakParser::FastrakParser(const Options& options)
  : Opts(options)
{
}

std::size_t FastrakParser::RecordSize() const
{
  return this->Opts.format == FastrakFormat::Binary ? BinaryRecordSize : AsciiRecordSize;
}

FastrakParser::Check FastrakParser::CheckStructure(const std::uint8_t* r) const
{
  if (r[1] < '0' || r[1] > '9')
  {
    return Check::NotARecord;
  }
  const Check failed = IsStationDigit(r[1]) ? Check::Malformed : Check::NotARecord;
  if (!IsStatusByte(r[2]))
  {
    return failed;
  }
  const std::size_t n = this->RecordSize();
  if (!IsStylusTail(r + n - 3))
  {
    return failed;
  }
  if (this->Opts.format == FastrakFormat::Ascii)
  {
    double ignored;
    for (std::size_t f = 0; f < 7; ++f)
    {
      if (!ParseAsciiField(r + 3 + f * AsciiFieldWidth, ignored))
      {
        return failed;
      }
    }
  }
  return Check::Valid;
}

bool FastrakParser::Decode(const std::uint8_t* r, double time, TrackerPose& pose) const
{
  const int station = r[1] - '0';
  if (station < 1 || station > 4)
  {
    return false;
  }
  double v[7];
  for (std::size_t f = 0; f < 7; ++f)
  {
    if (this->Opts.format == FastrakFormat::Binary)
    {
      v[f] = double(LittleEndianFloat(r + 3 + 4 * f));
    }
    else
    {
      ParseAsciiField(r + 3 + f * AsciiFieldWidth, v[f]);
    }
    if (!std::isfinite(v[f]))
    {
      return false;
    }
  }
  const double scale = this->Opts.units == FastrakUnits::Centimetres ? 10.0 : 25.4;
  const Vec3 position{ v[0] * scale, v[1] * scale, v[2] * scale };
  if (std::fabs(position.x) > this->Opts.maxAbsPositionMm ||
    std::fabs(position.y) > this->Opts.maxAbsPositionMm ||
    std::fabs(position.z) > this->Opts.maxAbsPositionMm)
  {
    return false;
  }
  const double norm = std::sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5] + v[6] * v[6]);
  if (!(std::fabs(norm - 1.0) <= this->Opts.quaternionTolerance))
  {
    return false;
  }
  pose.station = station;
  pose.position = position;
  pose.orientation = Quaternion{ v[3] / norm, v[4] / norm, v[5] / norm, v[6] / norm };
  pose.button = r[this->RecordSize() - 2] == '1';
  pose.status = char(r[2]);
  pose.time = time;
  return true;
}

void FastrakParser::Feed(const std::uint8_t* data,
  std::size_t size,
  double time,
  std::vector<TrackerPose>& out)
{
  if (size > 0)
  {
    this->Buffer.insert(this->Buffer.end(), data, data + size);
  }
  const std::size_t n = this->RecordSize();
  const bool ascii = this->Opts.format == FastrakFormat::Ascii;
  for (;;)
  {
    while (this->Begin < this->Buffer.size() && this->Buffer[this->Begin] != '0')
    {
      const std::uint8_t b = this->Buffer[this->Begin];
      if (!(ascii && (b == '\r' || b == '\n')))
      {
        ++this->Stats.garbageBytes;
      }
      ++this->Begin;
    }
    if (this->Buffer.size() - this->Begin < n)
    {
      break;
    }
    const std::uint8_t* record = this->Buffer.data() + this->Begin;
    const Check check = this->CheckStructure(record);
    if (check == Check::Valid)
    {
      TrackerPose pose;
      if (this->Decode(record, time, pose))
      {
        ++this->Stats.records;
        if (pose.status != ' ')
        {
          ++this->Stats.warnings;
        }
        out.push_back(pose);
      }
      else
      {
        ++this->Stats.dropped;
      }
      this->Begin += n;
    }
    else
    {
      // Resynchronise: the next record may start inside this candidate.
      ++(check == Check::Malformed ? this->Stats.malformed : this->Stats.garbageBytes);
      ++this->Begin;
    }
  }
  if (this->Begin == this->Buffer.size())
  {
    this->Buffer.clear();
    this->Begin = 0;
  }
  else if (this->Begin >= 4096)
  {
    this->Buffer.erase(this->Buffer.begin(), this->Buffer.begin() + std::ptrdiff_t(this->Begin));
    this->Begin = 0;
  }
}

std::vector<TrackerPose> FastrakParser::Feed(const std::vector<std::uint8_t>& data, double time)
{
  std::vector<TrackerPose> poses;
  this->Feed(data.data(), data.size(), time, poses);
  return poses;
}

void FastrakParser::Finish()
{
  const std::size_t left = this->Buffered();
  if (left > 0)
  {
    // Feed() stops hunting only at a '0' it cannot check yet.
    const bool header = left == 1 || IsStationDigit(this->Buffer[this->Begin + 1]);
    if (header)
    {
      ++this->Stats.truncated;
    }
    else
    {
      this->Stats.garbageBytes += left;
    }
  }
  this->Buffer.clear();
  this->Begin = 0;
}

void FastrakParser::Reset()
{
  this->Buffer.clear();
  this->Begin = 0;
  this->Stats = FastrakParserStatistics{};
}

} // namespace bender
