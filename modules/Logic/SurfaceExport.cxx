#include "SurfaceExport.h"

#include "BenderErrors.h"

namespace bender
{

std::vector<std::string> ExportSurface(vtkPolyData* surface,
  const std::string& path,
  const ExportOptions& options)
{
  if (options.frame != "LPS" && options.frame != "RAS")
  {
    throw InputError(path + ": unknown frame '" + options.frame + "' (LPS or RAS)");
  }
  ExportSurfaceOptions unified;
  unified.output = path;
  unified.frame = options.frame == "RAS" ? StlFrame::RAS : StlFrame::LPS;
  unified.unit = options.unit;
  unified.stlEncoding = options.stlEncoding;
  unified.patches = options.patches;
  unified.cap = options.cap;
  unified.protectedPath = options.protectedPath;
  return ExportSurface(surface, unified).written;
}

} // namespace bender
