#ifndef bender_FileUtilities_h
#define bender_FileUtilities_h

// Internal helpers shared by the readers and writers of this module; not part of the
// module's interface. The atomic write they use is public: AtomicFile.h.

#include "AtomicFile.h"

#include <cstdint>
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

} // namespace io_detail
} // namespace bender

#endif
