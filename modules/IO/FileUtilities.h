#ifndef bender_FileUtilities_h
#define bender_FileUtilities_h

// Internal helpers shared by MeshIO and WarpPlanIO; not part of the module's interface.

#include <cstdint>
#include <functional>
#include <string>

namespace bender
{
namespace io_detail
{

/// The last path component ("aneurysm.stl" for "/data/aneurysm.stl"); the whole path when it
/// has none. Used to prefix messages.
std::string DisplayName(const std::string& path);

/// The extension in lower case with its dot (".stl"), empty when there is none.
std::string LowerExtension(const std::string& path);

/// Checks that path names a readable, non-empty regular file and returns its size in bytes.
/// Otherwise returns false and sets problem to a short description ("no such file",
/// "is a folder, not a file", "empty file (0 bytes)", "cannot be opened for reading").
bool CheckReadableFile(const std::string& path, std::uintmax_t& size, std::string& problem);

/// Writes a file atomically: produce(tempPath) writes the whole content to a temporary file
/// in the target's folder (same file system), which is flushed to disk and renamed over
/// path. produce returns false, or throws, to abandon the write; the temporary file is then
/// removed and nothing at path changes. Returns false with problem set on failure (problem
/// is left as produce set it when produce fails). Exceptions thrown by produce propagate
/// after the temporary file is removed.
bool AtomicWrite(const std::string& path,
  const std::function<bool(const std::string& tempPath, std::string& problem)>& produce,
  std::string& problem);

} // namespace io_detail
} // namespace bender

#endif
