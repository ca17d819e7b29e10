#ifndef bender_SessionAutosave_h
#define bender_SessionAutosave_h

#include "WarpPlan.h"

#include <stdexcept>
#include <string>

namespace bender
{

/// A session file cannot be read or written; what() names the file and the problem.
class SessionFileError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// What an autosave keeps so that a crash loses nothing: a reference to the source surface
/// (a mesh file; a segmented surface is saved beside the autosave file first) and the plan
/// committed so far. JSON: {"format": "bender-session", "version": 1, "source": PATH,
/// "frame": "LPS", "plan": {warp-file-format.md object}}.
struct SessionSnapshot
{
  std::string sourcePath; ///< absolute path of the surface the plan applies to
  /// The surface's name in the window ("demo vessel (segmented)", "aneurysm.stl"); optional
  /// ("name" in the file), empty when unknown.
  std::string surfaceName;
  std::string frame = "LPS";
  WarpPlan plan;
};

/// Writes atomically (temporary file in the same folder, then rename); creates the folder.
/// Throws SessionFileError.
void WriteSessionFile(const SessionSnapshot& snapshot, const std::string& path);

/// Reads and validates (the plan as ReadWarpPlan would). Throws SessionFileError.
SessionSnapshot ReadSessionFile(const std::string& path);

} // namespace bender

#endif
