#ifndef bender_SurfaceExport_h
#define bender_SurfaceExport_h

// Compatibility for callers not yet switched to ExportSurface.h (BenderSession, MainWindow):
// the old options with the frame as a string, forwarding to the one export workflow,
// bender::ExportSurface(surface, ExportSurfaceOptions). To be removed once they use it.

#include "ExportSurface.h"

#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

/// Deprecated: use ExportSurfaceOptions (frame as an enum, output path inside).
struct ExportOptions
{
  StlEncoding stlEncoding = StlEncoding::Binary;
  std::string frame = "LPS"; ///< "LPS" or "RAS"
  std::string unit = "mm";
  bool cap = false;
  StlPatchMode patches = StlPatchMode::Single;
  std::string protectedPath;
};

/// Deprecated: forwards to ExportSurface(surface, ExportSurfaceOptions). Returns the files
/// written. Throws InputError naming the file (also for a frame other than LPS or RAS).
std::vector<std::string> ExportSurface(vtkPolyData* surface,
  const std::string& path,
  const ExportOptions& options);

} // namespace bender

#endif
