#ifndef bender_FuzzSupport_h
#define bender_FuzzSupport_h

// Shared by the libFuzzer harnesses: a per-process scratch file for the readers that take a
// path, and the check that an error message is one clean line.

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace bender_fuzz
{

/// A scratch folder for this process (removed at exit): $BENDER_FUZZ_SCRATCH when set (scripts/fuzz
/// gives each harness its own, so that the paths in messages, and with them the coverage, do not
/// depend on the process id and a fixed -seed replays the same run), else e.g.
/// /tmp/bender-fuzz-1234/.
inline const std::filesystem::path& ScratchFolder()
{
  static const std::filesystem::path folder = []
  {
    const char* fixed = std::getenv("BENDER_FUZZ_SCRATCH");
    const char* base = std::getenv("TMPDIR");
    std::filesystem::path p = fixed && *fixed
      ? std::filesystem::path(fixed)
      : std::filesystem::path(base && *base ? base : "/tmp") /
        ("bender-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(p);
    std::atexit(
      []
      {
        std::error_code ec;
        std::filesystem::remove_all(ScratchFolder(), ec);
      });
    return p;
  }();
  return folder;
}

/// Writes the input to ScratchFolder()/name and returns the path.
inline std::string WriteInput(const std::string& name, const std::uint8_t* data, std::size_t size)
{
  const std::string path = (ScratchFolder() / name).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out)
  {
    std::abort();
  }
  return path;
}

/// An input split for the stream harnesses: `count` bytes after the first give the sizes
/// (each byte + 1) of the chunks in which the rest, the stream, is fed (cycled; no size: the
/// whole stream at once).
struct ChunkedInput
{
  std::vector<std::size_t> sizes;
  const std::uint8_t* stream = nullptr;
  std::size_t size = 0;
};

/// `data` holds at least one byte (the harness's control byte).
inline ChunkedInput SplitChunks(const std::uint8_t* data, std::size_t size, std::size_t count)
{
  ChunkedInput in;
  count = std::min(count, size - 1);
  for (std::size_t i = 0; i < count; ++i)
  {
    in.sizes.push_back(std::size_t(data[1 + i]) + 1);
  }
  in.stream = data + 1 + count;
  in.size = size - 1 - count;
  return in;
}

/// Calls feed(bytes, n) over the stream, chunk after chunk.
template<typename Feed>
void FeedInChunks(const std::uint8_t* stream,
  std::size_t size,
  const std::vector<std::size_t>& sizes,
  const Feed& feed)
{
  std::size_t next = 0;
  for (std::size_t at = 0; at < size;)
  {
    const std::size_t piece = sizes.empty() ? size : sizes[next++ % sizes.size()];
    const std::size_t n = std::min(piece, size - at);
    feed(stream + at, n);
    at += n;
  }
}

/// Every message the project shows must be one line of printable ASCII without escape
/// sequences; anything else is a finding.
inline void CheckMessage(const std::string& message)
{
  for (const char c : message)
  {
    const auto u = static_cast<unsigned char>(c);
    if (u < 32 || u >= 127)
    {
      std::fprintf(
        stderr, "finding: non-printable byte 0x%02x in message: %s\n", u, message.c_str());
      std::abort();
    }
  }
  if (message.empty() || message.size() > 1000)
  {
    std::fprintf(stderr, "finding: empty or over-long (%zu bytes) message\n", message.size());
    std::abort();
  }
}

} // namespace bender_fuzz

#endif
