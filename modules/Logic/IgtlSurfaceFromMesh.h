#ifndef bender_IgtlSurfaceFromMesh_h
#define bender_IgtlSurfaceFromMesh_h

#include "IgtlSender.h"

#include <string>

class vtkPolyData;

namespace bender
{

/// The surface to send over OpenIGTLink (IgtlSender::SendSurface) from a mesh in LPS
/// millimetres: its points and its polygons (triangles and other polygons, with their point
/// ids); triangle strips, lines and vertices are not sent. Used by `bender-cli igtl-send` and
/// by the application's "Send to Slicer".
///
/// Throws InputError naming `name` when the mesh is null, has no polygons, or has more points
/// than OpenIGTLink can index (2^32 - 1).
IgtlSurface MakeIgtlSurface(vtkPolyData* mesh, const std::string& name);

} // namespace bender

#endif
