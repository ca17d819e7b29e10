#include "StreamRecorder.h"

#include "FaultInjection.h"
#include "TrackingErrors.h"

#include <cerrno>
#include <cstring>

namespace bender
{

StreamRecorder::StreamRecorder(const std::string& path)
  : FilePath(path)
{
  this->Data = std::fopen(path.c_str(), "wb");
  if (!this->Data)
  {
    throw RecordingError("recording " + path + ": cannot create (" + std::strerror(errno) + ")");
  }
  const std::string sidecar = SidecarPath(path);
  this->Times = std::fopen(sidecar.c_str(), "w");
  if (!this->Times)
  {
    const int error = errno;
    std::fclose(this->Data);
    this->Data = nullptr;
    throw RecordingError("recording " + sidecar + ": cannot create (" + std::strerror(error) + ")");
  }
  std::fprintf(this->Times, "# bender tracking recording v1: offset bytes seconds\n");
  std::fflush(this->Times);
}

StreamRecorder::~StreamRecorder()
{
  this->Close();
}

void StreamRecorder::Append(const std::uint8_t* data, std::size_t size, double time)
{
  if (!this->Data || !this->Times)
  {
    throw RecordingError("recording " + this->FilePath + ": written after Close()");
  }
  if (size == 0)
  {
    return;
  }
  // The bytes on disk first, then the line that lists them: a recording cut short between
  // the two holds one chunk more than its timestamps list, never a line without its bytes.
  bool ok = std::fwrite(data, 1, size, this->Data) == size && std::fflush(this->Data) == 0;
  if (ok)
  {
    FaultPoint("recording");
  }
  ok = ok &&
    std::fprintf(
      this->Times, "%llu %zu %.6f\n", static_cast<unsigned long long>(this->Offset), size, time) >
      0 &&
    std::fflush(this->Times) == 0;
  if (!ok)
  {
    throw RecordingError(
      "recording " + this->FilePath + ": write failed (" + std::strerror(errno) + ")");
  }
  this->Offset += size;
}

void StreamRecorder::Close()
{
  if (this->Data)
  {
    std::fclose(this->Data);
    this->Data = nullptr;
  }
  if (this->Times)
  {
    std::fclose(this->Times);
    this->Times = nullptr;
  }
}

} // namespace bender
