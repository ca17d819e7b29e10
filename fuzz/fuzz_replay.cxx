// libFuzzer harness for replay timestamps: the input is the ".timestamps" sidecar of a fixed
// 256-byte recording. A sidecar is accepted (and every byte of the recording is then read
// back exactly once, in order) or refused with a RecordingError of one clean line.

#include "FuzzSupport.h"
#include "ReplayTransport.h"
#include "TrackingErrors.h"

#include <chrono>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const std::string recording = []
  {
    std::vector<std::uint8_t> bytes(256);
    for (std::size_t i = 0; i < bytes.size(); ++i)
    {
      bytes[i] = static_cast<std::uint8_t>(i);
    }
    return bender_fuzz::WriteInput("replay.fastrak", bytes.data(), bytes.size());
  }();
  bender_fuzz::WriteInput("replay.fastrak.timestamps", data, size);
  try
  {
    bender::ReplayTransport replay(recording);
    std::uint8_t buffer[97];
    std::size_t total = 0;
    while (!replay.AtEnd())
    {
      const std::size_t n = replay.Read(buffer, sizeof buffer, std::chrono::milliseconds(0));
      for (std::size_t i = 0; i < n; ++i)
      {
        if (buffer[i] != static_cast<std::uint8_t>(total + i))
        {
          std::abort();
        }
      }
      total += n;
      if (n == 0 || total > 256)
      {
        std::abort();
      }
    }
    if (total != 256)
    {
      std::abort();
    }
  }
  catch (const bender::RecordingError& e)
  {
    bender_fuzz::CheckMessage(e.what());
  }
  return 0;
}
