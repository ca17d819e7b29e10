#ifndef bender_StreamRecorder_h
#define bender_StreamRecorder_h

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace bender
{

/// Writes a recording: FILE holds the raw bytes exactly as received, FILE.timestamps one
/// line per received chunk, "OFFSET SIZE SECONDS" (byte offset in FILE, chunk length,
/// receive time in seconds since the recording started), after a header line starting
/// with '#'. See docs/tracking.md. Both files are flushed after every chunk, the bytes before
/// their line, so a recording cut short by a crash (at any byte of either file) replays with
/// ReplayTransport: every listed chunk at its time, then the unlisted bytes at the last time.
class StreamRecorder
{
public:
  /// Creates (truncates) FILE and FILE.timestamps; throws RecordingError.
  explicit StreamRecorder(const std::string& path);
  ~StreamRecorder();
  StreamRecorder(const StreamRecorder&) = delete;
  StreamRecorder& operator=(const StreamRecorder&) = delete;

  /// Appends one chunk received at `time` seconds; throws RecordingError (disk full, ...).
  void Append(const std::uint8_t* data, std::size_t size, double time);
  void Close();

  const std::string& Path() const { return this->FilePath; }
  std::uint64_t BytesWritten() const { return this->Offset; }

  static std::string SidecarPath(const std::string& path) { return path + ".timestamps"; }

private:
  std::string FilePath;
  std::FILE* Data = nullptr;
  std::FILE* Times = nullptr;
  std::uint64_t Offset = 0;
};

} // namespace bender

#endif
