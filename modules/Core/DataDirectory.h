#ifndef bender_DataDirectory_h
#define bender_DataDirectory_h

#include <string>
#include <vector>

namespace bender
{

/// The folder of the running executable (from /proc/self/exe), empty when unknown.
std::string ExecutableDirectory();

/// The folders where Bender looks for its data (demo/, external/), in order:
///  1. the environment variable BENDER_DATA_DIR, when set and not empty (used as is);
///  2. <executable folder>/../share/bender: the install layout (bin/bender-cli,
///     share/bender/demo/...) and the build tree's (the build makes build/share/bender a link
///     to the source data folder, next to build/bin).
/// No source path is compiled in: the binaries are relocatable.
std::vector<std::string> DataDirectoryCandidates();

/// The first candidate that exists as a folder; when none does, the first candidate (so that
/// the error about the missing file names where it was looked for), or "share/bender".
std::string DataDirectory();

} // namespace bender

#endif
