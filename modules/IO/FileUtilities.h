#ifndef bender_FileUtilities_h
#define bender_FileUtilities_h

// Internal helpers shared by the readers and writers of this module; not part of the
// module's interface. The atomic write they use is public: AtomicFile.h; the file-name
// helpers (DisplayName, LowerExtension) are Core's StringUtil.h.

#include "AtomicFile.h"
#include "StringUtil.h"

#include <cstdint>
#include <string>

namespace bender
{
namespace io_detail
{

/// Checks that path names a readable, non-empty regular file and returns its size in bytes.
/// Otherwise returns false and sets problem to a short description ("no such file",
/// "is a folder, not a file", "empty file (0 bytes)", "cannot be opened for reading").
bool CheckReadableFile(const std::string& path, std::uintmax_t& size, std::string& problem);

} // namespace io_detail
} // namespace bender

#endif
