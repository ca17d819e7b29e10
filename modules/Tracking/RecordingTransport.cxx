#include "RecordingTransport.h"

#include "FileIdentity.h"
#include "ReplayTransport.h"
#include "TrackingErrors.h"

#include <filesystem>
#include <system_error>

namespace bender
{

namespace
{

// The recorder truncates FILE and FILE.timestamps on creation: refuse before that when either
// is a file of the replay being recorded (the replayed recording or its timestamps sidecar).
std::unique_ptr<Transport> RefuseRecordingOverInput(std::unique_ptr<Transport> inner,
  const std::string& path)
{
  if (const auto* replay = dynamic_cast<const ReplayTransport*>(inner.get()))
  {
    const std::string inputs[] = { replay->FilePath(),
      StreamRecorder::SidecarPath(replay->FilePath()) };
    const std::string outputs[] = { path, StreamRecorder::SidecarPath(path) };
    for (const std::string& output : outputs)
    {
      for (const std::string& input : inputs)
      {
        if (SameFile(output, input))
        {
          throw RecordingError("recording " + path + ": would overwrite " + input +
            ", a file of the replay being recorded");
        }
      }
    }
  }
  return inner;
}

} // namespace

RecordingTransport::RecordingTransport(std::unique_ptr<Transport> inner, const std::string& path)
  : Inner(RefuseRecordingOverInput(std::move(inner), path))
  , Recorder(path)
  , Start(std::chrono::steady_clock::now())
{
}

std::size_t RecordingTransport::Read(std::uint8_t* buffer,
  std::size_t capacity,
  std::chrono::milliseconds timeout)
{
  const std::size_t n = this->Inner->Read(buffer, capacity, timeout);
  if (n > 0)
  {
    // A replay being re-recorded keeps its own time base; a live device gets receive times.
    const double t = this->Inner->RecordedTime().value_or(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count());
    this->Recorder.Append(buffer, n, t);
  }
  return n;
}

void RecordingTransport::Close()
{
  this->Inner->Close();
  this->Recorder.Close();
}

} // namespace bender
