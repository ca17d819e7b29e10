#include "ReplayTransport.h"

#include "StreamRecorder.h"
#include "TrackingErrors.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <thread>

namespace bender
{

namespace
{
constexpr std::size_t MaxRecordingBytes = std::size_t(1) << 30;
// A sidecar has one short line per chunk of at least one byte.
constexpr std::size_t MaxSidecarBytes = std::size_t(1) << 28;
constexpr std::size_t MaxSidecarLine = 256;
// Recorded times are seconds since the recording started: a year is beyond any session.
constexpr double MaxRecordedSeconds = 366.0 * 24 * 3600;

// A file's bytes fit for a one-line message: printable ASCII, the rest as \xNN, cut short.
std::string Quote(const std::string& bytes, std::size_t maxLength = 60)
{
  static const char* const hex = "0123456789abcdef";
  std::string quoted;
  for (const char c : bytes)
  {
    const auto u = static_cast<unsigned char>(c);
    if (quoted.size() >= maxLength)
    {
      quoted += "...";
      break;
    }
    if (u >= 32 && u < 127 && u != '\\')
    {
      quoted += c;
    }
    else
    {
      quoted += std::string("\\x") + hex[u >> 4] + hex[u & 15];
    }
  }
  return quoted;
}

std::string Seconds(double t)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", t);
  return text;
}
} // namespace

ReplayTransport::ReplayTransport(const std::string& path)
  : ReplayTransport(path, Options{})
{
}

ReplayTransport::ReplayTransport(const std::string& path, const Options& options)
  : Path(path)
  , Opts(options)
{
  if (this->Opts.chunkSize == 0 || !(this->Opts.bytesPerSecond > 0.0))
  {
    throw TrackingConfigurationError("replay " + path + ": chunk size and byte rate must be > 0");
  }
  struct stat info
  {
  };
  if (::stat(path.c_str(), &info) != 0)
  {
    throw RecordingError("replay " + path + ": cannot open (" + std::strerror(errno) + ")");
  }
  if (!S_ISREG(info.st_mode))
  {
    throw RecordingError("replay " + path + ": not a regular file");
  }
  if (std::size_t(info.st_size) > MaxRecordingBytes)
  {
    throw RecordingError("replay " + path + ": larger than 1 GiB, not a tracker recording?");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    throw RecordingError("replay " + path + ": cannot open (" + std::strerror(errno) + ")");
  }
  this->Bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (this->Bytes.empty())
  {
    throw RecordingError("replay " + path + ": the recording is empty");
  }
  const std::string sidecar = StreamRecorder::SidecarPath(path);
  if (::stat(sidecar.c_str(), &info) == 0)
  {
    if (!S_ISREG(info.st_mode))
    {
      throw RecordingError("replay " + sidecar + ": not a regular file");
    }
    if (std::size_t(info.st_size) > MaxSidecarBytes)
    {
      throw RecordingError("replay " + sidecar + ": larger than 256 MiB, not a timestamps file?");
    }
    this->LoadSidecar(sidecar);
  }
  else
  {
    for (std::size_t offset = 0; offset < this->Bytes.size(); offset += this->Opts.chunkSize)
    {
      const std::size_t size = std::min(this->Opts.chunkSize, this->Bytes.size() - offset);
      this->Chunks.push_back({ offset, size, double(offset + size) / this->Opts.bytesPerSecond });
    }
  }
}

void ReplayTransport::LoadSidecar(const std::string& sidecar)
{
  std::ifstream in(sidecar);
  if (!in)
  {
    throw RecordingError("replay " + sidecar + ": cannot open (" + std::strerror(errno) + ")");
  }
  std::string line;
  int number = 0;
  std::size_t expected = 0;
  double previous = -1e300;
  while (std::getline(in, line))
  {
    ++number;
    if (line.size() > MaxSidecarLine)
    {
      throw RecordingError("replay " + sidecar + " line " + std::to_string(number) +
        ": longer than " + std::to_string(MaxSidecarLine) + " bytes");
    }
    // The recorder ends every line: a last line without its newline was cut while being
    // written, and its chunk is replayed as unlisted bytes below.
    if (in.eof())
    {
      break;
    }
    if (line.empty() || line[0] == '#')
    {
      continue;
    }
    std::istringstream fields(line);
    fields.imbue(std::locale::classic());
    unsigned long long offset = 0, size = 0;
    double time = 0.0;
    std::string extra;
    const std::string where = "replay " + sidecar + " line " + std::to_string(number);
    if (!(fields >> offset >> size >> time) || (fields >> extra))
    {
      throw RecordingError(where + ": expected 'OFFSET SIZE SECONDS', got '" + Quote(line) + "'");
    }
    // Compare without adding: offset + size wraps around for a forged size.
    if (offset != expected || size == 0 || offset > this->Bytes.size() ||
      size > this->Bytes.size() - offset)
    {
      throw RecordingError(where + ": chunk " + std::to_string(offset) + "+" +
        std::to_string(size) + " does not follow on from byte " + std::to_string(expected) +
        " within the " + std::to_string(this->Bytes.size()) + "-byte recording");
    }
    if (!std::isfinite(time) || std::fabs(time) > MaxRecordedSeconds)
    {
      throw RecordingError(
        where + ": time " + Seconds(time) + " s is out of range (at most a year from the start)");
    }
    if (time < previous)
    {
      throw RecordingError(where + ": time " + Seconds(time) + " goes backwards");
    }
    this->Chunks.push_back({ std::size_t(offset), std::size_t(size), time });
    expected = std::size_t(offset + size);
    previous = time;
  }
  // A recording cut short between a chunk's bytes and its line (StreamRecorder writes the
  // bytes first), or during either: the bytes after the last listed chunk were received, and
  // are replayed as one last chunk at the last listed time (nothing later is known).
  if (expected < this->Bytes.size())
  {
    this->Unlisted = this->Bytes.size() - expected;
    this->Chunks.push_back({ expected, this->Unlisted, this->Chunks.empty() ? 0.0 : previous });
  }
  this->Timestamped = true;
}

std::size_t ReplayTransport::Read(std::uint8_t* buffer,
  std::size_t capacity,
  std::chrono::milliseconds timeout)
{
  this->CheckOpen(!this->Closed);
  if (this->AtEnd() || capacity == 0)
  {
    return 0;
  }
  const ChunkInfo& chunk = this->Chunks[this->Chunk];
  if (this->Opts.realtime)
  {
    const auto now = std::chrono::steady_clock::now();
    if (!this->Started)
    {
      this->Started = true;
      this->StartTime = now -
        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(chunk.time));
    }
    const auto due = this->StartTime +
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(chunk.time));
    if (due > now)
    {
      if (due - now > timeout)
      {
        std::this_thread::sleep_for(timeout);
        return 0;
      }
      std::this_thread::sleep_until(due);
    }
  }
  const std::size_t n = std::min(capacity, chunk.size - this->ChunkDone);
  std::memcpy(buffer, this->Bytes.data() + chunk.offset + this->ChunkDone, n);
  this->LastTime = chunk.time;
  this->ChunkDone += n;
  if (this->ChunkDone == chunk.size)
  {
    ++this->Chunk;
    this->ChunkDone = 0;
  }
  return n;
}

} // namespace bender
