#ifndef bender_RecordingTransport_h
#define bender_RecordingTransport_h

#include "StreamRecorder.h"
#include "Transport.h"

#include <chrono>
#include <memory>

namespace bender
{

/// Passes everything through to `inner` and records every chunk that Read returns (the
/// bytes as received, with their receive time) through a StreamRecorder, so that the session
/// can be replayed with ReplayTransport. Bytes discarded by Flush() are not recorded: the
/// recording starts with what the device streams after its configuration.
class RecordingTransport : public Transport
{
public:
  /// Throws RecordingError when the files cannot be created, or, before creating anything,
  /// when `inner` is a ReplayTransport and FILE or FILE.timestamps is the replayed recording
  /// or its timestamps sidecar (the recorder would truncate its own input).
  RecordingTransport(std::unique_ptr<Transport> inner, const std::string& path);

  std::string Name() const override { return this->Inner->Name(); }
  std::size_t Read(std::uint8_t* buffer, std::size_t capacity, Timeout timeout) override;
  void Write(const std::uint8_t* data, std::size_t size, Timeout timeout) override
  {
    this->Inner->Write(data, size, timeout);
  }
  void Flush() override { this->Inner->Flush(); }
  void Close() override;
  bool AtEnd() const override { return this->Inner->AtEnd(); }
  std::optional<double> RecordedTime() const override { return this->Inner->RecordedTime(); }

private:
  std::unique_ptr<Transport> Inner;
  StreamRecorder Recorder;
  std::chrono::steady_clock::time_point Start;
};

} // namespace bender

#endif
