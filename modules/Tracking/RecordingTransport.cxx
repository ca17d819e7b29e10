#include "RecordingTransport.h"

namespace bender
{

RecordingTransport::RecordingTransport(std::unique_ptr<Transport> inner, const std::string& path)
  : Inner(std::move(inner))
  , Recorder(path)
  , Start(std::chrono::steady_clock::now())
{
}

std::size_t RecordingTransport::Read(
  std::uint8_t* buffer, std::size_t capacity, std::chrono::milliseconds timeout)
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
