#ifndef bender_ReplayTransport_h
#define bender_ReplayTransport_h

#include "Transport.h"

#include <chrono>
#include <string>
#include <vector>

namespace bender
{

/// Plays back a recording: FILE holds raw bytes as a Fastrak sent them (binary or ASCII,
/// output list `O n,2,11,16,0`); the optional sidecar FILE.timestamps (StreamRecorder)
/// gives the chunks as they were received and their receive times.
///
/// Deterministic by default: Read returns the recorded chunks (or, without a sidecar,
/// `chunkSize`-byte chunks) as fast as they are asked for, and RecordedTime() reports the
/// recorded time (without a sidecar: byte offset / bytesPerSecond). With `realtime`, each
/// chunk is held back until its recorded time has passed since the first Read. Writes are
/// accepted and ignored (a recording cannot be commanded); Flush() discards nothing.
class ReplayTransport : public Transport
{
public:
  struct Options
  {
    bool realtime = false;
    std::size_t chunkSize = 64;     ///< without a sidecar; > 0
    double bytesPerSecond = 4080.0; ///< without a sidecar: 34-byte records at 120 Hz; > 0
  };

  /// Loads FILE (and FILE.timestamps when present). Throws RecordingError naming the file
  /// (missing, unreadable, empty) or the sidecar line that is wrong. A recording cut short
  /// at any byte (StreamRecorder's promise) replays: a sidecar line cut before its newline
  /// is not read, and the bytes no line lists are replayed as one last chunk.
  explicit ReplayTransport(const std::string& path);
  ReplayTransport(const std::string& path, const Options& options);

  std::string Name() const override { return "replay " + this->Path; }
  std::size_t Read(std::uint8_t* buffer, std::size_t capacity, Timeout timeout) override;
  void Write(const std::uint8_t*, std::size_t, Timeout) override {}
  void Flush() override {}
  void Close() override { this->Closed = true; }
  bool AtEnd() const override { return this->Chunk >= this->Chunks.size(); }
  std::optional<double> RecordedTime() const override { return this->LastTime; }

  bool HasTimestamps() const { return this->Timestamped; }
  /// Bytes at the end of FILE that its sidecar does not list (a recording cut short between
  /// a chunk and its timestamp line): replayed as one last chunk at the last listed time.
  std::size_t UnlistedBytes() const { return this->Unlisted; }
  /// The recording being replayed (its sidecar is StreamRecorder::SidecarPath of it).
  const std::string& FilePath() const { return this->Path; }
  std::size_t Size() const { return this->Bytes.size(); }

private:
  struct ChunkInfo
  {
    std::size_t offset;
    std::size_t size;
    double time;
  };
  void LoadSidecar(const std::string& sidecar);

  std::string Path;
  Options Opts;
  std::vector<std::uint8_t> Bytes;
  std::vector<ChunkInfo> Chunks;
  std::size_t Chunk = 0;
  std::size_t ChunkDone = 0;
  std::size_t Unlisted = 0;
  double LastTime = 0.0;
  bool Timestamped = false;
  bool Closed = false;
  bool Started = false;
  std::chrono::steady_clock::time_point StartTime;
};

} // namespace bender

#endif
