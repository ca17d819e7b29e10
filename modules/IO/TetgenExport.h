#ifndef bender_TetgenExport_h
#define bender_TetgenExport_h

// TetGen input files of a labelled surface: .smesh (a surface mesh: nodes and triangular
// facets) and .poly (each triangle one facet of one polygon). The facet boundary marker of
// every triangle is its CellEntityIds label (wall 1, ends 2, 3, ...: PatchLabels.h), so that
// `tetgen -p` keeps them in its output .face file. No holes; one region attribute point
// inside the lumen when one is given (`tetgen -A` puts attribute 1 on the tetrahedra there).

#include "AtomicFile.h"
#include "BenderStlExport.h"

#include <string>

class vtkPolyData;

namespace bender
{

enum class TetgenFormat
{
  Smesh, ///< .smesh
  Poly   ///< .poly
};

/// The format for a path's extension (.smesh or .poly, any case); false for any other.
bool TetgenFormatForPath(const std::string& path, TetgenFormat& format);

/// The whole text of the TetGen file of mesh: its triangles (polygons fanned) with their
/// labels (its patch table), nodes numbered from 1 (only the points of triangles) in the
/// coordinates of `transform`, written with 17 significant digits. `insidePoint` (in those
/// coordinates, may be null) becomes the one region point. Throws StlExportError (no
/// triangles, non-finite coordinates, a cell array CellPatchIds refuses).
std::string TetgenText(const LabelledSurface& mesh,
  TetgenFormat format,
  const ExportTransform& transform,
  const double* insidePoint);

/// The file as a producer for AtomicWriteAll (the text is built now; throws like TetgenText,
/// the message starting with the file's base name).
AtomicFile TetgenFile(const LabelledSurface& mesh,
  const std::string& path,
  TetgenFormat format,
  const ExportTransform& transform,
  const double* insidePoint);
/// TetgenFile of a surface whose labels are not read yet (WriteMesh): read here, once.
AtomicFile TetgenFile(vtkPolyData* mesh,
  const std::string& path,
  TetgenFormat format,
  const ExportTransform& transform,
  const double* insidePoint);

} // namespace bender

#endif
